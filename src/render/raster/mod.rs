//! The raster stages: render [`crate::frame::Frame`]s with Vulkan as OpenGL 1.x specifies
//! (the reference image, the fallback without ray tracing, and the path that draws translucent,
//! sky and HUD geometry over traced images). [`renderer::Raster`] is one stage provider of
//! [`crate::render::frame::Renderer`]: it records the frame's command buffer (frames in
//! flight, framebuffers), the clears, pixel operations and draws in program order, the
//! read-back and the presentation; it knows nothing of tracing (the frame renderer tells it
//! which draws to leave out and where to stop).
//!
//! - [`ff`]: the fixed-function pipeline as shaders: turns a [`crate::frame::Draw`] into
//!   [`ff::Batch`]es (where their vertices and indices come from, a shader key and the uniform
//!   block); the draw's own vertices are packed straight into the upload ring.
//! - [`instance`]: the loader and the process's one Vulkan instance, shared by renderers.
//! - [`device`]: physical-device choice (`GLRT_DEVICE`), device, queue, memory.
//! - [`target`]: the colour and depth/stencil images (row 0 = top of the window).
//! - [`commands`]: a frame in flight (command buffer, fence, upload ring, descriptor sets).
//! - [`upload`]: the per-frame ring of vertices, indices and uniforms, copied in or written in
//!   place.
//! - [`pipelines`]: pipelines per (shader key, fixed state), cached; [`conv`]: state → Vulkan.
//! - [`dynamic`]: the pipeline and dynamic state a draw sets, recorded only when changed.
//! - [`programs`]: OpenGL 2.0 programs on the device (shader modules, descriptor set 1).
//! - [`textures`]: texture images and samplers.
//! - [`renderer`]: [`renderer::Raster`] (frame order, read-back, present) and the
//!   [`renderer::Recorder`] every stage records with.
//! - [`output`]: consumers of presented frames ([`output::FrameOutput`]): [`dump`]
//!   (`GLRT_DUMP`), presentation.
//! - [`multisample`]: sample counts, coverage and the passes of a multisampled draw.
//! - [`readback`] (`glReadPixels`), [`pixel_ops`] (pixel operations), [`occlusion`] (queries).

pub mod commands;
pub mod conv;
pub mod device;
pub mod dump;
pub mod dynamic;
pub mod ff;
pub mod instance;
pub mod multisample;
pub mod occlusion;
pub mod output;
pub mod pipelines;
pub mod programs;
pub mod pixel_ops;
pub mod readback;
pub mod renderer;
pub mod target;
pub mod textures;
pub mod upload;
