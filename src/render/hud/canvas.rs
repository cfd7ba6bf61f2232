//! The HUD's picture, drawn on the CPU: an RGBA8 image (rows top to bottom, the framebuffer's
//! [`crate::render::raster::target::COLOR_FORMAT`]) with filled rectangles and text in the
//! 8×8 bitmap font of basic Latin (`font8x8`, compiled in; characters outside ASCII are drawn
//! as `?`).

/// Width and height of a character cell in pixels.
pub const GLYPH: u32 = 8;

/// An RGBA8 image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Canvas {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// `4 × width × height` bytes, rows top to bottom.
    pub rgba: Vec<u8>,
}

impl Canvas {
    /// A canvas of `size` filled with `colour`.
    pub fn new(size: [u32; 2], colour: [u8; 4]) -> Canvas {
        Canvas { size, rgba: colour.repeat(size[0] as usize * size[1] as usize) }
    }

    /// The pixel at column `x`, row `y` (from the top).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        let i = 4 * (y as usize * self.size[0] as usize + x as usize);
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2], self.rgba[i + 3]]
    }

    /// Fills the rectangle at `x, y` of `w × h` (clipped to the canvas).
    pub fn fill(&mut self, [x, y, w, h]: [u32; 4], colour: [u8; 4]) {
        let [width, height] = self.size;
        for row in y.min(height)..(y + h).min(height) {
            for column in x.min(width)..(x + w).min(width) {
                let i = 4 * (row as usize * width as usize + column as usize);
                self.rgba[i..i + 4].copy_from_slice(&colour);
            }
        }
    }

    /// Draws `text` from `x, y` (the top-left corner of its first cell), one [`GLYPH`] per
    /// character, in `colour`; the background shows between the glyphs' pixels.
    pub fn text(&mut self, x: u32, y: u32, text: &str, colour: [u8; 4]) {
        for (n, c) in text.chars().enumerate() {
            let glyph = font8x8::legacy::BASIC_LEGACY[if c.is_ascii() { c as usize } else { '?' as usize }];
            let left = x + n as u32 * GLYPH;
            for (row, bits) in glyph.iter().enumerate() {
                // Bit 0 is the leftmost pixel.
                for column in (0..8).filter(|b| bits >> b & 1 == 1) {
                    self.fill([left + column, y + row as u32, 1, 1], colour);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INK: [u8; 4] = [255, 255, 255, 255];
    const PAPER: [u8; 4] = [0, 0, 0, 255];

    #[test]
    fn text_draws_the_glyphs_bits_left_to_right() {
        let mut canvas = Canvas::new([24, 8], PAPER);
        canvas.text(8, 0, "|", INK);
        // font8x8's '|': 0x18 (bits 3 and 4) in rows 0 to 2 and 4 to 6.
        let ink: Vec<(u32, u32)> = (0..8).flat_map(|y| (0..24).map(move |x| (x, y))).filter(|&(x, y)| canvas.pixel(x, y) == INK).collect();
        let expected: Vec<(u32, u32)> = [0, 1, 2, 4, 5, 6].into_iter().flat_map(|y| [(11, y), (12, y)]).collect();
        assert_eq!(ink, expected);
        let mut other = Canvas::new([24, 8], PAPER);
        other.text(8, 0, "é", INK);
        let mut question = Canvas::new([24, 8], PAPER);
        question.text(8, 0, "?", INK);
        assert_eq!(other, question, "outside ASCII: '?'");
    }

    #[test]
    fn fill_is_clipped_to_the_canvas() {
        let mut canvas = Canvas::new([4, 3], PAPER);
        canvas.fill([2, 1, 10, 10], INK);
        let ink = (0..3).flat_map(|y| (0..4).map(move |x| (x, y))).filter(|&(x, y)| canvas.pixel(x, y) == INK).count();
        assert_eq!(ink, 4);
        assert_eq!(canvas.pixel(1, 1), PAPER);
    }
}
