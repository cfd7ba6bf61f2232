//! glrt: a drop-in `libGL.so.1` for OpenGL 1.x programs.
//!
//! Data flows one way (see `DESIGN.md` in the planning repository and the README):
//! application → [`gl_entry`] (C ABI) → [`translate`] (OpenGL 1.x semantics) → [`frame::Frame`]
//! → [`render`] (Vulkan) → window or PNG. [`config`] reads `glrt.toml` for both sides.

pub mod config;
pub mod frame;
pub mod gl_entry;
pub mod logging;
pub mod render;
pub mod translate;
