//! Numbers the radiosity form factors share between the CPU reference
//! ([`super::form_factors`]) and the GPU version (`shaders/radiosity/form_factors.comp`), and
//! the GPU pass's descriptor bindings, as `generated/radiosity_constants.glsl` (see
//! [`crate::render::shader_abi`]), each named `RADIOSITY_<NAME>` there. The pass also binds
//! the tracer's BVH buffers at their own numbers (`trace/bvh.glsl`, [`crate::render::trace::bindings`]).

glsl_constants! {
    glsl_prefix = "RADIOSITY_";
    /// Visibility rays per source patch and receiver point.
    const VISIBILITY_SAMPLES: u32 = 4;
    /// Most receiver points of a patch: the centroids of its first triangles.
    const RECEIVER_POINTS: u32 = 8;

    /// The patches (`Patch` of `radiosity/form_factors.comp`).
    const BINDING_PATCHES: u32 = 20;
    /// Every patch's triangles, patch after patch, front side counter-clockwise.
    const BINDING_PATCH_TRIANGLES: u32 = 21;
    /// The rows of the matrix a dispatch computes, row-major.
    const BINDING_ROWS: u32 = 22;

    /// Invocations per workgroup of the form-factor pass (one per source patch).
    const GROUP: u32 = 64;
}
