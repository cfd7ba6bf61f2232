//! S3TC (DXT1, DXT3, DXT5) block decoding, as EXT_texture_compression_s3tc specifies it, to
//! canonical RGBA8 texels. Written here rather than taken from a crate: it is about a hundred
//! lines, and glrt only needs decoding (the renderer can also upload the blocks as BC1–BC3).

use super::formats::S3tc;

/// Expands an RGB565 colour to RGB888 by bit replication.
fn rgb565(c: u16) -> [u32; 3] {
    let (r, g, b) = (u32::from(c >> 11), u32::from((c >> 5) & 0x3f), u32::from(c & 0x1f));
    [(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)]
}

/// Decodes the colour part of a block (8 bytes) to 16 RGBA texels. `four_color` forces the
/// four-colour interpretation (DXT3/DXT5); `punch_alpha` makes index 3 of the three-colour
/// mode transparent (RGBA DXT1).
fn color_block(b: &[u8], four_color: bool, punch_alpha: bool) -> [[u8; 4]; 16] {
    let c0 = u16::from_le_bytes([b[0], b[1]]);
    let c1 = u16::from_le_bytes([b[2], b[3]]);
    let (p0, p1) = (rgb565(c0), rgb565(c1));
    let mix = |wa: u32, wb: u32, d: u32| -> [u8; 4] {
        let c = [0, 1, 2].map(|i| ((wa * p0[i] + wb * p1[i] + d / 2) / d) as u8);
        [c[0], c[1], c[2], 255]
    };
    let palette = if four_color || c0 > c1 {
        [mix(1, 0, 1), mix(0, 1, 1), mix(2, 1, 3), mix(1, 2, 3)]
    } else {
        [mix(1, 0, 1), mix(0, 1, 1), mix(1, 1, 2), [0, 0, 0, if punch_alpha { 0 } else { 255 }]]
    };
    let bits = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
    std::array::from_fn(|i| palette[((bits >> (2 * i)) & 3) as usize])
}

/// Alpha of DXT5's interpolated alpha block (8 bytes) for each of the 16 texels.
fn dxt5_alpha(b: &[u8]) -> [u8; 16] {
    let (a0, a1) = (u32::from(b[0]), u32::from(b[1]));
    let lerp = |i: u32, n: u32| (((n - i) * a0 + i * a1 + n / 2) / n) as u8;
    let table: [u8; 8] = if a0 > a1 {
        [a0 as u8, a1 as u8, lerp(1, 7), lerp(2, 7), lerp(3, 7), lerp(4, 7), lerp(5, 7), lerp(6, 7)]
    } else {
        [a0 as u8, a1 as u8, lerp(1, 5), lerp(2, 5), lerp(3, 5), lerp(4, 5), 0, 255]
    };
    let mut bits = [0u8; 8];
    bits[..6].copy_from_slice(&b[2..8]);
    let bits = u64::from_le_bytes(bits);
    std::array::from_fn(|i| table[((bits >> (3 * i)) & 7) as usize])
}

/// Decodes one block to 16 texels, row by row from the first row of the block.
pub fn decode_block(format: S3tc, b: &[u8]) -> [[u8; 4]; 16] {
    match format {
        S3tc::Dxt1Rgb => color_block(b, false, false),
        S3tc::Dxt1Rgba => color_block(b, false, true),
        S3tc::Dxt3 => {
            let mut t = color_block(&b[8..16], true, false);
            let alpha = u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]);
            for (i, texel) in t.iter_mut().enumerate() {
                texel[3] = ((alpha >> (4 * i)) & 0xf) as u8 * 17;
            }
            t
        }
        S3tc::Dxt5 => {
            let mut t = color_block(&b[8..16], true, false);
            for (texel, a) in t.iter_mut().zip(dxt5_alpha(&b[..8])) {
                texel[3] = a;
            }
            t
        }
    }
}

/// Decodes a `width` × `height` image of blocks (row-major) to RGBA8 texels; `None` when
/// `data` is shorter than the image needs.
pub fn decode(format: S3tc, width: usize, height: usize, data: &[u8]) -> Option<Vec<u8>> {
    let (bw, bh) = (width.div_ceil(4), height.div_ceil(4));
    let bytes = format.block_bytes();
    if data.len() < bw * bh * bytes {
        return None;
    }
    let mut out = vec![0u8; width * height * 4];
    for by in 0..bh {
        for bx in 0..bw {
            let at = (by * bw + bx) * bytes;
            let texels = decode_block(format, &data[at..at + bytes]);
            for (i, t) in texels.iter().enumerate() {
                let (x, y) = (bx * 4 + i % 4, by * 4 + i / 4);
                if x < width && y < height {
                    let o = (y * width + x) * 4;
                    out[o..o + 4].copy_from_slice(t);
                }
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dxt1_block_decodes_known_colors() {
        // c0 = pure red, c1 = pure blue; texel indices 0, 1, 2, 3 in the first row, 0 after.
        let block = [0x00, 0xf8, 0x1f, 0x00, 0b11_10_01_00, 0, 0, 0];
        let t = decode_block(S3tc::Dxt1Rgb, &block);
        assert_eq!(t[0], [255, 0, 0, 255]);
        assert_eq!(t[1], [0, 0, 255, 255]);
        assert_eq!(t[2], [170, 0, 85, 255]);
        assert_eq!(t[3], [85, 0, 170, 255]);
        assert_eq!(t[4], [255, 0, 0, 255]);
        // c0 ≤ c1: three colours and transparent black.
        let block = [0x1f, 0x00, 0x00, 0xf8, 0b11_10_00_00, 0, 0, 0];
        let t = decode_block(S3tc::Dxt1Rgba, &block);
        assert_eq!(t[2], [128, 0, 128, 255]);
        assert_eq!(t[3], [0, 0, 0, 0]);
    }

    #[test]
    fn dxt3_and_dxt5_alpha() {
        let mut block = [0u8; 16];
        block[0] = 0xf0; // texel 0 alpha 0, texel 1 alpha 15
        block[8..12].copy_from_slice(&[0xff, 0xff, 0xff, 0xff]);
        let t = decode_block(S3tc::Dxt3, &block);
        assert_eq!((t[0], t[1][3]), ([255, 255, 255, 0], 255));
        let mut block = [0u8; 16];
        block[0] = 255;
        block[1] = 0;
        block[2] = 0b010_001_000; // texels 0, 1, 2: indices 0, 1, 2
        let t = decode_block(S3tc::Dxt5, &block);
        assert_eq!([t[0][3], t[1][3], t[2][3]], [255, 0, 219]);
        assert!(decode(S3tc::Dxt5, 8, 4, &block).is_none());
        assert_eq!(decode(S3tc::Dxt5, 2, 2, &block).unwrap().len(), 16);
    }
}
