//! A 5×7 bitmap font embedded in the demo, drawn with `glBitmap` at twice its size (so the HUD
//! needs no X font and works headless). Glyph rows are written top to bottom, one bit per
//! pixel, the leftmost pixel in bit 4.

use crate::gl::Gl;

/// Glyph width and height in font pixels.
pub const GLYPH_W: usize = 5;
pub const GLYPH_H: usize = 7;
/// Screen pixels per font pixel.
const SCALE: usize = 2;
/// Bitmap size passed to `glBitmap`: 16 × 16 (two bytes per row).
const BITMAP: usize = 16;
/// Horizontal advance in screen pixels.
pub const ADVANCE: i32 = ((GLYPH_W + 1) * SCALE) as i32;

#[rustfmt::skip]
const GLYPHS: &[(char, [u8; GLYPH_H])] = &[
    (' ', [0, 0, 0, 0, 0, 0, 0]),
    ('0', [0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110]),
    ('1', [0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110]),
    ('2', [0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111]),
    ('3', [0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110]),
    ('4', [0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010]),
    ('5', [0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110]),
    ('6', [0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110]),
    ('7', [0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000]),
    ('8', [0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110]),
    ('9', [0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100]),
    ('A', [0b01110, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001]),
    ('B', [0b11110, 0b10001, 0b10001, 0b11110, 0b10001, 0b10001, 0b11110]),
    ('C', [0b01110, 0b10001, 0b10000, 0b10000, 0b10000, 0b10001, 0b01110]),
    ('D', [0b11100, 0b10010, 0b10001, 0b10001, 0b10001, 0b10010, 0b11100]),
    ('E', [0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b11111]),
    ('F', [0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b10000]),
    ('G', [0b01110, 0b10001, 0b10000, 0b10111, 0b10001, 0b10001, 0b01111]),
    ('H', [0b10001, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001]),
    ('I', [0b01110, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110]),
    ('J', [0b00111, 0b00010, 0b00010, 0b00010, 0b00010, 0b10010, 0b01100]),
    ('K', [0b10001, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010, 0b10001]),
    ('L', [0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b11111]),
    ('M', [0b10001, 0b11011, 0b10101, 0b10101, 0b10001, 0b10001, 0b10001]),
    ('N', [0b10001, 0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001]),
    ('O', [0b01110, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110]),
    ('P', [0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000]),
    ('Q', [0b01110, 0b10001, 0b10001, 0b10001, 0b10101, 0b10010, 0b01101]),
    ('R', [0b11110, 0b10001, 0b10001, 0b11110, 0b10100, 0b10010, 0b10001]),
    ('S', [0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110]),
    ('T', [0b11111, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100]),
    ('U', [0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110]),
    ('V', [0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100]),
    ('W', [0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010]),
    ('X', [0b10001, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001, 0b10001]),
    ('Y', [0b10001, 0b10001, 0b10001, 0b01010, 0b00100, 0b00100, 0b00100]),
    ('Z', [0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b11111]),
    (':', [0b00000, 0b01100, 0b01100, 0b00000, 0b01100, 0b01100, 0b00000]),
    ('.', [0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100]),
    ('-', [0b00000, 0b00000, 0b00000, 0b11111, 0b00000, 0b00000, 0b00000]),
    ('/', [0b00000, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b00000]),
    ('(', [0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010]),
    (')', [0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000]),
    ('?', [0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b00000, 0b00100]),
];

/// The rows of glyph `c` (top row first, the leftmost pixel in bit 4), `None` when the font
/// has no such glyph.
pub fn glyph_rows(c: char) -> Option<[u8; GLYPH_H]> {
    GLYPHS.iter().find(|g| g.0 == c).map(|g| g.1)
}

/// `glBitmap` images of every glyph, built once.
pub struct Font {
    bitmaps: Vec<(char, [u8; BITMAP * 2])>,
}

impl Font {
    /// Expands every glyph to its scaled `glBitmap` image.
    pub fn new() -> Self {
        Self { bitmaps: GLYPHS.iter().map(|&(c, rows)| (c, expand(&rows))).collect() }
    }

    /// Draws `text` with its lower left corner at window pixel (`x`, `y`) in the current
    /// raster colour (set before this call). Lower case is drawn as upper case, unknown
    /// characters as `?`. Expects `GL_UNPACK_ALIGNMENT` 1 or 2 and an orthographic projection
    /// in window pixels.
    pub fn draw(&self, gl: &Gl, x: i32, y: i32, text: &str) {
        // Safety: a context is current; each bitmap is 16 rows of 2 bytes, as passed.
        unsafe {
            gl.glRasterPos2i(x, y);
            for c in text.chars() {
                let bitmap = self.glyph(c.to_ascii_uppercase());
                gl.glBitmap(
                    BITMAP as i32,
                    BITMAP as i32,
                    0.0,
                    0.0,
                    ADVANCE as f32,
                    0.0,
                    bitmap.as_ptr(),
                );
            }
        }
    }

    fn glyph(&self, c: char) -> &[u8; BITMAP * 2] {
        let find = |c| self.bitmaps.iter().find(|(g, _)| *g == c).map(|(_, b)| b);
        find(c).or_else(|| find('?')).unwrap_or(&self.bitmaps[0].1)
    }
}

/// Scales a glyph by [`SCALE`] into a 16 × 16 bitmap, rows bottom to top (as `glBitmap` reads
/// them), the glyph's bottom row two pixels above the bitmap's.
fn expand(rows: &[u8; GLYPH_H]) -> [u8; BITMAP * 2] {
    let mut out = [0u8; BITMAP * 2];
    for (from_top, &row) in rows.iter().enumerate() {
        // Spread the 5 bits to 10 (each pixel twice), left-aligned in 16 bits.
        let mut wide: u16 = 0;
        for bit in 0..GLYPH_W {
            if row & (1 << (GLYPH_W - 1 - bit)) != 0 {
                wide |= 0b11 << (15 - 2 * bit - 1);
            }
        }
        let bottom_row = SCALE + (GLYPH_H - 1 - from_top) * SCALE;
        for r in bottom_row..bottom_row + SCALE {
            out[r * 2..r * 2 + 2].copy_from_slice(&wide.to_be_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyph_pixels_are_doubled_and_flipped() {
        // 'L': left column set on every row, full bottom row.
        let l = expand(&GLYPHS.iter().find(|g| g.0 == 'L').unwrap().1);
        // Bitmap rows 0-1 are the margin.
        assert_eq!(&l[0..4], &[0, 0, 0, 0]);
        // Rows 2-3: the glyph's bottom row, 10 pixels wide.
        assert_eq!(&l[4..6], &[0xFF, 0xC0]);
        assert_eq!(&l[6..8], &[0xFF, 0xC0]);
        // Rows 4-15: only the left column (2 pixels).
        assert!(l[8..].chunks(2).all(|r| r == [0xC0, 0x00]));
    }
}
