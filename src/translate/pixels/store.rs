//! Pixel storage modes (`glPixelStore`, OpenGL 1.5 section 3.6.1) and the memory layout they
//! give an image in client memory (section 3.6.4, "Unpacking"; section 4.3.2 for packing).

use super::super::Context;
use super::super::gl::{self, GLenum, GLfloat, GLint};

/// The storage modes of one direction (unpack or pack), table 3.1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StoreModes {
    /// `*_SWAP_BYTES`.
    pub swap_bytes: bool,
    /// `*_LSB_FIRST`.
    pub lsb_first: bool,
    /// `*_ROW_LENGTH` (0: the image width).
    pub row_length: i32,
    /// `*_IMAGE_HEIGHT` (0: the image height).
    pub image_height: i32,
    /// `*_SKIP_IMAGES`.
    pub skip_images: i32,
    /// `*_SKIP_ROWS`.
    pub skip_rows: i32,
    /// `*_SKIP_PIXELS`.
    pub skip_pixels: i32,
    /// `*_ALIGNMENT`: 1, 2, 4 or 8.
    pub alignment: i32,
}

impl Default for StoreModes {
    fn default() -> StoreModes {
        StoreModes {
            swap_bytes: false,
            lsb_first: false,
            row_length: 0,
            image_height: 0,
            skip_images: 0,
            skip_rows: 0,
            skip_pixels: 0,
            alignment: 4,
        }
    }
}

/// The state of `GL_CLIENT_PIXEL_STORE_BIT`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PixelStore {
    /// Modes for reading client memory (`glTexImage`, `glDrawPixels`, ...).
    pub unpack: StoreModes,
    /// Modes for writing client memory (`glReadPixels`, `glGetTexImage`, ...).
    pub pack: StoreModes,
    /// `GL_PIXEL_UNPACK_BUFFER_BINDING` (0: images are read from client memory; see
    /// [`crate::translate::pixel_buffers`]).
    pub unpack_buffer: u32,
    /// `GL_PIXEL_PACK_BUFFER_BINDING` (0: images are written to client memory).
    pub pack_buffer: u32,
}

/// Largest client image glrt reads or writes at once (bytes); larger requests raise
/// `GL_OUT_OF_MEMORY` instead of allocating.
pub const MAX_CLIENT_IMAGE_BYTES: u64 = 1 << 30;

/// Where the pixels of an image lie in client memory. Offsets are in bytes, except for
/// bitmaps (1 bit per pixel) whose `start` and `group` are in bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// Offset of the first pixel of the first row of the first image.
    pub start: usize,
    /// Size of one pixel group (bits for bitmaps).
    pub group: usize,
    /// Bytes from one row to the next.
    pub row_stride: usize,
    /// Bytes from one image to the next.
    pub image_stride: usize,
    /// Bytes from the pointer to the end of the last pixel: what the command reads or writes.
    pub span: usize,
    /// Pixels are single bits.
    pub bitmap: bool,
}

impl StoreModes {
    /// The layout of a `width` × `height` × `depth` image whose groups have `components`
    /// elements of `element` bytes each (`components` = 1 for packed types, where `element` is
    /// the packed size); `element` = 0 means a bitmap. `None` when the image does not fit the
    /// address space or [`MAX_CLIENT_IMAGE_BYTES`]. Sizes must be non-negative.
    pub fn layout(&self, element: usize, components: usize, width: usize, height: usize, depth: usize) -> Option<Layout> {
        let clamp = |v: i32| u64::try_from(v).unwrap_or(0);
        let row_pixels = if self.row_length > 0 { clamp(self.row_length) } else { width as u64 };
        let image_rows = if self.image_height > 0 { clamp(self.image_height) } else { height as u64 };
        let align = clamp(self.alignment).max(1);
        let (w, h, d) = (width as u64, height as u64, depth as u64);
        if element == 0 {
            // Bitmaps: k = a ⌈l / 8a⌉ bytes per row, offsets in bits.
            let row = align.checked_mul(row_pixels.div_ceil(8 * align))?;
            let start_bits = clamp(self.skip_rows).checked_mul(row)?.checked_mul(8)?.checked_add(clamp(self.skip_pixels))?;
            let last_bit = start_bits.checked_add(h.saturating_sub(1).checked_mul(row)?.checked_mul(8)?)?.checked_add(w)?;
            let span = if w == 0 || h == 0 { 0 } else { last_bit.div_ceil(8) };
            return finish(start_bits, 1, row, row.checked_mul(image_rows)?, span, true);
        }
        let (s, n) = (element as u64, components as u64);
        let group = s * n;
        // Row stride in elements: n l if s ≥ a, else (a / s) ⌈s n l / a⌉.
        let row = if s >= align {
            group.checked_mul(row_pixels)?
        } else {
            align.checked_mul(group.checked_mul(row_pixels)?.div_ceil(align))?
        };
        let image = row.checked_mul(image_rows)?;
        let start = clamp(self.skip_pixels)
            .checked_mul(group)?
            .checked_add(clamp(self.skip_rows).checked_mul(row)?)?
            .checked_add(clamp(self.skip_images).checked_mul(image)?)?;
        let span = if w == 0 || h == 0 || d == 0 {
            0
        } else {
            start
                .checked_add((d - 1).checked_mul(image)?)?
                .checked_add((h - 1).checked_mul(row)?)?
                .checked_add(w.checked_mul(group)?)?
        };
        finish(start, group, row, image, span, false)
    }
}

fn finish(start: u64, group: u64, row: u64, image: u64, span: u64, bitmap: bool) -> Option<Layout> {
    if span > MAX_CLIENT_IMAGE_BYTES {
        return None;
    }
    Some(Layout {
        start: usize::try_from(start).ok()?,
        group: usize::try_from(group).ok()?,
        row_stride: usize::try_from(row).ok()?,
        image_stride: usize::try_from(image).ok()?,
        span: usize::try_from(span).ok()?,
        bitmap,
    })
}

impl Layout {
    /// Offset of pixel (x, y, z) from the pointer: bytes, or bits for bitmaps.
    pub fn offset(&self, x: usize, y: usize, z: usize) -> usize {
        let rows = y * self.row_stride + z * self.image_stride;
        if self.bitmap { self.start + rows * 8 + x } else { self.start + rows + x * self.group }
    }
}

/// A storage mode: which direction and which field.
enum Mode {
    SwapBytes,
    LsbFirst,
    Int(fn(&mut StoreModes) -> &mut i32),
    Alignment,
}

fn mode_of(pname: GLenum) -> Option<(bool, Mode)> {
    use Mode::*;
    Some(match pname {
        gl::GL_PACK_SWAP_BYTES => (true, SwapBytes),
        gl::GL_UNPACK_SWAP_BYTES => (false, SwapBytes),
        gl::GL_PACK_LSB_FIRST => (true, LsbFirst),
        gl::GL_UNPACK_LSB_FIRST => (false, LsbFirst),
        gl::GL_PACK_ROW_LENGTH => (true, Int(|m| &mut m.row_length)),
        gl::GL_UNPACK_ROW_LENGTH => (false, Int(|m| &mut m.row_length)),
        gl::GL_PACK_IMAGE_HEIGHT => (true, Int(|m| &mut m.image_height)),
        gl::GL_UNPACK_IMAGE_HEIGHT => (false, Int(|m| &mut m.image_height)),
        gl::GL_PACK_SKIP_IMAGES => (true, Int(|m| &mut m.skip_images)),
        gl::GL_UNPACK_SKIP_IMAGES => (false, Int(|m| &mut m.skip_images)),
        gl::GL_PACK_SKIP_ROWS => (true, Int(|m| &mut m.skip_rows)),
        gl::GL_UNPACK_SKIP_ROWS => (false, Int(|m| &mut m.skip_rows)),
        gl::GL_PACK_SKIP_PIXELS => (true, Int(|m| &mut m.skip_pixels)),
        gl::GL_UNPACK_SKIP_PIXELS => (false, Int(|m| &mut m.skip_pixels)),
        gl::GL_PACK_ALIGNMENT => (true, Alignment),
        gl::GL_UNPACK_ALIGNMENT => (false, Alignment),
        _ => return None,
    })
}

impl Context {
    /// `glPixelStorei`: `GL_INVALID_ENUM` for an unknown name, `GL_INVALID_VALUE` for a negative
    /// length or skip, or an alignment other than 1, 2, 4, 8.
    pub fn glPixelStorei(&mut self, pname: GLenum, param: GLint) {
        let Some((pack, mode)) = mode_of(pname) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glPixelStore") };
        let store = &mut self.pixels.store;
        let modes = if pack { &mut store.pack } else { &mut store.unpack };
        match mode {
            Mode::SwapBytes => modes.swap_bytes = param != 0,
            Mode::LsbFirst => modes.lsb_first = param != 0,
            Mode::Int(field) if param >= 0 => *field(modes) = param,
            Mode::Alignment if matches!(param, 1 | 2 | 4 | 8) => modes.alignment = param,
            Mode::Int(_) | Mode::Alignment => self.set_error_in(gl::GL_INVALID_VALUE, "glPixelStore"),
        }
    }

    /// `glPixelStoref`: booleans are true for non-zero values, integers are rounded.
    pub fn glPixelStoref(&mut self, pname: GLenum, param: GLfloat) {
        let value = if Self::pixel_store_is_bool(pname) {
            GLint::from(param != 0.0)
        } else {
            param.round().clamp(i32::MIN as f32, i32::MAX as f32) as GLint
        };
        self.glPixelStorei(pname, value);
    }

    /// The value of a pixel store mode for `glGet`.
    pub(crate) fn pixel_store_value(&self, pname: GLenum) -> Option<i64> {
        let (pack, mode) = mode_of(pname)?;
        let mut modes = if pack { self.pixels.store.pack } else { self.pixels.store.unpack };
        Some(match mode {
            Mode::SwapBytes => i64::from(modes.swap_bytes),
            Mode::LsbFirst => i64::from(modes.lsb_first),
            Mode::Int(field) => i64::from(*field(&mut modes)),
            Mode::Alignment => i64::from(modes.alignment),
        })
    }

    /// Whether `pname` is a pixel store mode whose value is a boolean.
    pub(crate) fn pixel_store_is_bool(pname: GLenum) -> bool {
        matches!(mode_of(pname), Some((_, Mode::SwapBytes | Mode::LsbFirst)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_follows_row_length_alignment_and_skips() {
        let m = StoreModes { row_length: 5, skip_pixels: 1, skip_rows: 2, alignment: 4, ..StoreModes::default() };
        // RGB ubyte: 3 bytes a pixel, row of 5 pixels = 15 bytes, aligned to 16.
        let l = m.layout(1, 3, 3, 2, 1).unwrap();
        assert_eq!((l.start, l.row_stride, l.group), (3 + 32, 16, 3));
        assert_eq!(l.span, 35 + 16 + 9);
        // Shorts of 2 bytes with alignment 8 and 3 components: 6 l = 30 → 32.
        let m8 = StoreModes { alignment: 8, ..StoreModes::default() };
        assert_eq!(m8.layout(2, 3, 5, 1, 1).unwrap().row_stride, 32);
        // Elements larger than the alignment are not padded.
        let m1 = StoreModes { alignment: 2, ..StoreModes::default() };
        assert_eq!(m1.layout(4, 1, 3, 2, 1).unwrap().row_stride, 12);
        // Images: image height and skip images.
        let m3 = StoreModes { image_height: 4, skip_images: 1, alignment: 1, ..StoreModes::default() };
        let l3 = m3.layout(1, 1, 2, 2, 2).unwrap();
        assert_eq!((l3.image_stride, l3.start, l3.span), (8, 8, 8 + 8 + 2 + 2));
    }

    #[test]
    fn bitmap_layout_counts_bits() {
        let m = StoreModes { alignment: 1, skip_pixels: 3, skip_rows: 1, ..StoreModes::default() };
        let l = m.layout(0, 1, 10, 2, 1).unwrap();
        assert_eq!((l.row_stride, l.start), (2, 16 + 3));
        assert_eq!(l.offset(2, 1, 0), 19 + 16 + 2);
        assert_eq!(l.span, (19 + 16 + 10usize).div_ceil(8));
    }

    #[test]
    fn huge_images_are_refused() {
        let m = StoreModes::default();
        assert!(m.layout(4, 4, 1 << 20, 1 << 20, 1).is_none());
        assert!(m.layout(4, 4, usize::MAX / 2, 3, 1).is_none());
    }

    #[test]
    fn pixel_store_checks_values() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 3);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glPixelStorei(gl::GL_PACK_ROW_LENGTH, -1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glPixelStorei(gl::GL_TEXTURE_2D, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glPixelStoref(gl::GL_UNPACK_SKIP_ROWS, 2.6);
        ctx.glPixelStorei(gl::GL_PACK_SWAP_BYTES, 7);
        assert_eq!(ctx.pixels.store.unpack.skip_rows, 3);
        assert!(ctx.pixels.store.pack.swap_bytes);
        assert_eq!(ctx.pixel_store_value(gl::GL_UNPACK_ALIGNMENT), Some(4));
    }
}
