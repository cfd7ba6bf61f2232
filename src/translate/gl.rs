//! OpenGL C types and every `GL_*` constant, generated from gl.xml.

#![allow(non_upper_case_globals, non_camel_case_types, dead_code, clippy::unreadable_literal, clippy::unnecessary_cast)]

/// The C types the generated type aliases refer to.
pub mod __gl_imports {
    pub use std::os::raw;
}

/// GL C types (`GLenum`, `GLfloat`...).
pub mod types {
    #![allow(non_camel_case_types, non_snake_case, dead_code, missing_docs, clippy::all)]
    include!(concat!(env!("OUT_DIR"), "/gl_types.rs"));
    /// Types newer than `gl_generator`'s templates.
    pub type GLeglClientBufferEXT = *mut std::ffi::c_void;
    /// A Vulkan function pointer (`GL_NV_draw_vulkan_image`).
    pub type GLVULKANPROCNV = *const std::ffi::c_void;
}

pub use types::*;

include!(concat!(env!("OUT_DIR"), "/gl_enums.rs"));

/// The name of a GL constant, preferring core names over extension aliases.
pub fn enum_name(value: u32) -> Option<&'static str> {
    best_name(NAMES.iter().filter(|(_, v)| *v == u64::from(value)).map(|(n, _)| *n))
}

/// The preferred of several names of one value: core names before extension aliases, then
/// the shortest.
pub fn best_name(names: impl Iterator<Item = &'static str>) -> Option<&'static str> {
    names.min_by_key(|n| (n.ends_with("_ARB") || n.ends_with("_EXT") || n.contains("_SGI"), n.len()))
}

// gl_generator drops the enums whose names start with a digit after `GL_`.
/// `glCallLists` type: two-byte big-endian names.
pub const GL_2_BYTES: GLenum = 0x1407;
/// `glCallLists` type: three-byte big-endian names.
pub const GL_3_BYTES: GLenum = 0x1408;
/// `glCallLists` type: four-byte big-endian names.
pub const GL_4_BYTES: GLenum = 0x1409;
/// `glFeedbackBuffer` type: x, y.
pub const GL_2D: GLenum = 0x0600;
/// `glFeedbackBuffer` type: x, y, z.
pub const GL_3D: GLenum = 0x0601;
/// `glFeedbackBuffer` type: x, y, z and colour.
pub const GL_3D_COLOR: GLenum = 0x0602;
/// `glFeedbackBuffer` type: x, y, z, colour and texture coordinates.
pub const GL_3D_COLOR_TEXTURE: GLenum = 0x0603;
/// `glFeedbackBuffer` type: x, y, z, w, colour and texture coordinates.
pub const GL_4D_COLOR_TEXTURE: GLenum = 0x0604;
