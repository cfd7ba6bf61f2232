//! Images in integration tests: RGB8 images read from PNG files and `xwd` screenshots, written
//! as PNG, and compared with a per-pixel tolerance that forgives one-pixel edge shifts (two
//! OpenGL implementations may place a polygon edge one pixel apart and both be right).

#![allow(dead_code)] // each test binary uses part of this module

use std::path::Path;

/// An RGB8 image, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width × height × 3` bytes.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The pixel at column `x`, row `y` (from the top).
    pub fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let i = (y * self.width + x) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// The top-left `width × height` part.
    pub fn crop(&self, width: usize, height: usize) -> Image {
        let (w, h) = (width.min(self.width), height.min(self.height));
        let rgb = (0..h).flat_map(|y| self.rgb[y * self.width * 3..][..w * 3].to_vec()).collect();
        Image { width: w, height: h, rgb }
    }

    /// Reads an 8-bit RGB or RGBA PNG file (alpha dropped).
    pub fn load_png(path: &Path) -> Image {
        let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut reader = png::Decoder::new(std::io::BufReader::new(file))
            .read_info()
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut buf = vec![0; reader.output_buffer_size().expect("PNG size")];
        let info = reader.next_frame(&mut buf).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(info.bit_depth, png::BitDepth::Eight, "{}: 8-bit PNG expected", path.display());
        let channels = match info.color_type {
            png::ColorType::Rgb => 3,
            png::ColorType::Rgba => 4,
            other => panic!("{}: {other:?} PNG, RGB or RGBA expected", path.display()),
        };
        let (width, height) = (info.width as usize, info.height as usize);
        let rgb = buf[..width * height * channels].chunks_exact(channels).flat_map(|p| [p[0], p[1], p[2]]).collect();
        Image { width, height, rgb }
    }

    /// Writes the image as an RGB PNG file.
    pub fn save_png(&self, path: &Path) {
        let file = std::fs::File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().expect("PNG header");
        writer.write_image_data(&self.rgb).expect("PNG data");
    }

    /// Decodes an `xwd` screenshot (X Window Dump, 24 or 32 bits per pixel TrueColor).
    pub fn from_xwd(data: &[u8]) -> Image {
        assert!(data.len() >= 100, "xwd: header truncated");
        let field = |i: usize| u32::from_be_bytes(data[i * 4..i * 4 + 4].try_into().unwrap()) as usize;
        let (header_size, width, height) = (field(0), field(4), field(5));
        let (byte_order, bits_per_pixel, bytes_per_line) = (field(7), field(11), field(12));
        let masks = [field(14), field(15), field(16)];
        let colors = field(19);
        assert!(matches!(bits_per_pixel, 24 | 32), "xwd: {bits_per_pixel} bits per pixel");
        let step = bits_per_pixel / 8;
        let pixels = &data[header_size + 12 * colors..];
        assert!(pixels.len() >= bytes_per_line * height, "xwd: pixel data truncated");
        let mut rgb = Vec::with_capacity(width * height * 3);
        for y in 0..height {
            for x in 0..width {
                let bytes = &pixels[y * bytes_per_line + x * step..][..step];
                let value = if byte_order == 0 {
                    bytes.iter().rev().fold(0usize, |v, &b| v << 8 | b as usize)
                } else {
                    bytes.iter().fold(0usize, |v, &b| v << 8 | b as usize)
                };
                rgb.extend(masks.map(|m| ((value & m) >> m.trailing_zeros()) as u8));
            }
        }
        Image { width, height, rgb }
    }
}

/// How two images of one size differ.
#[derive(Clone, Copy, Debug)]
pub struct Difference {
    /// Fraction of pixels (of both images, each against the other) with no pixel of the other
    /// image within one pixel of its position whose every channel is within the tolerance.
    pub mismatched: f64,
    /// Mean absolute difference per channel, same position, in 0..=255.
    pub mean_abs: f64,
    /// Fraction of positions whose pixels are exactly equal.
    pub identical: f64,
}

/// Compares `a` and `b` (same size): a pixel matches when the other image has, at its position
/// or one of the 8 around it, a pixel whose channels all differ by at most `tolerance`.
pub fn compare(a: &Image, b: &Image, tolerance: u8) -> Difference {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let close = |p: [u8; 3], q: [u8; 3]| p.iter().zip(q).all(|(x, y)| x.abs_diff(y) <= tolerance);
    let unmatched = |from: &Image, to: &Image| {
        let mut n = 0usize;
        for y in 0..from.height {
            for x in 0..from.width {
                let p = from.pixel(x, y);
                let found = (y.saturating_sub(1)..=(y + 1).min(to.height - 1))
                    .any(|v| (x.saturating_sub(1)..=(x + 1).min(to.width - 1)).any(|u| close(p, to.pixel(u, v))));
                n += usize::from(!found);
            }
        }
        n
    };
    let pixels = (a.width * a.height).max(1) as f64;
    let mismatched = (unmatched(a, b) + unmatched(b, a)) as f64 / (2.0 * pixels);
    let sum: u64 = a.rgb.iter().zip(&b.rgb).map(|(x, y)| u64::from(x.abs_diff(*y))).sum();
    let identical = a.rgb.chunks_exact(3).zip(b.rgb.chunks_exact(3)).filter(|(p, q)| p == q).count() as f64 / pixels;
    Difference { mismatched, mean_abs: sum as f64 / (pixels * 3.0), identical }
}

/// An image of where `a` and `b` differ: black where equal, brighter with the difference.
pub fn difference_image(a: &Image, b: &Image) -> Image {
    let rgb = a.rgb.iter().zip(&b.rgb).map(|(x, y)| x.abs_diff(*y).saturating_mul(4)).collect();
    Image { width: a.width, height: a.height, rgb }
}

/// Images of one size laid out in rows of tiles, each row's first tile at the left (for
/// figures; a `None` tile, or a row shorter than the longest, is left black).
pub fn montage(rows: &[Vec<Option<&Image>>]) -> Image {
    let tile = rows.iter().flatten().flatten().next().expect("a montage of at least one image");
    let (w, h) = (tile.width, tile.height);
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    let width = columns * w;
    let mut rgb = vec![0u8; width * rows.len() * h * 3];
    for (r, row) in rows.iter().enumerate() {
        for (c, image) in row.iter().enumerate() {
            let Some(image) = image else { continue };
            assert_eq!((image.width, image.height), (w, h), "montage tiles of different sizes");
            for y in 0..h {
                let to = ((r * h + y) * width + c * w) * 3;
                rgb[to..to + w * 3].copy_from_slice(&image.rgb[y * w * 3..][..w * 3]);
            }
        }
    }
    Image { width, height: rows.len() * h, rgb }
}

/// The root-mean-square difference of `a` and `b` (same size) over every channel of every
/// pixel, in 0..=255.
pub fn rmse(a: &Image, b: &Image) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let sum: f64 = a.rgb.iter().zip(&b.rgb).map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2)).sum();
    (sum / a.rgb.len().max(1) as f64).sqrt()
}

/// The mean FLIP error of `test` against `reference` (same size, both sRGB): LDR-FLIP
/// (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020), NVIDIA's
/// reference implementation through the `nv-flip` crate, at its default 67 pixels per degree
/// (a 24-inch 4K monitor seen from 0.7 m). 0 where the images are alike, up to 1.
pub fn flip(test: &Image, reference: &Image) -> f64 {
    assert_eq!((test.width, test.height), (reference.width, reference.height), "images of different sizes");
    let flip_image = |image: &Image| nv_flip::FlipImageRgb8::with_data(image.width as u32, image.height as u32, &image.rgb);
    let errors = nv_flip::flip(flip_image(reference), flip_image(test), nv_flip::DEFAULT_PIXELS_PER_DEGREE).to_vec();
    errors.iter().map(|&e| f64::from(e)).sum::<f64>() / errors.len().max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: usize, height: usize, f: impl Fn(usize, usize) -> [u8; 3]) -> Image {
        let f = &f;
        let rgb = (0..height).flat_map(|y| (0..width).flat_map(move |x| f(x, y))).collect();
        Image { width, height, rgb }
    }

    #[test]
    fn rmse_is_the_root_mean_square_of_the_channel_differences() {
        let a = image(2, 1, |_, _| [10, 10, 10]);
        let b = image(2, 1, |x, _| if x == 0 { [10, 10, 10] } else { [16, 4, 10] });
        assert_eq!(rmse(&a, &a), 0.0);
        assert!((rmse(&a, &b) - (72.0f64 / 6.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn flip_is_zero_for_equal_images_one_for_green_against_blue_and_grows_with_noise() {
        let grey = image(64, 64, |_, _| [128, 128, 128]);
        // Noise of amplitude `a` around the grey, a fixed pseudo-random pattern.
        let noisy = |a: i32| image(64, 64, |x, y| [((x * 7919 + y * 104729) % 17) as i32 - 8; 3].map(|n| (128 + n * a / 8) as u8));
        let (none, small, large) = (flip(&grey, &grey), flip(&noisy(4), &grey), flip(&noisy(32), &grey));
        assert_eq!(none, 0.0);
        assert!(0.0 < small && small < large && large < 0.2, "noise +-4: {small}, +-32: {large}");
        // The paper normalises the colour difference by that of pure green and pure blue
        // (the largest): their FLIP is 1. Black and white lie a little below.
        let (green, blue) = (image(64, 64, |_, _| [0, 255, 0]), image(64, 64, |_, _| [0, 0, 255]));
        assert!((flip(&green, &blue) - 1.0).abs() < 1e-5, "{}", flip(&green, &blue));
        let black_white = flip(&image(64, 64, |_, _| [255; 3]), &image(64, 64, |_, _| [0; 3]));
        assert!(0.9 < black_white && black_white < 1.0, "{black_white}");
    }

    #[test]
    fn a_montage_lays_tiles_out_in_rows_and_leaves_missing_ones_black() {
        let red = image(2, 1, |_, _| [255, 0, 0]);
        let green = image(2, 1, |_, _| [0, 255, 0]);
        let m = montage(&[vec![Some(&red), Some(&green)], vec![None, Some(&red)]]);
        assert_eq!((m.width, m.height), (4, 2));
        assert_eq!([m.pixel(1, 0), m.pixel(2, 0), m.pixel(1, 1), m.pixel(3, 1)], [[255, 0, 0], [0, 255, 0], [0; 3], [255, 0, 0]]);
    }

    #[test]
    fn an_edge_one_pixel_apart_matches_and_a_missing_square_does_not() {
        let a = image(16, 16, |x, _| if x < 8 { [255, 0, 0] } else { [0; 3] });
        let shifted = image(16, 16, |x, _| if x < 9 { [255, 0, 0] } else { [0; 3] });
        assert_eq!(compare(&a, &shifted, 8).mismatched, 0.0);
        let missing = image(16, 16, |x, y| if x < 8 && y >= 4 { [255, 0, 0] } else { [0; 3] });
        let d = compare(&a, &missing, 8);
        assert!(d.mismatched > 0.05, "{d:?}");
    }
}
