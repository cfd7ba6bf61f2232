//! Pixel buffer objects (`ARB_pixel_buffer_object`, and `EXT_pixel_buffer_object`, which
//! shares its enums and adopts its errors). While a buffer is bound to
//! `GL_PIXEL_UNPACK_BUFFER`, the pointer argument of every command that unpacks pixels
//! (`glTexImage*`, `glTexSubImage*`, `glCompressedTex*Image*`, `glDrawPixels`, `glBitmap`,
//! `glPolygonStipple`, `glColorTable`, `glColorSubTable`, `glPixelMap*`) is a byte offset into
//! that buffer; while one is bound to `GL_PIXEL_PACK_BUFFER`, the commands that pack pixels
//! (`glReadPixels`, `glGetTexImage`, `glGetCompressedTexImage`, `glGetPolygonStipple`,
//! `glGetPixelMap*`, `glGetColorTable`) write into it. The two bindings are pixel-store client
//! state ([`super::pixels::PixelStore`], pushed with `GL_CLIENT_PIXEL_STORE_BIT`).
//!
//! Commands get their bytes from [`Context::unpack_bytes`] and write through
//! [`Context::pack_bytes`], which raise `GL_INVALID_OPERATION` before anything happens when the
//! buffer is mapped, when the access would run past the end of its data store, or when the
//! offset is not a multiple of the size of the GL data type (`datum`; 1 for the commands that
//! address bytes). Bytes read from a buffer are glrt's own, so they are not reported to the
//! capture ([`super::capture::reads`]); a captured offset replays as the same offset.
//!
//! Display lists (OpenGL 2.1 section 5.4): a command compiled while an unpack buffer is bound
//! takes its data from the buffer when it is compiled ([`Context::compile_unpack`]); the
//! recorded copy is read with no unpack buffer bound when the list runs.

use std::borrow::Cow;
use std::ffi::c_void;
use std::ops::Range;

use super::Context;
use super::buffer_objects::Buffer;
use super::get::Value;
use super::gl::{self, GLenum};
use super::lists::ListOp;

/// The byte range `offset..offset + span` of `buffer` a pixel command may access, or
/// `GL_INVALID_OPERATION`: no such buffer, mapped, past the end, or `offset` not a multiple of
/// `datum`.
fn access_range(buffer: Option<&Buffer>, offset: usize, span: usize, datum: usize) -> Result<Range<usize>, GLenum> {
    let buffer = buffer.filter(|b| !b.mapped && offset.is_multiple_of(datum.max(1))).ok_or(gl::GL_INVALID_OPERATION)?;
    match offset.checked_add(span) {
        Some(end) if end <= buffer.data.len() => Ok(offset..end),
        _ => Err(gl::GL_INVALID_OPERATION),
    }
}

impl Context {
    /// The `span` bytes an unpacking command reads at `pixels`: client memory (reported to the
    /// capture), or, with a buffer bound to `GL_PIXEL_UNPACK_BUFFER`, a copy of its bytes at
    /// offset `pixels`. `Ok(None)` for a null client pointer; `Err(())` after raising
    /// `GL_INVALID_OPERATION` (see the module documentation).
    ///
    /// # Safety
    /// With no unpack buffer bound, a non-null `pixels` must point to `span` readable bytes.
    pub(crate) unsafe fn unpack_bytes<'a>(&mut self, pixels: *const c_void, span: usize, datum: usize, command: &'static str) -> Result<Option<Cow<'a, [u8]>>, ()> {
        let name = self.pixels.store.unpack_buffer;
        if name == 0 {
            if pixels.is_null() {
                return Ok(None);
            }
            super::capture::reads::note(pixels, span);
            // Safety: the caller guarantees `span` readable bytes.
            return Ok(Some(Cow::Borrowed(unsafe { std::slice::from_raw_parts(pixels.cast::<u8>(), span) })));
        }
        let copy = {
            let shared = self.shared.lock();
            let buffer = shared.buffers.get(name);
            access_range(buffer, pixels as usize, span, datum).map(|r| buffer.map(|b| b.data[r].to_vec()).unwrap_or_default())
        };
        copy.map(|bytes| Some(Cow::Owned(bytes))).map_err(|e| self.set_error_in(e, command))
    }

    /// Lets `write` change the `span` bytes a packing command writes at `pixels`: client memory,
    /// or, with a buffer bound to `GL_PIXEL_PACK_BUFFER`, the buffer's bytes at offset
    /// `pixels` (the buffer's contents change). `write` sees the bytes as they are and leaves
    /// those it does not pack. Nothing is written (and the error raised) for the errors of the
    /// module documentation; a null client pointer is ignored (logged once).
    ///
    /// # Safety
    /// With no pack buffer bound, a non-null `pixels` must point to `span` writable bytes.
    pub(crate) unsafe fn pack_bytes(&mut self, pixels: *mut c_void, span: usize, datum: usize, command: &'static str, write: impl FnOnce(&mut [u8])) {
        let name = self.pixels.store.pack_buffer;
        if name == 0 {
            if pixels.is_null() {
                return self.null_pointer(command);
            }
            // Safety: the caller guarantees `span` writable bytes.
            return write(unsafe { std::slice::from_raw_parts_mut(pixels.cast::<u8>(), span) });
        }
        let result = {
            let mut shared = self.shared.lock();
            let buffer = shared.buffers.get_mut(name);
            access_range(buffer.as_deref(), pixels as usize, span, datum).map(|r| {
                if let Some(b) = buffer {
                    write(&mut b.data[r]);
                    b.version += 1;
                }
            })
        };
        if let Err(e) = result {
            self.set_error_in(e, command);
        }
    }

    /// Records a command that reads `span` bytes at `pixels` (offsets a multiple of `datum`)
    /// into the display list being compiled, with a copy of those bytes taken now from client
    /// memory or the unpack buffer. `size` is `None` when the arguments are invalid: the
    /// command is recorded without data and raises its error when the list runs. An unpack
    /// buffer access that fails raises `GL_INVALID_OPERATION` now and records nothing. When the
    /// list runs, `run` gets the copy's address (null without one) with the unpack modes of
    /// compile time and no unpack buffer bound.
    ///
    /// # Safety
    /// As [`Context::unpack_bytes`].
    pub(crate) unsafe fn compile_unpack(
        &mut self,
        pixels: *const c_void,
        size: Option<(usize, usize)>,
        command: &'static str,
        run: impl Fn(&mut Context, *const c_void) + Send + Sync + 'static,
    ) {
        let copy = match size {
            Some((span, datum)) => match unsafe { self.unpack_bytes(pixels, span, datum, command) } {
                Ok(bytes) => bytes.map(Cow::into_owned),
                Err(()) => return,
            },
            None => None,
        };
        let unpack = self.pixels.store.unpack;
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| {
            let store = &mut ctx.pixels.store;
            let saved = (std::mem::replace(&mut store.unpack, unpack), std::mem::take(&mut store.unpack_buffer));
            run(ctx, copy.as_ref().map_or(std::ptr::null(), |v| v.as_ptr().cast()));
            (ctx.pixels.store.unpack, ctx.pixels.store.unpack_buffer) = saved;
        })));
    }

    /// `GL_PIXEL_PACK_BUFFER_BINDING` and `GL_PIXEL_UNPACK_BUFFER_BINDING` for `glGet`.
    pub(crate) fn query_pixel_buffers(&self, pname: GLenum) -> Option<Value> {
        match pname {
            gl::GL_PIXEL_PACK_BUFFER_BINDING => Some(Value::int(self.pixels.store.pack_buffer)),
            gl::GL_PIXEL_UNPACK_BUFFER_BINDING => Some(Value::int(self.pixels.store.unpack_buffer)),
            _ => None,
        }
    }
}
