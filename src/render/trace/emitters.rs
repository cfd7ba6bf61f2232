//! The emitter list: the frame's emissive triangles, which next-event estimation samples
//! (`shaders/trace/emitters.glsl`), with the alias table (Walker 1977, Vose 1991) that draws
//! one in proportion to its estimated power in constant time.
//!
//! Listed are the triangles of the surfaces whose emission is light placed by the program
//! ([`is_emissive`]): surfaces with an emission pass (an additive glow over traced geometry)
//! and emissive materials (GL material emission, `glrt.toml` `emissive`). The raster colour
//! that baked surfaces emit ([`super::material`]) is not listed: it is the light of the whole
//! world, everywhere, and continuation rays find it.
//!
//! Each listed instance has one entry per triangle, in its BVH order, from its material's
//! `emitters` index on, so the shader finds the probability of the triangle a continuation ray
//! hit (for the MIS weight) without a search. A triangle's weight is its eye-space area times
//! an estimate of its emitted radiance ([`Estimate`]): the luminance of its emission passes'
//! mean corner colour times their texture's average colour (decoded to linear), plus the
//! material's emission. The estimate need not be exact: the sampling is unbiased whatever it
//! is, as long as it is not 0 where the surface emits (a triangle of weight 0 is found by
//! continuation rays alone, with full weight).

use glam::{Mat3, Mat4, Vec3};

use super::bvh::GpuTriangle;
use super::gpu_types::{GpuEmitter, GpuLayerCorners, GpuMaterial, GpuTriangleAttributes};
use super::scene::srgb_to_linear;
use super::shader_constants::{LAYER_EMISSION, LAYER_OFF, NO_TEXTURE, TRACED_UNITS};

/// Most entries of one frame's list; the instances past it are not listed (continuation rays
/// still find them).
pub const MAX_EMITTERS: usize = 1 << 20;

/// Whether the surfaces of material `m` are listed: an emission pass, or emission of their
/// own.
pub fn is_emissive(m: &GpuMaterial) -> bool {
    m.layer[TRACED_UNITS..].iter().take(m.passes as usize).any(|l| l.role == LAYER_EMISSION) || m.emission.iter().any(|&e| e > 0.0)
}

/// Rec. 709 luminance of linear `c`.
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Unpacks a unorm8 RGBA word.
fn unpack(word: u32) -> [f32; 4] {
    std::array::from_fn(|i| ((word >> (8 * i)) & 0xff) as f32 / 255.0)
}

/// The mean of three packed corner colours, display-encoded RGBA.
fn mean(colors: [u32; 3]) -> [f32; 4] {
    let c = colors.map(unpack);
    std::array::from_fn(|i| (c[0][i] + c[1][i] + c[2][i]) / 3.0)
}

/// The estimated emitted radiance (luminance) of a triangle of a material, from the average
/// colour of each texture in the texel pool.
pub struct Estimate<'a> {
    /// The material.
    pub material: &'a GpuMaterial,
    /// The average colour (packed like a texel) of texel pool texture `i`.
    pub average: &'a dyn Fn(u32) -> u32,
}

impl Estimate<'_> {
    /// The luminance a triangle with `attributes` and pass corners `corners` (the material's
    /// passes) emits, roughly (see the module doc).
    pub fn radiance(&self, attributes: &GpuTriangleAttributes, corners: &[GpuLayerCorners]) -> f32 {
        let m = self.material;
        let texture = |t: u32| if t == NO_TEXTURE { [1.0; 4] } else { unpack((self.average)(t)) };
        let linear = |c: [f32; 4]| Vec3::new(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]));
        let modulate = |a: [f32; 4], b: [f32; 4]| std::array::from_fn::<f32, 4, _>(|i| a[i] * b[i]);
        let mut e = luminance(Vec3::new(m.emission[0], m.emission[1], m.emission[2]));
        if m.emission[3] > 0.0 {
            let color = m.layer[..TRACED_UNITS].iter().filter(|l| l.role != LAYER_OFF).fold(mean(attributes.corner.map(|c| c.color)), |c, l| modulate(c, texture(l.texture)));
            e += m.emission[3] * luminance(linear(color));
        }
        for (layer, corner) in m.layer[TRACED_UNITS..].iter().zip(corners) {
            if layer.role == LAYER_EMISSION && corner.covered != 0 {
                let color = modulate(mean(corner.color), texture(layer.texture));
                e += luminance(linear(color));
            }
        }
        e
    }

    /// The weight of each triangle of a geometry placed by `object_to_eye` (its eye-space
    /// area times [`Estimate::radiance`]): `triangles`, `attributes` and the pass corners
    /// `corners` (the material's `passes` records per triangle), in BVH order.
    pub fn weights(&self, triangles: &[GpuTriangle], attributes: &[GpuTriangleAttributes], corners: &[GpuLayerCorners], object_to_eye: &Mat4) -> Vec<f32> {
        let passes = self.material.passes as usize;
        let corners_of = |t: usize| corners.get(t * passes..(t + 1) * passes).unwrap_or(&[]);
        triangles.iter().zip(attributes).enumerate().map(|(t, (triangle, a))| area(triangle, object_to_eye) * self.radiance(a, corners_of(t))).collect()
    }
}

/// The eye-space area of `t` placed by `object_to_eye`.
pub fn area(t: &GpuTriangle, object_to_eye: &Mat4) -> f32 {
    let m = Mat3::from_mat4(*object_to_eye);
    let e1 = m * Vec3::from_array(t.e1);
    let e2 = m * Vec3::from_array(t.e2);
    0.5 * e1.cross(e2).length()
}

/// The emitter list of a frame, built instance by instance.
#[derive(Debug, Default)]
pub struct EmitterList {
    /// Per entry: its instance, its triangle (global index) and its weight.
    entries: Vec<(u32, u32, f32)>,
}

impl EmitterList {
    /// Lists the triangles of instance `instance` (global indices from `first_triangle`) with
    /// `weights`; returns the index of its first entry, or `None` when it is not listed (no
    /// weight, or the list is full).
    pub fn add(&mut self, instance: u32, first_triangle: u32, weights: &[f32]) -> Option<u32> {
        let total: f32 = weights.iter().sum();
        if !(total > 0.0 && total.is_finite()) || self.entries.len() + weights.len() > MAX_EMITTERS {
            return None;
        }
        let first = self.entries.len() as u32;
        self.entries.extend(weights.iter().enumerate().map(|(i, &w)| (instance, first_triangle + i as u32, w.max(0.0))));
        Some(first)
    }

    /// Entries listed so far.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether nothing is listed.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The entries with their alias table: entry `i` is kept with probability
    /// `threshold`, else its `alias` is taken, so that triangle `i` is drawn with probability
    /// `probability` = its weight over the total.
    pub fn finish(self) -> Vec<GpuEmitter> {
        let n = self.entries.len();
        let total: f64 = self.entries.iter().map(|e| f64::from(e.2)).sum();
        let mut out: Vec<GpuEmitter> = self
            .entries
            .iter()
            .enumerate()
            .map(|(i, &(instance, triangle, w))| GpuEmitter { instance, triangle, alias: i as u32, threshold: 1.0, probability: (f64::from(w) / total) as f32 })
            .collect();
        // Vose's method: scaled probabilities below 1 take the rest of their column from one
        // above 1.
        let mut scaled: Vec<f64> = self.entries.iter().map(|e| f64::from(e.2) / total * n as f64).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(s), Some(&l)) = (small.pop(), large.last()) {
            out[s].threshold = scaled[s] as f32;
            out[s].alias = l as u32;
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::trace::gpu_types::{GpuCorner, GpuLayer};
    use crate::render::trace::shader_constants::{LAYER_COLOR, MATERIAL_LAYERS};

    /// The probability that the alias method draws each entry of `table`.
    fn drawn(table: &[GpuEmitter]) -> Vec<f64> {
        let n = table.len() as f64;
        let mut p = vec![0.0; table.len()];
        for (i, e) in table.iter().enumerate() {
            p[i] += f64::from(e.threshold) / n;
            p[e.alias as usize] += (1.0 - f64::from(e.threshold)) / n;
        }
        p
    }

    #[test]
    fn the_alias_table_draws_each_triangle_by_its_weight() {
        let mut list = EmitterList::default();
        assert_eq!(list.add(3, 100, &[1.0, 0.0, 6.0, 2.0]), Some(0));
        assert_eq!(list.add(4, 7, &[0.0, 0.0]), None, "nothing emits");
        assert_eq!(list.add(5, 10, &[1.0]), Some(4));
        assert_eq!(list.len(), 5);
        let table = list.finish();
        assert_eq!(table.iter().map(|e| (e.instance, e.triangle)).collect::<Vec<_>>(), [(3, 100), (3, 101), (3, 102), (3, 103), (5, 10)]);
        let weights = [1.0, 0.0, 6.0, 2.0, 1.0];
        for (i, (p, e)) in drawn(&table).iter().zip(&table).enumerate() {
            let want = weights[i] / 10.0;
            assert!((p - want).abs() < 1e-6 && (f64::from(e.probability) - want).abs() < 1e-6, "entry {i}: drawn {p}, listed {}, weight {want}", e.probability);
        }
        assert!(table.iter().all(|e| (0.0..=1.0).contains(&e.threshold)));
        assert!(EmitterList::default().is_empty() && EmitterList::default().finish().is_empty());
    }

    #[test]
    fn emission_passes_and_emissive_materials_are_listed() {
        let mut m = GpuMaterial { passes: 1, ..GpuMaterial::default() };
        assert!(!is_emissive(&m));
        m.layer[TRACED_UNITS].role = LAYER_EMISSION;
        assert!(is_emissive(&m));
        m.passes = 0;
        assert!(!is_emissive(&m), "a pass slot past the surface's passes");
        assert!(is_emissive(&GpuMaterial { emission: [0.0, 0.0, 0.0, 1.0], ..GpuMaterial::default() }));
        assert!(is_emissive(&GpuMaterial { emission: [0.0, 0.5, 0.0, 0.0], ..GpuMaterial::default() }));
    }

    #[test]
    fn estimates_follow_colours_textures_and_coverage() {
        let grey = |v: u8| u32::from_le_bytes([v, v, v, 255]);
        let mut layer = [GpuLayer { texture: NO_TEXTURE, ..GpuLayer::default() }; MATERIAL_LAYERS];
        layer[TRACED_UNITS] = GpuLayer { role: LAYER_EMISSION, texture: 0, ..GpuLayer::default() };
        layer[0] = GpuLayer { role: LAYER_COLOR, texture: 1, ..GpuLayer::default() };
        let m = GpuMaterial { layer, passes: 1, ..GpuMaterial::default() };
        let average = |t: u32| if t == 0 { grey(255) } else { grey(128) };
        let estimate = Estimate { material: &m, average: &average };
        let attributes = GpuTriangleAttributes { corner: [GpuCorner { color: grey(255), ..GpuCorner::default() }; 3] };
        let glow = GpuLayerCorners { color: [grey(255), grey(255), grey(0)], covered: 1, ..GpuLayerCorners::default() };
        let e = estimate.radiance(&attributes, &[glow]);
        assert!((e - srgb_to_linear(2.0 / 3.0)).abs() < 1e-4, "{e}");
        assert_eq!(estimate.radiance(&attributes, &[GpuLayerCorners { covered: 0, ..glow }]), 0.0, "uncovered: no glow");
        let emissive = GpuMaterial { emission: [0.0, 0.0, 0.0, 2.0], ..m };
        let e = Estimate { material: &emissive, average: &average }.radiance(&attributes, &[GpuLayerCorners::default()]);
        assert!((e - 2.0 * srgb_to_linear(128.0 / 255.0)).abs() < 1e-4, "2 × unit 0's texture: {e}");
        let t = GpuTriangle { v0: [0.0; 3], e1: [2.0, 0.0, 0.0], e2: [0.0, 3.0, 0.0], ..bytemuck::Zeroable::zeroed() };
        let scale = Mat4::from_scale(Vec3::new(1.0, 2.0, 5.0));
        assert!((area(&t, &scale) - 6.0).abs() < 1e-6);
        let weights = estimate.weights(&[t, t], &[attributes; 2], &[glow, GpuLayerCorners::default()], &scale);
        assert!((weights[0] - 6.0 * srgb_to_linear(2.0 / 3.0)).abs() < 1e-3 && weights[1] == 0.0, "{weights:?}");
    }
}
