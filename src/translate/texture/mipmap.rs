//! `GL_GENERATE_MIPMAP` (OpenGL 1.5 section 3.8.8, "Automatic Mipmap Generation"): each level
//! below the changed base level is a 2×2(×2) box filter of the one above
//! ([`crate::frame::mipmap`]), down to 1×1.

use std::sync::Arc;

use super::formats::Base;
use super::objects::{Level, TextureObject};
use crate::frame::mipmap::{downsample, downsample_floats, downsample_integers};
use crate::frame::texture::{TexImage, TexelFormat};

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
