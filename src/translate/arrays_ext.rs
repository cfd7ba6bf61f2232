//! The `EXT_vertex_array` pointer commands, which take an element count that OpenGL 1.1 dropped:
//! glrt checks it (`GL_INVALID_VALUE` when negative, as the extension says) and sets the
//! pointer like the core command. They are client state, so inside `glNewList` they take
//! effect at once instead of being compiled (section 5.4; `CLIENT_SIDE` in `build/overlay.rs`).

use std::ffi::c_void;

use super::Context;
use super::gl::{self, GLboolean, GLenum, GLint, GLsizei};

/// The element counts last given to the `EXT_vertex_array` pointer commands, answered to
/// `glGet(GL_*_ARRAY_COUNT_EXT)` (initially 0). A count is stored once it passes the
/// extension's check, before the core command validates the other arguments.
#[derive(Default)]
pub(crate) struct ArrayCounts {
    counts: [GLsizei; 6],
}

/// The `GL_*_ARRAY_COUNT_EXT` names, in the order of [`ArrayCounts::counts`].
const COUNT_NAMES: [GLenum; 6] = [
    gl::GL_VERTEX_ARRAY_COUNT_EXT,
    gl::GL_NORMAL_ARRAY_COUNT_EXT,
    gl::GL_COLOR_ARRAY_COUNT_EXT,
    gl::GL_INDEX_ARRAY_COUNT_EXT,
    gl::GL_TEXTURE_COORD_ARRAY_COUNT_EXT,
    gl::GL_EDGE_FLAG_ARRAY_COUNT_EXT,
];

impl Context {
    /// Whether an `EXT_vertex_array` count is valid; raises `GL_INVALID_VALUE` if not, and
    /// records it as the count of the array named `count_name` if so.
    fn ext_count_ok(&mut self, count_name: GLenum, count: GLsizei, command: &'static str) -> bool {
        if count < 0 {
            self.set_error_in(gl::GL_INVALID_VALUE, command);
            return false;
        }
        if let Some(i) = COUNT_NAMES.iter().position(|&n| n == count_name) {
            self.arrays_ext.counts[i] = count;
        }
        true
    }

    /// `glGet` of the `GL_*_ARRAY_COUNT_EXT` values.
    pub(crate) fn query_arrays_ext(&self, pname: GLenum) -> Option<super::get::Value> {
        let i = COUNT_NAMES.iter().position(|&n| n == pname)?;
        Some(super::get::Value::int(self.arrays_ext.counts[i]))
    }

    /// `glVertexPointerEXT`.
    pub fn glVertexPointerEXT(
        &mut self,
        size: GLint,
        type_: GLenum,
        stride: GLsizei,
        count: GLsizei,
        pointer: *const c_void,
    ) {
        if self.ext_count_ok(gl::GL_VERTEX_ARRAY_COUNT_EXT, count, "glVertexPointerEXT") {
            self.glVertexPointer(size, type_, stride, pointer);
        }
    }

    /// `glNormalPointerEXT`.
    pub fn glNormalPointerEXT(&mut self, type_: GLenum, stride: GLsizei, count: GLsizei, pointer: *const c_void) {
        if self.ext_count_ok(gl::GL_NORMAL_ARRAY_COUNT_EXT, count, "glNormalPointerEXT") {
            self.glNormalPointer(type_, stride, pointer);
        }
    }

    /// `glColorPointerEXT`.
    pub fn glColorPointerEXT(
        &mut self,
        size: GLint,
        type_: GLenum,
        stride: GLsizei,
        count: GLsizei,
        pointer: *const c_void,
    ) {
        if self.ext_count_ok(gl::GL_COLOR_ARRAY_COUNT_EXT, count, "glColorPointerEXT") {
            self.glColorPointer(size, type_, stride, pointer);
        }
    }

    /// `glIndexPointerEXT`.
    pub fn glIndexPointerEXT(&mut self, type_: GLenum, stride: GLsizei, count: GLsizei, pointer: *const c_void) {
        if self.ext_count_ok(gl::GL_INDEX_ARRAY_COUNT_EXT, count, "glIndexPointerEXT") {
            self.glIndexPointer(type_, stride, pointer);
        }
    }

    /// `glTexCoordPointerEXT`.
    pub fn glTexCoordPointerEXT(
        &mut self,
        size: GLint,
        type_: GLenum,
        stride: GLsizei,
        count: GLsizei,
        pointer: *const c_void,
    ) {
        if self.ext_count_ok(gl::GL_TEXTURE_COORD_ARRAY_COUNT_EXT, count, "glTexCoordPointerEXT") {
            self.glTexCoordPointer(size, type_, stride, pointer);
        }
    }

    /// `glEdgeFlagPointerEXT`.
    pub fn glEdgeFlagPointerEXT(&mut self, stride: GLsizei, count: GLsizei, pointer: *const GLboolean) {
        if self.ext_count_ok(gl::GL_EDGE_FLAG_ARRAY_COUNT_EXT, count, "glEdgeFlagPointerEXT") {
            self.glEdgeFlagPointer(stride, pointer.cast());
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn ext_pointers_set_state_even_while_compiling() {
        let (mut ctx, _) = Context::with_recording();
        let data = [0u8; 64];
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glVertexPointerEXT(&mut ctx, 3, gl::GL_SHORT, 6, 4, data.as_ptr().cast());
            dispatch::glEdgeFlagPointerEXT(&mut ctx, 1, 4, data.as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        let mut v = [0i32; 3];
        unsafe {
            ctx.glGetIntegerv(gl::GL_VERTEX_ARRAY_SIZE, &mut v[0]);
            ctx.glGetIntegerv(gl::GL_VERTEX_ARRAY_TYPE, &mut v[1]);
            ctx.glGetIntegerv(gl::GL_EDGE_FLAG_ARRAY_STRIDE, &mut v[2]);
        }
        assert_eq!(v, [3, gl::GL_SHORT as i32, 1]);
        assert_eq!(ctx.arrays.vertex.pointer, data.as_ptr() as usize);
        unsafe { dispatch::glColorPointerEXT(&mut ctx, 4, gl::GL_FLOAT, 0, -1, data.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { dispatch::glTexCoordPointerEXT(&mut ctx, 5, gl::GL_FLOAT, 0, 1, data.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }

    #[test]
    fn counts_are_queryable() {
        let (mut ctx, _) = Context::with_recording();
        let data = [0u8; 64];
        let count = |ctx: &mut Context, pname| {
            let mut v = -1;
            unsafe { ctx.glGetIntegerv(pname, &mut v) };
            v
        };
        assert_eq!(count(&mut ctx, gl::GL_NORMAL_ARRAY_COUNT_EXT), 0);
        unsafe {
            dispatch::glNormalPointerEXT(&mut ctx, gl::GL_FLOAT, 0, 7, data.as_ptr().cast());
            dispatch::glEdgeFlagPointerEXT(&mut ctx, 0, 3, data.as_ptr());
            dispatch::glNormalPointerEXT(&mut ctx, gl::GL_FLOAT, 0, -2, data.as_ptr().cast());
        }
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(count(&mut ctx, gl::GL_NORMAL_ARRAY_COUNT_EXT), 7);
        assert_eq!(count(&mut ctx, gl::GL_EDGE_FLAG_ARRAY_COUNT_EXT), 3);
        assert_eq!(count(&mut ctx, gl::GL_VERTEX_ARRAY_COUNT_EXT), 0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}
