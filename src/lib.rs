//! glrt: a drop-in `libGL.so.1` for OpenGL 1.x programs.
//!
//! Data flows one way (see `DESIGN.md` in the planning repository and the README):
//! application → [`gl_entry`] (C ABI) → [`translate`] (OpenGL 1.x semantics) → [`frame::Frame`]
//! → [`render`] (Vulkan) → window or PNG. [`config`] reads `glrt.toml` for both sides;
//! [`faults`] injects failures for the tests of the degrade paths.
//!
//! The layers name each other one way only (`tests/layering.rs` keeps it so):
//! - [`frame`], the interface between the two sides (the frame, its sink, its target), names
//!   none of the others;
//! - [`translate`] names [`frame`], never [`render`], [`gl_entry`] or [`replay`];
//! - [`render`] names [`frame`], never [`translate`], [`gl_entry`] or [`replay`];
//! - [`gl_entry`] joins them: it names [`translate`], [`frame`] and [`render`];
//! - [`replay`], a client of the exported C API, names whatever it needs; nothing names it.
//!
//! What a lower layer needs from a higher one is handed down at the call or installed by the
//! higher one at start (the call log's texture notes, the replay's address map).

pub mod config;
pub mod faults;
pub mod frame;
pub mod gl_entry;
pub mod logging;
pub mod render;
pub mod replay;
pub mod translate;
