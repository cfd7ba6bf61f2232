//! Mapping buffer objects: `glMapBuffer`, `glUnmapBuffer`, `glGetBufferPointerv` (OpenGL 1.5
//! section 2.9) and `ARB_map_buffer_range`'s `glMapBufferRange` and
//! `glFlushMappedBufferRange`.
//!
//! A buffer's data store is glrt's own memory, so a mapping is the address of the mapped range
//! inside it: it stays valid until `glUnmapBuffer`, or until `glBufferData` or
//! `glDeleteBuffers` replaces the store (which ends the mapping, as the specification says).
//! `glMapBuffer(access)` is `glMapBufferRange` of the whole store with the read and write bits
//! `access` names (OpenGL 3.0 section 2.9.3). The optional flags keep their meaning trivially
//! on a store that the CPU owns: nothing is pending on it, so `GL_MAP_UNSYNCHRONIZED_BIT`
//! waits for nothing; the contents the invalidate bits allow to be discarded are left as they
//! were (one of the values the specification allows); and writes to a
//! `GL_MAP_FLUSH_EXPLICIT_BIT` mapping land in the store at once, `glFlushMappedBufferRange`
//! marking them as changed.

use std::ffi::c_void;

use super::Context;
use super::buffer_objects::{Buffer, byte_range};
use super::convert::write_slice;
use super::gl::{self, GLbitfield, GLboolean, GLenum, GLintptr, GLsizeiptr};

/// Every `GL_MAP_*_BIT` of `ARB_map_buffer_range`.
const MAP_BITS: GLbitfield = gl::GL_MAP_READ_BIT
    | gl::GL_MAP_WRITE_BIT
    | gl::GL_MAP_INVALIDATE_RANGE_BIT
    | gl::GL_MAP_INVALIDATE_BUFFER_BIT
    | gl::GL_MAP_FLUSH_EXPLICIT_BIT
    | gl::GL_MAP_UNSYNCHRONIZED_BIT;

/// The bits that may not go with `GL_MAP_READ_BIT`.
const NOT_WITH_READ: GLbitfield = gl::GL_MAP_INVALIDATE_RANGE_BIT | gl::GL_MAP_INVALIDATE_BUFFER_BIT | gl::GL_MAP_UNSYNCHRONIZED_BIT;

/// `GL_BUFFER_ACCESS` of a mapping with `flags` (`ARB_map_buffer_range` table 2.mbr).
fn access_of(flags: GLbitfield) -> GLenum {
    match flags & (gl::GL_MAP_READ_BIT | gl::GL_MAP_WRITE_BIT) {
        gl::GL_MAP_READ_BIT => gl::GL_READ_ONLY,
        gl::GL_MAP_WRITE_BIT => gl::GL_WRITE_ONLY,
        _ => gl::GL_READ_WRITE,
    }
}

/// Checks a `glMapBufferRange` of `buffer` and maps it: the address of the range, or the error
/// (`GL_INVALID_VALUE` for a negative or too long range or unknown bits,
/// `GL_INVALID_OPERATION` for a mapped buffer or a bad combination of bits).
fn map_range(buffer: &mut Buffer, offset: GLintptr, length: GLsizeiptr, flags: GLbitfield) -> Result<*mut c_void, GLenum> {
    let range = byte_range(offset, length, buffer.data.len())?;
    if flags & !MAP_BITS != 0 {
        return Err(gl::GL_INVALID_VALUE);
    }
    let read = flags & gl::GL_MAP_READ_BIT != 0;
    let write = flags & gl::GL_MAP_WRITE_BIT != 0;
    let bad_flush = flags & gl::GL_MAP_FLUSH_EXPLICIT_BIT != 0 && !write;
    if buffer.mapped || !(read || write) || (read && flags & NOT_WITH_READ != 0) || bad_flush {
        return Err(gl::GL_INVALID_OPERATION);
    }
    buffer.mapped = true;
    buffer.access = access_of(flags);
    buffer.access_flags = flags;
    buffer.map_offset = range.start;
    buffer.map_length = range.len();
    Ok(buffer.data[range.start..].as_mut_ptr().cast())
}

impl Context {
    /// `glMapBuffer`: the whole store, readable and/or writable as `access` says
    /// (`GL_INVALID_ENUM` for another value); null on error.
    pub fn glMapBuffer(&mut self, target: GLenum, access: GLenum) -> *mut c_void {
        let flags = match access {
            gl::GL_READ_ONLY => gl::GL_MAP_READ_BIT,
            gl::GL_WRITE_ONLY => gl::GL_MAP_WRITE_BIT,
            gl::GL_READ_WRITE => gl::GL_MAP_READ_BIT | gl::GL_MAP_WRITE_BIT,
            _ => {
                self.set_error_in(gl::GL_INVALID_ENUM, "glMapBuffer");
                return std::ptr::null_mut();
            }
        };
        let mapped = self.with_bound_buffer(target, "glMapBuffer", |b| {
            let whole = GLsizeiptr::try_from(b.data.len()).unwrap_or(GLsizeiptr::MAX);
            map_range(b, 0, whole, flags)
        });
        mapped.unwrap_or(std::ptr::null_mut())
    }

    /// `glMapBufferRange`: `length` bytes from `offset`, with the `GL_MAP_*_BIT` flags of
    /// `access` (see the module documentation); null on error. `GL_INVALID_ENUM` for a bad
    /// target, `GL_INVALID_OPERATION` when no buffer is bound, and the errors of
    /// `ARB_map_buffer_range` (with OpenGL 3.0's `GL_INVALID_VALUE` for unknown bits).
    pub fn glMapBufferRange(&mut self, target: GLenum, offset: GLintptr, length: GLsizeiptr, access: GLbitfield) -> *mut c_void {
        let mapped = self.with_bound_buffer(target, "glMapBufferRange", |b| map_range(b, offset, length, access));
        mapped.unwrap_or(std::ptr::null_mut())
    }

    /// `glFlushMappedBufferRange`: marks `length` bytes from `offset` (relative to the mapped
    /// range) as modified. `GL_INVALID_VALUE` for a negative range or one past the mapping's
    /// end, `GL_INVALID_OPERATION` when the buffer is not mapped with
    /// `GL_MAP_FLUSH_EXPLICIT_BIT`.
    pub fn glFlushMappedBufferRange(&mut self, target: GLenum, offset: GLintptr, length: GLsizeiptr) {
        self.with_bound_buffer(target, "glFlushMappedBufferRange", |b| {
            if !b.mapped || b.access_flags & gl::GL_MAP_FLUSH_EXPLICIT_BIT == 0 {
                return Err(gl::GL_INVALID_OPERATION);
            }
            byte_range(offset, length, b.map_length)?;
            b.version += 1;
            Ok(())
        });
    }

    /// `glUnmapBuffer`: ends the mapping (the mapping state returns to its initial values);
    /// `GL_TRUE`, as glrt's stores are never corrupted. `GL_INVALID_OPERATION` when the buffer
    /// is not mapped.
    pub fn glUnmapBuffer(&mut self, target: GLenum) -> GLboolean {
        let done = self.with_bound_buffer(target, "glUnmapBuffer", |b| {
            if !b.mapped {
                return Err(gl::GL_INVALID_OPERATION);
            }
            b.mapped = false;
            b.access_flags = 0;
            b.map_offset = 0;
            b.map_length = 0;
            b.version += 1;
            Ok(())
        });
        GLboolean::from(done.is_some())
    }

    /// `glGetBufferPointerv`: the address of the mapped range, null when the buffer is not
    /// mapped.
    ///
    /// # Safety
    /// `params` must have room for one pointer.
    pub unsafe fn glGetBufferPointerv(&mut self, target: GLenum, pname: GLenum, params: *const *mut c_void) {
        let value = self.with_bound_buffer(target, "glGetBufferPointerv", |b| match pname {
            gl::GL_BUFFER_MAP_POINTER if b.mapped => Ok(b.data[b.map_offset..].as_mut_ptr().cast::<c_void>()),
            gl::GL_BUFFER_MAP_POINTER => Ok(std::ptr::null_mut()),
            _ => Err(gl::GL_INVALID_ENUM),
        });
        if let Some(p) = value {
            unsafe { write_slice(params.cast_mut(), &[p]) };
        }
    }
}
