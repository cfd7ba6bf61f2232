//! Drawing and reading pixels (OpenGL 1.5 sections 3.6.4, 3.7, 4.2.4 and 4.3): `glBitmap`,
//! `glDrawPixels`, `glCopyPixels`, `glReadPixels`, `glPixelZoom` and `glAccum`. Draw
//! operations are recorded into the frame in order with the draws; `glReadPixels` asks the
//! renderer for the pixels of the frame so far.

use std::ffi::c_void;
use std::sync::Arc;

use super::super::Context;
use super::super::gl::{self, GLenum, GLfloat, GLint, GLsizei, GLubyte};
use super::super::render_mode::RasterEvent;
use super::codec::{self, Codec, Kind};
use super::transfer::Unpacked;
use crate::frame::pixels::{AccumOp, PixelBuffer, PixelData, PixelKind, PixelOp, clip_to_window};

/// Converts colours in [0, 1] to RGBA8 bytes.
pub fn rgba8(colors: &[[f32; 4]]) -> Vec<u8> {
    colors.iter().flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
}

/// Width and height as `usize`, or `GL_INVALID_VALUE` for a negative one.
fn size2(ctx: &mut Context, w: GLsizei, h: GLsizei, command: &'static str) -> Option<[usize; 2]> {
    match (usize::try_from(w), usize::try_from(h)) {
        (Ok(w), Ok(h)) => Some([w, h]),
        _ => {
            ctx.set_error_in(gl::GL_INVALID_VALUE, command);
            None
        }
    }
}

impl Context {
    /// Appends a pixel operation to the frame, before the next draw, with the raster state
    /// its fragments go through and what they take from the raster position (shared with the
    /// previous operation when equal, as for a run of `glBitmap` characters).
    pub(crate) fn push_pixel_op(&mut self, kind: PixelKind) {
        if self.framebuffer_incomplete("pixel operation") {
            return;
        }
        let state = self.raster_snapshot();
        self.enter_framebuffer(&state.framebuffer);
        let before_draw = self.frame.draws.len();
        let after_clears = self.frame.clears.len();
        let fragment = self.raster_fragment();
        let raster = match self.frame.pixels.last() {
            Some(last) if *last.raster == fragment => last.raster.clone(),
            _ => Arc::new(fragment),
        };
        self.frame.pixels.push(PixelOp { before_draw, after_clears, kind, state, raster });
        self.keep_frame_in_budget();
    }

    /// `glBitmap`: `GL_INVALID_VALUE` for a negative size; nothing happens while the raster
    /// position is invalid. The bitmap's lower-left corner is the raster position minus the
    /// origin; afterwards the raster position moves by (`xmove`, `ymove`). In selection and
    /// feedback mode nothing is drawn (feedback records `GL_BITMAP_TOKEN`, section 5.3), but
    /// the raster position still moves.
    ///
    /// # Safety
    /// A non-null `bitmap` must point to the bits the unpack modes describe.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn glBitmap(&mut self, width: GLsizei, height: GLsizei, xorig: GLfloat, yorig: GLfloat, xmove: GLfloat, ymove: GLfloat, bitmap: *const GLubyte) {
        let Some([w, h]) = size2(self, width, height, "glBitmap") else { return };
        if !self.pixels.raster.valid {
            return;
        }
        let drawn = !self.raster_event(RasterEvent::Bitmap);
        if drawn && w > 0 && h > 0 {
            let (format, ty) = (codec::format(gl::GL_COLOR_INDEX), codec::pixel_type(gl::GL_BITMAP));
            let (Some(format), Some(ty)) = (format, ty) else { return };
            let modes = self.pixels.store.unpack;
            let layout = ty.layout(format, &modes, w, h, 1).filter(|_| w.checked_mul(h).is_some_and(|n| n <= super::MAX_DECODED_VALUES));
            let Some(layout) = layout else { return self.set_error_in(gl::GL_OUT_OF_MEMORY, "glBitmap") };
            let bytes = match unsafe { self.unpack_bytes(bitmap.cast(), layout.span, ty.datum_size(), "glBitmap") } {
                Ok(bytes) => bytes,
                Err(()) => return,
            };
            // A null client pointer draws nothing; the raster position still moves.
            if let Some(bytes) = bytes {
                self.draw_bitmap(&Codec { format, ty, layout, modes: &modes }.decode(&bytes, w, h, 1), [w, h], [xorig, yorig]);
            }
        }
        self.pixels.raster.window[0] += xmove;
        self.pixels.raster.window[1] += ymove;
    }

    /// Records a bitmap of `w` × `h` decoded `bits` whose origin is `orig`, at the raster
    /// position in the raster colour.
    fn draw_bitmap(&mut self, bits: &[f64], [w, h]: [usize; 2], [xorig, yorig]: [f32; 2]) {
        let mask: Arc<[u8]> = bits.iter().map(|&b| if b != 0.0 { 255 } else { 0 }).collect();
        let r = &self.pixels.raster;
        let kind = PixelKind::Bitmap {
            window_pos: [r.window[0] - xorig, r.window[1] - yorig, r.window[2]],
            size: [w as u32, h as u32],
            color: r.data.color,
            mask,
        };
        self.push_pixel_op(kind);
    }

    /// `glBitmap` in a display list: the bits are copied when compiled.
    ///
    /// # Safety
    /// As [`Context::glBitmap`].
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn compile_glBitmap(&mut self, width: GLsizei, height: GLsizei, xorig: GLfloat, yorig: GLfloat, xmove: GLfloat, ymove: GLfloat, bitmap: *const GLubyte) {
        let run = move |ctx: &mut Context, p: *const c_void| unsafe {
            super::super::dispatch::exec_glBitmap(ctx, width, height, xorig, yorig, xmove, ymove, p.cast())
        };
        unsafe { self.compile_image_command(gl::GL_COLOR_INDEX, gl::GL_BITMAP, [width, height, 1], bitmap.cast(), "glBitmap", run) }
    }

    /// `glDrawPixels`: the image is unpacked and transferred now and drawn at the raster
    /// position with the zoom (nothing while the raster position is invalid; in feedback mode
    /// `GL_DRAW_PIXEL_TOKEN` instead, nothing in selection mode). An integer format
    /// (EXT_texture_integer) is `GL_INVALID_OPERATION`, with any type (`GL_FLOAT` included):
    /// OpenGL 3.0 section 3.7.4 bans drawing integer pixels without a fragment shader that
    /// writes integers, and glrt's colour buffers are not integer; Mesa and piglit's
    /// `ext_texture_integer-api-drawpixels` agree.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glDrawPixels(&mut self, width: GLsizei, height: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let Some([w, h]) = size2(self, width, height, "glDrawPixels") else { return };
        if codec::format(format).is_some_and(|f| f.kind == Kind::Integer) {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glDrawPixels");
        }
        let Some(ft) = self.parse_pixel_format(format, type_, "glDrawPixels") else { return };
        if !self.pixels.raster.valid || self.raster_event(RasterEvent::DrawPixels) {
            return;
        }
        let data = match unsafe { self.unpack_client(ft, [w, h, 1], pixels, false, true, "glDrawPixels") } {
            Ok(Some(unpacked)) => pixel_data(unpacked),
            Ok(None) => return self.null_pointer("glDrawPixels"),
            Err(()) => return,
        };
        let r = &self.pixels.raster;
        let kind = PixelKind::Image {
            window_pos: [r.window[0], r.window[1], r.window[2]],
            zoom: self.pixels.zoom,
            size: [w as u32, h as u32],
            color: r.data.color,
            data,
        };
        self.push_pixel_op(kind);
    }

    /// `glDrawPixels` in a display list: the image is copied when compiled.
    ///
    /// # Safety
    /// As [`Context::glDrawPixels`].
    pub unsafe fn compile_glDrawPixels(&mut self, width: GLsizei, height: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p: *const c_void| unsafe { super::super::dispatch::exec_glDrawPixels(ctx, width, height, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [width, height, 1], pixels, "glDrawPixels", run) }
    }

    /// `glCopyPixels`: `GL_INVALID_ENUM` for a type other than `GL_COLOR`, `GL_DEPTH`,
    /// `GL_STENCIL` and `GL_DEPTH_STENCIL`; `GL_INVALID_VALUE` for a negative size. In feedback
    /// mode `GL_COPY_PIXEL_TOKEN` instead, nothing in selection mode. glrt's visuals always have
    /// depth and stencil buffers, so `GL_DEPTH_STENCIL`'s `GL_INVALID_OPERATION` for a missing
    /// one never applies.
    pub fn glCopyPixels(&mut self, x: GLint, y: GLint, width: GLsizei, height: GLsizei, type_: GLenum) {
        let buffer = match type_ {
            gl::GL_COLOR => Some(PixelBuffer::Color),
            gl::GL_DEPTH => Some(PixelBuffer::Depth),
            gl::GL_STENCIL => Some(PixelBuffer::Stencil),
            gl::GL_DEPTH_STENCIL => None,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glCopyPixels"),
        };
        if size2(self, width, height, "glCopyPixels").is_none() || !self.pixels.raster.valid {
            return;
        }
        if self.raster_event(RasterEvent::CopyPixels) {
            return;
        }
        let r = &self.pixels.raster;
        let window_pos = [r.window[0], r.window[1], r.window[2]];
        if buffer.is_none() || self.framebuffers.read_bound != self.framebuffers.bound {
            return self.copy_through_readback(type_, [x, y, width, height], window_pos);
        }
        let Some(buffer) = buffer else { return };
        let kind = PixelKind::Copy { src: [x, y, width, height], window_pos, zoom: self.pixels.zoom, buffer, color: r.data.color };
        self.push_pixel_op(kind);
    }

    /// `glCopyPixels` that the renderer cannot do in place: `GL_DEPTH_STENCIL`
    /// (EXT_packed_depth_stencil section 4.3.3), and copies whose read framebuffer is not the
    /// draw framebuffer (`GL_EXT_framebuffer_blit`). The values of `src` are read as
    /// `glReadPixels` reads them, go through pixel transfer and are written as `glDrawPixels`
    /// writes them, at `window_pos` with the zoom (depth/stencil pixels through the scissor
    /// test and the depth and stencil write masks only). The read happens now (the renderer
    /// draws the frame so far), so the recorded operation is an image; source pixels outside
    /// the read framebuffer produce no fragments. Without a renderer that reads back nothing
    /// is copied (logged once).
    fn copy_through_readback(&mut self, type_: GLenum, src: [i32; 4], window_pos: [f32; 3]) {
        let size = match self.read_framebuffer_object() {
            Ok(crate::frame::Framebuffer::Object(fbo)) => fbo.size,
            _ => self.frame.size,
        };
        let Some((rect, skipped)) = clip_to_window(src, size) else { return };
        let format = match type_ {
            gl::GL_COLOR => gl::GL_RGBA,
            gl::GL_DEPTH => gl::GL_DEPTH_COMPONENT,
            gl::GL_STENCIL => gl::GL_STENCIL_INDEX,
            other => other,
        };
        let Some(format) = codec::format(format) else { return };
        let Some(unpacked) = self.read_transferred(format, rect, "glCopyPixels") else { return };
        let zoom = self.pixels.zoom;
        let kind = PixelKind::Image {
            window_pos: [window_pos[0] + skipped[0] as f32 * zoom[0], window_pos[1] + skipped[1] as f32 * zoom[1], window_pos[2]],
            zoom,
            size: [rect[2] as u32, rect[3] as u32],
            color: self.pixels.raster.data.color,
            data: pixel_data(unpacked),
        };
        self.push_pixel_op(kind);
    }

    /// Reads `rect` of the buffers that groups of `format` come from and applies pixel
    /// transfer, as `glCopyPixels` and `glCopyTexImage` do (section 4.3.3: the values are
    /// "subjected to the pixel transfer operations described in section 3.6.5, just as if
    /// ReadPixels were called"). `None` (logged once) when the renderer cannot read back.
    pub(crate) fn read_transferred(&mut self, format: codec::Format, rect: [i32; 4], command: &str) -> Option<Unpacked> {
        let Some(read) = self.read_groups(format.kind, rect) else {
            self.log_no_readback(command);
            return None;
        };
        Some(self.pixels.transfer.apply(format, &groups_of(&read, format.components), false, true))
    }

    /// Reads `rect` of the buffers that groups of `kind` come from (colour for colours and
    /// indices), as [`crate::frame::FrameSink::read_pixels`] returns them; depth/stencil
    /// groups read the depth and the stencil buffer and hold the depth in the first component,
    /// the stencil index in the second. `None` when the renderer cannot read back.
    fn read_groups(&mut self, kind: Kind, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        let buffer = match kind {
            Kind::Color | Kind::Index | Kind::Integer => PixelBuffer::Color,
            Kind::Depth => PixelBuffer::Depth,
            Kind::Stencil => PixelBuffer::Stencil,
            Kind::DepthStencil => {
                let depth = self.read_framebuffer(PixelBuffer::Depth, rect)?;
                let stencil = self.read_framebuffer(PixelBuffer::Stencil, rect)?;
                return (depth.len() == stencil.len()).then(|| depth.iter().zip(&stencil).map(|(d, s)| [d[0], s[0], 0.0, 0.0]).collect());
            }
        };
        self.read_framebuffer(buffer, rect)
    }

    /// Logs once that `command` found no renderer that reads pixels back.
    fn log_no_readback(&mut self, command: &str) {
        if !self.pixels.readback_logged {
            log::warn!("{command}: the renderer cannot read pixels back; nothing is read");
            self.pixels.readback_logged = true;
        }
    }

    /// `glReadPixels`: checks its arguments (`GL_INVALID_OPERATION` for `GL_COLOR_INDEX`,
    /// as glrt's framebuffers are RGBA, and for EXT_texture_integer's integer formats, as
    /// they are not integer either; `GL_FLOAT` with those is `GL_INVALID_ENUM` first), then asks the renderer for the pixels of the frame so
    /// far and packs them with pixel transfer and the pack modes. Without a renderer that can
    /// read back, the client's memory is left untouched (logged once).
    ///
    /// # Safety
    /// A non-null `pixels` must point to writable memory as the pack modes describe.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn glReadPixels(&mut self, x: GLint, y: GLint, width: GLsizei, height: GLsizei, format: GLenum, type_: GLenum, pixels: *mut c_void) {
        let Some([w, h]) = size2(self, width, height, "glReadPixels") else { return };
        let Some((f, t)) = self.parse_pixel_format(format, type_, "glReadPixels") else { return };
        if matches!(f.kind, Kind::Index | Kind::Integer) {
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glReadPixels");
        }
        if t.layout(f, &self.pixels.store.pack, w, h, 1).is_none() {
            return self.set_error_in(gl::GL_OUT_OF_MEMORY, "glReadPixels");
        }
        if w == 0 || h == 0 {
            return;
        }
        let Some(read) = self.read_groups(f.kind, [x, y, width, height]) else { return self.log_no_readback("glReadPixels") };
        if read.len() != w * h {
            return log::warn!("glReadPixels: the renderer returned {} pixels instead of {}", read.len(), w * h);
        }
        let values = self.transfer_for_pack(f, &read, codec::Luminance::Sum, true);
        unsafe { self.pack_client((f, t), [w, h, 1], pixels, &values, "glReadPixels") }
    }

    /// Pixel transfer for packing (section 4.3.2): colours are scaled, biased, mapped, clamped
    /// (when `clamp`) and converted to `format` (luminance formed as `luminance` says); depth and stencil
    /// values take their own transfer.
    pub(crate) fn transfer_for_pack(&self, f: codec::Format, read: &[[f32; 4]], luminance: codec::Luminance, clamp: bool) -> Vec<f32> {
        let t = &self.pixels.transfer;
        let mut values = Vec::with_capacity(read.len() * f.components);
        match f.kind {
            Kind::Color => read.iter().for_each(|&c| codec::from_rgba(f.gl, t.color(c, clamp), luminance, &mut values)),
            _ => match t.apply(f, &groups_of(read, f.components), true, clamp) {
                Unpacked::Depth(v) => values = v,
                Unpacked::Stencil(v) | Unpacked::Index(v) => values = v.iter().map(|&i| i as f32).collect(),
                Unpacked::DepthStencil(d, s) => values = d.iter().zip(&s).flat_map(|(&d, &s)| [d, s as f32]).collect(),
                Unpacked::Rgba(_) | Unpacked::Integer(_) => {}
            },
        }
        values
    }

    /// `glPixelZoom`.
    pub fn glPixelZoom(&mut self, xfactor: GLfloat, yfactor: GLfloat) {
        self.pixels.zoom = [xfactor, yfactor];
    }

    /// `glAccum` (section 4.2.4): `GL_INVALID_ENUM` for an unknown operation; recorded into
    /// the frame for the renderer, which owns the accumulation buffer.
    pub fn glAccum(&mut self, op: GLenum, value: GLfloat) {
        let op = match op {
            gl::GL_LOAD => AccumOp::Load,
            gl::GL_ACCUM => AccumOp::Accum,
            gl::GL_RETURN => AccumOp::Return,
            gl::GL_MULT => AccumOp::Mult,
            gl::GL_ADD => AccumOp::Add,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glAccum"),
        };
        if self.framebuffers.bound != 0 {
            // A framebuffer object has no accumulation buffer (EXT_framebuffer_object 4.2.4).
            return self.set_error_in(gl::GL_INVALID_OPERATION, "glAccum");
        }
        self.push_pixel_op(PixelKind::Accum { op, value });
    }
}

/// The image data of transferred pixels. Integer components (which `glDrawPixels` refuses;
/// no read-back yields them, glrt's buffers not being integer) are clamped to [0, 1].
pub(crate) fn pixel_data(unpacked: Unpacked) -> PixelData {
    match unpacked {
        Unpacked::Rgba(c) => PixelData::Rgba8(rgba8(&c).into()),
        Unpacked::Integer(c) => PixelData::Rgba8(rgba8(&c.iter().map(|c| c.map(|v| v.clamp(0, 1) as f32)).collect::<Vec<_>>()).into()),
        Unpacked::Depth(d) => PixelData::Depth(d.into()),
        Unpacked::Stencil(s) | Unpacked::Index(s) => PixelData::Stencil(s.iter().map(|&v| v as u32).collect()),
        Unpacked::DepthStencil(d, s) => PixelData::DepthStencil(d.into(), s.iter().map(|&v| v as u32).collect()),
    }
}

/// The elements of pixels read by [`Context::read_groups`], `n` a pixel, for pixel transfer:
/// the depth, stencil index or colour index in the first component; depth/stencil pixels hold
/// their stencil index in the second.
fn groups_of(read: &[[f32; 4]], n: usize) -> Vec<f64> {
    read.iter().flat_map(|c| c.iter().take(n).map(|&v| f64::from(v))).collect()
}

#[cfg(test)]
mod tests {
    use crate::frame::pixels::{PixelData, PixelKind};
    use crate::translate::gl;
    use crate::translate::{Context, dispatch};

    #[test]
    fn bitmap_records_mask_and_advances_raster_position() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glWindowPos3f(10.0, 20.0, 0.0);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        let bits = [0b1000_0001u8, 0b0100_0000];
        unsafe { dispatch::glBitmap(&mut ctx, 8, 2, 1.0, 2.0, 9.0, 1.0, bits.as_ptr()) };
        assert_eq!(ctx.pixels.raster.window[..2], [19.0, 21.0]);
        let PixelKind::Bitmap { window_pos, size, mask, .. } = &ctx.frame.pixels[0].kind else { panic!("not a bitmap") };
        assert_eq!((window_pos[0], window_pos[1], *size), (9.0, 18.0, [8, 2]));
        assert_eq!(mask[..8], [255, 0, 0, 0, 0, 0, 0, 255]);
        assert_eq!(mask[8..10], [0, 255]);
        unsafe { dispatch::glBitmap(&mut ctx, -1, 2, 0.0, 0.0, 1.0, 1.0, bits.as_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        // An invalid raster position: no bitmap and no move.
        ctx.pixels.raster.valid = false;
        unsafe { dispatch::glBitmap(&mut ctx, 0, 0, 0.0, 0.0, 5.0, 5.0, std::ptr::null()) };
        assert_eq!(ctx.pixels.raster.window[..2], [19.0, 21.0]);
    }

    #[test]
    fn bitmaps_in_display_lists_keep_their_bits() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        let mut bits = vec![0xffu8];
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glBitmap(&mut ctx, 4, 1, 0.0, 0.0, 4.0, 0.0, bits.as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        bits[0] = 0;
        drop(bits);
        ctx.glPixelStorei(gl::GL_UNPACK_LSB_FIRST, 1);
        ctx.glWindowPos3f(0.0, 0.0, 0.0);
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        let PixelKind::Bitmap { mask, .. } = &ctx.frame.pixels[0].kind else { panic!("not a bitmap") };
        assert_eq!(mask[..], [255, 255, 255, 255]);
        assert_eq!(ctx.pixels.raster.window[0], 4.0);
        assert!(ctx.pixels.store.unpack.lsb_first);
    }

    #[test]
    fn draw_pixels_records_transferred_image() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glWindowPos3f(5.0, 6.0, 0.0);
        ctx.glPixelZoom(2.0, -1.0);
        ctx.glPixelTransferf(gl::GL_GREEN_BIAS, 1.0);
        let px = [255u8, 0, 0, 255, 0, 0, 255, 128];
        unsafe { dispatch::glDrawPixels(&mut ctx, 2, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        let PixelKind::Image { zoom, size, data: PixelData::Rgba8(d), .. } = &ctx.frame.pixels[0].kind else { panic!("not an image") };
        assert_eq!((*zoom, *size), ([2.0, -1.0], [2, 1]));
        assert_eq!(d[..], [255, 255, 0, 255, 0, 255, 255, 128]);
        unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_RGB, gl::GL_UNSIGNED_SHORT_4_4_4_4, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glCopyPixels(0, 0, 4, 4, gl::GL_RGBA);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glAccum(gl::GL_RGBA, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glAccum(gl::GL_RETURN, 0.5);
        assert_eq!(ctx.frame.pixels.len(), 2);
    }

    #[test]
    fn stencil_draw_pixels_keep_every_bit_of_32_bit_indices() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glWindowPos3f(0.0, 0.0, 0.0);
        // An f32 keeps 24 bits: 0x12345679 would become 0x12345680.
        let uints = [0x1234_5679u32, 0xffff_fffe];
        unsafe { dispatch::glDrawPixels(&mut ctx, 2, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_INT, uints.as_ptr().cast()) };
        let ints = [-3i32, 0x7654_3211];
        unsafe { dispatch::glDrawPixels(&mut ctx, 2, 1, gl::GL_STENCIL_INDEX, gl::GL_INT, ints.as_ptr().cast()) };
        ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 1);
        unsafe { dispatch::glDrawPixels(&mut ctx, 2, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_INT, uints.as_ptr().cast()) };
        let drawn: Vec<Vec<u32>> = ctx.frame.pixels.iter().map(|p| match &p.kind {
            PixelKind::Image { data: PixelData::Stencil(s), .. } => s.to_vec(),
            other => panic!("not a stencil image: {other:?}"),
        }).collect();
        assert_eq!(drawn, [vec![0x1234_5679, 0xffff_fffe], vec![0xffff_fffd, 0x7654_3211], vec![0x1234_567a, 0xffff_ffff]]);
    }

    #[test]
    fn read_pixels_checks_and_leaves_memory_without_renderer() {
        let (mut ctx, _) = Context::with_recording();
        let mut out = [7u8; 4];
        unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, 1, 1, gl::GL_COLOR_INDEX, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, 1, -1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!((ctx.glGetError(), out), (gl::GL_NO_ERROR, [7; 4]));
    }
}

#[cfg(test)]
mod readback_tests {
    use crate::frame::Frame;
    use crate::frame::FrameSink;
    use crate::frame::pixels::PixelBuffer;
    use crate::translate::context::ContextConfig;
    use crate::translate::{Context, dispatch, gl};

    /// A renderer whose pixel (x, y) has colour (x / 4, y / 4, 0.5, 1) and depth 0.25.
    struct Gradient;

    impl FrameSink for Gradient {
        fn present(&mut self, _frame: Frame) {}
        fn read_pixels(&mut self, _frame: &Frame, buffer: PixelBuffer, [x, y, w, h]: [i32; 4]) -> Option<Vec<[f32; 4]>> {
            let mut out = Vec::new();
            for j in y..y + h {
                for i in x..x + w {
                    out.push(match buffer {
                        PixelBuffer::Color => [i as f32 / 4.0, j as f32 / 4.0, 0.5, 1.0],
                        _ => [0.25, 0.0, 0.0, 0.0],
                    });
                }
            }
            Some(out)
        }
    }

    #[test]
    fn read_pixels_packs_what_the_renderer_returns() {
        let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(Gradient) });
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        let mut rgb = [0u8; 2 * 2 * 3];
        unsafe { dispatch::glReadPixels(&mut ctx, 1, 2, 2, 2, gl::GL_BGR, gl::GL_UNSIGNED_BYTE, rgb.as_mut_ptr().cast()) };
        assert_eq!(rgb[..6], [128, 128, 64, 128, 128, 128]);
        assert_eq!(rgb[6..9], [128, 191, 64]);
        ctx.glPixelTransferf(gl::GL_RED_SCALE, 0.0);
        let mut lum = [0u8; 1];
        unsafe { dispatch::glReadPixels(&mut ctx, 2, 0, 1, 1, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, lum.as_mut_ptr().cast()) };
        assert_eq!(lum, [128]);
        ctx.glPixelTransferf(gl::GL_DEPTH_SCALE, 2.0);
        let mut depth = [0u16; 1];
        unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_UNSIGNED_SHORT, depth.as_mut_ptr().cast()) };
        assert_eq!(depth, [32768]);
    }
}
