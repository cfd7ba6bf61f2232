//! GL lights as physical lights (DESIGN.md, "The frame"; issue 6 part 2).
//!
//! OpenGL lights a surface of diffuse reflectance `m` with `m · d · cos θ · att` (display
//! units, `d` the light's diffuse colour, `att = 1 / (k0 + k1 r + k2 r²)`). The path tracer
//! needs physical quantities whose Lambertian result, `albedo / π · E · cos θ`, looks the same:
//!
//! - a **directional** light (`w = 0`) becomes a sun of irradiance `E = π · linear(d)` at normal
//!   incidence, with the angular size of the settings (soft shadows);
//! - a **positional** light becomes a point light of intensity `I` with inverse-square falloff,
//!   fitted to GL's attenuation at the distance `r₀` from the light to the viewer, as RTX Remix
//!   fits legacy lights: `I = π · linear(d) · r₀² · att(r₀)`. A purely quadratic attenuation
//!   (`k0 = k1 = 0`) gives exactly `π · linear(d) / k2` at every distance; the GL default (no
//!   attenuation) matches GL's brightness where the camera is and falls off physically
//!   around it. Spot cone and exponent are kept as GL defines them.
//! - with a `light_radius` r > 0 (settings), a positional light is a **sphere** of that radius
//!   of the same intensity: a uniform (Lambertian) emitter of radiance `L = I / (π r²)`, whose
//!   intensity towards every direction is `L · π r² = I`. Its irradiance on a surface that
//!   sees all of it (the sphere above its horizon) is exactly the point light's, `I cos θ /
//!   d²` (Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", section 4.7.2), so such
//!   receivers see GL's brightness at any distance; shadows get penumbrae. `shaders/trace/lights.glsl` samples the cone of
//!   directions the sphere fills as seen from the shaded point (uniform in solid angle,
//!   Shirley et al. 1996), with one shadow ray to the sphere's surface; the spot cone
//!   applies to the direction from the sphere's centre. Lights are not geometry: camera and
//!   bounce rays do not see them.
//!
//! GL's ambient terms are left out: indirect light and the environment replace them.
//!
//! A **dynamic light** recovered from a game's dynamic-light passes
//! ([`crate::frame::class::DynamicLight`]: a colour `c` added as `c · falloff / d²` around its
//! centre) is a GL light of diffuse `c` and quadratic attenuation `1 / falloff`: a point light
//! of intensity `π · linear(c) · falloff`, a sphere of [`DYNAMIC_SOURCE`] of its radius (at
//! least the settings' `light_radius`): its centre lies inside the model that carries it (a
//! rocket, a gun), which must not shadow it, and shadow rays end on the sphere; what lies
//! inside the sphere (that model: its colours hold the light already) it does not light, nor
//! any vertex-lit model (their colours hold it too: [`super::material`]'s
//! `MATERIAL_VERTEX_LIT`). It
//! reaches as far as its radius, as the program's pass does (`params.z`: the light fades
//! smoothly to nothing there, `shaders/trace/lights.glsl`).
//!
//! A **baked** surface shows the game's raster colour `C` (its bake holds the level's
//! lights, never a rocket's), and the game lights it by the pass, not by a physical light:
//! there the dynamic light brings what the pass brings, `b = colour · m(h) · min(1, falloff
//! / d²)` (0 below the texture's floor; `d` across the pass's projection axis, `m` its fade
//! with the height `h` along it, [`DynamicLight`]), added to `C` in display units (or `C · b`
//! for a pass that modulates), where a shadow ray to the sphere finds it unoccluded. A point
//! light reflected by the albedo, in linear units, brought a fifth of the pass's light on
//! Quake 3's floors (issue 16). The packing (`params.w < 0`: a dynamic light): `spot.xyz` the
//! projection axis (`spot.w = -2`: no spot cone), `params.x` the floor, `params.y` the
//! falloff, `params.w` -1 for a pass that adds, -2 for one that modulates.

use glam::{Mat4, Vec3};

use super::gpu_types::GpuLight;
use super::scene::srgb_to_linear;
use super::settings::Settings;
use crate::frame::class::DynamicLight;
use crate::frame::{Draw, Frame};
use crate::frame::state::Light;

/// How GL lights are converted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSettings {
    /// Multiplies every light.
    pub scale: f32,
    /// Angular diameter of directional lights, in degrees.
    pub sun_angle: f32,
    /// A direction towards the sun in the world frame, for the strongest directional light.
    pub sun_direction: Option<Vec3>,
    /// Radius of positional lights (0: points).
    pub radius: f32,
}

impl Default for LightSettings {
    fn default() -> LightSettings {
        LightSettings { scale: 1.0, sun_angle: 0.53, sun_direction: None, radius: 0.0 }
    }
}

impl LightSettings {
    /// The conversion the tracer's `settings` ask for.
    pub fn of(settings: &Settings) -> LightSettings {
        LightSettings { scale: settings.light_scale, sun_angle: settings.sun_angle, sun_direction: settings.sun_direction, radius: settings.light_radius }
    }
}

/// Distance below which a positional light counts as at the viewer (the fit uses this one).
const NEAREST_FIT: f32 = 1e-3;

/// The physical light of GL light `light`.
pub fn convert(light: &Light, settings: &LightSettings) -> GpuLight {
    let d = light.diffuse;
    let color = Vec3::new(srgb_to_linear(d[0]), srgb_to_linear(d[1]), srgb_to_linear(d[2])) * std::f32::consts::PI * settings.scale.max(0.0);
    let [x, y, z, w] = light.position;
    if w == 0.0 {
        let dir = Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::Z);
        let radius = (settings.sun_angle.clamp(0.0, 180.0) * 0.5).to_radians();
        return GpuLight {
            position: [dir.x, dir.y, dir.z, 0.0],
            radiance: [color.x, color.y, color.z, 0.0],
            spot: [0.0, 0.0, -1.0, -2.0],
            params: [0.0, radius.cos(), 0.0, 0.0],
        };
    }
    let p = Vec3::new(x, y, z) / w;
    let r = p.length().max(NEAREST_FIT);
    let [k0, k1, k2] = light.attenuation;
    let att = k0 + k1 * r + k2 * r * r;
    let intensity = if att > 0.0 { color * (r * r / att) } else { Vec3::ZERO };
    let spot = Vec3::from_array(light.spot_direction).try_normalize().unwrap_or(Vec3::NEG_Z);
    let cutoff = if light.spot_cutoff >= 180.0 { -2.0 } else { light.spot_cutoff.to_radians().cos() };
    GpuLight {
        position: [p.x, p.y, p.z, 1.0],
        radiance: [intensity.x, intensity.y, intensity.z, settings.radius.max(0.0)],
        spot: [spot.x, spot.y, spot.z, cutoff],
        params: [light.spot_exponent, 1.0, 0.0, 0.0],
    }
}

/// The radius of a dynamic light's sphere, as a fraction of the light's radius (25 units for
/// Quake 3's rocket light of radius 200; its rocket is 32 long).
pub const DYNAMIC_SOURCE: f32 = 0.125;

/// The physical light of dynamic light `light` (see the module doc).
pub fn dynamic(light: &DynamicLight, settings: &LightSettings) -> GpuLight {
    let [r, g, b] = light.color.map(srgb_to_linear);
    let intensity = Vec3::new(r, g, b) * std::f32::consts::PI * light.falloff.max(0.0) * settings.scale.max(0.0);
    let [x, y, z] = light.position;
    GpuLight {
        position: [x, y, z, 1.0],
        radiance: [intensity.x, intensity.y, intensity.z, settings.radius.max(DYNAMIC_SOURCE * light.radius)],
        spot: [light.axis[0], light.axis[1], light.axis[2], -2.0],
        params: [light.floor, light.falloff, light.radius, if light.modulates { -2.0 } else { -1.0 }],
    }
}

/// The lights of a frame: the distinct enabled GL lights of `lights` (each with the eye space
/// it was specified in), converted; the sun direction of the settings replaces the direction
/// of the strongest directional light, taken to eye space by `view` (world to eye).
pub fn gather<'a>(lights: impl IntoIterator<Item = &'a Light>, view: Option<&Mat4>, settings: &LightSettings) -> Vec<GpuLight> {
    let mut seen: Vec<&Light> = Vec::new();
    for light in lights {
        let black = light.diffuse[..3].iter().all(|&c| c <= 0.0);
        if !black && !seen.contains(&light) {
            seen.push(light);
        }
    }
    let mut out: Vec<GpuLight> = seen.iter().map(|l| convert(l, settings)).collect();
    if let (Some(sun), Some(view)) = (settings.sun_direction, view) {
        let strength = |l: &GpuLight| l.radiance[0] + l.radiance[1] + l.radiance[2];
        let strongest = out.iter_mut().filter(|l| l.position[3] == 0.0).max_by(|a, b| strength(a).total_cmp(&strength(b)));
        if let Some(light) = strongest {
            let dir = view.transform_vector3(sun).try_normalize().unwrap_or(Vec3::Z);
            light.position = [dir.x, dir.y, dir.z, 0.0];
        }
    }
    out
}

/// The lights of `frame` in its eye space: the distinct enabled GL lights of `draws` (the
/// draws whose lighting counts) by [`gather`], then the frame's dynamic lights.
pub fn of_frame<'a>(frame: &Frame, draws: impl IntoIterator<Item = &'a Draw>, settings: &LightSettings) -> Vec<GpuLight> {
    let gl_lights = draws.into_iter().filter_map(|d| d.state.lighting.as_ref()).flat_map(|l| l.lights.iter().map(|(_, light)| light));
    let mut lights = gather(gl_lights, frame.view.as_ref().map(|v| &v.view), settings);
    lights.extend(frame.lights.iter().map(|l| dynamic(l, settings)));
    lights
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_white_directional_light_has_irradiance_pi() {
        let l = convert(&Light::initial(0), &LightSettings { sun_angle: 0.0, ..LightSettings::default() });
        assert_eq!(l.position, [0.0, 0.0, 1.0, 0.0]);
        assert!((l.radiance[0] - std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(l.params[1], 1.0);
    }

    #[test]
    fn quadratic_attenuation_is_matched_exactly() {
        let light = Light { position: [0.0, 3.0, -4.0, 1.0], attenuation: [0.0, 0.0, 0.5], ..Light::initial(0) };
        let l = convert(&light, &LightSettings::default());
        // I / r² = π / (k2 r²) at every distance: I = π / k2.
        assert!((l.radiance[1] - std::f32::consts::PI / 0.5).abs() < 1e-4, "{:?}", l.radiance);
        assert_eq!(l.position, [0.0, 3.0, -4.0, 1.0]);
        assert_eq!(l.spot[3], -2.0);
    }

    #[test]
    fn constant_attenuation_is_fitted_at_the_viewer_distance() {
        let light = Light { position: [0.0, 0.0, -10.0, 2.0], spot_cutoff: 60.0, ..Light::initial(0) };
        let l = convert(&light, &LightSettings::default());
        // At r = 5 from the viewer, I / r² equals GL's unattenuated π · d.
        assert!((l.radiance[0] / 25.0 - std::f32::consts::PI).abs() < 1e-4);
        assert!((l.spot[3] - 0.5).abs() < 1e-6);
        assert_eq!(l.radiance[3], 0.0, "a point by default");
        let sphere = convert(&light, &LightSettings { radius: 0.25, ..LightSettings::default() });
        assert_eq!(sphere.radiance, [l.radiance[0], l.radiance[1], l.radiance[2], 0.25], "the same intensity, a radius");
    }

    #[test]
    fn a_dynamic_light_is_a_point_light_of_its_falloff_and_its_pass_on_baked_surfaces() {
        let light = DynamicLight { position: [1.0, 2.0, -30.0], color: [1.0, 0.5, 0.0], radius: 200.0, falloff: 2451.0, axis: [0.0, 1.0, 0.0], floor: 0.3, modulates: false };
        let l = dynamic(&light, &LightSettings::default());
        assert_eq!(l.position, [1.0, 2.0, -30.0, 1.0]);
        // I / d² = π · linear(c) · falloff / d²: GL's diffuse c with attenuation 1 / (d² / falloff).
        let pi = std::f32::consts::PI;
        assert!((l.radiance[0] - pi * 2451.0).abs() < 0.1 && (l.radiance[1] - pi * 2451.0 * srgb_to_linear(0.5)).abs() < 0.1 && l.radiance[2] == 0.0, "{l:?}");
        assert_eq!((l.spot[3], l.params[2], l.params[3]), (-2.0, 200.0, -1.0), "no spot; reaches its radius; a pass that adds");
        assert_eq!((l.spot, l.params[0], l.params[1]), ([0.0, 1.0, 0.0, -2.0], 0.3, 2451.0), "the pass on baked surfaces: axis, floor, falloff");
        let modulates = dynamic(&DynamicLight { modulates: true, ..light }, &LightSettings::default());
        assert_eq!(modulates.params[3], -2.0);
        assert_eq!(l.radiance[3], 25.0, "a sphere of an eighth of its radius");
    }

    #[test]
    fn duplicates_and_black_lights_are_dropped_and_the_sun_is_overridden() {
        let sun = Light::initial(0);
        let black = Light::initial(1);
        let view = Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2);
        let settings = LightSettings { sun_direction: Some(Vec3::X), ..LightSettings::default() };
        let lights = gather([&sun, &sun, &black], Some(&view), &settings);
        assert_eq!(lights.len(), 1);
        let expected = view.transform_vector3(Vec3::X);
        assert!(Vec3::from_slice(&lights[0].position[..3]).distance(expected) < 1e-6);
    }
}
