//! RGBA8 images (rows bottom to top as OpenGL reads them, or top to bottom as the raster
//! renderer stores them) converted to the pixel layout of an X `ZPixmap` image: any TrueColor masks, 16, 24 or 32 bits per pixel, either byte order.
//! The layout comes from the visual's masks, never assumed (BGRX is common, not universal).

/// One colour channel of a pixel value: where its bits are, as an 8-bit value maps to them.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Channel {
    /// The channel's value for each 8-bit component, already shifted into place.
    table: Box<[u32; 256]>,
}

impl Channel {
    /// The channel of `mask` (contiguous bits): an 8-bit component `c` becomes the nearest
    /// value of the mask's width, `round(c * max / 255)`.
    fn new(mask: u32) -> Option<Channel> {
        let shift = mask.trailing_zeros();
        let bits = mask.count_ones();
        if bits == 0 || bits > 16 || (mask >> shift) != (1u32 << bits) - 1 {
            return None;
        }
        let max = (1u32 << bits) - 1;
        let mut table = Box::new([0u32; 256]);
        for (c, slot) in table.iter_mut().enumerate() {
            *slot = ((c as u32 * max + 127) / 255) << shift;
        }
        Some(Channel { table })
    }
}

/// How an X image stores a pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PixelFormat {
    red: Channel,
    green: Channel,
    blue: Channel,
    /// Bits of the depth that no colour mask covers (the alpha of 32-bit visuals), all set:
    /// a GL 1.x window is opaque, whatever alpha the program left in its colour buffer.
    fill: u32,
    /// 2, 3 or 4.
    bytes_per_pixel: usize,
    /// `MSBFirst` byte order.
    msb_first: bool,
}

impl PixelFormat {
    /// The format of an image with these masks, depth, bits per pixel and byte order (the
    /// fields of an `XImage`); `None` for layouts that are not TrueColor with 16 to 32 bits
    /// per pixel.
    pub fn new(masks: [u32; 3], depth: u32, bits_per_pixel: u32, msb_first: bool) -> Option<PixelFormat> {
        if !matches!(bits_per_pixel, 16 | 24 | 32) || depth > bits_per_pixel || depth == 0 {
            return None;
        }
        let depth_mask = if depth == 32 { u32::MAX } else { (1u32 << depth) - 1 };
        Some(PixelFormat {
            red: Channel::new(masks[0])?,
            green: Channel::new(masks[1])?,
            blue: Channel::new(masks[2])?,
            fill: depth_mask & !(masks[0] | masks[1] | masks[2]),
            bytes_per_pixel: bits_per_pixel as usize / 8,
            msb_first,
        })
    }

    /// The pixel value of an RGBA8 colour.
    pub fn pixel(&self, [r, g, b, _]: [u8; 4]) -> u32 {
        self.red.table[r as usize] | self.green.table[g as usize] | self.blue.table[b as usize] | self.fill
    }

    /// Converts `rgba` (`width` × `height`, tightly packed, rows bottom to top when
    /// `bottom_up`, else top to bottom) into `dst`, an image with rows top to bottom `stride`
    /// bytes apart. Returns false (writing nothing) when either buffer is too small.
    pub fn convert(&self, rgba: &[u8], width: usize, height: usize, bottom_up: bool, dst: &mut [u8], stride: usize) -> bool {
        let row_bytes = width * self.bytes_per_pixel;
        let fits = |len: usize, pitch: usize, used: usize| height == 0 || (pitch >= used && len >= pitch * (height - 1) + used);
        if !fits(rgba.len(), width * 4, width * 4) || !fits(dst.len(), stride, row_bytes) {
            return false;
        }
        for y in 0..height {
            let row = if bottom_up { height - 1 - y } else { y };
            let src = &rgba[row * width * 4..][..width * 4];
            let out = &mut dst[y * stride..][..row_bytes];
            match (self.bytes_per_pixel, self.msb_first) {
                (4, false) => self.convert_row::<4>(src, out, u32::to_le_bytes),
                (4, true) => self.convert_row::<4>(src, out, u32::to_be_bytes),
                (3, false) => self.convert_row::<3>(src, out, |p| first3(p.to_le_bytes())),
                (3, true) => self.convert_row::<3>(src, out, |p| last3(p.to_be_bytes())),
                (_, false) => self.convert_row::<2>(src, out, |p| first2(p.to_le_bytes())),
                (_, true) => self.convert_row::<2>(src, out, |p| last2(p.to_be_bytes())),
            }
        }
        true
    }

    /// One row: each RGBA8 pixel of `src` as `N` bytes of `out`, laid out by `bytes`.
    #[inline(always)]
    fn convert_row<const N: usize>(&self, src: &[u8], out: &mut [u8], bytes: impl Fn(u32) -> [u8; N]) {
        for (px, o) in src.chunks_exact(4).zip(out.chunks_exact_mut(N)) {
            o.copy_from_slice(&bytes(self.pixel([px[0], px[1], px[2], px[3]])));
        }
    }
}

fn first3(b: [u8; 4]) -> [u8; 3] {
    [b[0], b[1], b[2]]
}
fn last3(b: [u8; 4]) -> [u8; 3] {
    [b[1], b[2], b[3]]
}
fn first2(b: [u8; 4]) -> [u8; 2] {
    [b[0], b[1]]
}
fn last2(b: [u8; 4]) -> [u8; 2] {
    [b[2], b[3]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2 image, rows bottom to top: bottom row red, green; top row blue, white.
    const IMAGE: [u8; 16] = [255, 0, 0, 9, 0, 255, 0, 9, 0, 0, 255, 9, 255, 255, 255, 9];

    #[test]
    fn bgrx_flips_rows_and_places_channels() {
        let f = PixelFormat::new([0xff0000, 0xff00, 0xff], 24, 32, false).unwrap();
        let mut out = [0u8; 2 * 12];
        assert!(f.convert(&IMAGE, 2, 2, true, &mut out, 12));
        // Top row first: blue, white; then red, green. Bytes B, G, R, X (X = 0: depth 24).
        assert_eq!(&out[..8], &[255, 0, 0, 0, 255, 255, 255, 0]);
        assert_eq!(&out[12..20], &[0, 0, 255, 0, 0, 255, 0, 0]);
        assert_eq!(&out[8..12], &[0; 4], "padding untouched");
        // Top-down input: the rows stay in order.
        assert!(f.convert(&IMAGE, 2, 2, false, &mut out, 12));
        assert_eq!(&out[..8], &[0, 0, 255, 0, 0, 255, 0, 0]);
    }

    #[test]
    fn other_masks_and_byte_orders() {
        // RGBX masks, MSB first, depth 32: the uncovered byte (alpha) is opaque.
        let f = PixelFormat::new([0xff00_0000, 0xff_0000, 0xff00], 32, 32, true).unwrap();
        assert_eq!(f.pixel([1, 2, 3, 0]), 0x0102_03ff);
        let mut out = [0u8; 8];
        assert!(f.convert(&IMAGE[..8], 2, 1, true, &mut out, 8));
        assert_eq!(out, [255, 0, 0, 255, 0, 255, 0, 255]);
        // RGB565: 8-bit components rounded to 5 and 6 bits.
        let f = PixelFormat::new([0xf800, 0x07e0, 0x001f], 16, 16, false).unwrap();
        assert_eq!(f.pixel([255, 255, 255, 255]), 0xffff);
        assert_eq!(f.pixel([128, 128, 128, 0]), (16 << 11) | (32 << 5) | 16);
        let mut out = [0u8; 4];
        assert!(f.convert(&IMAGE[..8], 2, 1, true, &mut out, 4));
        assert_eq!(out, [0x00, 0xf8, 0xe0, 0x07]);
        // 24 bits per pixel, LSB first.
        let f = PixelFormat::new([0xff0000, 0xff00, 0xff], 24, 24, false).unwrap();
        let mut out = [0u8; 6];
        assert!(f.convert(&IMAGE[..8], 2, 1, false, &mut out, 6));
        assert_eq!(out, [0, 0, 255, 0, 255, 0]);
    }

    #[test]
    fn refuses_bad_layouts_and_short_buffers() {
        assert!(PixelFormat::new([0xf0f0, 0xff00, 0xff], 24, 32, false).is_none(), "holes in a mask");
        assert!(PixelFormat::new([0xff0000, 0xff00, 0xff], 24, 8, false).is_none());
        assert!(PixelFormat::new([0xff0000, 0, 0xff], 24, 32, false).is_none());
        let f = PixelFormat::new([0xff0000, 0xff00, 0xff], 24, 32, false).unwrap();
        let mut out = [7u8; 15];
        assert!(!f.convert(&IMAGE, 2, 2, true, &mut out, 8));
        assert!(!f.convert(&IMAGE[..12], 2, 2, true, &mut [0u8; 16], 8));
        assert_eq!(out, [7; 15]);
    }
}
