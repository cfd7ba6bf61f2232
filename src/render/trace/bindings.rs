//! Descriptor bindings of the tracing pipelines (set 0), as `shaders/trace/bindings.glsl`
//! numbers them: storage buffers `0..COUNT`, then the sky's cube map ([`SKY`]).

/// `TraceFrame`: camera, settings, counts.
pub const FRAME: u32 = 0;
/// Bottom-level BVH nodes of every geometry.
pub const BLAS_NODES: u32 = 1;
/// The top-level BVH over the instances, rebuilt per frame.
pub const TLAS_NODES: u32 = 2;
/// Triangle positions in BVH order.
pub const TRIANGLES: u32 = 3;
/// Instance records.
pub const INSTANCES: u32 = 4;
/// Per-triangle shading attributes, in BVH order.
pub const ATTRIBUTES: u32 = 5;
/// Material records.
pub const MATERIALS: u32 = 6;
/// Light records.
pub const LIGHTS: u32 = 7;
/// The texel pool.
pub const TEXELS: u32 = 8;
/// The texture table into the pool.
pub const TEXTURES: u32 = 9;
/// Running radiance sums per pixel.
pub const ACCUMULATION: u32 = 10;
/// The primary-hit G-buffer per pixel.
pub const GBUFFER: u32 = 11;
/// Tone-mapped colour and depth per pixel, read by the composite.
pub const OUTPUT: u32 = 12;
/// Ray counters.
pub const COUNTERS: u32 = 13;
/// The previous frame's G-buffer and colour (temporal filter).
pub const HISTORY: u32 = 14;

/// Number of storage-buffer bindings (`0..COUNT`).
pub const COUNT: u32 = 15;
/// The environment cube map of the sky draws ([`super::sky`]): a combined image sampler.
pub const SKY: u32 = COUNT;
