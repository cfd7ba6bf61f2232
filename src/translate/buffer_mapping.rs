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
    /// is not mapped. The range of a writable mapping goes to the capture
    /// ([`super::capture::mapped_writes`]).
    pub fn glUnmapBuffer(&mut self, target: GLenum) -> GLboolean {
        let done = self.with_bound_buffer(target, "glUnmapBuffer", |b| {
            if !b.mapped {
                return Err(gl::GL_INVALID_OPERATION);
            }
            if b.access_flags & gl::GL_MAP_WRITE_BIT != 0
                && let Some(written) = b.data.get(b.map_offset..b.map_offset + b.map_length)
            {
                super::capture::mapped_writes(target, b.map_offset, written);
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

#[cfg(test)]
mod tests {
    use crate::translate::{Context, gl};

    const T: gl::GLenum = gl::GL_ARRAY_BUFFER;

    fn param(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = -1;
        unsafe { ctx.glGetBufferParameteriv(T, pname, &mut v) };
        v
    }

    /// A bound buffer holding the bytes 0, 1, ..., 99.
    fn context_with_buffer() -> Context {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindBuffer(T, 1);
        let bytes: Vec<u8> = (0..100).collect();
        unsafe { ctx.glBufferData(T, 100, bytes.as_ptr().cast(), gl::GL_STATIC_DRAW) };
        ctx
    }

    #[test]
    fn map_range_reads_and_writes_the_range_and_sets_the_mapping_state() {
        let mut ctx = context_with_buffer();
        let flags = gl::GL_MAP_WRITE_BIT | gl::GL_MAP_INVALIDATE_RANGE_BIT | gl::GL_MAP_FLUSH_EXPLICIT_BIT;
        let p = ctx.glMapBufferRange(T, 10, 20, flags).cast::<u8>();
        assert!(!p.is_null());
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(unsafe { p.read() }, 10, "invalidated contents are kept");
        unsafe { p.add(19).write(200) };
        ctx.glFlushMappedBufferRange(T, 19, 1);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_MAPPED), 1);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS_FLAGS) as u32, flags);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS) as u32, gl::GL_WRITE_ONLY);
        assert_eq!((param(&mut ctx, gl::GL_BUFFER_MAP_OFFSET), param(&mut ctx, gl::GL_BUFFER_MAP_LENGTH)), (10, 20));
        let mut q = std::ptr::null_mut();
        unsafe { ctx.glGetBufferPointerv(T, gl::GL_BUFFER_MAP_POINTER, &raw mut q) };
        assert_eq!(q.cast::<u8>(), p, "the pointer of the mapped range");
        assert_eq!(ctx.glUnmapBuffer(T), 1);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_MAPPED), 0);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS_FLAGS), 0);
        assert_eq!((param(&mut ctx, gl::GL_BUFFER_MAP_OFFSET), param(&mut ctx, gl::GL_BUFFER_MAP_LENGTH)), (0, 0));
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS) as u32, gl::GL_WRITE_ONLY, "the last mapping's access stays");
        let mut back = [0u8; 3];
        unsafe { ctx.glGetBufferSubData(T, 28, 3, back.as_mut_ptr().cast()) };
        assert_eq!(back, [28, 200, 30]);

        // glMapBuffer is the whole range with the bits its access names.
        let whole = ctx.glMapBuffer(T, gl::GL_READ_WRITE).cast::<u8>();
        assert_eq!(unsafe { whole.add(29).read() }, 200);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS_FLAGS) as u32, gl::GL_MAP_READ_BIT | gl::GL_MAP_WRITE_BIT);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_MAP_LENGTH), 100);
        ctx.glUnmapBuffer(T);
        let read = ctx.glMapBufferRange(T, 99, 1, gl::GL_MAP_READ_BIT);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS) as u32, gl::GL_READ_ONLY);
        assert_eq!(unsafe { read.cast::<u8>().read() }, 99);
        ctx.glUnmapBuffer(T);
        let unsynchronized = gl::GL_MAP_WRITE_BIT | gl::GL_MAP_INVALIDATE_BUFFER_BIT | gl::GL_MAP_UNSYNCHRONIZED_BIT;
        assert!(!ctx.glMapBufferRange(T, 100, 0, unsynchronized).is_null(), "an empty range at the end");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn map_range_errors() {
        let mut ctx = context_with_buffer();
        let rw = gl::GL_MAP_READ_BIT | gl::GL_MAP_WRITE_BIT;
        let map = |ctx: &mut Context, target, offset, length, access| {
            let p = ctx.glMapBufferRange(target, offset, length, access);
            let e = ctx.glGetError();
            assert_eq!(p.is_null(), e != gl::GL_NO_ERROR, "null exactly on error");
            e
        };
        assert_eq!(map(&mut ctx, gl::GL_TEXTURE_2D, 0, 1, rw), gl::GL_INVALID_ENUM);
        assert_eq!(map(&mut ctx, T, -1, 1, rw), gl::GL_INVALID_VALUE);
        assert_eq!(map(&mut ctx, T, 0, -1, rw), gl::GL_INVALID_VALUE);
        assert_eq!(map(&mut ctx, T, 1, 100, rw), gl::GL_INVALID_VALUE);
        assert_eq!(map(&mut ctx, T, 0, 10, 0xffff_ffff), gl::GL_INVALID_VALUE);
        assert_eq!(map(&mut ctx, T, 0, 10, 0), gl::GL_INVALID_OPERATION, "neither read nor write");
        for bit in [gl::GL_MAP_INVALIDATE_RANGE_BIT, gl::GL_MAP_INVALIDATE_BUFFER_BIT, gl::GL_MAP_UNSYNCHRONIZED_BIT] {
            assert_eq!(map(&mut ctx, T, 0, 10, gl::GL_MAP_READ_BIT | bit), gl::GL_INVALID_OPERATION, "read with {bit:#x}");
        }
        assert_eq!(map(&mut ctx, T, 0, 10, gl::GL_MAP_READ_BIT | gl::GL_MAP_FLUSH_EXPLICIT_BIT), gl::GL_INVALID_OPERATION);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_MAPPED), 0, "no failed call mapped the buffer");
        assert_eq!(map(&mut ctx, T, 0, 10, rw), gl::GL_NO_ERROR);
        assert_eq!(map(&mut ctx, T, 0, 10, rw), gl::GL_INVALID_OPERATION, "already mapped");
        assert_eq!(ctx.glMapBuffer(T, gl::GL_READ_ONLY), std::ptr::null_mut());
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glFlushMappedBufferRange(T, 0, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "mapped without GL_MAP_FLUSH_EXPLICIT_BIT");
        ctx.glUnmapBuffer(T);
        ctx.glFlushMappedBufferRange(T, 0, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "not mapped");
        ctx.glMapBufferRange(T, 50, 10, gl::GL_MAP_WRITE_BIT | gl::GL_MAP_FLUSH_EXPLICIT_BIT);
        for (offset, length) in [(-1, 1), (0, -1), (5, 6)] {
            ctx.glFlushMappedBufferRange(T, offset, length);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE, "flush {offset} + {length} of a 10-byte mapping");
        }
        ctx.glFlushMappedBufferRange(T, 5, 5);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glBindBuffer(T, 0);
        assert_eq!(map(&mut ctx, T, 0, 0, rw), gl::GL_INVALID_OPERATION, "no buffer bound");
        ctx.glFlushMappedBufferRange(T, 0, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }

    #[test]
    fn buffer_data_ends_a_mapping() {
        let mut ctx = context_with_buffer();
        ctx.glMapBufferRange(T, 0, 4, gl::GL_MAP_READ_BIT);
        unsafe { ctx.glBufferData(T, 8, std::ptr::null(), gl::GL_STREAM_DRAW) };
        assert_eq!((param(&mut ctx, gl::GL_BUFFER_MAPPED), param(&mut ctx, gl::GL_BUFFER_ACCESS_FLAGS)), (0, 0));
        assert_eq!(ctx.glUnmapBuffer(T), 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }
}
