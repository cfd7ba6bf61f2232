//! The hardware ray-tracing back end (`VK_KHR_ray_tracing_pipeline` and
//! `VK_KHR_acceleration_structure`, DESIGN.md "Ray tracing back ends"): the same tracer as the
//! compute back end ([`super::compute`]: the same scene records, texel pool, G-buffer, passes
//! and resolve) with the driver's acceleration structures and traversal in place of glrt's
//! BVHs. The path integrator is one source for both, `shaders/trace/path.glsl`: the compute
//! back end runs it in `pathtrace.comp` over `trace/bvh.glsl`, this one in `pathtrace.rgen`
//! over `trace/hardware.glsl`, so they cannot drift apart.
//!
//! - [`accel`]: a bottom-level structure per resident geometry, a top level per frame.
//! - [`pipeline`]: the ray-tracing pipeline and its shader binding table.
//! - The static world's chunks of a region are merged into one bottom level ([`super::regions`]).

pub mod accel;
pub mod pipeline;
