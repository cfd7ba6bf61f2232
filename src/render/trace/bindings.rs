//! Descriptor bindings of the tracing pipelines (set 0): storage buffers `0..COUNT`, then the
//! sky's cube map ([`SKY`]), then (hardware tracer only) the top-level acceleration structure
//! ([`ACCELERATION`]). Shared with the shaders as `generated/trace_bindings.glsl`, each
//! named `BINDING_<NAME>` there (see [`crate::render::shader_abi`]).

glsl_constants! {
    glsl_prefix = "BINDING_";
    /// `TraceFrameBlock`: camera, settings, counts (`scene.glsl`).
    const FRAME: u32 = 0;
    /// Bottom-level BVH nodes of every geometry (`bvh_wide.glsl`, or `bvh.glsl` for binary nodes).
    const BLAS_NODES: u32 = 1;
    /// The top-level BVH over the instances, rebuilt per frame (`bvh_wide.glsl` or `bvh.glsl`).
    const TLAS_NODES: u32 = 2;
    /// Triangle positions in BVH order (`triangles.glsl`).
    const TRIANGLES: u32 = 3;
    /// Instance records (`instance.glsl`).
    const INSTANCES: u32 = 4;
    /// Per-triangle shading attributes, in BVH order (`scene.glsl`).
    const ATTRIBUTES: u32 = 5;
    /// Material records (`scene.glsl`).
    const MATERIALS: u32 = 6;
    /// Light records (`scene.glsl`).
    const LIGHTS: u32 = 7;
    /// The texel pool (`texels.glsl`).
    const TEXELS: u32 = 8;
    /// The texture table into the pool (`texels.glsl`).
    const TEXTURES: u32 = 9;
    /// Running radiance sums per pixel (`gbuffer.glsl`).
    const ACCUMULATION: u32 = 10;
    /// The primary-hit G-buffer per pixel, then per gradient stratum (`gbuffer.glsl`,
    /// [`super::gpu_types::gbuffer_records`]).
    const GBUFFER: u32 = 11;
    /// Tone-mapped colour and depth per pixel, read by the composite (`gbuffer.glsl`).
    const OUTPUT: u32 = 12;
    /// Ray counters (`gbuffer.glsl`).
    const COUNTERS: u32 = 13;
    /// The previous frame's G-buffer and colour, for the temporal filter (`gbuffer.glsl`).
    const HISTORY: u32 = 14;
    /// Per-triangle corners of the materials' passes, in BVH order (`scene.glsl`).
    const LAYER_CORNERS: u32 = 15;
    /// The frame's emissive triangles and their alias table (`scene.glsl`, `emitters.glsl`).
    const EMITTERS: u32 = 16;
    /// The sky's distribution of directions: per cell, its probability and the cumulative
    /// probability (`super::sky_distribution`, `sky_sampling.glsl`).
    const SKY_DISTRIBUTION: u32 = 17;
    /// Radiosity's indirect light at the corners of the static world's triangles
    /// (`scene.glsl`, `radiosity.glsl`; [`super::radiosity`]).
    const RADIOSITY: u32 = 18;
    /// Deforming meshes' last-frame triangles, in their new shapes' BVH order (`triangles.glsl`;
    /// [`super::resident::Resident::previous`]).
    const PREVIOUS_TRIANGLES: u32 = 19;
    /// Number of storage-buffer bindings (`0..COUNT`).
    const COUNT: u32 = 20;
    /// The environment cube map of the sky draws ([`super::sky`]), a combined image sampler
    /// (`environment.glsl`).
    const SKY: u32 = COUNT;
    /// The frame's top-level acceleration structure (`hardware.glsl`; the hardware tracer's
    /// set layout alone has it).
    const ACCELERATION: u32 = COUNT + 1;
}
