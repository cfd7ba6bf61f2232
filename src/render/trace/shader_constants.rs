//! The flag bits, codes and special values of the tracer's GPU records, shared with the
//! tracing shaders as `generated/trace_constants.glsl` (see [`crate::render::shader_abi`]);
//! the descriptor bindings are [`super::bindings`].

glsl_constants! {
    /// Local size of the compute shaders in x and y.
    const TRACE_GROUP: u32 = 8;

    /// A texture index meaning "no texture" (a material's unit that does not texture; the
    /// texel pool samples it as opaque white).
    const NO_TEXTURE: u32 = u32::MAX;

    /// Texture units a material traces, each a [`GpuLayer`](super::gpu_types::GpuLayer): the
    /// units whose coordinates a triangle's corners carry.
    const TRACED_UNITS: usize = 2;
    /// Passes (draws of class `Layer`) a material traces after its units, each a `GpuLayer`
    /// whose corners are `GpuLayerCorners` records: `crate::frame::class::MAX_LAYERS`.
    const MAX_PASSES: usize = 4;
    /// Layers of a material: its units, then its passes.
    const MATERIAL_LAYERS: usize = TRACED_UNITS + MAX_PASSES;
    /// `GpuLayer::role`: the unit or pass does not texture (or is left out).
    const LAYER_OFF: u32 = 0;
    /// `GpuLayer::role`: colour: the unit's texture environment applies to the surface colour
    /// after the layers before it (`texenv.glsl`); a pass blends its colour over it. Part of
    /// the albedo.
    const LAYER_COLOR: u32 = 1;
    /// `GpuLayer::role`: baked light: a light unit (`Instance::light_units`) or a lightmap
    /// pass. Part of the raster colour, left out of the albedo (`super::material`'s module
    /// doc).
    const LAYER_BAKED_LIGHT: u32 = 2;
    /// `GpuLayer::role`: an additive pass: what it adds to the raster colour is emitted light,
    /// left out of the albedo.
    const LAYER_EMISSION: u32 = 3;

    /// `GpuMaterial::flags`: baked: the surface emits its raster colour and reflects no traced
    /// light (the path ends on it).
    const MATERIAL_BAKED: u32 = 1;
    /// `GpuMaterial::flags`: the vertex colours are light: the albedo takes
    /// `GpuMaterial::tint` for their RGB (a vertex-lit model: their hue; a surface baked
    /// into its vertex colours: white).
    const MATERIAL_TINT_PRIMARY: u32 = 2;
    /// `GpuMaterial::flags`: a vertex-lit model ([`crate::frame::class::SurfaceLighting::VertexLit`]):
    /// the game adds the dynamic lights to its colours (Quake 3's `R_SetupEntityLighting`),
    /// so the dynamic lights (`render::trace::lights`) do not light it again.
    const MATERIAL_VERTEX_LIT: u32 = 4;
    /// `GpuMaterial::emitters` of a surface that is not in the emitter list.
    const NO_EMITTER: u32 = u32::MAX;
    /// `GpuMaterial::radiosity` of a surface without radiosity's light (not in the static
    /// world, or radiosity off).
    const NO_RADIOSITY: u32 = u32::MAX;
    /// `GpuInstance::previous_triangles` of an instance whose shape is last frame's (or new).
    const NO_PREVIOUS_TRIANGLES: u32 = u32::MAX;

    /// Blend factor of a pass (`GpuLayer::blend`, OpenGL 1.5 table 4.2): `GL_ZERO`.
    const FACTOR_ZERO: u32 = 0;
    /// `GL_ONE`.
    const FACTOR_ONE: u32 = 1;
    /// `GL_SRC_COLOR`.
    const FACTOR_SRC_COLOR: u32 = 2;
    /// `GL_ONE_MINUS_SRC_COLOR`.
    const FACTOR_ONE_MINUS_SRC_COLOR: u32 = 3;
    /// `GL_DST_COLOR`.
    const FACTOR_DST_COLOR: u32 = 4;
    /// `GL_ONE_MINUS_DST_COLOR`.
    const FACTOR_ONE_MINUS_DST_COLOR: u32 = 5;
    /// `GL_SRC_ALPHA`.
    const FACTOR_SRC_ALPHA: u32 = 6;
    /// `GL_ONE_MINUS_SRC_ALPHA`.
    const FACTOR_ONE_MINUS_SRC_ALPHA: u32 = 7;
    /// `GL_DST_ALPHA`.
    const FACTOR_DST_ALPHA: u32 = 8;
    /// `GL_ONE_MINUS_DST_ALPHA`.
    const FACTOR_ONE_MINUS_DST_ALPHA: u32 = 9;
    /// `GL_CONSTANT_COLOR`.
    const FACTOR_CONSTANT_COLOR: u32 = 10;
    /// `GL_ONE_MINUS_CONSTANT_COLOR`.
    const FACTOR_ONE_MINUS_CONSTANT_COLOR: u32 = 11;
    /// `GL_CONSTANT_ALPHA`.
    const FACTOR_CONSTANT_ALPHA: u32 = 12;
    /// `GL_ONE_MINUS_CONSTANT_ALPHA`.
    const FACTOR_ONE_MINUS_CONSTANT_ALPHA: u32 = 13;
    /// `GL_SRC_ALPHA_SATURATE`.
    const FACTOR_SRC_ALPHA_SATURATE: u32 = 14;
    /// Blend equation of a pass (table 4.1): `GL_FUNC_ADD`.
    const EQUATION_ADD: u32 = 0;
    /// `GL_FUNC_SUBTRACT`.
    const EQUATION_SUBTRACT: u32 = 1;
    /// `GL_FUNC_REVERSE_SUBTRACT`.
    const EQUATION_REVERSE_SUBTRACT: u32 = 2;
    /// `GL_MIN`.
    const EQUATION_MIN: u32 = 3;
    /// `GL_MAX`.
    const EQUATION_MAX: u32 = 4;

    /// `GpuInstance::flags`: traversal runs the alpha test (`trace_alpha_accept`).
    const INSTANCE_ALPHA_TESTED: u32 = 1;
    /// `GpuInstance::flags`: the merged BVH of a region's chunks ([`super::regions`]); with
    /// `INSTANCE_ALPHA_TESTED` when some chunk of it is alpha tested.
    const INSTANCE_MERGED: u32 = 2;

    /// `GpuFrame::flags[0]`: the bits of the tone mapping operator, `TONEMAP_*`.
    const FRAME_TONEMAP_MASK: u32 = 3;
    /// `GpuFrame::flags[0]`: perspective camera (else orthographic).
    const FRAME_PERSPECTIVE: u32 = 4;
    /// `GpuFrame::flags[0]`: missed rays sample the sky's cube map (`super::sky`), not
    /// `GpuFrame::environment`.
    const FRAME_SKY: u32 = 8;
    /// `GpuFrame::flags[0]`: the scene and camera are as they were last frame (the history
    /// cap is `accumulate`: accumulation while still).
    const FRAME_STILL: u32 = 16;
    /// `GpuFrame::flags[0]`: the tracer's gradient pass traces one pixel of every 3x3 again
    /// with last frame's random numbers, a temporal gradient sample for the denoiser
    /// (`trace/gradient.glsl`).
    const FRAME_GRADIENTS: u32 = 32;
    /// Traced pixels per side of a temporal gradient stratum: each has one gradient sample a
    /// frame (`trace/gradient.glsl`, [`super::gpu_types::gradient_strata`]).
    const GRADIENT_STRATUM: u32 = 3;
    /// `GpuFrame::flags[0]`: next-event estimation samples the sky (`super::sky_distribution`,
    /// the `SKY_DISTRIBUTION` binding holds its cells).
    const FRAME_SKY_SAMPLED: u32 = 64;
    /// `GpuFrame::flags[0]`: the tracer splits the specular lobe's light off the direct and
    /// indirect channels into the G-buffer's specular channel, for the denoiser
    /// (`trace/channels.glsl`, `[denoise] specular`).
    const FRAME_SPECULAR: u32 = 128;
    /// Cells per side of a cube face in the sky's distribution of directions
    /// (`super::sky_distribution`, `trace/sky_sampling.glsl`).
    const SKY_CELLS: usize = 16;
    /// Tone mapping: clamp to [0, 1].
    const TONEMAP_CLAMP: u32 = 0;
    /// Tone mapping: Reinhard, x / (1 + x).
    const TONEMAP_REINHARD: u32 = 1;
    /// Tone mapping: the ACES filmic curve fitted by Narkowicz (2015).
    const TONEMAP_ACES: u32 = 2;
    /// Tone mapping: the identity up to the knee, a Reinhard shoulder above it
    /// (`trace/tonemap.glsl`, [`super::settings::Tonemap::Knee`]).
    const TONEMAP_KNEE: u32 = 3;

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
    /// Children of a wide BVH node (`BvhWideNode` in `bvh_wide.glsl`, `GpuWideNode`).
    const BVH_WIDTH: usize = 8;
    /// The most primitives the leaves of one wide node hold: the traversal's hit mask has a
    /// bit for each (and one for each inner child above them).
    const BVH_WIDE_LEAVES: u32 = 24;
    /// A wide node's meta byte of a slot holding no child (its offset, 31, is beyond
    /// [`BVH_WIDE_LEAVES`]).
    const BVH_WIDE_EMPTY: u32 = 0xff;
}

glsl_fields! {
    /// `GpuLayer::blend`: source factor of the colour channels, `FACTOR_*`.
    BLEND_SRC_RGB = (0, 4);
    /// Destination factor of the colour channels.
    BLEND_DST_RGB = (4, 4);
    /// Source factor of alpha.
    BLEND_SRC_ALPHA = (8, 4);
    /// Destination factor of alpha.
    BLEND_DST_ALPHA = (12, 4);
    /// Equation of the colour channels, `EQUATION_*`.
    BLEND_EQUATION_RGB = (16, 3);
    /// Equation of alpha.
    BLEND_EQUATION_ALPHA = (19, 3);
    /// A wide leaf's meta byte (`GpuWideNode::meta`): its first primitive relative to the
    /// node's `leaf_base`.
    BVH_WIDE_OFFSET = (0, 5);
    /// A wide leaf's meta byte: its primitives less one (1 to 8 primitives).
    BVH_WIDE_COUNT = (5, 3);
    /// `GpuWideNode::frame`: which slots hold inner children.
    BVH_WIDE_IMASK = (24, 8);
}
