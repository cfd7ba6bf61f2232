//! Lightmaps baked at start-up, stored as Quake 3 stores them: every surface gets a block of
//! luxels, one per [`LUXEL`] units, allocated in 128 × 128 pages (Q3's `LIGHTMAP_SIZE`) by
//! the skyline allocator q3map uses; each luxel holds the light of [`lights::irradiance`] at its
//! place on the surface, encoded as a map's bytes (a quarter of the light: maps keep two bits
//! of overbright range, `r_mapOverBrightBits 2`).
//!
//! Loading shifts the bytes back up as Q3's `R_ColorShiftLightingBytes` does, keeping the hue
//! when a channel would pass 255. That is Q3's path without a hardware gamma ramp
//! (`r_overBrightBits 0`, windowed): light brighter than the texture is clamped per luxel, so
//! a lamp's warm light stays warm instead of going white. The other path (half-bright
//! lightmaps and vertex colours made whole again by a doubled gamma ramp) needs the display's
//! gamma ramp, which a GL 1.x library does not own; it is not done.

use glam::Vec3;

use super::images::{CLAMPED, Images, Rgba};
use super::level::Surface;
use super::lights;
use crate::gl::{GLuint, Gl};

/// Side of a lightmap page, in luxels.
pub const LIGHTMAP_SIZE: usize = 128;
/// World units per luxel (q3map's default lightmap scale).
pub const LUXEL: f32 = 16.0;
/// Overbright bits kept in the map's bytes (`r_mapOverBrightBits`).
pub const MAP_OVERBRIGHT_BITS: u32 = 2;

/// A page of luxels as a map stores them (RGB bytes, row 0 at t = 0).
pub struct Page {
    pub luxels: Vec<[u8; 3]>,
}

/// The skyline of one page: the first free row above each column.
struct Skyline {
    allocated: [usize; LIGHTMAP_SIZE],
}

impl Skyline {
    /// The lowest place for a `w` × `h` block, taken; `None` when the page is full.
    fn alloc(&mut self, w: usize, h: usize) -> Option<(usize, usize)> {
        let mut best = LIGHTMAP_SIZE;
        let mut x = 0;
        for i in 0..=LIGHTMAP_SIZE - w {
            let top = self.allocated[i..i + w].iter().copied().max().unwrap_or(0);
            if top < best {
                (best, x) = (top, i);
            }
        }
        if best + h > LIGHTMAP_SIZE {
            return None;
        }
        self.allocated[x..x + w].fill(best + h);
        Some((x, best))
    }
}

/// Luxels along a side of `length` units (both ends included).
fn luxels(length: f32) -> usize {
    (length / LUXEL).ceil() as usize + 1
}

/// Allocates every lit surface's block (the water is not lightmapped), sets the surfaces'
/// lightmap coordinates and pages, and bakes the pages.
pub fn bake(level: &mut super::level::Level) -> Vec<Page> {
    let mut skylines: Vec<Skyline> = Vec::new();
    let mut blocks = Vec::new();
    for (index, s) in level.surfaces.iter_mut().enumerate() {
        if !s.material.lightmapped() {
            continue;
        }
        let (w, h) = (luxels(s.rect.u.length()), luxels(s.rect.v.length()));
        let placed = skylines.iter_mut().enumerate().find_map(|(page, sky)| sky.alloc(w, h).map(|at| (page, at)));
        let (page, (x, y)) = placed.unwrap_or_else(|| {
            let mut fresh = Skyline { allocated: [0; LIGHTMAP_SIZE] };
            let at = fresh.alloc(w, h).expect("a surface's block fits an empty page");
            skylines.push(fresh);
            (skylines.len() - 1, at)
        });
        s.lightmap_page = page;
        set_lightmap_st(s, x, y);
        blocks.push((index, page, x, y, w, h));
    }
    let mut pages: Vec<Page> = skylines.iter().map(|_| Page { luxels: vec![[0; 3]; LIGHTMAP_SIZE * LIGHTMAP_SIZE] }).collect();
    for (index, page, x, y, w, h) in blocks {
        let s = &level.surfaces[index];
        for j in 0..h {
            for i in 0..w {
                let light = lights::irradiance(level, luxel_position(s, i, j), s.normal);
                pages[page].luxels[(y + j) * LIGHTMAP_SIZE + x + i] = encode(light);
            }
        }
    }
    pages
}

/// Lightmap coordinates of a surface whose block starts at luxel (`x`, `y`): the centre of
/// luxel (i, j) is at `i · LUXEL` along u and `j · LUXEL` along v from the surface's origin.
fn set_lightmap_st(s: &mut Surface, x: usize, y: usize) {
    let (du, dv) = (s.rect.u.normalize(), s.rect.v.normalize());
    for (p, st) in s.xyz.iter().zip(&mut s.lightmap_st) {
        let d = *p - s.rect.origin;
        let (i, j) = (d.dot(du) / LUXEL, d.dot(dv) / LUXEL);
        *st = [(x as f32 + 0.5 + i) / LIGHTMAP_SIZE as f32, (y as f32 + 0.5 + j) / LIGHTMAP_SIZE as f32];
    }
}

/// Where luxel (i, j) of `s` samples light: on the surface, pulled one unit inside its edges
/// and lifted one unit off it (so that the faces it meets do not shade it).
fn luxel_position(s: &Surface, i: usize, j: usize) -> Vec3 {
    let (lu, lv) = (s.rect.u.length(), s.rect.v.length());
    let a = (i as f32 * LUXEL).clamp(1.0, lu - 1.0) / lu;
    let b = (j as f32 * LUXEL).clamp(1.0, lv - 1.0) / lv;
    s.rect.at(a, b) + s.normal
}

/// Light as a map's bytes: a quarter of it (two overbright bits), clamped to 255.
pub fn encode(light: Vec3) -> [u8; 3] {
    let scale = 255.0 / (1 << MAP_OVERBRIGHT_BITS) as f32;
    (light * scale).round().clamp(Vec3::ZERO, Vec3::splat(255.0)).to_array().map(|c| c as u8)
}

/// Q3's `R_ColorShiftLightingBytes`: shifts a map's bytes up by `shift` bits; when a channel
/// passes 255, all three are scaled so that the largest is 255 (the hue is kept).
pub fn color_shift(rgb: [u8; 3], shift: u32) -> [u8; 3] {
    let c = rgb.map(|v| u32::from(v) << shift);
    let max = c.iter().copied().max().unwrap_or(0);
    if max > 255 { c.map(|v| (v * 255 / max) as u8) } else { c.map(|v| v as u8) }
}

/// Uploads the pages as Q3's `R_LoadLightmaps` does: bytes shifted back by
/// [`MAP_OVERBRIGHT_BITS`] (no gamma ramp: see the module doc), RGBA, clamped, no mipmaps.
pub fn upload(gl: &Gl, images: &mut Images, pages: &[Page]) -> Vec<GLuint> {
    pages
        .iter()
        .map(|page| {
            let texels = page.luxels.iter().map(|&l| {
                let [r, g, b] = color_shift(l, MAP_OVERBRIGHT_BITS);
                [r, g, b, 255]
            });
            let image = Rgba { width: LIGHTMAP_SIZE, height: LIGHTMAP_SIZE, texels: texels.collect() };
            images.create(gl, &image, CLAMPED)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q3::level::{Level, Material};

    #[test]
    fn the_skyline_fills_a_page_bottom_up_and_refuses_when_full() {
        let mut sky = Skyline { allocated: [0; LIGHTMAP_SIZE] };
        assert_eq!(sky.alloc(100, 20), Some((0, 0)));
        assert_eq!(sky.alloc(28, 30), Some((100, 0)));
        assert_eq!(sky.alloc(50, 10), Some((0, 20)));
        assert_eq!(sky.alloc(128, 99), None, "only 98 rows are free everywhere");
        assert_eq!(sky.alloc(128, 98), Some((0, 30)));
    }

    #[test]
    fn color_shift_keeps_the_hue_past_255() {
        assert_eq!(color_shift([10, 20, 30], 2), [40, 80, 120]);
        assert_eq!(color_shift([128, 64, 32], 2), [255, 127, 63]);
        assert_eq!(color_shift(encode(Vec3::new(0.5, 0.25, 1.0)), MAP_OVERBRIGHT_BITS), [127, 63, 255]);
    }

    #[test]
    fn every_lit_surface_gets_a_block_inside_a_page() {
        let mut level = Level::new();
        let pages = bake(&mut level);
        assert!(!pages.is_empty() && pages.len() <= 3, "{} pages", pages.len());
        for s in level.surfaces.iter().filter(|s| s.material.lightmapped()) {
            assert!(s.lightmap_page < pages.len());
            assert!(s.lightmap_st.iter().flatten().all(|&c| c > 0.0 && c < 1.0));
        }
        let water = level.surfaces.iter().find(|s| s.material == Material::Water).unwrap();
        assert!(water.lightmap_st.iter().all(|st| *st == [0.0, 0.0]));
        // Lit and unlit luxels both exist: the lamps and sun, the shadows and corners.
        let all: Vec<u32> = pages.iter().flat_map(|p| p.luxels.iter().map(|l| l.iter().map(|&c| u32::from(c)).sum())).collect();
        assert!(all.iter().any(|&l| l > 3 * 100) && all.iter().any(|&l| l > 0 && l < 3 * 12));
    }
}
