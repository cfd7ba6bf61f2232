//! Numbers the radiosity form factors share between the CPU reference
//! ([`super::form_factors`]) and the GPU version (`shaders/radiosity/form_factors.comp`), and
//! the descriptor bindings of the GPU passes (form factors, `direct.comp`, `gather.comp`), as `generated/radiosity_constants.glsl` (see
//! [`crate::render::shader_abi`]), each named `RADIOSITY_<NAME>` there. The pass also binds
//! the tracer's BVH buffers at their own numbers (`trace/bvh.glsl`, [`crate::render::trace::bindings`]).

glsl_constants! {
    glsl_prefix = "RADIOSITY_";
    /// Visibility rays per source patch and receiver point.
    const VISIBILITY_SAMPLES: u32 = 4;
    /// Most receiver points of a patch: the centroids of its first triangles.
    const RECEIVER_POINTS: u32 = 8;
    /// Points a patch receives direct light at (`radiosity/direct.comp`): the centroids of the
    /// four quarters of its area. An update traces them all or a slice of them
    /// (`radiosity_direct_slices`: 1, 2 or 4 slices, each a divisor of this).
    const DIRECT_POINTS: u32 = 4;

    /// The patches (`Patch` of `radiosity/form_factors.comp`).
    const BINDING_PATCHES: u32 = 20;
    /// Every patch's triangles, patch after patch, front side counter-clockwise.
    const BINDING_PATCH_TRIANGLES: u32 = 21;
    /// The rows of the matrix a dispatch computes, row-major.
    const BINDING_ROWS: u32 = 22;

    /// The compressed matrix's BC1 image (`radiosity/gather.comp`, a combined image sampler).
    const BINDING_MATRIX: u32 = 0;
    /// `order[a]`: the patch at row and column `a` of the image.
    const BINDING_ORDER: u32 = 1;
    /// The exact part's row offsets (`n + 1`), in patch order.
    const BINDING_SPARSE_OFFSETS: u32 = 2;
    /// The exact part's entries (`SparseEntry`: column and value).
    const BINDING_SPARSE_ENTRIES: u32 = 3;
    /// Each patch's primary radiosity (emitted plus reflected direct light), written by the
    /// CPU per frame.
    const BINDING_PRIMARY: u32 = 4;
    /// Each patch's radiosity: primary plus k bounces.
    const BINDING_RADIOSITY: u32 = 5;

    /// The frame's lights in the static world's frame (`Light` of `trace/light.glsl`), for
    /// the direct-light pass (`radiosity/direct.comp`).
    const BINDING_LIGHTS: u32 = 23;
    /// Each patch's albedo and emission (`PatchSurface`).
    const BINDING_PATCH_SURFACES: u32 = 24;
    /// Each patch's direct irradiance and primary radiosity (`PatchLight`), written by the
    /// direct-light pass.
    const BINDING_DIRECT: u32 = 25;
    /// Each patch's irradiance at each of its direct-light points (`vec4` per point, patch
    /// after patch), kept on the device from update to update: an update that traces a slice
    /// of the points takes the others from here.
    const BINDING_DIRECT_POINTS: u32 = 26;

    /// The product pass's left factor (`radiosity/product.comp`: one channel of the colour
    /// matrix, row-major `f32`).
    const BINDING_PRODUCT_LEFT: u32 = 27;
    /// Its right factor (the k-bounce sum so far).
    const BINDING_PRODUCT_RIGHT: u32 = 28;
    /// The rows of the result a dispatch computes.
    const BINDING_PRODUCT_ROWS: u32 = 29;
    /// Side of the square of results one workgroup of the product pass computes (16 × 16
    /// invocations of 4 × 4 results each).
    const PRODUCT_TILE: u32 = 64;

    /// Invocations per workgroup of the form-factor pass (one per source patch), of the
    /// direct-light pass (one per patch) and of the gathering pass (one row, these invocations
    /// across its columns).
    const GROUP: u32 = 64;
}
