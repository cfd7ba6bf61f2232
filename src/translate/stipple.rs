//! The polygon stipple pattern (OpenGL 1.5 section 3.5.2): `glPolygonStipple` unpacks a 32×32
//! bitmap like `glBitmap` data (section 3.6.4, type `GL_BITMAP`), `glGetPolygonStipple` packs
//! it back (section 4.3.2).
//! Both honour the pixel-store state: the unpack modes (and the pixel unpack buffer) when the
//! pattern is given, the pack modes (and the pixel pack buffer) when it is read back.

use super::Context;
use super::pixels::store::StoreModes;
use super::gl::GLubyte;
use super::lists::ListOp;

/// Where the bits of a bitmap lie in client memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitmapLayout {
    /// Bytes from one row to the next.
    pub row_stride: usize,
    /// Byte offset of the first row (`SKIP_ROWS`).
    pub first_row: usize,
    /// Bit offset of the first pixel in a row (`SKIP_PIXELS`).
    pub first_bit: usize,
    /// `LSB_FIRST`: the leftmost pixel is bit 0 of a byte rather than bit 7.
    pub lsb_first: bool,
}

/// Side of the stipple pattern, in pixels.
const SIDE: usize = 32;

impl BitmapLayout {
    /// The layout the storage modes `m` give a 32-pixel-wide bitmap.
    pub fn of(m: &StoreModes) -> BitmapLayout {
        BitmapLayout::new(m.alignment, m.row_length, m.skip_rows, m.skip_pixels, m.lsb_first)
    }

    /// The layout of a 32-pixel-wide bitmap for pixel-store values (section 3.6.4): rows of
    /// `ROW_LENGTH` (or 32) bits padded to `alignment` bytes. Negative values count as 0 and a
    /// bad alignment as 1 (`glPixelStore` rejects both before they get here).
    pub fn new(alignment: i32, row_length: i32, skip_rows: i32, skip_pixels: i32, lsb_first: bool) -> BitmapLayout {
        let a = if matches!(alignment, 1 | 2 | 4 | 8) { alignment as usize } else { 1 };
        let bits = if row_length > 0 { row_length as usize } else { SIDE };
        let row_stride = a * bits.div_ceil(8 * a);
        BitmapLayout {
            row_stride,
            first_row: row_stride * skip_rows.max(0) as usize,
            first_bit: skip_pixels.max(0) as usize,
            lsb_first,
        }
    }

    /// Byte index and bit mask of pixel `col` of row `row`.
    fn bit(&self, row: usize, col: usize) -> (usize, u8) {
        let bit = self.first_bit + col;
        let mask = if self.lsb_first { 1 << (bit % 8) } else { 0x80 >> (bit % 8) };
        (self.first_row + row * self.row_stride + bit / 8, mask)
    }

    /// Bytes spanned by the 32×32 bitmap.
    fn len(&self) -> usize {
        self.bit(SIDE - 1, SIDE - 1).0 + 1
    }
}

/// Unpacks a 32×32 bitmap from the bytes the layout spans into rows (bit 31 = leftmost pixel).
fn unpack(bytes: &[u8], layout: &BitmapLayout) -> [u32; SIDE] {
    std::array::from_fn(|row| {
        (0..SIDE).fold(0u32, |acc, col| {
            let (i, mask) = layout.bit(row, col);
            acc | (u32::from(bytes.get(i).is_some_and(|&b| b & mask != 0)) << (31 - col))
        })
    })
}

impl Context {
    /// The pattern at `mask` (client memory or the unpack buffer, [`Context::unpack_bytes`])
    /// as the unpack modes lay it out; `None` after an error or for a null client pointer.
    ///
    /// # Safety
    /// A non-null `mask` must point to the 32×32 bitmap as the unpack state lays it out.
    unsafe fn read_stipple(&mut self, mask: *const GLubyte) -> Option<[u32; SIDE]> {
        let layout = BitmapLayout::of(&self.pixels.store.unpack);
        match unsafe { self.unpack_bytes(mask.cast(), layout.len(), 1, "glPolygonStipple") } {
            Ok(Some(bytes)) => Some(unpack(&bytes, &layout)),
            Ok(None) => {
                self.null_pointer("glPolygonStipple");
                None
            }
            Err(()) => None,
        }
    }

    /// Replaces the pattern.
    fn set_polygon_stipple(&mut self, rows: [u32; SIDE]) {
        self.fixed_mut().raster.stipple = rows;
    }

    /// `glPolygonStipple`.
    ///
    /// # Safety
    /// `mask` must point to the 32×32 bitmap as the unpack state lays it out.
    pub unsafe fn glPolygonStipple(&mut self, mask: *const GLubyte) {
        if let Some(rows) = unsafe { self.read_stipple(mask) } {
            self.set_polygon_stipple(rows);
        }
    }

    /// `glPolygonStipple` in a display list: unpacked when compiled (section 5.4).
    ///
    /// # Safety
    /// As [`Context::glPolygonStipple`].
    pub unsafe fn compile_glPolygonStipple(&mut self, mask: *const GLubyte) {
        if let Some(rows) = unsafe { self.read_stipple(mask) } {
            self.lists.record(ListOp::Deferred(Box::new(move |ctx| ctx.set_polygon_stipple(rows))));
        }
    }

    /// `glGetPolygonStipple`: writes only the bits of the pattern, leaving padding bytes and
    /// skipped bits as they were.
    ///
    /// # Safety
    /// `mask` must point to writable memory for the 32×32 bitmap as the pack state lays it out.
    pub unsafe fn glGetPolygonStipple(&mut self, mask: *mut GLubyte) {
        let layout = BitmapLayout::of(&self.pixels.store.pack);
        let rows = self.fixed.raster.stipple;
        let pack = |bytes: &mut [u8]| {
            for (row, bits) in rows.iter().enumerate() {
                for col in 0..SIDE {
                    let (i, m) = layout.bit(row, col);
                    if let Some(byte) = bytes.get_mut(i) {
                        *byte = if bits & (1 << (31 - col)) != 0 { *byte | m } else { *byte & !m };
                    }
                }
            }
        };
        unsafe { self.pack_bytes(mask.cast(), layout.len(), 1, "glGetPolygonStipple", pack) }
    }
}

#[cfg(test)]
mod tests {
    use super::{BitmapLayout, unpack};
    use crate::translate::Context;
    use crate::translate::{dispatch, gl};

    #[test]
    fn stipple_round_trips_and_is_compiled_unpacked() {
        let (mut ctx, _) = Context::with_recording();
        let pattern: Vec<u8> = (0..128u32).map(|i| (i * 37 % 256) as u8).collect();
        unsafe { ctx.glPolygonStipple(pattern.as_ptr()) };
        assert_eq!(ctx.fixed.raster.stipple[0], u32::from_be_bytes([0, 37, 74, 111]));
        let mut back = [0u8; 128];
        unsafe { ctx.glGetPolygonStipple(back.as_mut_ptr()) };
        assert_eq!(back.to_vec(), pattern);

        let zeros = [0u8; 128];
        unsafe {
            dispatch::glNewList(&mut ctx, 5, gl::GL_COMPILE);
            dispatch::glPolygonStipple(&mut ctx, zeros.as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        assert_eq!(ctx.fixed.raster.stipple[0], u32::from_be_bytes([0, 37, 74, 111]));
        unsafe { dispatch::glCallList(&mut ctx, 5) };
        assert_eq!(ctx.fixed.raster.stipple, [0; 32]);
    }

    #[test]
    fn compiled_stipple_inside_begin_end_is_invalid_operation() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glNewList(&mut ctx, 5, gl::GL_COMPILE);
            dispatch::glPolygonStipple(&mut ctx, [0x55u8; 128].as_ptr());
            dispatch::glEndList(&mut ctx);
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glCallList(&mut ctx, 5);
            dispatch::glEnd(&mut ctx);
        }
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        assert_eq!(ctx.fixed.raster.stipple, [u32::MAX; 32], "the pattern changed inside Begin/End");
    }

    #[test]
    fn layout_follows_pixel_store_values() {
        let l = BitmapLayout::new(8, 0, 1, 4, true);
        assert_eq!((l.row_stride, l.first_row, l.first_bit), (8, 8, 4));
        let mut bytes = vec![0u8; 8 * 33];
        bytes[8] = 0x10; // row 0, pixel 0 is bit 4 (LSB first, 4 pixels skipped)
        let rows = unpack(&bytes, &l);
        assert_eq!(rows[0], 1 << 31);
        assert_eq!(rows[1], 0);
        assert_eq!(BitmapLayout::new(4, 0, 0, 0, false), BitmapLayout::of(&Default::default()));
    }
}
