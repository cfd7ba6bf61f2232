//! The pixel path of OpenGL 1.5 (sections 3.6–3.7, 4.3): pixel storage modes, pixel transfer
//! and maps, the raster position, `glBitmap`, `glDrawPixels`, `glCopyPixels`,
//! `glReadPixels`, `glPixelZoom` and `glAccum`. Images are read from client memory or the
//! pixel unpack buffer here (`Context::unpack_client`) for texture uploads too, and written
//! back by `Context::pack_client` (see [`super::pixel_buffers`]).
//!
//! Bitmaps, images and copies go into [`crate::frame::Frame::pixels`] in order with the draws;
//! read-backs ask the renderer through [`crate::frame::FrameSink::read_pixels`].

pub mod codec;
#[cfg(test)]
mod depth_stencil_tests;
pub mod draw;
pub mod raster;
pub mod small_float;
pub mod store;
pub mod transfer;

use std::ffi::c_void;

use super::Context;
use super::get::Value;
use super::gl::{self, GLenum};
use codec::{Codec, Format, Type};
pub use store::PixelStore;
pub use transfer::{PixelTransfer, Unpacked};

/// Most pixel components one command decodes (1 GiB of `f32`); larger images raise
/// `GL_OUT_OF_MEMORY`.
pub const MAX_DECODED_VALUES: usize = 1 << 28;

/// Pixel state of a context.
#[derive(Clone, Debug)]
pub struct PixelState {
    /// `glPixelStore` (client state).
    pub store: PixelStore,
    /// `glPixelTransfer`, `glPixelMap`.
    pub transfer: PixelTransfer,
    /// `glPixelZoom`: x and y factors.
    pub zoom: [f32; 2],
    /// The current raster position.
    pub raster: raster::RasterPos,
    /// Whether a failed read-back has been logged.
    pub(crate) readback_logged: bool,
}

impl Default for PixelState {
    fn default() -> PixelState {
        PixelState {
            store: PixelStore::default(),
            transfer: PixelTransfer::default(),
            zoom: [1.0, 1.0],
            raster: raster::RasterPos::default(),
            readback_logged: false,
        }
    }
}

/// Saved `GL_PIXEL_MODE_BIT` state (transfer, maps and zoom).
#[derive(Clone, Debug)]
pub struct PixelModeAttrib {
    transfer: PixelTransfer,
    zoom: [f32; 2],
}

impl Context {
    /// Parses a `format`/`type` pair, raising the error of [`codec::parse`].
    pub(crate) fn parse_pixel_format(&mut self, format: GLenum, type_: GLenum, command: &'static str) -> Option<(Format, Type)> {
        match codec::parse(format, type_) {
            Ok(v) => Some(v),
            Err(e) => {
                self.set_error_in(e, command);
                None
            }
        }
    }

    /// Reads a `w` × `h` × `d` image from client memory or the unpack buffer
    /// ([`Context::unpack_bytes`]) with the unpack modes and applies pixel transfer (colours
    /// clamped to [0, 1] when `clamp`).
    /// `Ok(None)` for a null client pointer; `Err(())` after `GL_OUT_OF_MEMORY` when the image
    /// is too large to read, or the unpack buffer's `GL_INVALID_OPERATION`. Sizes must have
    /// been checked non-negative.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the memory the unpack modes describe.
    pub(crate) unsafe fn unpack_client(
        &mut self,
        (format, ty): (Format, Type),
        [w, h, d]: [usize; 3],
        pixels: *const c_void,
        keep_index: bool,
        clamp: bool,
        command: &'static str,
    ) -> Result<Option<Unpacked>, ()> {
        let modes = self.pixels.store.unpack;
        let values = w.checked_mul(h).and_then(|v| v.checked_mul(d)).and_then(|v| v.checked_mul(format.components));
        let layout = ty.layout(format, &modes, w, h, d).filter(|_| values.is_some_and(|v| v <= MAX_DECODED_VALUES));
        let Some(layout) = layout else {
            self.set_error_in(gl::GL_OUT_OF_MEMORY, command);
            return Err(());
        };
        let Some(bytes) = (unsafe { self.unpack_bytes(pixels, layout.span, ty.datum_size(), command) })? else { return Ok(None) };
        let groups = Codec { format, ty, layout, modes: &modes }.decode(&bytes, w, h, d);
        Ok(Some(self.pixels.transfer.apply(format, &groups, keep_index, clamp)))
    }

    /// Writes `values` (groups of `format`, in format order) to client memory or the pack
    /// buffer ([`Context::pack_bytes`]) with the pack modes, leaving bytes between pixels
    /// untouched.
    ///
    /// # Safety
    /// A non-null `pixels` must point to writable memory as the pack modes describe.
    pub(crate) unsafe fn pack_client(
        &mut self,
        (format, ty): (Format, Type),
        [w, h, d]: [usize; 3],
        pixels: *mut c_void,
        values: &[f32],
        command: &'static str,
    ) {
        unsafe { self.pack_with((format, ty), [w, h, d], pixels, command, |codec, bytes| codec.encode(bytes, values, w, h, d)) }
    }

    /// [`Context::pack_client`] for integer components (EXT_texture_integer's `*_INTEGER`
    /// formats), each clamped to the type ([`Codec::encode_integers`]).
    ///
    /// # Safety
    /// As [`Context::pack_client`].
    pub(crate) unsafe fn pack_client_integers(&mut self, (format, ty): (Format, Type), [w, h, d]: [usize; 3], pixels: *mut c_void, values: &[i64], command: &'static str) {
        unsafe { self.pack_with((format, ty), [w, h, d], pixels, command, |codec, bytes| codec.encode_integers(bytes, values, w, h, d)) }
    }

    /// Lays out a `w` × `h` × `d` image of `format` and `ty` with the pack modes and lets
    /// `encode` write it into client memory or the pack buffer.
    ///
    /// # Safety
    /// As [`Context::pack_client`].
    unsafe fn pack_with(&mut self, (format, ty): (Format, Type), [w, h, d]: [usize; 3], pixels: *mut c_void, command: &'static str, encode: impl FnOnce(&Codec, &mut [u8])) {
        let modes = self.pixels.store.pack;
        let Some(layout) = ty.layout(format, &modes, w, h, d) else { return self.set_error_in(gl::GL_OUT_OF_MEMORY, command) };
        let codec = Codec { format, ty, layout, modes: &modes };
        unsafe { self.pack_bytes(pixels, layout.span, ty.datum_size(), command, |bytes| encode(&codec, bytes)) }
    }

    /// Records a command that reads an image into the display list being compiled, with a copy
    /// of that image (section 5.4: the image is unpacked when the list is compiled; see
    /// [`Context::compile_unpack`]); when the list runs, the command reads the copy with the
    /// unpack modes of compile time.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the memory the unpack modes describe.
    pub(crate) unsafe fn compile_image_command(
        &mut self,
        format: GLenum,
        type_: GLenum,
        dims: [i32; 3],
        pixels: *const c_void,
        command: &'static str,
        run: impl Fn(&mut Context, *const c_void) + Send + Sync + 'static,
    ) {
        let size = codec::parse(format, type_).ok().and_then(|(f, t)| {
            let [w, h, d] = dims.map(|v| usize::try_from(v).ok());
            Some((t.layout(f, &self.pixels.store.unpack, w?, h?, d?)?.span, t.datum_size()))
        });
        unsafe { self.compile_unpack(pixels, size, command, run) }
    }

    /// `glGet` values of the pixel path: storage modes, transfer, maps, zoom, raster position.
    pub(crate) fn query_pixels(&self, pname: GLenum) -> Option<Value> {
        if let Some(v) = self.pixel_store_value(pname) {
            return Some(if Self::pixel_store_is_bool(pname) { Value::bool(v != 0) } else { Value::int(v) });
        }
        match pname {
            gl::GL_ZOOM_X => Some(Value::float(self.pixels.zoom[0])),
            gl::GL_ZOOM_Y => Some(Value::float(self.pixels.zoom[1])),
            _ => self.query_transfer(pname).or_else(|| self.query_raster(pname)),
        }
    }

    /// Captures `GL_PIXEL_MODE_BIT` (`glPushAttrib`; the read buffer is the framebuffer
    /// module's).
    pub fn save_pixel_mode_attrib(&self) -> PixelModeAttrib {
        PixelModeAttrib { transfer: self.pixels.transfer.clone(), zoom: self.pixels.zoom }
    }

    /// Restores `GL_PIXEL_MODE_BIT` (`glPopAttrib`).
    pub fn restore_pixel_mode_attrib(&mut self, saved: PixelModeAttrib) {
        self.pixels.transfer = saved.transfer;
        self.pixels.zoom = saved.zoom;
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, gl};

    fn get_i(ctx: &mut Context, pname: u32) -> Vec<i32> {
        let mut v = [-1i32; 8];
        unsafe { ctx.glGetIntegerv(pname, v.as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "{pname:#x}");
        v.to_vec()
    }

    #[test]
    fn pixel_and_texture_state_answers_glget() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPixelStorei(gl::GL_UNPACK_ROW_LENGTH, 17);
        ctx.glPixelStorei(gl::GL_PACK_LSB_FIRST, 1);
        ctx.glPixelZoom(2.0, -3.0);
        ctx.glPixelTransferf(gl::GL_ALPHA_BIAS, 0.5);
        ctx.glPixelTransferi(gl::GL_MAP_STENCIL, 1);
        ctx.glActiveTexture(gl::GL_TEXTURE2);
        ctx.glBindTexture(gl::GL_TEXTURE_CUBE_MAP, 12);
        assert_eq!(get_i(&mut ctx, gl::GL_UNPACK_ROW_LENGTH)[0], 17);
        assert_eq!(get_i(&mut ctx, gl::GL_PACK_LSB_FIRST)[0], 1);
        assert_eq!(get_i(&mut ctx, gl::GL_UNPACK_ALIGNMENT)[0], 4);
        assert_eq!(get_i(&mut ctx, gl::GL_ZOOM_Y)[0], -3);
        assert_eq!(get_i(&mut ctx, gl::GL_MAP_STENCIL)[0], 1);
        assert_eq!(get_i(&mut ctx, gl::GL_PIXEL_MAP_A_TO_A_SIZE)[0], 1);
        assert_eq!(get_i(&mut ctx, gl::GL_MAX_PIXEL_MAP_TABLE)[0], 256);
        assert_eq!(get_i(&mut ctx, gl::GL_TEXTURE_BINDING_CUBE_MAP)[0], 12);
        assert_eq!(get_i(&mut ctx, gl::GL_MAX_TEXTURE_SIZE)[0], 8192);
        assert_eq!(get_i(&mut ctx, gl::GL_MAX_3D_TEXTURE_SIZE)[0], 2048);
        assert_eq!(get_i(&mut ctx, gl::GL_MAX_CUBE_MAP_TEXTURE_SIZE)[0], 8192);
        assert_eq!(get_i(&mut ctx, gl::GL_COMPRESSED_TEXTURE_FORMATS)[..4], [0x83f0, 0x83f1, 0x83f2, 0x83f3]);
        let mut bias = 0.0f32;
        unsafe { ctx.glGetFloatv(gl::GL_ALPHA_BIAS, &mut bias) };
        assert_eq!(bias, 0.5);
        assert_eq!(get_i(&mut ctx, gl::GL_CURRENT_RASTER_POSITION_VALID)[0], 1);
        ctx.glActiveTexture(gl::GL_TEXTURE0);
        assert_eq!(get_i(&mut ctx, gl::GL_TEXTURE_BINDING_CUBE_MAP)[0], 0);
    }

    #[test]
    fn attribute_groups_round_trip() {
        let (mut ctx, _) = Context::with_recording();
        let mode = ctx.save_pixel_mode_attrib();
        ctx.glPixelZoom(3.0, 3.0);
        ctx.glPixelTransferf(gl::GL_DEPTH_BIAS, 1.0);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_ROWS, 4);
        ctx.restore_pixel_mode_attrib(mode);
        assert_eq!((ctx.pixels.zoom, ctx.pixels.transfer.depth), ([1.0, 1.0], [1.0, 0.0]));
        assert_eq!(ctx.pixels.store.unpack.skip_rows, 4);
    }
}
