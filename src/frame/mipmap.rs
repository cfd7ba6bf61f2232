//! The box filter that makes a mipmap level from the one above it (OpenGL 1.5 section 3.8.8,
//! "Automatic Mipmap Generation": each texel the average of a 2×2(×2) block): one definition
//! for `translate`, which generates levels for `GL_GENERATE_MIPMAP`, and the renderer, which
//! completes a texture's chain down to 1×1 the same way for the tracer's texture LOD.

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
