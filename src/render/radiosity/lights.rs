//! The frame's lights in the static world's frame, where the patches are: the tracer's lights
//! ([`crate::render::trace::lights::of_frame`], in the frame's eye space) taken back through
//! the recovered view. The view is taken as rigid (rotation and translation): positions,
//! directions and spot axes move, intensities and reaches stay; and whether two updates'
//! lights are the same ([`same_lights`]).

use glam::{Mat4, Vec3};

use crate::frame::Frame;
use crate::render::trace::gpu_types::GpuLight;
use crate::render::trace::lights::{self, LightSettings};

/// Largest change of a light's number, relative to its size (at least 1), still taken as no
/// change: the lights come back to the world frame through each frame's recovered view, whose
/// round-off moves a light that did not move by about this much.
pub const LIGHT_TOLERANCE: f32 = 1.0e-4;

/// `light` (eye space) in the world frame, `eye_to_world` the inverse of the view.
pub fn to_world(light: &GpuLight, eye_to_world: &Mat4) -> GpuLight {
    let [x, y, z, w] = light.position;
    let position = if w == 0.0 {
        eye_to_world.transform_vector3(Vec3::new(x, y, z)).normalize_or_zero().extend(0.0)
    } else {
        eye_to_world.transform_point3(Vec3::new(x, y, z)).extend(1.0)
    };
    let spot = eye_to_world.transform_vector3(Vec3::from_slice(&light.spot[..3])).normalize_or_zero().extend(light.spot[3]);
    GpuLight { position: position.to_array(), spot: spot.to_array(), ..*light }
}

/// The lights of `frame` that light its static world (the GL lights of all its draws and its
/// dynamic lights) in the world frame; none without a recovered view.
pub fn of_frame(frame: &Frame, settings: &LightSettings) -> Vec<GpuLight> {
    let Some(view) = &frame.view else {
        return Vec::new();
    };
    let eye_to_world = view.view.inverse();
    lights::of_frame(frame, &frame.draws, settings).iter().map(|l| to_world(l, &eye_to_world)).collect()
}

/// Whether the lights `b` are the lights `a` (to [`LIGHT_TOLERANCE`]).
pub fn same_lights(a: &[GpuLight], b: &[GpuLight]) -> bool {
    let close = |x: &[f32; 4], y: &[f32; 4]| x.iter().zip(y).all(|(&x, &y)| (x - y).abs() <= LIGHT_TOLERANCE * x.abs().max(y.abs()).max(1.0));
    a.len() == b.len() && a.iter().zip(b).all(|(a, b)| close(&a.position, &b.position) && close(&a.radiance, &b.radiance) && close(&a.spot, &b.spot) && close(&a.params, &b.params))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::class::{DynamicLight, View};

    #[test]
    fn lights_move_back_to_the_world_frame() {
        // The camera at (0, 0, 10) in the world looking down -z, turned a quarter about y.
        let view = Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2) * Mat4::from_translation(Vec3::new(0.0, 0.0, -10.0));
        let world = Vec3::new(1.0, 2.0, 3.0);
        let eye = view.transform_point3(world);
        let frame = Frame {
            view: Some(View { view, ..View::default() }),
            lights: vec![DynamicLight { position: eye.to_array(), color: [1.0; 3], radius: 50.0, falloff: 100.0, axis: [0.0, 0.0, 1.0], floor: 0.3, modulates: false }],
            ..Frame::default()
        };
        let out = of_frame(&frame, &LightSettings::default());
        assert_eq!(out.len(), 1);
        assert!(Vec3::from_slice(&out[0].position[..3]).distance(world) < 1e-4, "{:?}", out[0].position);
        assert_eq!((out[0].position[3], out[0].params[2]), (1.0, 50.0));
        let sun = GpuLight { position: [0.0, 0.0, 1.0, 0.0], spot: [0.0, 0.0, -1.0, -2.0], ..GpuLight::default() };
        let moved = to_world(&sun, &view.inverse());
        assert!(Vec3::from_slice(&moved.position[..3]).distance(view.inverse().transform_vector3(Vec3::Z)) < 1e-6);
        assert_eq!((moved.position[3], moved.spot[3]), (0.0, -2.0));
        assert!(of_frame(&Frame { view: None, ..frame }, &LightSettings::default()).is_empty(), "no view, no world frame");
    }
}
