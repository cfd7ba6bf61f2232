//! The images of `--q3`, made procedurally (no files) and uploaded the way Quake 3's
//! `R_CreateImage` does: texture names counted from 1024 without `glGenTextures`, RGBA data
//! with a `GL_RGB8` or `GL_RGBA8` internal format, mipmaps built on the CPU by a 2 × 2 box filter
//! and uploaded level by level, `GL_LINEAR_MIPMAP_NEAREST` (Q3's default `r_textureMode`)
//! for mipmapped images, clamped or repeating wrap.

use crate::font;
use crate::gl::*;
use crate::scene::textures::{brick, noise, stone};

/// The first texture name (Q3 numbers its images `1024 + i`).
const FIRST_NAME: GLuint = 1024;

/// How an image is uploaded.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Flags {
    /// Build and upload mipmaps.
    pub mipmap: bool,
    /// `GL_CLAMP_TO_EDGE` instead of `GL_REPEAT`.
    pub clamp: bool,
}

/// Repeating and mipmapped (world and model textures).
pub const WORLD: Flags = Flags { mipmap: true, clamp: false };
/// Clamped, no mipmaps (lightmaps, sky sides, sprites, 2D pictures).
pub const CLAMPED: Flags = Flags { mipmap: false, clamp: true };

/// An RGBA image, rows in upload order: row 0 at t = 0, the top of the picture (as Q3's
/// images are).
pub struct Rgba {
    pub width: usize,
    pub height: usize,
    pub texels: Vec<[u8; 4]>,
}

impl Rgba {
    /// A `size` × `size` image from a texel function of (x, y).
    pub fn square(size: usize, texel: impl Fn(usize, usize) -> [u8; 4]) -> Rgba {
        Rgba { width: size, height: size, texels: (0..size * size).map(|i| texel(i % size, i / size)).collect() }
    }

    /// Half the size, each texel the mean of 2 × 2 (Q3's `R_MipMap`).
    fn mip(&self) -> Rgba {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let at = |x: usize, y: usize| self.texels[y.min(self.height - 1) * self.width + x.min(self.width - 1)];
        let texels = (0..w * h)
            .map(|i| {
                let (x, y) = (2 * (i % w), 2 * (i / w));
                let q = [at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)];
                std::array::from_fn(|c| ((q.iter().map(|t| u32::from(t[c])).sum::<u32>() + 2) / 4) as u8)
            })
            .collect();
        Rgba { width: w, height: h, texels }
    }

    fn opaque(&self) -> bool {
        self.texels.iter().all(|t| t[3] == 255)
    }
}

/// The texture names handed out so far (for `glDeleteTextures`).
#[derive(Default)]
pub struct Images {
    count: GLuint,
}

impl Images {
    /// Uploads `image` under the next name and returns the name.
    pub fn create(&mut self, gl: &Gl, image: &Rgba, flags: Flags) -> GLuint {
        let name = FIRST_NAME + self.count;
        self.count += 1;
        let internal = if image.opaque() { GL_RGB8 } else { GL_RGBA8 };
        let filter_min = if flags.mipmap { GL_LINEAR_MIPMAP_NEAREST } else { GL_LINEAR };
        let wrap = if flags.clamp { GL_CLAMP_TO_EDGE } else { GL_REPEAT };
        // Safety: a context is current; every level's texels hold width × height RGBA texels
        // (4 bytes, so any unpack alignment fits).
        unsafe {
            gl.glBindTexture(GL_TEXTURE_2D, name);
            let mut level = 0;
            let mut mip = None;
            loop {
                let current: &Rgba = mip.as_ref().unwrap_or(image);
                let (w, h) = (current.width as GLsizei, current.height as GLsizei);
                gl.glTexImage2D(GL_TEXTURE_2D, level, internal as GLint, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, current.texels.as_ptr().cast());
                if !flags.mipmap || (w == 1 && h == 1) {
                    break;
                }
                mip = Some(current.mip());
                level += 1;
            }
            gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter_min as GLint);
            gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR as GLint);
            gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap as GLint);
            gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap as GLint);
        }
        name
    }

    /// Deletes every texture made by [`Images::create`].
    pub fn delete(&self, gl: &Gl) {
        let names: Vec<GLuint> = (0..self.count).map(|i| FIRST_NAME + i).collect();
        // Safety: a context is current; `names` holds `count` names.
        unsafe { gl.glDeleteTextures(names.len() as GLsizei, names.as_ptr()) }
    }
}

fn opaque([r, g, b]: [u8; 3]) -> [u8; 4] {
    [r, g, b, 255]
}

fn scale(rgb: [u8; 3], f: f32) -> [u8; 4] {
    opaque(rgb.map(|c| (c as f32 * f).clamp(0.0, 255.0) as u8))
}

/// Distance of texel (x, y) from the centre of a `size` image, in units of half the size.
fn radius(x: usize, y: usize, size: usize) -> f32 {
    let c = size as f32 / 2.0;
    ((x as f32 + 0.5 - c).hypot(y as f32 + 0.5 - c)) / c
}

/// Floor tiles: 16-texel beige tiles in dark grout (64 × 64).
pub fn floor_tiles() -> Rgba {
    Rgba::square(64, |x, y| {
        let n = noise(x, y) / 2;
        if x % 16 == 0 || y % 16 == 0 {
            opaque([70 + n, 66 + n, 60 + n])
        } else {
            let tone = if (x / 16 + y / 16) % 2 == 0 { 0 } else { 18 };
            opaque([178 - tone + n, 166 - tone + n, 140 - tone + n])
        }
    })
}

/// Brick walls (the scene's bricks, 64 × 64).
pub fn bricks() -> Rgba {
    Rgba::square(64, |x, y| opaque(brick(x, y)))
}

/// Blue-grey metal panels with seams and rivets (64 × 64).
pub fn metal() -> Rgba {
    Rgba::square(64, |x, y| {
        let n = noise(x, y) / 3;
        let seam = x % 32 == 0 || y % 32 == 0;
        let (rx, ry) = (x % 32, y % 32);
        let rivet = (rx == 3 || rx == 28) && (ry == 3 || ry == 28);
        match (seam, rivet) {
            (true, _) => opaque([40 + n, 44 + n, 52 + n]),
            (_, true) => opaque([190, 195, 205]),
            _ => opaque([110 + n, 118 + n, 132 + n]),
        }
    })
}

/// Concrete (the scene's stone, 64 × 64).
pub fn concrete() -> Rgba {
    Rgba::square(64, |x, y| opaque(stone(x, y)))
}

/// The frame of a light panel: light grey with a dark rim (32 × 32).
pub fn panel() -> Rgba {
    Rgba::square(32, |x, y| {
        let rim = x < 3 || y < 3 || x > 28 || y > 28;
        if rim { opaque([60, 60, 64]) } else { opaque([200, 200, 196]) }
    })
}

/// What a light panel adds (`GL_ONE, GL_ONE`): a bright warm tube, black (nothing) on the rim
/// (32 × 32).
pub fn glow() -> Rgba {
    Rgba::square(32, |x, y| {
        let rim = x < 4 || y < 4 || x > 27 || y > 27;
        if rim {
            opaque([0, 0, 0])
        } else {
            let falloff = 1.0 - ((x as f32 - 15.5).abs() / 12.0).powi(2) * 0.5;
            scale([255, 236, 190], falloff)
        }
    })
}

/// A detail texture for `GL_DST_COLOR, GL_SRC_COLOR` (2 × source × destination): grey
/// around 128, which leaves the destination as it is on average (64 × 64).
pub fn detail() -> Rgba {
    Rgba::square(64, |x, y| {
        let v = 104 + noise(x, y) + noise(x / 2 + 7, y / 2 + 3) / 2;
        opaque([v, v, v])
    })
}

/// Water: blue-green ripples (32 × 32); alpha comes from the shader (`alphaGen const`).
pub fn water() -> Rgba {
    Rgba::square(32, |x, y| {
        let wave = ((x as f32 * 0.4).sin() + (y as f32 * 0.3 + x as f32 * 0.1).cos()) * 12.0;
        let n = noise(x, y) as f32 / 2.0;
        opaque([(30.0 + wave + n) as u8, (90.0 + wave + n) as u8, (120.0 + wave + n) as u8])
    })
}

/// One side of the sky box (32 × 32): `side` as in `sky::SIDES` (0..4 around, 4 up, 5 down),
/// a gradient from pale at the horizon to deep blue up, with streaks of cloud.
pub fn sky_side(side: usize) -> Rgba {
    Rgba::square(32, |x, y| {
        // Row 0 is the top of a side (t = 0, the zenith end of the sides around).
        let up = match side {
            4 => 1.0,
            5 => 0.0,
            _ => 1.0 - y as f32 / 31.0,
        };
        let cloud = if noise(x / 3 + side * 11, y / 2) > 24 { 0.25 } else { 0.0 };
        let mix = |horizon: f32, zenith: f32| ((horizon + (zenith - horizon) * up) * (1.0 - cloud) + 235.0 * cloud) as u8;
        opaque([mix(200.0, 40.0), mix(215.0, 90.0), mix(235.0, 190.0)])
    })
}

/// Cloud layer added over the sky box (`GL_ONE, GL_ONE`): soft white blobs on black (32 × 32).
pub fn clouds() -> Rgba {
    Rgba::square(32, |x, y| {
        let blob = (noise(x / 4, y / 4) as f32 + noise(x / 2 + 5, y / 2 + 9) as f32 / 2.0 - 18.0).max(0.0) * 4.0;
        let v = blob.min(120.0) as u8;
        opaque([v, v, v])
    })
}

/// Q3's dynamic light image (`R_CreateDlightImage`): 16 × 16, brightness 4000 / d² of the
/// squared distance from the centre in texels, clamped to 255 and cut to 0 below 75.
pub fn dlight() -> Rgba {
    Rgba::square(16, |x, y| {
        let d = (8.0 - x as f32 - 0.5).powi(2) + (8.0 - y as f32 - 0.5).powi(2);
        let b = (4000.0 / d).min(255.0);
        let b = if b < 75.0 { 0 } else { b as u8 };
        [b, b, b, 255]
    })
}

/// A smoke puff: grey with a soft round alpha (32 × 32).
pub fn smoke() -> Rgba {
    Rgba::square(32, |x, y| {
        let a = (1.0 - radius(x, y, 32)).max(0.0).powf(1.5) * (200.0 + noise(x, y) as f32);
        [150, 150, 150, a.min(255.0) as u8]
    })
}

/// A rocket's flame, added (`GL_ONE, GL_ONE`): orange-white fading to black (32 × 32).
pub fn flare() -> Rgba {
    Rgba::square(32, |x, y| scale([255, 200, 120], (1.0 - radius(x, y, 32)).max(0.0).powi(2)))
}

/// A player's skin: a suit of `colour` with a belt and boots (32 × 32).
pub fn suit(colour: [u8; 3]) -> Rgba {
    Rgba::square(32, |x, y| {
        let n = noise(x, y) as f32 / 64.0;
        let dark = y < 6 || (14..17).contains(&y);
        scale(colour, if dark { 0.4 } else { 0.85 + n })
    })
}

/// A face: skin tone with two eyes and a mouth (32 × 32).
pub fn face() -> Rgba {
    Rgba::square(32, |x, y| {
        let eye = (y == 10 || y == 11) && (x == 11 || x == 12 || x == 19 || x == 20);
        let mouth = y == 19 && (12..20).contains(&x);
        if eye || mouth { opaque([40, 25, 20]) } else { scale([220, 170, 130], 0.9 + noise(x, y) as f32 / 160.0) }
    })
}

/// Armour plates: yellow with darker seams (32 × 32).
pub fn armour() -> Rgba {
    Rgba::square(32, |x, y| if x % 8 == 0 || y % 8 == 0 { opaque([120, 90, 20]) } else { scale([240, 200, 60], 0.9 + noise(x, y) as f32 / 160.0) })
}

/// The energy shell added over the armour (`GL_ONE, GL_ONE`): green bands (32 × 32).
pub fn shell() -> Rgba {
    Rgba::square(32, |x, y| {
        let band = ((y as f32 * 0.8 + x as f32 * 0.2).sin() * 0.5 + 0.5).powi(3);
        scale([60, 255, 120], band * 0.8)
    })
}

/// Dark gunmetal (rocket and weapon; 32 × 32).
pub fn gunmetal() -> Rgba {
    Rgba::square(32, |x, y| {
        let n = noise(x, y) / 2;
        if y % 16 < 2 { opaque([150, 40, 30]) } else { opaque([70 + n, 72 + n, 78 + n]) }
    })
}

/// The character set: 16 × 16 cells of 8 × 8 texels, cell `c` (row `c / 16` from the top)
/// holding glyph `c` of the demo's font, white with alpha (128 × 128).
pub fn charset() -> Rgba {
    Rgba::square(128, |x, y| {
        let c = char::from((y / 8 * 16 + x / 8) as u8);
        // Inside a cell: a 1-texel margin left and top.
        let (gx, gy) = ((x % 8).wrapping_sub(1), (y % 8).wrapping_sub(1));
        let lit = font::glyph_rows(c).is_some_and(|rows| gx < font::GLYPH_W && gy < font::GLYPH_H && rows[gy] & (1 << (font::GLYPH_W - 1 - gx)) != 0);
        if lit { [255; 4] } else { [255, 255, 255, 0] }
    })
}

/// The crosshair: a small open cross, white with alpha (32 × 32).
pub fn crosshair() -> Rgba {
    Rgba::square(32, |x, y| {
        let (dx, dy) = (x.abs_diff(16), y.abs_diff(16));
        let arm = (dx <= 1 && (4..12).contains(&dy)) || (dy <= 1 && (4..12).contains(&dx));
        if arm { [255; 4] } else { [255, 255, 255, 0] }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mipmaps_average_and_halve() {
        let image = Rgba { width: 2, height: 2, texels: vec![[0, 0, 0, 255], [255, 255, 255, 255], [255, 0, 0, 255], [0, 0, 255, 255]] };
        let m = image.mip();
        assert_eq!((m.width, m.height), (1, 1));
        assert_eq!(m.texels, [[128, 64, 128, 255]]);
    }

    #[test]
    fn the_dlight_image_falls_off_from_its_centre() {
        let d = dlight();
        assert_eq!(d.texels[8 * 16 + 8][0], 255);
        assert_eq!(d.texels[0][0], 0, "a corner is dark");
        assert!((75..255).contains(&d.texels[8 * 16 + 1][0]), "{:?}", d.texels[8 * 16 + 1]);
    }

    #[test]
    fn the_charset_holds_the_font() {
        let c = charset();
        let lit = |ch: u8, x: usize, y: usize| c.texels[((ch as usize / 16) * 8 + y) * 128 + (ch as usize % 16) * 8 + x][3] == 255;
        // '1' (0x31): its top row is 0b00100: the third pixel (x = 1 + 2) of row 1.
        assert!(lit(b'1', 3, 1) && !lit(b'1', 1, 1));
        // 'L': the left column lit on each of its 7 rows, nothing in the margins.
        assert!((1..8).all(|y| lit(b'L', 1, y)) && !lit(b'L', 0, 1) && !lit(b'L', 1, 0));
        assert!(c.texels.iter().filter(|t| t[3] == 255).count() > 500);
    }
}
