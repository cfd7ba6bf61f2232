//! `GL_GENERATE_MIPMAP` (OpenGL 1.5 section 3.8.8, "Automatic Mipmap Generation"): each level
//! below the changed base level is a 2×2(×2) box filter of the one above, down to 1×1.

use std::sync::Arc;

use super::formats::Base;
use super::objects::{Level, TextureObject};
use crate::frame::texture::{TexImage, TexelFormat};

/// The box-filter footprints of halving an image of `size` (without border): for each texel
/// of the half-size image, in order, the indices of the 1 to 8 source texels it averages.
fn footprints(size: [usize; 3]) -> (Vec<Vec<usize>>, [usize; 3]) {
    let out_size = size.map(|s| (s / 2).max(1));
    let step = size.map(|s| if s > 1 { 2 } else { 1 });
    let mut out = Vec::with_capacity(out_size[0] * out_size[1] * out_size[2]);
    for z in 0..out_size[2] {
        for y in 0..out_size[1] {
            for x in 0..out_size[0] {
                let mut group = Vec::with_capacity(8);
                for dz in 0..step[2] {
                    for dy in 0..step[1] {
                        for dx in 0..step[0] {
                            group.push(((z * step[2] + dz) * size[1] + y * step[1] + dy) * size[0] + x * step[0] + dx);
                        }
                    }
                }
                out.push(group);
            }
        }
    }
    (out, out_size)
}

/// Halves RGBA8 texels `src` (`size` without border) with a box filter, rounding to nearest.
pub fn downsample(src: &[u8], size: [usize; 3]) -> (Vec<u8>, [usize; 3]) {
    let (groups, out_size) = footprints(size);
    let mut out = Vec::with_capacity(groups.len() * 4);
    for group in groups {
        let n = group.len() as u32;
        let mut sum = [0u32; 4];
        for i in group {
            for (c, s) in sum.iter_mut().enumerate() {
                *s += u32::from(src.get(i * 4 + c).copied().unwrap_or(0));
            }
        }
        out.extend(sum.map(|s| ((s + n / 2) / n) as u8));
    }
    (out, out_size)
}

/// Halves `f32` texels of `per_texel` values (depth values, or the RGBA values of float
/// levels) `src` (`size` without border) with a box filter.
pub fn downsample_floats(src: &[f32], per_texel: usize, size: [usize; 3]) -> Vec<f32> {
    let (groups, _) = footprints(size);
    let mut out = Vec::with_capacity(groups.len() * per_texel);
    for g in groups {
        for c in 0..per_texel {
            out.push(g.iter().map(|&i| src.get(i * per_texel + c).copied().unwrap_or(0.0)).sum::<f32>() / g.len() as f32);
        }
    }
    out
}

/// Halves the integer texels (four components each) of an integer level (EXT_texture_integer)
/// `src` (`size` without border) with a box filter, each average rounded to nearest (halves
/// away from zero), so that the components stay within the format's range.
pub fn downsample_integers(src: &[i64], size: [usize; 3]) -> Vec<i64> {
    let (groups, _) = footprints(size);
    let mut out = Vec::with_capacity(groups.len() * 4);
    for g in groups {
        let n = g.len() as i64;
        for c in 0..4 {
            let sum: i64 = g.iter().map(|&i| src.get(i * 4 + c).copied().unwrap_or(0)).sum();
            out.push(if sum >= 0 { (sum + n / 2) / n } else { (sum - n / 2) / n });
        }
    }
    out
}

/// Removes the border of an image whose texels are `per_texel` consecutive values of `data`.
fn interior<T: Copy>(data: &[T], per_texel: usize, size: [usize; 3], border: usize) -> Vec<T> {
    if border == 0 {
        return data.to_vec();
    }
    let inner = [size[0] - 2, size[1].saturating_sub(2).max(1), size[2].saturating_sub(2).max(1)];
    let b = |i: usize| if size[i] > 1 { 1 } else { 0 };
    let mut out = Vec::with_capacity(inner[0] * inner[1] * inner[2] * per_texel);
    for z in 0..inner[2] {
        for y in 0..inner[1] {
            let row = ((z + b(2)) * size[1] + y + b(1)) * size[0] + 1;
            out.extend_from_slice(data.get(row * per_texel..(row + inner[0]) * per_texel).unwrap_or(&[]));
        }
    }
    out
}

/// Regenerates the levels below `base` of `face` from it. Generated levels have no border
/// (their border texels would be zero) and keep the base level's internal format; those of a
/// paletted base are stored as RGBA texels. Depth levels also average their full-precision
/// depth values; depth/stencil levels get stencil indices 0 (the spec defines no filtering of
/// stencil indices). Rectangle textures have one level: nothing is generated.
pub fn generate(obj: &mut TextureObject, face: usize, base: usize) {
    if obj.target == Some(super::objects::Target::Rect) {
        return; // One level (ARB_texture_rectangle).
    }
    let Some(top) = obj.level(face, base).cloned() else { return };
    let dims = obj.target.map_or(2, |t| t.dims());
    let border = top.border;
    let mut size: [usize; 3] = std::array::from_fn(|i| if i < dims { top.size[i] - 2 * border } else { 1 });
    let mut texels = interior(&top.image.texels, 4, top.size, border);
    let mut depth = interior(&top.image.depth_values, 1, top.size, border);
    let mut values = interior(&top.image.values, 4, top.size, border);
    let mut integers = interior(&top.image.integers, 4, top.size, border);
    let precision = top.image.precision;
    let base_format = match top.base {
        Base::ColorIndex => Base::Texel(TexelFormat::Rgba),
        b => b,
    };
    let mut level = base;
    while size.iter().any(|&s| s > 1) && level + 1 < obj.faces.first().map_or(0, Vec::len) {
        let (next, next_size) = downsample(&texels, size);
        let next_depth = if depth.is_empty() { Vec::new() } else { downsample_floats(&depth, 1, size) };
        let next_values = if values.is_empty() { Vec::new() } else { downsample_floats(&values, 4, size) };
        let next_integers = if integers.is_empty() { Vec::new() } else { downsample_integers(&integers, size) };
        level += 1;
        let [w, h, d] = next_size.map(|v| v as u32);
        let mut generated = Level {
            image: Arc::new(TexImage { width: w, height: h, depth: d, border: 0, texels: next.clone(), precision, values: next_values.clone(), integers: next_integers.clone(), depth_values: next_depth.clone() }),
            size: next_size,
            border: 0,
            internal_format: top.internal_format,
            base: base_format,
            compressed: None,
            indices: None,
            stencil: top.stencil.as_ref().map(|_| Arc::new(vec![0; next_size.iter().product()])),
        };
        super::compressed::recompress(&mut generated);
        *obj.level_slot(face, level) = Some(generated);
        texels = next;
        depth = next_depth;
        values = next_values;
        integers = next_integers;
        size = next_size;
    }
}

#[cfg(test)]
mod tests {
    use super::{downsample, downsample_floats};

    #[test]
    fn box_filter_averages_and_rounds() {
        // 2×2 → 1×1: (10 + 20 + 30 + 41) / 4 = 25.25 → 25; alpha (255 × 3 + 0) / 4 = 191.25 → 191.
        let src = [10, 0, 0, 255, 20, 0, 0, 255, 30, 0, 0, 255, 41, 0, 0, 0];
        assert_eq!(downsample(&src, [2, 2, 1]), (vec![25, 0, 0, 191], [1, 1, 1]));
        // 4×1 → 2×1: pairs only horizontally.
        let row = [0, 0, 0, 0, 100, 100, 100, 100, 1, 1, 1, 1, 2, 2, 2, 2];
        assert_eq!(downsample(&row, [4, 1, 1]), (vec![50, 50, 50, 50, 2, 2, 2, 2], [2, 1, 1]));
        // Depth averages without rounding to 8 bits.
        assert_eq!(downsample_floats(&[0.125, 0.25, 0.5, 0.0], 1, [2, 2, 1]), vec![0.21875]);
        assert_eq!(downsample_floats(&[0.1, 0.3, 1.0, 0.5], 1, [4, 1, 1]), vec![0.2, 0.75]);
        // Float levels average each of their four values, beyond [0, 1] too.
        assert_eq!(downsample_floats(&[-1.0, 2.0, 0.0, 0.0, -3.0, 4.0, 0.0, 1.0], 4, [2, 1, 1]), vec![-2.0, 3.0, 0.0, 0.5]);
    }
}
