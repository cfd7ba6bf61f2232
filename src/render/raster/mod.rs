//! The raster back end: renders [`crate::frame::Frame`]s with Vulkan as OpenGL 1.x specifies
//! (the reference image, the fallback without ray tracing, and the path that draws translucent,
//! sky and HUD geometry over traced images).
//!
//! - [`ff`]: the fixed-function pipeline as shaders: turns a [`crate::frame::Draw`] into
//!   [`ff::Batch`]es (packed vertices, indices, a shader key and the uniform block).

pub mod ff;
