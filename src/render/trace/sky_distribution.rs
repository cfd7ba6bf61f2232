//! A distribution of directions for sampling the sky (issue 16, item 4: next-event estimation
//! towards the environment, [`super::sky`]): in proportion to the sky cube's luminance times
//! solid angle, over a low-resolution grid of [`CELLS`]² cells per face.
//!
//! **Building** ([`SkyDistribution::build`]): each cell's weight is the mean linear luminance
//! (Rec. 709) of the cube texels it covers times the cell's solid angle (exact: the solid angle
//! of a rectangle on a cube face, [`face_solid_angle`]), plus a share of the mean weight
//! ([`UNIFORM_SHARE`]), so that every direction keeps a density above zero (a sky brighter
//! than its texels say, a sun between cells, is still found). The cells' weights make a
//! cumulative distribution in cell order (face by face in Vulkan's layer order, rows from the
//! top, columns from the left).
//!
//! **Sampling** ([`SkyDistribution::sample`]): a cell by the cumulative distribution, then a
//! point uniform in the cell's face coordinates. The density in solid angle of direction `d`
//! ([`SkyDistribution::density`]) is the cell's probability over its area in face coordinates
//! (`(2 / CELLS)²`, the face spanning `[-1, 1]²`), times the Jacobian from face coordinates
//! to solid angle, `(1 + s² + t²)^(3/2)` at face coordinates `(s, t)`. It integrates to 1 over
//! the sphere, and the sampled direction's density is the one returned with it.
//!
//! Face coordinates follow Vulkan's cube map face selection (as [`super::sky`]'s faces are
//! drawn): face `f` and `(s, t)` in `[-1, 1]²` (t from the top row) name the direction
//! [`direction`] gives.

use glam::Vec3;

use super::scene::srgb_to_linear;
use super::shader_constants::SKY_CELLS as CELLS;

/// The share of the mean cell weight added to every cell.
const UNIFORM_SHARE: f64 = 0.1;

/// The direction (not normalised) of face coordinates `(s, t)` of face `face` (Vulkan's layer
/// order: +X, −X, +Y, −Y, +Z, −Z; `t` from the top row).
pub fn direction(face: usize, s: f32, t: f32) -> Vec3 {
    match face {
        0 => Vec3::new(1.0, -t, -s),
        1 => Vec3::new(-1.0, -t, s),
        2 => Vec3::new(s, 1.0, t),
        3 => Vec3::new(s, -1.0, -t),
        4 => Vec3::new(s, -t, 1.0),
        _ => Vec3::new(-s, -t, -1.0),
    }
}

/// The face and face coordinates `(s, t)` of direction `d` (Vulkan's cube map face selection).
pub fn face_coordinates(d: Vec3) -> (usize, f32, f32) {
    let a = d.abs();
    let (face, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
        if d.x > 0.0 { (0, -d.z, -d.y, a.x) } else { (1, d.z, -d.y, a.x) }
    } else if a.y >= a.z {
        if d.y > 0.0 { (2, d.x, d.z, a.y) } else { (3, d.x, -d.z, a.y) }
    } else if d.z > 0.0 {
        (4, d.x, -d.y, a.z)
    } else {
        (5, -d.x, -d.y, a.z)
    };
    (face, sc / ma, tc / ma)
}

/// The solid angle of the rectangle `[s0, s1] × [t0, t1]` of a cube face (face coordinates in
/// `[-1, 1]`): `Σ ± atan2(s t, √(s² + t² + 1))` over its corners.
pub fn face_solid_angle(s0: f64, s1: f64, t0: f64, t1: f64) -> f64 {
    let corner = |s: f64, t: f64| (s * t).atan2((s * s + t * t + 1.0).sqrt());
    corner(s1, t1) - corner(s0, t1) - corner(s1, t0) + corner(s0, t0)
}

/// The face coordinate of the low edge of cell `i` (`i = CELLS`: the high edge of the last).
fn cell_edge(i: usize) -> f64 {
    2.0 * i as f64 / CELLS as f64 - 1.0
}

/// The sky's distribution of directions (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct SkyDistribution {
    /// Per cell (`face · CELLS² + row · CELLS + column`), its probability.
    pub probability: Vec<f32>,
    /// Per cell, the probability of the cells before it and of itself: the cumulative
    /// distribution (its last entry is 1).
    pub cumulative: Vec<f32>,
}

impl SkyDistribution {
    /// The distribution of the cube whose faces are `faces` (Vulkan's layer order, each
    /// `size`² RGBA8 texels, sRGB-encoded, rows from the top: what [`super::sky`] draws), or
    /// `None` when the cube is black (nothing to sample) or not `size`² texels a face.
    pub fn build(faces: &[&[u8]; 6], size: usize) -> Option<SkyDistribution> {
        if size == 0 || faces.iter().any(|f| f.len() != size * size * 4) {
            return None;
        }
        let decode: Vec<f64> = (0..=255u8).map(|c| f64::from(srgb_to_linear(f32::from(c) / 255.0))).collect();
        let luminance = |p: &[u8]| 0.2126 * decode[p[0] as usize] + 0.7152 * decode[p[1] as usize] + 0.0722 * decode[p[2] as usize];
        let mut weights = vec![0.0f64; 6 * CELLS * CELLS];
        for (face, texels) in faces.iter().enumerate() {
            // Each texel adds to the cell its centre lies in, counted per cell.
            let mut sums = vec![(0.0f64, 0u32); CELLS * CELLS];
            for row in 0..size {
                for column in 0..size {
                    let cell = (row * CELLS / size) * CELLS + column * CELLS / size;
                    let i = (row * size + column) * 4;
                    sums[cell].0 += luminance(&texels[i..i + 4]);
                    sums[cell].1 += 1;
                }
            }
            for (cell, (sum, count)) in sums.into_iter().enumerate() {
                let (row, column) = (cell / CELLS, cell % CELLS);
                let omega = face_solid_angle(cell_edge(column), cell_edge(column + 1), cell_edge(row), cell_edge(row + 1));
                // Faces smaller than the grid leave cells without texels: those of their texel.
                let mean = if count > 0 { sum / f64::from(count) } else { luminance_at(texels, size, row, column, &luminance) };
                weights[face * CELLS * CELLS + cell] = mean * omega;
            }
        }
        let total: f64 = weights.iter().sum();
        if total <= 0.0 {
            return None;
        }
        let floor = UNIFORM_SHARE * total / weights.len() as f64;
        weights.iter_mut().for_each(|w| *w += floor);
        let total: f64 = weights.iter().sum();
        let probability: Vec<f32> = weights.iter().map(|w| (w / total) as f32).collect();
        let mut running = 0.0f64;
        let mut cumulative: Vec<f32> = weights
            .iter()
            .map(|w| {
                running += w / total;
                running as f32
            })
            .collect();
        if let Some(last) = cumulative.last_mut() {
            *last = 1.0;
        }
        Some(SkyDistribution { probability, cumulative })
    }

    /// Per cell, its probability and cumulative probability: the `SKY_DISTRIBUTION` records
    /// the shaders sample (`trace/sky_sampling.glsl`).
    pub fn cells(&self) -> Vec<[f32; 2]> {
        self.probability.iter().zip(&self.cumulative).map(|(&p, &c)| [p, c]).collect()
    }

    /// A direction (unit) drawn from the distribution by the uniform numbers `u` (each in
    /// `[0, 1)`), with its density in solid angle.
    pub fn sample(&self, u: [f32; 3]) -> (Vec3, f32) {
        let cell = self.cumulative.partition_point(|&c| c <= u[0]).min(self.cumulative.len() - 1);
        let (face, row, column) = (cell / (CELLS * CELLS), cell / CELLS % CELLS, cell % CELLS);
        let s = (cell_edge(column) + (cell_edge(column + 1) - cell_edge(column)) * f64::from(u[1])) as f32;
        let t = (cell_edge(row) + (cell_edge(row + 1) - cell_edge(row)) * f64::from(u[2])) as f32;
        (direction(face, s, t).normalize(), self.cell_density(cell, s, t))
    }

    /// The density in solid angle with which [`SkyDistribution::sample`] draws direction `d`.
    pub fn density(&self, d: Vec3) -> f32 {
        let (face, s, t) = face_coordinates(d);
        let index = |x: f32| ((x + 1.0) * 0.5 * CELLS as f32).floor().clamp(0.0, CELLS as f32 - 1.0) as usize;
        self.cell_density(face * CELLS * CELLS + index(t) * CELLS + index(s), s, t)
    }

    /// The density in solid angle at face coordinates `(s, t)` of cell `cell`.
    fn cell_density(&self, cell: usize, s: f32, t: f32) -> f32 {
        let area = (2.0 / CELLS as f32).powi(2);
        self.probability[cell] / area * (1.0 + s * s + t * t).powf(1.5)
    }
}

/// The luminance of the texel of a `size`² face under cell (`row`, `column`)'s centre.
fn luminance_at(texels: &[u8], size: usize, row: usize, column: usize, luminance: &impl Fn(&[u8]) -> f64) -> f64 {
    let texel = |cell: usize| ((cell * 2 + 1) * size / (2 * CELLS)).min(size - 1);
    let i = (texel(row) * size + texel(column)) * 4;
    luminance(&texels[i..i + 4])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Six faces of `size`² texels of grey `value`, with the texels for which `bright(face,
    /// row, column)` holds white.
    fn cube(size: usize, value: u8, bright: impl Fn(usize, usize, usize) -> bool) -> Vec<Vec<u8>> {
        (0..6)
            .map(|face| {
                (0..size * size)
                    .flat_map(|i| {
                        let v = if bright(face, i / size, i % size) { 255 } else { value };
                        [v, v, v, 255]
                    })
                    .collect()
            })
            .collect()
    }

    fn build(faces: &[Vec<u8>], size: usize) -> Option<SkyDistribution> {
        let faces: [&[u8]; 6] = std::array::from_fn(|f| faces[f].as_slice());
        SkyDistribution::build(&faces, size)
    }

    #[test]
    fn faces_tile_the_sphere() {
        let total: f64 = (0..CELLS).flat_map(|r| (0..CELLS).map(move |c| (r, c))).map(|(r, c)| face_solid_angle(cell_edge(c), cell_edge(c + 1), cell_edge(r), cell_edge(r + 1))).sum();
        assert!((6.0 * total - 4.0 * std::f64::consts::PI).abs() < 1e-9, "{}", 6.0 * total);
        for face in 0..6 {
            for (s, t) in [(-0.9, 0.3), (0.5, -0.7), (0.0, 0.0)] {
                let (f, s2, t2) = face_coordinates(direction(face, s, t));
                assert_eq!(f, face);
                assert!((s2 - s).abs() < 1e-6 && (t2 - t).abs() < 1e-6, "face {face}: ({s}, {t}) came back as ({s2}, {t2})");
            }
        }
    }

    /// The density integrates to 1 over the sphere (midpoint rule, 64² points a face), for a
    /// uniform sky and for one with a small bright patch.
    #[test]
    fn the_density_integrates_to_one() {
        let size = 32;
        let skies = [cube(size, 100, |_, _, _| false), cube(size, 10, |face, row, column| face == 2 && (5..8).contains(&row) && (20..22).contains(&column))];
        for faces in &skies {
            let d = build(faces, size).expect("a sky");
            let n = 64;
            let mut integral = 0.0f64;
            for face in 0..6 {
                for i in 0..n {
                    for j in 0..n {
                        let edge = |k: usize| 2.0 * k as f64 / n as f64 - 1.0;
                        let (s, t) = (0.5 * (edge(j) + edge(j + 1)), 0.5 * (edge(i) + edge(i + 1)));
                        let omega = face_solid_angle(edge(j), edge(j + 1), edge(i), edge(i + 1));
                        integral += f64::from(d.density(direction(face, s as f32, t as f32))) * omega;
                    }
                }
            }
            assert!((integral - 1.0).abs() < 1e-3, "∫ density dω = {integral}");
            assert!((d.probability.iter().map(|&p| f64::from(p)).sum::<f64>() - 1.0).abs() < 1e-5);
        }
    }

    /// Each sampled direction comes with the density [`SkyDistribution::density`] gives it,
    /// and the samples fall in the bright patch as often as its share of luminance × solid
    /// angle says.
    #[test]
    fn samples_follow_the_luminance_and_carry_their_density() {
        let size = 32;
        // Face +Y (up), rows 4..8 and columns 20..24 of 32: four cells of the 16² grid.
        let patch = |face: usize, row: usize, column: usize| face == 2 && (4..8).contains(&row) && (20..24).contains(&column);
        let faces = cube(size, 5, patch);
        let d = build(&faces, size).expect("a sky");
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 40) as f32 / (1u64 << 24) as f32
        };
        let (mut inside, n) = (0usize, 20000);
        for _ in 0..n {
            let (dir, density) = d.sample([next(), next(), next()]);
            assert!((dir.length() - 1.0).abs() < 1e-5);
            let again = d.density(dir);
            assert!((density - again).abs() <= 1e-3 * density, "{dir}: sampled with {density}, density {again}");
            let (face, s, t) = face_coordinates(dir);
            let texel = |x: f32| (((x + 1.0) * 0.5 * size as f32) as usize).min(size - 1);
            inside += usize::from(patch(face, texel(t), texel(s)));
        }
        // The patch's share of the weights (cells 2..4 by 10..12 of face +Y).
        let cells = (2..4).flat_map(|r| (10..12).map(move |c| 2 * CELLS * CELLS + r * CELLS + c));
        let share: f64 = cells.map(|c| f64::from(d.probability[c])).sum();
        let measured = inside as f64 / n as f64;
        assert!(share > 0.5, "the bright patch holds most of the weight: {share}");
        assert!((measured - share).abs() < 0.02, "samples in the patch: {measured}, its probability {share}");
    }

    #[test]
    fn a_black_sky_has_no_distribution() {
        assert_eq!(build(&cube(8, 0, |_, _, _| false), 8), None);
        assert_eq!(build(&cube(8, 50, |_, _, _| false), 9), None, "faces of another size");
    }
}
