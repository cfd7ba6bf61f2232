//! Radiosity in the path tracer (issue 19): at the first diffuse bounce that hits the static
//! world, the path (`shaders/trace/path.glsl`, both tracers) adds radiosity's indirect light
//! there and ends: light of every bounce after it for one ray (`[radiosity] enabled` in
//! pathtrace mode, [`crate::render::radiosity::stage`] computing it per frame).
//!
//! - **What the tracer reads.** Per triangle of a static-world instance (a chunk of the
//!   static world, or a draw the world holds whole, [`super::chunks::is_covered`]), the
//!   indirect irradiance / π at its three corners, [`IndirectLight::at`] (what the raster
//!   draws get per vertex: the bounced light over the albedo, interpolated from the patches
//!   around the corner on the triangle's front side), in its geometry's BVH triangle order
//!   ([`GpuRadiosityTriangle`]). `trace/radiosity.glsl` interpolates it at the hit, and the
//!   path adds `throughput · diffuse albedo · value`: the surface's own texels reflect it.
//! - **Not counted twice.** The value is the light the bounces added (radiosity less the
//!   primary radiosity, [`IndirectLight`]): the direct light and emission at that vertex come
//!   from its next-event estimation as at every vertex, then the path ends.
//! - **Front side.** A corner's normal is its triangle's geometric normal in the world, on the
//!   side of the draw's `glFrontFace` (as the patches take it), mirrored with a transform
//!   that mirrors.
//! - **Cost.** The values are kept per placed geometry (its key and world placement) for as
//!   long as the frames' indirect light is the same one (a new update makes a new one).

use std::collections::HashMap;
use std::sync::Arc;

use glam::{Mat4, Vec3};
use xxhash_rust::xxh3::Xxh3;

use super::bvh::GpuTriangle;
use super::gpu_types::GpuRadiosityTriangle;
use crate::frame::state::Winding;
use crate::render::radiosity::patches::face_normal;
use crate::render::radiosity::transfer::IndirectLight;

/// Steps per world unit the placement of a geometry is rounded to in the cache key (the
/// world placement of a static draw comes through the recovered view, exact to rounding).
const PLACEMENT_STEPS: f32 = 1024.0;

/// The radiosity values of the static world's placed geometries under one indirect light.
#[derive(Default)]
pub struct TracedRadiosity {
    light: Option<Arc<IndirectLight>>,
    /// By [`placement_key`].
    values: HashMap<u64, Vec<GpuRadiosityTriangle>>,
}

impl TracedRadiosity {
    /// Starts a frame lit by `light` (`None`: no radiosity): the values of another light are
    /// dropped.
    pub fn begin_frame(&mut self, light: Option<&Arc<IndirectLight>>) {
        let same = match (&self.light, light) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if !same {
            self.light = light.cloned();
            self.values.clear();
        }
    }

    /// The values of the geometry `key`, whose triangles (object space, BVH order) are
    /// `triangles`, placed in the world by `object_to_world`, its front side `front`; `None`
    /// without an indirect light.
    pub fn values(&mut self, key: u64, triangles: &[GpuTriangle], object_to_world: &Mat4, front: Winding) -> Option<&[GpuRadiosityTriangle]> {
        let light = self.light.as_ref()?;
        let values = self.values.entry(placement_key(key, object_to_world, front)).or_insert_with(|| of_triangles(light, triangles, object_to_world, front));
        Some(values)
    }
}

/// The cache key of geometry `key` placed by `object_to_world` with front side `front`.
fn placement_key(key: u64, object_to_world: &Mat4, front: Winding) -> u64 {
    let mut h = Xxh3::new();
    h.update(&key.to_le_bytes());
    h.update(&[u8::from(front == Winding::Cw)]);
    for x in object_to_world.to_cols_array() {
        h.update(&((x * PLACEMENT_STEPS).round() as i64).to_le_bytes());
    }
    h.digest()
}

/// The radiosity values of `triangles` (object space) placed by `object_to_world`, their
/// front side `front`, under `light`.
pub fn of_triangles(light: &IndirectLight, triangles: &[GpuTriangle], object_to_world: &Mat4, front: Winding) -> Vec<GpuRadiosityTriangle> {
    let flip = (front == Winding::Cw) != (object_to_world.determinant() < 0.0);
    triangles
        .iter()
        .map(|t| {
            let v0 = Vec3::from(t.v0);
            let corners = [v0, v0 + Vec3::from(t.e1), v0 + Vec3::from(t.e2)].map(|p| object_to_world.transform_point3(p));
            let normal = if flip { -face_normal(&corners) } else { face_normal(&corners) };
            let mut out = GpuRadiosityTriangle::default();
            for (k, p) in corners.iter().enumerate() {
                out.corner[3 * k..3 * k + 3].copy_from_slice(&light.at(*p, normal).to_array());
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::patches::{Patch, Patches};

    /// One patch on the floor z = 0 facing up, one on the ceiling z = 4 facing down, their
    /// bounced light 1 and 3 (albedo 0.5, primary 1).
    fn floor_and_ceiling() -> Arc<IndirectLight> {
        let patch = |z: f32, normal: Vec3| Patch { position: Vec3::new(0.5, 0.5, z), normal, area: 1.0, albedo: Vec3::splat(0.5), emission: Vec3::ZERO, triangles: 0..0 };
        let patches = Patches { patches: vec![patch(0.0, Vec3::Z), patch(4.0, -Vec3::Z)], ..Patches::default() };
        Arc::new(IndirectLight::new(&patches, &[Vec3::splat(1.5), Vec3::splat(2.5)], &[Vec3::splat(1.0), Vec3::splat(1.0)]))
    }

    /// A counter-clockwise triangle (seen from +z) at height `z`, as stored.
    fn triangle(z: f32) -> GpuTriangle {
        let (v0, v1, v2) = (Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z), Vec3::new(0.0, 1.0, z));
        GpuTriangle { v0: v0.into(), e1: (v1 - v0).into(), e2: (v2 - v0).into(), ..bytemuck::Zeroable::zeroed() }
    }

    #[test]
    fn each_corner_gets_the_light_of_the_patches_on_its_front_side() {
        let light = floor_and_ceiling();
        let pi = std::f32::consts::PI;
        let (floor, ceiling) = (0.5 / 0.5 / pi, 1.5 / 0.5 / pi);
        // Counter-clockwise from above: faces up, the floor patch's light at every corner.
        let up = of_triangles(&light, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Ccw);
        assert!(up[0].corner.iter().all(|&c| (c - floor).abs() < 1e-6), "{:?}", up[0]);
        // The same triangle with a clockwise front faces down: the ceiling's light.
        let down = of_triangles(&light, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Cw);
        assert!(down[0].corner.iter().all(|&c| (c - ceiling).abs() < 1e-6), "{:?}", down[0]);
        // Object space placed in the world: lifted to the ceiling and mirrored (z → −z about
        // its plane) it faces down there, counter-clockwise front and all.
        let mirror = Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0)) * Mat4::from_scale(Vec3::new(1.0, 1.0, -1.0));
        let placed = of_triangles(&light, &[triangle(0.0)], &mirror, Winding::Ccw);
        assert!(placed[0].corner.iter().all(|&c| (c - ceiling).abs() < 1e-6), "{:?}", placed[0]);
    }

    #[test]
    fn values_are_kept_per_placement_while_the_light_is_the_same() {
        let light = floor_and_ceiling();
        let mut traced = TracedRadiosity::default();
        assert!(traced.values(1, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Ccw).is_none(), "no light, no values");
        traced.begin_frame(Some(&light));
        let floor = traced.values(1, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Ccw).expect("values").to_vec();
        // The same geometry placed elsewhere is another entry, the same placement the same one.
        let lifted = Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0)) * Mat4::from_scale(Vec3::new(1.0, 1.0, -1.0));
        assert_ne!(traced.values(1, &[triangle(0.0)], &lifted, Winding::Ccw).expect("values").to_vec(), floor);
        assert_eq!(traced.values(1, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Ccw).expect("values"), &floor[..]);
        assert_eq!(traced.values.len(), 2);
        traced.begin_frame(Some(&light));
        assert_eq!(traced.values.len(), 2, "the same light keeps them");
        traced.begin_frame(Some(&floor_and_ceiling()));
        assert!(traced.values.is_empty(), "another light drops them");
        traced.begin_frame(None);
        assert!(traced.values(1, &[triangle(0.0)], &Mat4::IDENTITY, Winding::Ccw).is_none());
    }
}
