//! The flag bits and special values of the tracer's GPU records, shared with the tracing
//! shaders as `generated/trace_constants.glsl` (see [`crate::render::shader_abi`]); the
//! descriptor bindings are [`super::bindings`].

glsl_constants! {
    /// Local size of the compute shaders in x and y.
    const TRACE_GROUP: u32 = 8;

    /// A texture index meaning "no texture" (a material's unit that does not texture; the
    /// texel pool samples it as opaque white).
    const NO_TEXTURE: u32 = u32::MAX;

    /// Texture units a material traces, each a [`GpuLayer`](super::gpu_types::GpuLayer): the
    /// units whose coordinates a triangle's corners carry.
    const TRACED_UNITS: usize = 2;
    /// `GpuLayer::role`: the unit does not texture (or is left out).
    const LAYER_OFF: u32 = 0;
    /// `GpuLayer::role`: the unit's texture environment applies to the surface colour, after
    /// the layers before it (`texenv.glsl`).
    const LAYER_COLOR: u32 = 1;
    /// `GpuLayer::role`: a kept lightmap: the unit's texels, times its RGB scale, are the
    /// surface's baked irradiance (`super::scene`'s module doc).
    const LAYER_BAKED_LIGHT: u32 = 2;

    /// `GpuInstance::flags`: traversal runs the alpha test (`trace_alpha_accept`).
    const INSTANCE_ALPHA_TESTED: u32 = 1;

    /// `GpuFrame::flags[0]`: the bits of the tone mapping operator, `TONEMAP_*`.
    const FRAME_TONEMAP_MASK: u32 = 3;
    /// `GpuFrame::flags[0]`: perspective camera (else orthographic).
    const FRAME_PERSPECTIVE: u32 = 4;
    /// `GpuFrame::flags[0]`: missed rays sample the sky's cube map (`super::sky`), not
    /// `GpuFrame::environment`.
    const FRAME_SKY: u32 = 8;
    /// Tone mapping: clamp to [0, 1].
    const TONEMAP_CLAMP: u32 = 0;
    /// Tone mapping: Reinhard, x / (1 + x).
    const TONEMAP_REINHARD: u32 = 1;
    /// Tone mapping: the ACES filmic curve fitted by Narkowicz (2015).
    const TONEMAP_ACES: u32 = 2;

    /// `GpuTexture::flags`: wrap mode `GL_REPEAT` (s in bits 0-1, t in bits 2-3).
    const TEXEL_WRAP_REPEAT: u32 = 0;
    /// Wrap mode `GL_CLAMP_TO_EDGE` (also `GL_CLAMP` and `GL_CLAMP_TO_BORDER`, approximated).
    const TEXEL_WRAP_CLAMP: u32 = 1;
    /// Wrap mode `GL_MIRRORED_REPEAT`.
    const TEXEL_WRAP_MIRROR: u32 = 2;
    /// Shift of the t wrap mode in `GpuTexture::flags`.
    const TEXEL_WRAP_T_SHIFT: u32 = 2;
    /// Magnification is bilinear.
    const TEXEL_MAG_LINEAR: u32 = 1 << 4;
    /// Minification within a level is bilinear.
    const TEXEL_MIN_LINEAR: u32 = 1 << 5;
    /// Minification uses the levels (a GL mipmap filter, or a generated chain).
    const TEXEL_MIPMAP: u32 = 1 << 6;
    /// Minification blends the two nearest levels.
    const TEXEL_MIP_LINEAR: u32 = 1 << 7;
    /// Coordinates are in texels (rectangle textures).
    const TEXEL_RECT: u32 = 1 << 8;
    /// Texels are sRGB-encoded and decoded when sampled.
    const TEXEL_SRGB: u32 = 1 << 9;
    /// Magnification up to a LOD of 0.5, not 0 (OpenGL 1.5 section 3.8.9: linear
    /// magnification with a `NEAREST_MIPMAP_*` minification filter).
    const TEXEL_MAG_TO_HALF: u32 = 1 << 10;

    /// Bit of a BVH child's `meta` word marking a leaf; the low bits count its primitives.
    const BVH_LEAF: u32 = 0x8000_0000;
    /// The most nodes on any root-to-leaf path of a BVH built here (TLAS or BLAS). Traversal
    /// pushes at most one entry per level, so its one stack of `2 * BVH_MAX_DEPTH` entries
    /// (`BVH_STACK_SIZE` in `bvh.glsl`) holds a TLAS path and a BLAS path.
    const BVH_MAX_DEPTH: usize = 32;
}
