//! The CPU mirror of `texel_sample` in `shaders/trace/texels.glsl`: the same steps in the same
//! order, in `f32`, so tests can check the shader against it. Level selection follows OpenGL
//! 1.5 section 3.8.8 (λ clamped to the LOD range; magnification up to λ = 0 or 0.5;
//! `NEAREST_MIPMAP_*` picks level ⌈λ + ½⌉ − 1; `LINEAR_MIPMAP_*` blends levels ⌊λ⌋ and
//! ⌊λ⌋ + 1 by the fraction of λ); texel addressing follows Vulkan's (nearest: ⌊u·w⌋; linear:
//! ⌊u·w − ½⌋ and its right neighbour, each wrapped as an integer index).

use super::{GpuTexture, level_size};
use crate::render::trace::shader_constants::{NO_TEXTURE, TEXEL_MAG_LINEAR, TEXEL_MAG_TO_HALF, TEXEL_MIN_LINEAR, TEXEL_MIPMAP, TEXEL_MIP_LINEAR, TEXEL_RECT, TEXEL_SRGB, TEXEL_WRAP_CLAMP, TEXEL_WRAP_MIRROR};

/// Texel coordinates are clamped to ±2²⁴ before they become integers (as in the shader).
const COORD_LIMIT: f32 = 16_777_216.0;

/// The colour of `texture` (a table index, or [`NO_TEXTURE`]: opaque white) at GL texture
/// coordinates `uv` (t = 0 is the first, bottom row; in texels for rectangle textures) and
/// level of detail `lod` (log2 of base-level texels per footprint), RGBA in [0, 1].
pub fn sample(words: &[u32], table: &[GpuTexture], texture: u32, uv: [f32; 2], lod: f32) -> [f32; 4] {
    let Some(t) = table.get(texture as usize).filter(|_| texture != NO_TEXTURE) else { return [1.0; 4] };
    if t.levels == 0 {
        return decode(t.average, t.flags);
    }
    let size = [t.width as f32, t.height as f32];
    let uv = if t.has(TEXEL_RECT) { [uv[0] / size[0], uv[1] / size[1]] } else { uv };
    let lod = if lod.is_nan() { 0.0 } else { lod.max(t.lod_min).min(t.lod_max) };
    let switch = if t.has(TEXEL_MAG_TO_HALF) { 0.5 } else { 0.0 };
    if lod <= switch {
        return level(words, t, 0, uv, t.has(TEXEL_MAG_LINEAR));
    }
    let linear = t.has(TEXEL_MIN_LINEAR);
    if !t.has(TEXEL_MIPMAP) {
        return level(words, t, 0, uv, linear);
    }
    let last = (t.levels - 1) as f32;
    if !t.has(TEXEL_MIP_LINEAR) {
        let d = if lod <= 0.5 { 0.0 } else { ((lod + 0.5).ceil() - 1.0).min(last) };
        return level(words, t, d as u32, uv, linear);
    }
    let d1 = lod.floor().min(last);
    let d2 = (d1 + 1.0).min(last);
    let f = if d1 >= last { 0.0 } else { lod - lod.floor() };
    let (a, b) = (level(words, t, d1 as u32, uv, linear), level(words, t, d2 as u32, uv, linear));
    std::array::from_fn(|c| mix(a[c], b[c], f))
}

/// Base level width and height in texels ((1, 1) for [`NO_TEXTURE`]), as `texel_size`.
pub fn texel_size(table: &[GpuTexture], texture: u32) -> [f32; 2] {
    table.get(texture as usize).filter(|_| texture != NO_TEXTURE).map_or([1.0; 2], |t| [t.width as f32, t.height as f32])
}

/// Level `level` of `t` at `uv`, nearest or bilinear.
fn level(words: &[u32], t: &GpuTexture, level: u32, uv: [f32; 2], linear: bool) -> [f32; 4] {
    let mut offset = t.offset as usize;
    for l in 0..level {
        let [w, h] = level_size(t.width, t.height, l);
        offset += w as usize * h as usize;
    }
    let [w, h] = level_size(t.width, t.height, level).map(i64::from);
    let x = (uv[0] * w as f32).clamp(-COORD_LIMIT, COORD_LIMIT);
    let y = (uv[1] * h as f32).clamp(-COORD_LIMIT, COORD_LIMIT);
    let fetch = |i: i64, j: i64| {
        let (i, j) = (wrap(i, w, t.wrap(0)), wrap(j, h, t.wrap(1)));
        decode(words.get(offset + (j * w + i) as usize).copied().unwrap_or(0), t.flags)
    };
    if !linear {
        return fetch(x.floor() as i64, y.floor() as i64);
    }
    let (x, y) = (x - 0.5, y - 0.5);
    let (i, j) = (x.floor(), y.floor());
    let (a, b) = (x - i, y - j);
    let (i, j) = (i as i64, j as i64);
    let (t00, t10, t01, t11) = (fetch(i, j), fetch(i + 1, j), fetch(i, j + 1), fetch(i + 1, j + 1));
    std::array::from_fn(|c| mix(mix(t00[c], t10[c], a), mix(t01[c], t11[c], a), b))
}

/// Integer texel index `i` wrapped into [0, n) by `mode` (`TEXEL_WRAP_*`).
fn wrap(i: i64, n: i64, mode: u32) -> i64 {
    match mode {
        TEXEL_WRAP_CLAMP => i.clamp(0, n - 1),
        TEXEL_WRAP_MIRROR => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
        _ => i.rem_euclid(n),
    }
}

/// A packed texel as RGBA in [0, 1], sRGB-decoded when `flags` says so.
fn decode(texel: u32, flags: u32) -> [f32; 4] {
    let c = texel.to_le_bytes().map(|b| f32::from(b) / 255.0);
    if flags & TEXEL_SRGB == 0 {
        return c;
    }
    let linear = |v: f32| if v <= 0.04045 { v / 12.92 } else { ((v + 0.055) / 1.055).powf(2.4) };
    [linear(c[0]), linear(c[1]), linear(c[2]), c[3]]
}

/// GLSL's `mix`.
fn mix(a: f32, b: f32, f: f32) -> f32 {
    a * (1.0 - f) + b * f
}
