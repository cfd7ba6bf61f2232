//! The `EXT_vertex_array` pointer commands, which take an element count that OpenGL 1.1 dropped:
//! glrt checks it (`GL_INVALID_VALUE` when negative, as the extension says) and sets the
//! pointer like the core command. They are client state, so inside `glNewList` they take
//! effect at once instead of being compiled (section 5.4; `CLIENT_SIDE` in `build/overlay.rs`).

use std::ffi::c_void;

use super::Context;
use super::gl::{self, GLboolean, GLenum, GLint, GLsizei};

impl Context {
    /// Whether an `EXT_vertex_array` count is valid; raises `GL_INVALID_VALUE` if not.
    fn ext_count_ok(&mut self, count: GLsizei, command: &'static str) -> bool {
        if count < 0 {
            self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        count >= 0
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
        if self.ext_count_ok(count, "glVertexPointerEXT") {
            self.glVertexPointer(size, type_, stride, pointer);
        }
    }

    /// `glNormalPointerEXT`.
    pub fn glNormalPointerEXT(&mut self, type_: GLenum, stride: GLsizei, count: GLsizei, pointer: *const c_void) {
        if self.ext_count_ok(count, "glNormalPointerEXT") {
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
        if self.ext_count_ok(count, "glColorPointerEXT") {
            self.glColorPointer(size, type_, stride, pointer);
        }
    }

    /// `glIndexPointerEXT`.
    pub fn glIndexPointerEXT(&mut self, type_: GLenum, stride: GLsizei, count: GLsizei, pointer: *const c_void) {
        if self.ext_count_ok(count, "glIndexPointerEXT") {
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
        if self.ext_count_ok(count, "glTexCoordPointerEXT") {
            self.glTexCoordPointer(size, type_, stride, pointer);
        }
    }

    /// `glEdgeFlagPointerEXT`.
    pub fn glEdgeFlagPointerEXT(&mut self, stride: GLsizei, count: GLsizei, pointer: *const GLboolean) {
        if self.ext_count_ok(count, "glEdgeFlagPointerEXT") {
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
}
