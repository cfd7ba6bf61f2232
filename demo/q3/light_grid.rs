//! The light grid and the lighting of models, as Quake 3 lights its entities: the level's light
//! is sampled once at start-up on a grid of points [`GRID_STEP`] apart (ambient colour,
//! directed colour and the direction it comes from, in a map's bytes, shifted up at load like
//! the lightmaps); each frame an entity's light is the grid trilinearly interpolated at its
//! origin, skipping points inside walls, plus a minimum ambient and the dynamic lights
//! (`R_SetupEntityLighting`); its vertex colours are then ambient + max(0, n · l) · directed
//! per vertex (`RB_CalcDiffuseColor`), computed on the CPU by `super::shade`.

use glam::{Mat3, Vec3};

use super::level::Level;
use super::lightmaps::{MAP_OVERBRIGHT_BITS, color_shift, encode};
use super::lights::{self, AMBIENT};

/// Distance between grid points (Q3's default grid is 64 × 64 × 128).
pub const GRID_STEP: f32 = 64.0;
/// The grid's first point and its size in points.
const GRID_ORIGIN: Vec3 = Vec3::new(0.0, -64.0, -32.0);
const GRID_BOUNDS: [usize; 3] = [17, 9, 6];
/// Q3's `r_ambientScale` and `r_directedScale`.
const AMBIENT_SCALE: f32 = 0.6;
const DIRECTED_SCALE: f32 = 1.0;
/// Q3 gives every entity at least this much ambient light (in bytes).
const MINIMUM_AMBIENT: f32 = 32.0;
/// Q3's `DLIGHT_AT_RADIUS` and `DLIGHT_MINIMUM_RADIUS`.
const DLIGHT_AT_RADIUS: f32 = 16.0;
const DLIGHT_MINIMUM_RADIUS: f32 = 16.0;

/// One grid point: light in bytes (0 everywhere inside walls).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Cell {
    ambient: [u8; 3],
    directed: [u8; 3],
    direction: Vec3,
}

/// The baked grid.
pub struct LightGrid {
    cells: Vec<Cell>,
}

/// A dynamic light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dlight {
    pub origin: Vec3,
    pub radius: f32,
    /// 0..=1 per channel.
    pub colour: Vec3,
}

/// An entity's light (`trRefEntity_t`'s lighting fields), in bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EntityLight {
    pub ambient: Vec3,
    pub directed: Vec3,
    /// Towards the light, in the entity's own axes.
    pub direction: Vec3,
}

impl EntityLight {
    /// The light of an entity drawn without the world (`RDF_NOWORLDMODEL`: 3D HUD icons): 150
    /// ambient and directed (plus the minimum ambient) from `sun`, in the entity's axes.
    pub fn without_world(axis: &Mat3, sun: Vec3) -> EntityLight {
        EntityLight { ambient: Vec3::splat(150.0 + MINIMUM_AMBIENT), directed: Vec3::splat(150.0), direction: axis.transpose() * sun }
    }

    /// Vertex colour for unit normal `n` (Q3's `RB_CalcDiffuseColor`).
    pub fn diffuse(&self, n: Vec3) -> [u8; 4] {
        let incoming = n.dot(self.direction);
        let c = if incoming <= 0.0 { self.ambient } else { (self.ambient + self.directed * incoming).min(Vec3::splat(255.0)) };
        let [r, g, b] = c.to_array().map(|v| v as u8);
        [r, g, b, 255]
    }
}

impl LightGrid {
    /// Bakes the grid: at each point in the open, the arrivals of `lights::arrivals`; the
    /// direction is their brightness-weighted mean, the directed colour what comes from it
    /// (times the cosine), the ambient colour [`AMBIENT`] plus half of the rest.
    pub fn bake(level: &Level) -> LightGrid {
        let [nx, ny, nz] = GRID_BOUNDS;
        let mut cells = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let p = GRID_ORIGIN + Vec3::new(i as f32, j as f32, k as f32) * GRID_STEP;
                    cells.push(if level.inside(p) { Self::cell(level, p) } else { Cell::default() });
                }
            }
        }
        LightGrid { cells }
    }

    fn cell(level: &Level, p: Vec3) -> Cell {
        let arrivals = lights::arrivals(level, p, None);
        let sum: Vec3 = arrivals.iter().map(|a| a.direction * a.light.element_sum()).sum();
        let direction = sum.try_normalize().unwrap_or(Vec3::Z);
        let (mut ambient, mut directed) = (AMBIENT, Vec3::ZERO);
        for a in &arrivals {
            let along = a.direction.dot(direction).max(0.0);
            directed += a.light * along;
            ambient += a.light * (1.0 - along) * 0.5;
        }
        let shift = |light: Vec3| color_shift(encode(light), MAP_OVERBRIGHT_BITS);
        // A lit point must not read as "inside a wall" (all zero).
        let ambient = shift(ambient).map(|c| c.max(1));
        Cell { ambient, directed: shift(directed), direction }
    }

    /// The light of an entity at `origin` with axes `axis` (columns), with `dlights` added
    /// (Q3's `R_SetupEntityLighting` with `R_SetupEntityLightingGrid`).
    pub fn entity_light(&self, origin: Vec3, axis: &Mat3, dlights: &[Dlight]) -> EntityLight {
        let v = (origin - GRID_ORIGIN) / GRID_STEP;
        let pos = v.floor();
        let frac = v - pos;
        let clamp = |c: f32, n: usize| (c.max(0.0) as usize).min(n - 1);
        let base = [clamp(pos.x, GRID_BOUNDS[0]), clamp(pos.y, GRID_BOUNDS[1]), clamp(pos.z, GRID_BOUNDS[2])];
        let (mut ambient, mut directed, mut direction, mut total) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, 0.0);
        for corner in 0..8 {
            let mut factor = 1.0;
            let mut at = base;
            let mut outside = false;
            for axis_index in 0..3 {
                if corner & (1 << axis_index) != 0 {
                    at[axis_index] += 1;
                    outside |= at[axis_index] >= GRID_BOUNDS[axis_index];
                    factor *= frac[axis_index];
                } else {
                    factor *= 1.0 - frac[axis_index];
                }
            }
            if outside {
                continue;
            }
            let cell = self.cells[(at[2] * GRID_BOUNDS[1] + at[1]) * GRID_BOUNDS[0] + at[0]];
            if cell.ambient.iter().all(|&c| c == 0) {
                continue; // inside a wall
            }
            total += factor;
            ambient += Vec3::from(cell.ambient.map(f32::from)) * factor;
            directed += Vec3::from(cell.directed.map(f32::from)) * factor;
            direction += cell.direction * factor;
        }
        if total > 0.0 && total < 0.99 {
            (ambient, directed) = (ambient / total, directed / total);
        }
        ambient = ambient * AMBIENT_SCALE + Vec3::splat(MINIMUM_AMBIENT);
        directed *= DIRECTED_SCALE;
        let mut towards = direction.normalize_or_zero() * directed.length();
        for dl in dlights {
            let to = dl.origin - origin;
            let d = to.length().max(DLIGHT_MINIMUM_RADIUS);
            let power = DLIGHT_AT_RADIUS * dl.radius * dl.radius / (d * d);
            directed += dl.colour * power;
            towards += to.normalize_or_zero() * power;
        }
        let world = towards.normalize_or(Vec3::Z);
        EntityLight { ambient: ambient.min(Vec3::splat(255.0)), directed, direction: axis.transpose() * world }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entities_are_lit_by_the_lamps_and_the_rocket() {
        let level = Level::new();
        let grid = LightGrid::bake(&level);
        assert!(grid.cells.iter().any(|c| *c == Cell::default()), "points inside walls");
        let near = grid.entity_light(Vec3::new(440.0, 80.0, 60.0), &Mat3::IDENTITY, &[]);
        let dark = grid.entity_light(Vec3::new(40.0, 40.0, 30.0), &Mat3::IDENTITY, &[]);
        assert!(near.directed.element_sum() > dark.directed.element_sum() + 60.0, "{near:?} {dark:?}");
        // Beside the warm lamp, the light comes from the east (+x).
        assert!(near.direction.x > 0.5, "{near:?}");
        assert!(near.ambient.min_element() >= MINIMUM_AMBIENT && near.ambient.max_element() <= 255.0);
        let rocket = Dlight { origin: Vec3::new(40.0, 40.0, 80.0), radius: 200.0, colour: Vec3::new(1.0, 0.7, 0.3) };
        let lit = grid.entity_light(Vec3::new(40.0, 40.0, 30.0), &Mat3::IDENTITY, &[rocket]);
        assert!(lit.directed.x > dark.directed.x + 100.0 && lit.direction.z > 0.5, "{lit:?}");
        // A turned entity gets the direction in its own axes.
        let turned = Mat3::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let t = grid.entity_light(Vec3::new(440.0, 80.0, 60.0), &turned, &[]);
        assert!(t.direction.abs_diff_eq(turned.transpose() * (near.direction), 1e-5));
    }

    #[test]
    fn diffuse_colours_are_ambient_behind_and_saturate_in_front() {
        let l = EntityLight { ambient: Vec3::splat(40.0), directed: Vec3::new(300.0, 100.0, 50.0), direction: Vec3::X };
        assert_eq!(l.diffuse(-Vec3::X), [40, 40, 40, 255]);
        assert_eq!(l.diffuse(Vec3::X), [255, 140, 90, 255]);
        let icon = EntityLight::without_world(&Mat3::IDENTITY, Vec3::Z);
        assert_eq!(icon.diffuse(Vec3::Z), [255, 255, 255, 255]);
        assert_eq!(icon.diffuse(Vec3::X), [182, 182, 182, 255]);
    }
}
