//! OpenGL 1.x semantics on the CPU: the context state machine, its errors and queries, and the
//! per-frame scene ([`crate::frame::Frame`]) it hands to the renderer. No Vulkan here.
//!
//! Each GL command is a method of [`Context`] named exactly after the C function
//! (`Context::glVertex4f`), in the module that owns its state; the build script finds these
//! methods and generates the C exports and the [`dispatch`] layer (display-list recording and
//! the `glBegin`/`glEnd` rule) around them. Methods that take client pointers are `unsafe`: the
//! pointer must be valid for what the command reads or writes, as the GL specification says.

// GL commands are methods named exactly after their C functions (`glVertex4f`): the build script
// finds them by that name, and the names match the specification and the reference pages.
#![allow(non_snake_case)]

pub mod array_convert;
pub mod array_fetch;
pub mod arrays;
pub mod arrays_ext;
pub mod assemble;
pub mod attrib;
pub mod begin_material;
pub mod buffer_mapping;
pub mod buffer_objects;
pub mod buffers;
pub mod capture;
pub mod classify;
pub mod clear;
pub mod client_attrib;
pub mod clip_planes;
pub mod clip_test;
pub mod context;
pub mod convert;
pub mod cull;
pub mod dispatch;
pub mod draw_arrays;
pub mod draw_buffers;
pub mod enable;
pub mod enums;
pub mod error;
pub mod eval;
pub mod fixed;
pub mod fixed_vertex;
pub mod fog;
pub mod fragment;
pub mod frame_builder;
pub mod frame_memory;
pub mod framebuffers;
pub mod glsl;
pub mod get;
pub mod gl;
pub mod hints;
pub mod immediate;
pub mod implementation;
pub mod lighting;
pub mod limits;
pub mod lists;
pub mod locked_arrays;
pub mod params;
pub mod pixel_buffers;
#[cfg(test)]
mod pixel_buffer_tests;
pub mod pixels;
pub mod programs;
pub mod queries;
pub mod rasterization;
pub mod render_mode;
pub mod sgis_multitexture;
pub mod stencil;
pub mod stipple;
pub mod strings;
pub mod target;
pub mod texture;
pub mod texunit;
pub mod transform;
pub mod vertex_attribs;
pub mod vertex_lighting;
pub mod vertex_texgen;
pub mod viewport;
#[cfg(test)]
mod robustness;

pub use context::Context;
