//! The transfer of the patches' radiosity to the raster draws of the static world: per
//! vertex, the indirect light that replaces the GL lighting's scene ambient term (`ff.vert`
//! under the shader key's `RADIOSITY`: material diffuse × indirect irradiance / π, GL's
//! vertex lighting carrying it across the triangle like the rest of its light). The
//! radiosity is in the tracer's linear units (a GL light of diffuse colour `d` lights as
//! `π · linear(d)`, [`crate::render::trace::lights`]), so the shader adds the reflected
//! indirect light to GL's light in linear units and encodes the sum for display again, as
//! the tracer's image is encoded.
//!
//! - **Per patch.** The indirect irradiance is what the bounces added: `(B − P) / albedo`
//!   per channel (the radiosity less the primary radiosity is the reflected bounced light;
//!   0 where the albedo is), kept as irradiance / π, the factor GL's diffuse colour
//!   multiplies (its direct term is `diffuse · light · cos`, a radiance for a white light).
//! - **Per vertex.** The patches around the vertex's world position on its side of the
//!   surface (normals within 60°), weighted by `cos⁴ · (1 − d / R)²` over the reach `R`
//!   ([`REACH`] typical patch sides); where none is that near, the nearest such patch.
//!   Patches are found through a grid of cells of side `R`.
//! - **Which draws.** Static draws lit by GL lighting, without a program ([`receives`]).
//!   Lightmapped surfaces (Quake 3's) are unlit, their light baked in the lightmap (unit 1 or
//!   a layer pass): they keep it, as every unlit draw, which has no ambient term to replace. A
//!   lit draw whose unit 1 modulates its light (the demo's room darkens its corners so)
//!   modulates the indirect light as it does the rest.

use std::collections::HashMap;

use glam::{Mat3, Mat4, Vec3};

use super::patches::Patches;
use crate::frame::Draw;
use crate::frame::class::DrawClass;

/// Reach of the per-vertex interpolation, in typical patch sides (square roots of the mean
/// patch area).
pub const REACH: f32 = 1.5;
/// Smallest cosine between a vertex's normal and a patch's that the patch lights.
const MIN_COSINE: f32 = 0.5;

/// The patches' indirect light, found by position.
#[derive(Clone, Debug, Default)]
pub struct IndirectLight {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    /// Indirect irradiance / π per patch.
    light: Vec<Vec3>,
    /// Reach `R` and side of the grid's cells.
    reach: f32,
    cells: HashMap<[i32; 3], Vec<u32>>,
}

impl IndirectLight {
    /// The indirect light of `patches` whose radiosity is `radiosity` and primary radiosity
    /// `primary` (one value per patch each).
    pub fn new(patches: &Patches, radiosity: &[Vec3], primary: &[Vec3]) -> IndirectLight {
        let n = patches.patches.len();
        let area: f32 = patches.patches.iter().map(|p| p.area).sum();
        let reach = REACH * (area / n.max(1) as f32).sqrt();
        let mut out = IndirectLight { reach: if reach > 0.0 { reach } else { 1.0 }, ..IndirectLight::default() };
        for (i, p) in patches.patches.iter().enumerate() {
            let bounced = (radiosity.get(i).copied().unwrap_or_default() - primary.get(i).copied().unwrap_or_default()).max(Vec3::ZERO);
            let irradiance = Vec3::select(p.albedo.cmpgt(Vec3::ZERO), bounced / p.albedo.max(Vec3::splat(f32::MIN_POSITIVE)), Vec3::ZERO);
            out.positions.push(p.position);
            out.normals.push(p.normal);
            out.light.push(irradiance / std::f32::consts::PI);
            out.cells.entry(out.cell(p.position)).or_default().push(i as u32);
        }
        out
    }

    fn cell(&self, p: Vec3) -> [i32; 3] {
        (p / self.reach).floor().as_ivec3().to_array()
    }

    /// Indirect irradiance / π at world position `position` on a surface facing `normal`.
    pub fn at(&self, position: Vec3, normal: Vec3) -> Vec3 {
        let n = normal.normalize_or_zero();
        let [cx, cy, cz] = self.cell(position);
        let (mut sum, mut weights) = (Vec3::ZERO, 0.0f32);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &i in self.cells.get(&[cx + dx, cy + dy, cz + dz]).map_or(&[][..], |v| &v[..]) {
                        let i = i as usize;
                        let cos = n.dot(self.normals[i]);
                        let d = position.distance(self.positions[i]);
                        if cos < MIN_COSINE || d >= self.reach {
                            continue;
                        }
                        let w = cos.powi(4) * (1.0 - d / self.reach).powi(2);
                        sum += w * self.light[i];
                        weights += w;
                    }
                }
            }
        }
        if weights > 0.0 {
            return sum / weights;
        }
        let nearest = (0..self.positions.len())
            .filter(|&i| n.dot(self.normals[i]) >= MIN_COSINE)
            .min_by(|&a, &b| position.distance_squared(self.positions[a]).total_cmp(&position.distance_squared(self.positions[b])));
        nearest.map_or(Vec3::ZERO, |i| self.light[i])
    }

    /// The indirect light on each vertex of `draw` (drawn with the world-to-eye transform
    /// whose inverse is `eye_to_world`), when it [`receives`] it.
    pub fn of_draw(&self, draw: &Draw, eye_to_world: &Mat4) -> Option<Vec<[f32; 3]>> {
        if !receives(draw) {
            return None;
        }
        let to_world = *eye_to_world * draw.modelview;
        let normals = Mat3::from_mat4(*eye_to_world) * Mat3::from_mat4(draw.modelview).inverse().transpose();
        let v = &draw.vertices;
        Some(
            v.position
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let position = to_world.project_point3(Vec3::new(p[0], p[1], p[2]) / if p[3] != 0.0 { p[3] } else { 1.0 });
                    let normal = normals * Vec3::from(v.normal.get(i).unwrap_or([0.0, 0.0, 1.0]));
                    self.at(position, normal).to_array()
                })
                .collect(),
        )
    }
}

/// Whether `draw` gets radiosity's indirect light: static, lit by GL lighting, no program.
pub fn receives(draw: &Draw) -> bool {
    draw.class == DrawClass::Static && draw.state.lighting.is_some() && draw.program.is_none()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::patches::Patch;

    /// Patches of side 1 on the floor z = 0 (x in 0..4) and on the wall x = 0 facing +x.
    fn floor_and_wall() -> Patches {
        let mut patches = Vec::new();
        for i in 0..4 {
            patches.push(Patch { position: Vec3::new(i as f32 + 0.5, 0.5, 0.0), normal: Vec3::Z, area: 1.0, albedo: Vec3::splat(0.5), emission: Vec3::ZERO, triangles: 0..0 });
        }
        patches.push(Patch { position: Vec3::new(0.0, 0.5, 0.5), normal: Vec3::X, area: 1.0, albedo: Vec3::new(0.5, 0.25, 0.0), emission: Vec3::ZERO, triangles: 0..0 });
        Patches { patches, ..Patches::default() }
    }

    #[test]
    fn bounced_light_over_albedo_over_pi_per_patch() {
        let p = floor_and_wall();
        let primary = vec![Vec3::splat(1.0); 5];
        let radiosity: Vec<Vec3> = (0..5).map(|i| Vec3::splat(1.0 + 0.1 * i as f32)).collect();
        let light = IndirectLight::new(&p, &radiosity, &primary);
        let pi = std::f32::consts::PI;
        // Past the reach of every patch: the nearest on the vertex's side.
        let far = light.at(Vec3::new(10.0, 0.5, 0.0), Vec3::Z);
        assert!((far - Vec3::splat(0.3 / 0.5 / pi)).length() < 1e-6, "{far}");
        // The wall: its own patch, the blue channel with zero albedo gives 0.
        let wall = light.at(Vec3::new(0.0, 0.5, 0.5), Vec3::X);
        assert!((wall - Vec3::new(0.4 / 0.5 / pi, 0.4 / 0.25 / pi, 0.0)).length() < 1e-5, "{wall}");
        // Halfway between floor patches 1 and 2: between their values, symmetric weights.
        let mid = light.at(Vec3::new(2.0, 0.5, 0.0), Vec3::Z);
        assert!(mid.x > 0.1 / 0.5 / pi && mid.x < 0.2 / 0.5 / pi, "{mid}");
        // A surface facing down sees none of them.
        assert_eq!(light.at(Vec3::new(1.0, 0.5, 0.0), -Vec3::Z), Vec3::ZERO);
    }

    #[test]
    fn only_lit_static_draws_receive_it() {
        use crate::frame::state::{Lighting, RasterState};
        let lit = std::sync::Arc::new(RasterState { lighting: Some(Lighting::default()), ..RasterState::default() });
        let mut draw = Draw { class: DrawClass::Static, state: lit, ..Draw::default() };
        draw.vertices.position = vec![[1.0, 0.5, 0.0, 1.0], [0.0, 0.5, 0.5, 1.0]];
        draw.vertices.normal.values = vec![[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
        let p = floor_and_wall();
        let light = IndirectLight::new(&p, &[Vec3::splat(2.0); 5], &[Vec3::ONE; 5]);
        // The eye frame turned a quarter about z from the world: the draw's normals come back.
        let view = Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let eye_draw = Draw { modelview: view, ..draw.clone() };
        let out = light.of_draw(&eye_draw, &view.inverse()).expect("received");
        let expected = [light.at(Vec3::new(1.0, 0.5, 0.0), Vec3::Z), light.at(Vec3::new(0.0, 0.5, 0.5), Vec3::X)];
        for (o, e) in out.iter().zip(expected) {
            assert!((Vec3::from(*o) - e).length() < 1e-5, "{o:?} {e}");
        }
        assert!(expected[1].y > expected[0].y, "the wall's lower green albedo gives more irradiance");
        assert!(receives(&draw));
        assert!(!receives(&Draw { class: DrawClass::Dynamic, ..draw.clone() }));
        assert!(!receives(&Draw { state: std::sync::Arc::new(RasterState::default()), ..draw.clone() }), "unlit (lightmapped)");
    }
}
