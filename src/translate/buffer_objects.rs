//! Buffer objects (OpenGL 1.5 section 2.9, `ARB_vertex_buffer_object`): names, data stores,
//! and the `GL_ARRAY_BUFFER` / `GL_ELEMENT_ARRAY_BUFFER` / `GL_PIXEL_PACK_BUFFER` /
//! `GL_PIXEL_UNPACK_BUFFER` bindings; mapping is in [`super::buffer_mapping`]. Objects live in the
//! share group ([`super::context::SharedObjects::buffers`]); the bindings are client state of
//! each context ([`super::arrays::ArrayState`], [`super::pixels::PixelStore`]). Array pointers
//! given while a buffer is bound to `GL_ARRAY_BUFFER` are offsets into it (see
//! [`super::arrays`]); pixel pointers given while one is bound to a pixel target are offsets
//! into it (see [`super::pixel_buffers`]).

use std::collections::BTreeMap;
use std::ffi::c_void;

use super::Context;
use super::convert::write_slice;
use super::gl::{self, GLbitfield, GLboolean, GLenum, GLint, GLintptr, GLsizei, GLsizeiptr, GLuint};

/// Largest data store glrt accepts (larger requests raise `GL_OUT_OF_MEMORY`).
pub const MAX_BUFFER_SIZE: usize = 1 << 31;

/// One buffer object.
#[derive(Clone, Debug)]
pub struct Buffer {
    /// The data store (`GL_BUFFER_SIZE` bytes).
    pub data: Vec<u8>,
    /// `GL_BUFFER_USAGE`.
    pub usage: GLenum,
    /// `GL_BUFFER_ACCESS`.
    pub access: GLenum,
    /// `GL_BUFFER_MAPPED`.
    pub mapped: bool,
    /// `GL_BUFFER_ACCESS_FLAGS` of the mapping (`GL_MAP_*_BIT`; 0 when unmapped).
    pub access_flags: GLbitfield,
    /// `GL_BUFFER_MAP_OFFSET`: where the mapped range starts (0 when unmapped).
    pub map_offset: usize,
    /// `GL_BUFFER_MAP_LENGTH`: bytes mapped (0 when unmapped).
    pub map_length: usize,
    /// Bumped whenever the contents may have changed, so hashes of the data can be cached.
    pub version: u64,
}

impl Default for Buffer {
    /// The initial state of table 2.6: empty, `GL_STATIC_DRAW`, `GL_READ_WRITE`, unmapped.
    fn default() -> Buffer {
        Buffer {
            data: Vec::new(),
            usage: gl::GL_STATIC_DRAW,
            access: gl::GL_READ_WRITE,
            mapped: false,
            access_flags: 0,
            map_offset: 0,
            map_length: 0,
            version: 0,
        }
    }
}

/// The buffer objects of a share group: a name maps to `None` while it is only reserved by
/// `glGenBuffers`, to the object once it has been bound.
#[derive(Default)]
pub struct BufferTable {
    names: BTreeMap<GLuint, Option<Buffer>>,
}

impl BufferTable {
    /// The object of `name`, if it exists.
    pub fn get(&self, name: GLuint) -> Option<&Buffer> {
        self.names.get(&name)?.as_ref()
    }

    /// The object of `name`, mutably.
    pub fn get_mut(&mut self, name: GLuint) -> Option<&mut Buffer> {
        self.names.get_mut(&name)?.as_mut()
    }
}

/// Usages `glBufferData` accepts.
const USAGES: [GLenum; 9] = [
    gl::GL_STREAM_DRAW,
    gl::GL_STREAM_READ,
    gl::GL_STREAM_COPY,
    gl::GL_STATIC_DRAW,
    gl::GL_STATIC_READ,
    gl::GL_STATIC_COPY,
    gl::GL_DYNAMIC_DRAW,
    gl::GL_DYNAMIC_READ,
    gl::GL_DYNAMIC_COPY,
];

/// Checks `offset`/`size` against a store of `len` bytes: the byte range, or `GL_INVALID_VALUE`.
pub(super) fn byte_range(offset: GLintptr, size: GLsizeiptr, len: usize) -> Result<std::ops::Range<usize>, GLenum> {
    let (Ok(offset), Ok(size)) = (usize::try_from(offset), usize::try_from(size)) else {
        return Err(gl::GL_INVALID_VALUE);
    };
    match offset.checked_add(size) {
        Some(end) if end <= len => Ok(offset..end),
        _ => Err(gl::GL_INVALID_VALUE),
    }
}

impl Context {
    /// The buffer bound to `target` in this context, or `None` for a target that is not one.
    fn binding(&mut self, target: GLenum) -> Option<&mut GLuint> {
        match target {
            gl::GL_ARRAY_BUFFER => Some(&mut self.arrays.array_buffer),
            gl::GL_ELEMENT_ARRAY_BUFFER => Some(&mut self.arrays.element_buffer),
            gl::GL_PIXEL_PACK_BUFFER => Some(&mut self.pixels.store.pack_buffer),
            gl::GL_PIXEL_UNPACK_BUFFER => Some(&mut self.pixels.store.unpack_buffer),
            _ => None,
        }
    }

    /// Runs `f` on the buffer bound to `target`: `GL_INVALID_ENUM` for a bad target,
    /// `GL_INVALID_OPERATION` when no buffer is bound, and the error `f` returns.
    pub(super) fn with_bound_buffer<R>(
        &mut self,
        target: GLenum,
        command: &'static str,
        f: impl FnOnce(&mut Buffer) -> Result<R, GLenum>,
    ) -> Option<R> {
        let Some(&mut name) = self.binding(target) else {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
            return None;
        };
        let result = match self.shared.lock().buffers.get_mut(name) {
            Some(buffer) => f(buffer),
            None => Err(gl::GL_INVALID_OPERATION),
        };
        result.map_err(|e| self.set_error_in(e, command)).ok()
    }

    /// `glGenBuffers`.
    ///
    /// # Safety
    /// `buffers` must have room for `n` names.
    pub unsafe fn glGenBuffers(&mut self, n: GLsizei, buffers: *mut GLuint) {
        let Ok(n) = usize::try_from(n) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glGenBuffers");
        };
        if buffers.is_null() {
            return self.null_pointer("glGenBuffers");
        }
        let mut shared = self.shared.lock();
        let names = &mut shared.buffers.names;
        let mut next = names.keys().next_back().map_or(1, |&k| k.wrapping_add(1).max(1));
        for i in 0..n {
            while names.contains_key(&next) || next == 0 {
                next = next.wrapping_add(1);
            }
            names.insert(next, None);
            // Safety: the caller gives room for n names.
            unsafe { buffers.add(i).write_unaligned(next) };
        }
    }

    /// `glDeleteBuffers`: deleted buffers are unbound from this context's bindings and arrays
    /// (a mapping ends with its buffer).
    ///
    /// # Safety
    /// `buffers` must point to `n` names.
    pub unsafe fn glDeleteBuffers(&mut self, n: GLsizei, buffers: *const GLuint) {
        let Ok(n) = usize::try_from(n) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteBuffers");
        };
        let Some(names) = (unsafe { super::convert::read_slice(buffers, n) }) else {
            return self.null_pointer("glDeleteBuffers");
        };
        for name in names.into_iter().filter(|&b| b != 0) {
            self.shared.lock().buffers.names.remove(&name);
            self.arrays.unbind_buffer(name);
            let store = &mut self.pixels.store;
            for binding in [&mut store.pack_buffer, &mut store.unpack_buffer] {
                if *binding == name {
                    *binding = 0;
                }
            }
        }
    }

    /// `glIsBuffer`: true for names of existing buffer objects.
    pub fn glIsBuffer(&mut self, buffer: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().buffers.get(buffer).is_some())
    }

    /// `glBindBuffer`: binding a new name creates its object.
    pub fn glBindBuffer(&mut self, target: GLenum, buffer: GLuint) {
        let Some(binding) = self.binding(target) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glBindBuffer");
        };
        *binding = buffer;
        if buffer != 0 {
            let mut shared = self.shared.lock();
            let slot = shared.buffers.names.entry(buffer).or_insert(None);
            slot.get_or_insert_with(Buffer::default);
        }
    }

    /// `glBufferData`: a new data store of `size` bytes, copied from `data` unless it is null;
    /// an existing mapping is released.
    ///
    /// # Safety
    /// A non-null `data` must point to `size` readable bytes.
    pub unsafe fn glBufferData(&mut self, target: GLenum, size: GLsizeiptr, data: *const c_void, usage: GLenum) {
        const NAME: &str = "glBufferData";
        let Ok(size) = usize::try_from(size) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, NAME);
        };
        if !USAGES.contains(&usage) {
            return self.set_error_in(gl::GL_INVALID_ENUM, NAME);
        }
        self.with_bound_buffer(target, NAME, |buffer| {
            let mut store = Vec::new();
            if size > MAX_BUFFER_SIZE || store.try_reserve_exact(size).is_err() {
                return Err(gl::GL_OUT_OF_MEMORY);
            }
            if data.is_null() {
                store.resize(size, 0);
            } else {
                super::capture::reads::note(data, size);
                // Safety: the caller guarantees `size` readable bytes.
                store.extend_from_slice(unsafe { std::slice::from_raw_parts(data.cast::<u8>(), size) });
            }
            *buffer = Buffer { data: store, usage, version: buffer.version + 1, ..Buffer::default() };
            Ok(())
        });
    }

    /// `glBufferSubData`.
    ///
    /// # Safety
    /// `data` must point to `size` readable bytes.
    pub unsafe fn glBufferSubData(&mut self, target: GLenum, offset: GLintptr, size: GLsizeiptr, data: *const c_void) {
        self.with_bound_buffer(target, "glBufferSubData", |buffer| {
            let range = byte_range(offset, size, buffer.data.len())?;
            if buffer.mapped {
                return Err(gl::GL_INVALID_OPERATION);
            }
            if !data.is_null() {
                super::capture::reads::note(data, range.len());
                // Safety: the caller guarantees `size` readable bytes, not inside the store.
                let src = unsafe { std::slice::from_raw_parts(data.cast::<u8>(), range.len()) };
                buffer.data[range].copy_from_slice(src);
                buffer.version += 1;
            }
            Ok(())
        });
    }

    /// `glGetBufferSubData`.
    ///
    /// # Safety
    /// `data` must have room for `size` bytes.
    pub unsafe fn glGetBufferSubData(&mut self, target: GLenum, offset: GLintptr, size: GLsizeiptr, data: *mut c_void) {
        self.with_bound_buffer(target, "glGetBufferSubData", |buffer| {
            let range = byte_range(offset, size, buffer.data.len())?;
            if buffer.mapped {
                return Err(gl::GL_INVALID_OPERATION);
            }
            // Safety: the caller gives room for `size` bytes.
            unsafe { write_slice(data.cast::<u8>(), &buffer.data[range]) };
            Ok(())
        });
    }

    /// `glGetBufferParameteriv`.
    ///
    /// # Safety
    /// `params` must have room for one integer.
    pub unsafe fn glGetBufferParameteriv(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        let value = self.with_bound_buffer(target, "glGetBufferParameteriv", |b| {
            Ok(match pname {
                gl::GL_BUFFER_SIZE => GLint::try_from(b.data.len()).unwrap_or(GLint::MAX),
                gl::GL_BUFFER_USAGE => b.usage as GLint,
                gl::GL_BUFFER_ACCESS => b.access as GLint,
                gl::GL_BUFFER_MAPPED => GLint::from(b.mapped),
                gl::GL_BUFFER_ACCESS_FLAGS => b.access_flags as GLint,
                gl::GL_BUFFER_MAP_OFFSET => GLint::try_from(b.map_offset).unwrap_or(GLint::MAX),
                gl::GL_BUFFER_MAP_LENGTH => GLint::try_from(b.map_length).unwrap_or(GLint::MAX),
                _ => return Err(gl::GL_INVALID_ENUM),
            })
        });
        if let Some(v) = value {
            unsafe { write_slice(params, &[v]) };
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, gl};

    fn param(ctx: &mut Context, pname: gl::GLenum) -> i32 {
        let mut v = -1;
        unsafe { ctx.glGetBufferParameteriv(gl::GL_ARRAY_BUFFER, pname, &mut v) };
        v
    }

    #[test]
    fn names_data_and_mapping() {
        let (mut ctx, _) = Context::with_recording();
        let mut names = [0u32; 2];
        unsafe { ctx.glGenBuffers(2, names.as_mut_ptr()) };
        assert!(names[0] != 0 && names[1] != 0 && names[0] != names[1]);
        assert_eq!(ctx.glIsBuffer(names[0]), 0, "a generated name is no object until bound");
        ctx.glBindBuffer(gl::GL_ARRAY_BUFFER, names[0]);
        assert_eq!(ctx.glIsBuffer(names[0]), 1);
        let data = [1u8, 2, 3, 4, 5, 6, 7, 8];
        unsafe { ctx.glBufferData(gl::GL_ARRAY_BUFFER, 8, data.as_ptr().cast(), gl::GL_DYNAMIC_DRAW) };
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_SIZE), 8);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_USAGE), gl::GL_DYNAMIC_DRAW as i32);
        unsafe { ctx.glBufferSubData(gl::GL_ARRAY_BUFFER, 2, 2, [9u8, 9].as_ptr().cast()) };
        let mut back = [0u8; 4];
        unsafe { ctx.glGetBufferSubData(gl::GL_ARRAY_BUFFER, 1, 4, back.as_mut_ptr().cast()) };
        assert_eq!(back, [2, 9, 9, 5]);
        let p = ctx.glMapBuffer(gl::GL_ARRAY_BUFFER, gl::GL_WRITE_ONLY).cast::<u8>();
        assert!(!p.is_null());
        unsafe { p.add(7).write(42) };
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_MAPPED), 1);
        assert_eq!(param(&mut ctx, gl::GL_BUFFER_ACCESS), gl::GL_WRITE_ONLY as i32);
        let mut q = std::ptr::null_mut();
        unsafe { ctx.glGetBufferPointerv(gl::GL_ARRAY_BUFFER, gl::GL_BUFFER_MAP_POINTER, &raw mut q) };
        assert_eq!(q.cast::<u8>(), p);
        unsafe { ctx.glBufferSubData(gl::GL_ARRAY_BUFFER, 0, 1, [0u8].as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "sub-data of a mapped buffer");
        assert_eq!(ctx.glMapBuffer(gl::GL_ARRAY_BUFFER, gl::GL_READ_ONLY), std::ptr::null_mut());
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "mapping twice");
        assert_eq!(ctx.glUnmapBuffer(gl::GL_ARRAY_BUFFER), 1);
        assert_eq!(ctx.glUnmapBuffer(gl::GL_ARRAY_BUFFER), 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe { ctx.glGetBufferSubData(gl::GL_ARRAY_BUFFER, 7, 1, back.as_mut_ptr().cast()) };
        assert_eq!(back[0], 42);
        let mut binding = 0;
        unsafe { ctx.glGetIntegerv(gl::GL_ARRAY_BUFFER_BINDING, &mut binding) };
        assert_eq!(binding, names[0] as i32);
        unsafe { ctx.glDeleteBuffers(1, names.as_ptr()) };
        unsafe { ctx.glGetIntegerv(gl::GL_ARRAY_BUFFER_BINDING, &mut binding) };
        assert_eq!(binding, 0, "deleting a bound buffer unbinds it");
        assert_eq!(ctx.glIsBuffer(names[0]), 0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn errors() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindBuffer(gl::GL_TEXTURE_2D, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glBufferData(gl::GL_ARRAY_BUFFER, 4, std::ptr::null(), gl::GL_STATIC_DRAW) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "no buffer bound");
        ctx.glBindBuffer(gl::GL_ELEMENT_ARRAY_BUFFER, 3);
        unsafe { ctx.glBufferData(gl::GL_ELEMENT_ARRAY_BUFFER, -1, std::ptr::null(), gl::GL_STATIC_DRAW) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { ctx.glBufferData(gl::GL_ELEMENT_ARRAY_BUFFER, 4, std::ptr::null(), gl::GL_FLOAT) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glBufferData(gl::GL_ELEMENT_ARRAY_BUFFER, 1 << 40, std::ptr::null(), gl::GL_STATIC_DRAW) };
        assert_eq!(ctx.glGetError(), gl::GL_OUT_OF_MEMORY);
        unsafe { ctx.glBufferData(gl::GL_ELEMENT_ARRAY_BUFFER, 4, std::ptr::null(), gl::GL_STATIC_DRAW) };
        unsafe { ctx.glBufferSubData(gl::GL_ELEMENT_ARRAY_BUFFER, 2, 3, [0u8; 3].as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE, "range past the end");
        unsafe { ctx.glBufferSubData(gl::GL_ELEMENT_ARRAY_BUFFER, -1, 1, [0u8; 3].as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(ctx.glMapBuffer(gl::GL_ELEMENT_ARRAY_BUFFER, gl::GL_FLOAT), std::ptr::null_mut());
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let mut v = 0;
        unsafe { ctx.glGetBufferParameteriv(gl::GL_ELEMENT_ARRAY_BUFFER, gl::GL_FLOAT, &mut v) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        unsafe { ctx.glGenBuffers(-1, [0u32].as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }
}
