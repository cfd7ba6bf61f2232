//! Radiosity's indirect light in the fixed-function lighting (issue 19): a lit static draw
//! given the patches' indirect light ([`Raster::set_indirect`]) drops the scene ambient term
//! and adds `linear(diffuse) · indirect` to GL's light in linear units, display-encoded again
//! (`shaders/ff.vert` under the shader key's `RADIOSITY`); without it, or for a draw that is not
//! static, GL's ambient stays.

use std::sync::Arc;

use crate::lavapipe;

use glam::{Mat4, Vec3};
use glrt::frame::class::DrawClass;
use glrt::frame::pixels::PixelBuffer;
use glrt::frame::state::{Lighting, Material};
use glrt::frame::{Attrib, Draw, Frame, RasterState, Topology};
use glrt::render::radiosity::patches::{Patch, Patches};
use glrt::render::radiosity::stage::FrameIndirect;
use glrt::render::radiosity::transfer::IndirectLight;
use glrt::render::raster::renderer::Raster;

const SIZE: i32 = 8;

/// Frame `number`, clearing to black and drawing the whole window with a lit quad of class `class`:
/// material ambient and diffuse 0.5, no lights, the scene ambient GL's 0.2.
fn frame(number: u64, class: DrawClass) -> Frame {
    let lighting = Lighting { front: Material { ambient: [0.5, 0.5, 0.5, 1.0], diffuse: [0.5, 0.5, 0.5, 1.0], ..Material::default() }, ..Lighting::default() };
    let state = RasterState { viewport: [0, 0, SIZE, SIZE], lighting: Some(lighting), ..RasterState::default() };
    let positions = vec![[-1.0, -1.0, 0.0, 1.0], [1.0, -1.0, 0.0, 1.0], [1.0, 1.0, 0.0, 1.0], [-1.0, 1.0, 0.0, 1.0]];
    let mut draw = Draw { vertex_count: 4, topology: Topology::Triangles, indices: vec![0, 1, 2, 0, 2, 3], state: Arc::new(state), class, ..Draw::default() };
    draw.vertices.position = positions;
    draw.vertices.normal = Attrib { values: vec![[0.0, 0.0, 1.0]] };
    Frame { number, draws: vec![draw], clears: vec![crate::program::clear_all()], size: [SIZE as u32; 2], ..Frame::default() }
}

/// The centre pixel of `frame` drawn by `raster`, RGB 0..255.
fn centre(raster: &mut Raster, frame: &Frame) -> [f32; 3] {
    raster.record(frame, None, &|_| true).expect("record");
    let p = raster.read(frame, PixelBuffer::Color, [SIZE / 2, SIZE / 2, 1, 1]).expect("read").expect("pixels")[0];
    [p[0] * 255.0, p[1] * 255.0, p[2] * 255.0]
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

#[test]
fn indirect_light_replaces_the_ambient_term_of_lit_static_draws() {
    let mut raster = lavapipe::select(Raster::new);
    // One patch of albedo 1 facing the eye at the eye-space origin (the world frame is the
    // eye's), whose bounces added π · (0.4, 0.2, 0.1): indirect irradiance / π (0.4, 0.2, 0.1).
    let patch = Patch { position: Vec3::ZERO, normal: Vec3::Z, area: 16.0, albedo: Vec3::ONE, emission: Vec3::ZERO, triangles: 0..0 };
    let patches = Patches { patches: vec![patch], ..Patches::default() };
    let indirect = Vec3::new(0.4, 0.2, 0.1);
    let light = IndirectLight::new(&patches, &[Vec3::ONE + std::f32::consts::PI * indirect], &[Vec3::ONE]);
    let expected = indirect.to_array().map(|e| 255.0 * linear_to_srgb(srgb_to_linear(0.5) * e));
    // GL's ambient: 0.5 x 0.2.
    let gl = [25.5; 3];
    for (number, (class, on, want)) in [(DrawClass::Static, false, gl), (DrawClass::Static, true, expected), (DrawClass::Dynamic, true, gl)].into_iter().enumerate() {
        raster.set_indirect(on.then(|| FrameIndirect { light: Arc::new(light.clone()), eye_to_world: Mat4::IDENTITY }));
        let got = centre(&mut raster, &frame(number as u64, class));
        for c in 0..3 {
            assert!((got[c] - want[c]).abs() <= 1.5, "{class:?}, radiosity {on}: {got:?}, expected {want:?}");
        }
    }
}
