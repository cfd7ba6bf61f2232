//! S3TC (DXT1, DXT3, DXT5) blocks, as EXT_texture_compression_s3tc specifies them: decoding to
//! canonical RGBA8 texels, and a simple encoder (bounding-box endpoints, nearest palette entry)
//! for images given uncompressed with an S3TC internal format. Written here rather than taken
//! from a crate: both fit in a couple of hundred lines, and the encoder's quality matters
//! little (the renderer samples the decoded texels).

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

/// The eight alphas of a DXT5 alpha block with endpoints `a0`, `a1`.
fn alpha_table(a0: u8, a1: u8) -> [u8; 8] {
    let (a0, a1) = (u32::from(a0), u32::from(a1));
    let lerp = |i: u32, n: u32| (((n - i) * a0 + i * a1 + n / 2) / n) as u8;
    if a0 > a1 {
        [a0 as u8, a1 as u8, lerp(1, 7), lerp(2, 7), lerp(3, 7), lerp(4, 7), lerp(5, 7), lerp(6, 7)]
    } else {
        [a0 as u8, a1 as u8, lerp(1, 5), lerp(2, 5), lerp(3, 5), lerp(4, 5), 0, 255]
    }
}

/// Alpha of DXT5's interpolated alpha block (8 bytes) for each of the 16 texels.
fn dxt5_alpha(b: &[u8]) -> [u8; 16] {
    let table = alpha_table(b[0], b[1]);
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

/// RGB888 → RGB565.
fn to565(c: [u8; 4]) -> u16 {
    (u16::from(c[0] >> 3) << 11) | (u16::from(c[1] >> 2) << 5) | u16::from(c[2] >> 3)
}

/// Index of the entry of `palette` nearest to `c` (squared distance over `channels`).
fn nearest<const N: usize>(palette: &[[u8; 4]; N], c: [u8; 4], channels: std::ops::Range<usize>) -> usize {
    let dist = |p: &[u8; 4]| channels.clone().map(|i| (i32::from(p[i]) - i32::from(c[i])).pow(2)).sum::<i32>();
    (0..N).min_by_key(|&i| dist(&palette[i])).unwrap_or(0)
}

/// Endpoints of the colours: the corners of their bounding box along its diagonal that
/// follows the colours' main direction (a channel anti-correlated with the channel of largest
/// variance runs the other way), as RGB565 (first, second).
fn endpoints(colors: &[&[u8; 4]]) -> (u16, u16) {
    if colors.is_empty() {
        return (0, 0);
    }
    let n = colors.len() as f32;
    let mean: [f32; 3] = std::array::from_fn(|i| colors.iter().map(|c| f32::from(c[i])).sum::<f32>() / n);
    let cov = |a: usize, b: usize| colors.iter().map(|c| (f32::from(c[a]) - mean[a]) * (f32::from(c[b]) - mean[b])).sum::<f32>();
    let main = (0..3).max_by(|&a, &b| cov(a, a).total_cmp(&cov(b, b))).unwrap_or(0);
    let mut hi = [0u8; 4];
    let mut lo = [0u8; 4];
    for i in 0..3 {
        let (max, min) = colors.iter().fold((0u8, 255u8), |(mx, mn), c| (mx.max(c[i]), mn.min(c[i])));
        (hi[i], lo[i]) = if i != main && cov(main, i) < 0.0 { (min, max) } else { (max, min) };
    }
    (to565(hi), to565(lo))
}

/// Encodes the colour part of a block. With `punch_alpha`, texels with alpha below 128 use
/// the transparent entry of the three-colour mode.
fn encode_color(texels: &[[u8; 4]; 16], four_color: bool, punch_alpha: bool) -> [u8; 8] {
    let transparent = |t: &[u8; 4]| punch_alpha && t[3] < 128;
    let opaque: Vec<&[u8; 4]> = texels.iter().filter(|t| !transparent(t)).collect();
    let (hi, lo) = endpoints(&opaque);
    let three = !four_color && texels.iter().any(transparent);
    // Four colours need c0 > c1, three colours c0 ≤ c1.
    let (c0, c1) = if three { (lo.min(hi), lo.max(hi)) } else { (hi.max(lo), hi.min(lo)) };
    let mut block = [0u8; 8];
    block[..2].copy_from_slice(&c0.to_le_bytes());
    block[2..4].copy_from_slice(&c1.to_le_bytes());
    block[4] = 0b11_10_01_00;
    let decoded = color_block(&block, four_color, punch_alpha);
    let palette = [decoded[0], decoded[1], decoded[2], decoded[3]];
    let choices = if three { 3 } else { 4 };
    let mut bits = 0u32;
    for (i, t) in texels.iter().enumerate() {
        let index = if transparent(t) {
            3
        } else if c0 == c1 && !three {
            0
        } else {
            let usable: [[u8; 4]; 4] = std::array::from_fn(|k| if k < choices { palette[k] } else { [0, 0, 0, 0] });
            let k = nearest(&usable, *t, 0..3);
            if k < choices { k } else { 0 }
        };
        bits |= (index as u32) << (2 * i);
    }
    block[4..].copy_from_slice(&bits.to_le_bytes());
    block
}

/// Encodes DXT5's alpha block.
fn encode_dxt5_alpha(texels: &[[u8; 4]; 16]) -> [u8; 8] {
    let hi = texels.iter().map(|t| t[3]).max().unwrap_or(255);
    let lo = texels.iter().map(|t| t[3]).min().unwrap_or(255);
    let table = alpha_table(hi, lo);
    let mut bits = 0u64;
    for (i, t) in texels.iter().enumerate() {
        let k = if hi == lo { 0 } else { (0..8).min_by_key(|&k| (i32::from(table[k]) - i32::from(t[3])).abs()).unwrap_or(0) };
        bits |= (k as u64) << (3 * i);
    }
    let mut block = [0u8; 8];
    block[0] = hi;
    block[1] = lo;
    block[2..].copy_from_slice(&bits.to_le_bytes()[..6]);
    block
}

/// Encodes one block of 16 texels (rows of the block in order).
pub fn encode_block(format: S3tc, texels: &[[u8; 4]; 16]) -> Vec<u8> {
    match format {
        S3tc::Dxt1Rgb => encode_color(texels, false, false).to_vec(),
        S3tc::Dxt1Rgba => encode_color(texels, false, true).to_vec(),
        S3tc::Dxt3 => {
            let mut alpha = 0u64;
            for (i, t) in texels.iter().enumerate() {
                alpha |= u64::from((u32::from(t[3]) * 15 + 127) / 255) << (4 * i);
            }
            [alpha.to_le_bytes(), encode_color(texels, true, false)].concat()
        }
        S3tc::Dxt5 => [encode_dxt5_alpha(texels), encode_color(texels, true, false)].concat(),
    }
}

/// Encodes a `width` × `height` RGBA8 image (edge texels repeat into partial blocks).
pub fn encode(format: S3tc, width: usize, height: usize, texels: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(width.div_ceil(4) * height.div_ceil(4) * format.block_bytes());
    for by in 0..height.div_ceil(4) {
        for bx in 0..width.div_ceil(4) {
            let block: [[u8; 4]; 16] = std::array::from_fn(|i| {
                let x = (bx * 4 + i % 4).min(width.saturating_sub(1));
                let y = (by * 4 + i / 4).min(height.saturating_sub(1));
                let o = (y * width + x) * 4;
                texels.get(o..o + 4).map_or([0; 4], |t| [t[0], t[1], t[2], t[3]])
            });
            out.extend(encode_block(format, &block));
        }
    }
    out
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
    fn encoder_round_trips_endpoint_colors() {
        // Two colours exactly representable in 565: the decode gives them back.
        let red = [255, 0, 0, 255];
        let blue = [0, 0, 255, 255];
        let texels: [[u8; 4]; 16] = std::array::from_fn(|i| if i % 3 == 0 { red } else { blue });
        for f in [S3tc::Dxt1Rgb, S3tc::Dxt3, S3tc::Dxt5] {
            assert_eq!(decode_block(f, &encode_block(f, &texels)), texels, "{f:?}");
        }
        // Punch-through alpha keeps transparent texels transparent.
        let mut holes = texels;
        holes[5] = [0, 0, 0, 0];
        assert_eq!(decode_block(S3tc::Dxt1Rgba, &encode_block(S3tc::Dxt1Rgba, &holes)), holes);
        // DXT5 alpha: endpoints exact, others nearest.
        let alphas: [[u8; 4]; 16] = std::array::from_fn(|i| [0, 0, 0, (i * 17) as u8]);
        let back = decode_block(S3tc::Dxt5, &encode_block(S3tc::Dxt5, &alphas));
        assert_eq!((back[0][3], back[15][3]), (0, 255));
        assert!(back.iter().zip(alphas).all(|(b, a)| (i32::from(b[3]) - i32::from(a[3])).abs() <= 19));
        assert_eq!(encode(S3tc::Dxt1Rgb, 5, 3, &[9; 60]).len(), 16);
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
