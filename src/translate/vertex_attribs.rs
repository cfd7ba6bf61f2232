//! Generic vertex attributes (OpenGL 2.0 sections 2.7 and 2.8): their current values
//! (`glVertexAttrib*`, every variant of which the generated dispatch turns into
//! `glVertexAttrib4f`), their arrays (`glVertexAttribPointer`,
//! `glEnable/DisableVertexAttribArray`) and their queries. Attribute 0 is the vertex:
//! `glVertexAttrib*(0, ...)` is `glVertex`, and an enabled array 0 gives the positions.
//!
//! Draws store the generic attributes ([`crate::frame::Vertices::generic`]) only while a
//! program is in use: fixed-function draws do not read them.

use std::ffi::c_void;

use super::Context;
use super::arrays::{ArrayKind, ArrayPointer};
use super::convert::write_slice;
use super::gl::{self, GLboolean, GLdouble, GLenum, GLfloat, GLint, GLsizei, GLuint};
use super::get::Value;
use super::immediate::bits;
use super::limits::MAX_VERTEX_ATTRIBS;


impl Context {
    /// How many generic attributes draws store now: all while a program is in use, none
    /// otherwise.
    pub(crate) fn generic_attributes(&self) -> usize {
        if self.programs.current != 0 { MAX_VERTEX_ATTRIBS } else { 0 }
    }

    /// `glVertexAttrib4f`: attribute 0 is a vertex (`glVertex4f`); `GL_INVALID_VALUE` for an
    /// index past the last attribute.
    pub fn glVertexAttrib4f(&mut self, index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat) {
        match index as usize {
            0 => self.glVertex4f(x, y, z, w),
            i if i < MAX_VERTEX_ATTRIBS => self.immediate.set(bits::GENERIC1 << (i - 1), |c| c.generic[i] = [x, y, z, w]),
            _ => self.set_error_in(gl::GL_INVALID_VALUE, "glVertexAttrib"),
        }
    }

    /// The generic array `index`, or `GL_INVALID_VALUE` raised by `command`.
    fn generic_array(&mut self, index: GLuint, command: &'static str) -> Option<&mut ArrayPointer> {
        if index as usize >= MAX_VERTEX_ATTRIBS {
            self.set_error_in(gl::GL_INVALID_VALUE, command);
            return None;
        }
        Some(self.arrays.get_mut(ArrayKind::Generic(index as usize)))
    }

    /// `glVertexAttribPointer`: sizes 1 to 4, the integer and floating-point types; integers
    /// map to [-1, 1] / [0, 1] when `normalized` (table 2.9), else convert as they are.
    pub fn glVertexAttribPointer(
        &mut self,
        index: GLuint,
        size: GLint,
        type_: GLenum,
        normalized: GLboolean,
        stride: GLsizei,
        pointer: *const c_void,
    ) {
        let command = "glVertexAttribPointer";
        if index as usize >= MAX_VERTEX_ATTRIBS || !(1..=4).contains(&size) || stride < 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        if !super::arrays::COLOR_TYPES.contains(&type_) {
            return self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
        let buffer = self.arrays.array_buffer;
        if let Some(a) = self.generic_array(index, command) {
            *a = ArrayPointer { enabled: a.enabled, size, type_, stride, pointer: pointer as usize, buffer, normalized: normalized != 0 };
        }
    }

    /// `glEnableVertexAttribArray`.
    pub fn glEnableVertexAttribArray(&mut self, index: GLuint) {
        if let Some(a) = self.generic_array(index, "glEnableVertexAttribArray") {
            a.enabled = true;
        }
    }

    /// `glDisableVertexAttribArray`.
    pub fn glDisableVertexAttribArray(&mut self, index: GLuint) {
        if let Some(a) = self.generic_array(index, "glDisableVertexAttribArray") {
            a.enabled = false;
        }
    }

    /// The value of `pname` for attribute `index` (section 6.1.12): `GL_INVALID_VALUE` for a
    /// bad index, `GL_INVALID_ENUM` for a bad name, `GL_INVALID_OPERATION` for the current
    /// value of attribute 0 (the vertex has none).
    fn vertex_attrib(&mut self, index: GLuint, pname: GLenum, command: &'static str) -> Option<Value> {
        let i = index as usize;
        let result = if i >= MAX_VERTEX_ATTRIBS {
            Err(gl::GL_INVALID_VALUE)
        } else {
            let a = &self.arrays.generic[i];
            match pname {
                gl::GL_VERTEX_ATTRIB_ARRAY_ENABLED => Ok(Value::bool(a.enabled)),
                gl::GL_VERTEX_ATTRIB_ARRAY_SIZE => Ok(Value::int(a.size)),
                gl::GL_VERTEX_ATTRIB_ARRAY_STRIDE => Ok(Value::int(a.stride)),
                gl::GL_VERTEX_ATTRIB_ARRAY_TYPE => Ok(Value::int(a.type_)),
                gl::GL_VERTEX_ATTRIB_ARRAY_NORMALIZED => Ok(Value::bool(a.normalized)),
                gl::GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING => Ok(Value::int(a.buffer)),
                gl::GL_CURRENT_VERTEX_ATTRIB if i == 0 => Err(gl::GL_INVALID_OPERATION),
                gl::GL_CURRENT_VERTEX_ATTRIB => Ok(Value::floats(&self.immediate.current().generic[i])),
                _ => Err(gl::GL_INVALID_ENUM),
            }
        };
        result.map_err(|e| self.set_error_in(e, command)).ok()
    }

    /// `glGetVertexAttribdv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname` (4 for the current value).
    pub unsafe fn glGetVertexAttribdv(&mut self, index: GLuint, pname: GLenum, params: *mut GLdouble) {
        if let Some(v) = self.vertex_attrib(index, pname, "glGetVertexAttribdv") {
            unsafe { write_slice(params, &v.to_doubles()) }
        }
    }

    /// `glGetVertexAttribfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname` (4 for the current value).
    pub unsafe fn glGetVertexAttribfv(&mut self, index: GLuint, pname: GLenum, params: *mut GLfloat) {
        if let Some(v) = self.vertex_attrib(index, pname, "glGetVertexAttribfv") {
            let floats: Vec<GLfloat> = v.to_doubles().iter().map(|&x| x as f32).collect();
            unsafe { write_slice(params, &floats) }
        }
    }

    /// `glGetVertexAttribiv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname` (4 for the current value).
    pub unsafe fn glGetVertexAttribiv(&mut self, index: GLuint, pname: GLenum, params: *mut GLint) {
        if let Some(v) = self.vertex_attrib(index, pname, "glGetVertexAttribiv") {
            unsafe { write_slice(params, &v.to_ints()) }
        }
    }

    /// `glGetVertexAttribPointerv`.
    ///
    /// # Safety
    /// `pointer` must have room for one pointer.
    pub unsafe fn glGetVertexAttribPointerv(&mut self, index: GLuint, pname: GLenum, pointer: *const *mut c_void) {
        if index as usize >= MAX_VERTEX_ATTRIBS {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glGetVertexAttribPointerv");
        }
        if pname != gl::GL_VERTEX_ATTRIB_ARRAY_POINTER {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glGetVertexAttribPointerv");
        }
        let p = self.arrays.generic[index as usize].pointer as *mut c_void;
        unsafe { write_slice(pointer.cast_mut(), &[p]) }
    }
}

#[cfg(test)]
mod tests;
