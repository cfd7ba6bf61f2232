//! The level's light sources and the light they bring to a point, traced against the level's
//! faces (what q3map's light stage does, much simplified): four point lights in front of the
//! light panels with inverse-square falloff, the sun through the courtyard's opening, light
//! from the sky over a fixed set of directions, and a small constant ambient term. Light is a
//! multiplier of the surface's texture (1.0 shows the texture as it is).

use glam::Vec3;

use super::level::Level;

/// A point light.
#[derive(Clone, Copy, Debug)]
pub struct PointLight {
    pub origin: Vec3,
    pub colour: Vec3,
    /// Light at distance d is `colour · intensity / (d² + FALLOFF_NEAR²)`.
    pub intensity: f32,
}

/// Distance below which a point light stops getting brighter (no infinite peaks).
const FALLOFF_NEAR: f32 = 48.0;

/// The level's lights.
pub const POINT_LIGHTS: [PointLight; 4] = [
    // Warm, in front of the south panel beside the doorway.
    PointLight { origin: Vec3::new(490.0, 64.0, 128.0), colour: Vec3::new(1.0, 0.82, 0.6), intensity: 30_000.0 },
    // Cooler, in front of the north panel.
    PointLight { origin: Vec3::new(490.0, 320.0, 128.0), colour: Vec3::new(0.75, 0.85, 1.0), intensity: 22_000.0 },
    // Dim, under the ceiling panel in the west of the hall.
    PointLight { origin: Vec3::new(128.0, 192.0, 200.0), colour: Vec3::new(1.0, 0.95, 0.85), intensity: 9_000.0 },
    // In front of the courtyard's panel.
    PointLight { origin: Vec3::new(1020.0, 192.0, 192.0), colour: Vec3::new(1.0, 0.9, 0.7), intensity: 20_000.0 },
];
/// Towards the sun: from the east-south-east, 41° high, so that sunlight falls through the
/// doorway into the hall and the courtyard's south wall shades the southern part of its floor
/// and of its west wall (a diagonal edge).
pub fn sun_direction() -> Vec3 {
    Vec3::new(0.6, -0.45, 0.66).normalize()
}
/// Sunlight on a surface facing the sun.
pub const SUN: Vec3 = Vec3::new(1.0, 0.92, 0.75);
/// Light from the whole sky on an unoccluded upward surface.
pub const SKY: Vec3 = Vec3::new(0.16, 0.19, 0.26);
/// Light everywhere (q3map's `_ambient`), so that nothing is pitch black.
pub const AMBIENT: Vec3 = Vec3::new(0.05, 0.05, 0.06);
/// Directions the sky is sampled in.
const SKY_SAMPLES: usize = 12;

/// Unit directions over the upper hemisphere, spread evenly (a golden-angle spiral).
fn sky_directions() -> [Vec3; SKY_SAMPLES] {
    std::array::from_fn(|i| {
        let z = 1.0 - (i as f32 + 0.5) / SKY_SAMPLES as f32;
        let r = (1.0 - z * z).sqrt();
        let phi = i as f32 * 2.399_963;
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// One source's light arriving at a point: its colour (already attenuated) and the unit
/// direction towards it.
#[derive(Clone, Copy, Debug)]
pub struct Arrival {
    pub light: Vec3,
    pub direction: Vec3,
}

/// The light arriving at `p` from every source that `p` sees, each from its direction;
/// `facing`: only sources on the side of this normal. [`AMBIENT`] is not included.
pub fn arrivals(level: &Level, p: Vec3, facing: Option<Vec3>) -> Vec<Arrival> {
    let in_front = |d: Vec3| facing.is_none_or(|n| n.dot(d) > 0.0);
    let mut out = Vec::new();
    for l in &POINT_LIGHTS {
        let d = l.origin - p;
        if in_front(d) && !level.occluded(p, l.origin) {
            out.push(Arrival { light: l.colour * l.intensity / (d.length_squared() + FALLOFF_NEAR * FALLOFF_NEAR), direction: d.normalize() });
        }
    }
    let sun = sun_direction();
    if in_front(sun) && level.reaches_sky(p, sun) {
        out.push(Arrival { light: SUN, direction: sun });
    }
    // Each sky direction stands for its share of the hemisphere: 2 / N of the sky's light
    // (the mean of 2·cos over the hemisphere is 1).
    for d in sky_directions() {
        if in_front(d) && level.reaches_sky(p, d) {
            out.push(Arrival { light: SKY * (2.0 / SKY_SAMPLES as f32), direction: d });
        }
    }
    out
}

/// Light on a surface at `p` with unit normal `n`: ambient plus every arrival times the cosine.
pub fn irradiance(level: &Level, p: Vec3, n: Vec3) -> Vec3 {
    arrivals(level, p, Some(n)).iter().fold(AMBIENT, |sum, a| sum + a.light * n.dot(a.direction).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pillar_shades_the_floor_behind_it_from_the_warm_light() {
        let level = Level::new();
        // Floor points on the line from the warm light past the pillar's centre, in front of and
        // behind it.
        let light = POINT_LIGHTS[0].origin;
        let through = Vec3::new(240.0, 112.0, 0.0);
        let behind = light + (through - light).with_z(0.0) * 1.4;
        let before = light + (through - light).with_z(0.0) * 0.6;
        let (b, f) = (behind.with_z(1.0), before.with_z(1.0));
        let from_warm = |p: Vec3| arrivals(&level, p, Some(Vec3::Z)).iter().any(|a| a.direction.abs_diff_eq((light - p).normalize(), 1e-4));
        assert!(!from_warm(b) && from_warm(f));
        assert!(irradiance(&level, b, Vec3::Z).length() < irradiance(&level, f, Vec3::Z).length());
    }

    #[test]
    fn the_sun_reaches_the_courtyard_and_the_hall_through_the_doorway() {
        let level = Level::new();
        let sunlit = |p: Vec3| level.reaches_sky(p, sun_direction());
        assert!(sunlit(Vec3::new(700.0, 200.0, 1.0)));
        // The south wall's shadow: on the floor near it, on the west wall low and south.
        assert!(!sunlit(Vec3::new(700.0, 50.0, 1.0)));
        assert!(!sunlit(Vec3::new(529.0, 60.0, 100.0)) && sunlit(Vec3::new(529.0, 60.0, 250.0)));
        // Right in front of the east wall, the wall itself is between the floor and the sun.
        assert!(!sunlit(Vec3::new(1000.0, 200.0, 1.0)));
        // The patch of sun on the hall floor inside the doorway, not beside it.
        assert!(sunlit(Vec3::new(470.0, 180.0, 1.0)));
        assert!(!sunlit(Vec3::new(470.0, 40.0, 1.0)));
        let sky = sky_directions();
        assert!(sky.iter().all(|d| d.z > 0.0 && (d.length() - 1.0).abs() < 1e-5));
    }
}
