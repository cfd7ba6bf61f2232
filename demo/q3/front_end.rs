//! The front end of a view (`tr_world.c`, `tr_main.c`): which level surfaces are drawn (in the
//! view frustum, not facing away, nearest first as a BSP walk would give them), which of them a
//! dynamic light touches (`R_DlightSurface`: within the light's radius of the surface's plane
//! and box), the entities' surfaces (models culled by a bounding box, sprites always), and the
//! sort of them all by key (`R_SortDrawSurfs`).

use glam::Vec3;

use super::back_end::{DrawSurf, ENTITY_WORLD, EntityKind, RefEntity, SurfaceRef, ViewParms};
use super::level::{Level, Surface};
use super::light_grid::Dlight;
use super::shaders::{Cull, ShaderId, Shaders};
use crate::rebatch::box_meets_frustum;

/// How far behind its plane the eye may be before a front-sided surface is culled (Q3's 8).
const BACKFACE_EPSILON: f32 = 8.0;

/// Whether a dynamic light reaches surface `s`.
fn dlight_touches(dl: &Dlight, s: &Surface) -> bool {
    let plane = s.normal.dot(dl.origin - s.rect.origin);
    plane.abs() <= dl.radius && dl.origin.cmpge(s.mins - dl.radius).all() && dl.origin.cmple(s.maxs + dl.radius).all()
}

/// The level's surfaces drawn in `view`, nearest first; `shader_of[i]` is surface i's shader.
pub fn world_surfaces(level: &Level, shader_of: &[ShaderId], shaders: &Shaders, view: &ViewParms, dlights: &[Dlight]) -> Vec<DrawSurf> {
    let clip = view.projection * view.world;
    let mut visible: Vec<(f32, usize)> = level
        .surfaces
        .iter()
        .enumerate()
        .filter(|(i, s)| {
            let front_only = shaders.get(shader_of[*i]).cull == Cull::FrontSided;
            let behind = s.normal.dot(view.origin - s.rect.origin) < -BACKFACE_EPSILON;
            !(front_only && behind) && box_meets_frustum(&clip, s.mins, s.maxs)
        })
        .map(|(i, s)| (((s.mins + s.maxs) * 0.5).distance(view.origin), i))
        .collect();
    visible.sort_by(|a, b| a.0.total_cmp(&b.0));
    visible
        .into_iter()
        .map(|(_, i)| {
            let lit = dlights.iter().any(|dl| dlight_touches(dl, &level.surfaces[i]));
            DrawSurf::new(shaders, shader_of[i], ENTITY_WORLD, lit, SurfaceRef::World(i))
        })
        .collect()
}

/// Half the size of the box a model is culled by.
const MODEL_RADIUS: f32 = 40.0;

/// The surfaces of `entities` drawn in `view` (one surface each).
pub fn entity_surfaces(entities: &[RefEntity], shaders: &Shaders, view: &ViewParms) -> Vec<DrawSurf> {
    let clip = view.projection * view.world;
    entities
        .iter()
        .enumerate()
        .filter(|(_, e)| match e.kind {
            EntityKind::Sprite { .. } => true,
            EntityKind::Model { .. } => e.depth_hack || box_meets_frustum(&clip, e.origin - Vec3::splat(MODEL_RADIUS), e.origin + Vec3::splat(MODEL_RADIUS)),
        })
        .map(|(i, e)| DrawSurf::new(shaders, e.shader, i, false, SurfaceRef::Entity(i)))
        .collect()
}

/// Sorts surfaces by key, keeping the order of equal keys (`R_SortDrawSurfs`).
pub fn sort(surfaces: &mut [DrawSurf]) {
    surfaces.sort_by_key(|s| s.sort);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q3::level::Material;

    #[test]
    fn a_dlight_touches_surfaces_within_its_radius() {
        let level = Level::new();
        let floor = level.surfaces.iter().find(|s| s.material == Material::Floor && s.mins == Vec3::ZERO).unwrap();
        let near = Dlight { origin: Vec3::new(100.0, 100.0, 60.0), radius: 200.0, colour: Vec3::ONE };
        assert!(dlight_touches(&near, floor));
        assert!(!dlight_touches(&Dlight { origin: Vec3::new(100.0, 100.0, 260.0), ..near }, floor), "too high above");
        assert!(!dlight_touches(&Dlight { origin: Vec3::new(700.0, 100.0, 60.0), ..near }, floor), "too far aside");
    }
}
