//! The compute path tracer (`GLRT_MODE=pathtrace`): traces the traced classes of a
//! [`crate::frame::Frame`] (static, movable, dynamic draws) with BVH traversal in compute
//! shaders, so it runs on every Vulkan 1.2 device, lavapipe included (DESIGN.md, "Ray tracing
//! back ends"), and hands the traced image and depth to the raster renderer, which draws the
//! sky, translucent and overlay draws around it in program order (thesis 4.3.6).
//!
//! Space: rays are traced in the **eye space of the current frame** (camera at the origin,
//! looking down −z, as OpenGL's modelview leaves it). Each traced draw is an instance whose
//! object-to-eye transform is its modelview; geometry stays in object space in its bottom-level
//! BVH, reused across frames by geometry key; the top-level BVH over the instances is rebuilt
//! every frame. GL lights are stored in eye space already.
//!
//! Environment: a ray that leaves the scene sees the frame's `Sky` draws, rendered by the
//! raster pipelines into an eye-space cube map around the eye ([`sky`]); without sky draws,
//! the linear clear colour. The cube lights and is reflected in the traced surfaces; the sky
//! visible where primary rays miss stays the rasterized one (the composite leaves those
//! pixels to the framebuffer).
//!
//! The persistent static world of hash tracking is traced too ([`chunks`]): each chunk is an
//! instance of world-space triangles placed by the recovered view, built once, and traced
//! whether the program drew it this frame or not; the draws the chunks hold are left out.
//! A dynamic draw whose vertices moved refits its last BVH instead of building a new one
//! ([`tracks`], [`resident`]).
//!
//! Parts:
//! - [`bindings`]: descriptor bindings and [`shader_constants`]: flags and special values, both
//!   shared with the shaders as generated headers ([`crate::render::shader_abi`]).
//! - [`gpu_types`]: the structures the shaders read, checked against the compiled SPIR-V.
//! - [`bvh`]: bottom-level BVHs of triangle sets and the per-frame top-level BVH (CPU build,
//!   GPU layout, CPU traversal for tests); `shaders/trace/bvh.glsl` traverses them.
//! - [`texels`]: every texture level the tracer samples, packed into one storage buffer (no
//!   descriptor indexing on lavapipe); `shaders/trace/texels.glsl` samples it.
//! - [`settings`]: `glrt.toml` `[pathtrace]` and `GLRT_*` settings.
//! - [`scene`]: traced draws as geometries, instances and materials; [`chunks`]: the static
//!   world's chunks as geometries; [`instances`]: a frame's instances, draws and chunks;
//!   [`lights`]: GL lights as physical lights; [`sky`]: the sky draws as the environment cube
//!   map.
//! - [`tracks`]: dynamic instances across frames (what their next shape refits).
//! - [`stats`]: rays traced by kind, traversal work and the tracing pass's GPU time.
//! - [`resident`]: geometries on the GPU; [`pipelines`]: the tracer's pipelines;
//!   [`tracer`]: one traced frame, recorded into the raster renderer's command buffer.

pub mod bindings;
pub mod bvh;
pub mod chunks;
pub mod gpu_types;
pub mod instances;
pub mod lights;
pub mod pipelines;
pub mod resident;
pub mod scene;
pub mod settings;
pub mod shader_constants;
pub mod sky;
pub mod stats;
pub mod texels;
pub mod tracer;
pub mod tracks;
