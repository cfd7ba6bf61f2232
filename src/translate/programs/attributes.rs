//! Vertex attribute bindings of programs (OpenGL 2.0 section 2.15.3, "Vertex Attributes"):
//! `glBindAttribLocation` (applied at the next link), `glGetAttribLocation`,
//! `glGetActiveAttrib`.

use std::ffi::CStr;

use super::info::{Active, write_active};
use super::uniforms::linked_program;
use crate::translate::Context;
use crate::translate::capture::reads;
use crate::translate::gl::{self, GLchar, GLenum, GLint, GLsizei, GLuint};
use crate::translate::limits::MAX_VERTEX_ATTRIBS;

/// Reads a NUL-terminated name argument (reporting it to capture); `None` for null.
///
/// # Safety
/// `name` must be null or a NUL-terminated string.
pub(super) unsafe fn name_arg(name: *const GLchar) -> Option<String> {
    if name.is_null() {
        return None;
    }
    let name = unsafe { CStr::from_ptr(name) };
    reads::note(name.as_ptr(), name.count_bytes() + 1);
    Some(name.to_string_lossy().into_owned())
}

impl Context {
    /// `glBindAttribLocation`: `GL_INVALID_VALUE` for an index past the last attribute,
    /// `GL_INVALID_OPERATION` for a `gl_` name.
    ///
    /// # Safety
    /// `name` must be null or a NUL-terminated string.
    pub unsafe fn glBindAttribLocation(&mut self, program: GLuint, index: GLuint, name: *const GLchar) {
        let Some(name) = (unsafe { name_arg(name) }) else { return self.null_pointer("glBindAttribLocation") };
        let error = if index as usize >= MAX_VERTEX_ATTRIBS {
            Some(gl::GL_INVALID_VALUE)
        } else {
            match self.shared.lock().programs.program_mut(program) {
                Err(e) => Some(e),
                Ok(_) if name.starts_with("gl_") => Some(gl::GL_INVALID_OPERATION),
                Ok(p) => {
                    p.bindings.insert(name, index);
                    None
                }
            }
        };
        if let Some(e) = error {
            self.set_error_in(e, "glBindAttribLocation");
        }
    }

    /// `glGetAttribLocation`: the index of an active attribute of a linked program, -1 for
    /// another name.
    ///
    /// # Safety
    /// `name` must be null or a NUL-terminated string.
    pub unsafe fn glGetAttribLocation(&mut self, program: GLuint, name: *const GLchar) -> GLint {
        let Some(name) = (unsafe { name_arg(name) }) else {
            self.null_pointer("glGetAttribLocation");
            return -1;
        };
        let found = linked_program(&self.shared.lock().programs, program)
            .map(|l| l.attributes.iter().find(|a| a.name == name).map_or(-1, |a| a.index as GLint));
        found.unwrap_or_else(|e| {
            self.set_error_in(e, "glGetAttribLocation");
            -1
        })
    }

    /// `glGetActiveAttrib`.
    ///
    /// # Safety
    /// `name` must have room for `bufSize` bytes; `length`, `size` and `type_` must be null or
    /// writable.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn glGetActiveAttrib(
        &mut self,
        program: GLuint,
        index: GLuint,
        bufSize: GLsizei,
        length: *mut GLsizei,
        size: *mut GLint,
        type_: *mut GLenum,
        name: *mut GLchar,
    ) {
        let found = self.shared.lock().programs.program(program).and_then(|p| {
            let l = p.linked.as_ref().filter(|_| p.link_ok).ok_or(gl::GL_INVALID_VALUE)?;
            let a = l.attributes.get(index as usize).ok_or(gl::GL_INVALID_VALUE)?;
            Ok(Active { name: a.name.clone(), size: 1, ty: a.ty })
        });
        match found {
            Err(e) => self.set_error_in(e, "glGetActiveAttrib"),
            Ok(a) => unsafe { write_active(self, "glGetActiveAttrib", a, bufSize, length, size, type_, name) },
        }
    }
}
