//! The renderer's radiosity stage (`radiosity::stage`): a new static world's precompute runs on
//! its own thread while the frames go on without radiosity, then radiosity switches on; the
//! update runs again only when the lights change (not for a light the recovered view's
//! round-off moved by a millionth).

use std::time::{Duration, Instant};

use glam::Vec3;

use glrt::frame::Frame;
use glrt::frame::class::{DynamicLight, View};
use glrt::render::radiosity::settings::Settings;
use glrt::render::radiosity::stage::RadiosityStage;
use glrt::render::radiosity::test_scenes::quad;
use glrt::render::raster::device::Device;
use glrt::render::trace::lights::LightSettings;

use crate::lavapipe;

#[test]
fn frames_go_on_without_radiosity_until_its_precompute_is_done_then_it_switches_on() {
    let device = lavapipe::select(Device::new);
    // The inside of the box [0, 2]³, patches of 0.5 (96); the view is the world frame; a
    // dynamic light (a sphere of 0.4, reaching 3.2: every patch) inside.
    let (x, y, z) = (Vec3::X * 2.0, Vec3::Y * 2.0, Vec3::Z * 2.0);
    let faces = [quad(1, Vec3::ZERO, x, y), quad(2, z, y, x), quad(3, Vec3::ZERO, y, z), quad(4, x, z, y), quad(5, Vec3::ZERO, z, x), quad(6, y, x, z)];
    let light = |at: [f32; 3]| DynamicLight { position: at, color: [1.0; 3], radius: 3.2, falloff: 1.0, axis: [0.0, 0.0, 1.0], floor: 0.3, modulates: false };
    let frame = |at: [f32; 3]| Frame { view: Some(View::default()), static_world: faces.to_vec().into(), lights: vec![light(at)], ..Frame::default() };
    let cache = std::env::temp_dir().join(format!("glrt-radiosity-stage-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&cache);
    let settings = Settings { enabled: true, patch_size: 0.5, ..Settings::default() };
    let mut stage = RadiosityStage::new(settings, LightSettings::default()).with_cache_dir(cache.clone());

    // The frame that meets the world starts the precompute and goes on without radiosity.
    let lit = frame([1.0, 1.0, 1.5]);
    let start = Instant::now();
    assert!(stage.update(&device, &lit).is_none());
    assert!(start.elapsed() < Duration::from_secs(2), "the frame did not wait: {:?}", start.elapsed());
    assert_eq!((stage.frames_without(), stage.updates()), (1, 0));
    let indirect = loop {
        if let Some(indirect) = stage.update(&device, &lit) {
            break indirect;
        }
        assert!(start.elapsed() < Duration::from_secs(600), "the precompute never ended");
        std::thread::sleep(Duration::from_millis(20));
    };
    eprintln!("{} frames without radiosity, then radiosity after {:?}", stage.frames_without(), start.elapsed());
    assert!(stage.frames_without() >= 2, "{}", stage.frames_without());
    assert_eq!(stage.updates(), 1);
    // Bounced light on the floor's centre: the light's, off the walls and the ceiling.
    let floor = indirect.light.at(Vec3::new(1.0, 1.0, 0.0), Vec3::Z);
    assert!(floor.min_element() > 0.0, "{floor}");
    let frames_without = stage.frames_without();

    // The same lights (to round-off): no update; the light moved: one.
    let again = stage.update(&device, &frame([1.0, 1.0, 1.5 * (1.0 + 1e-6)])).expect("radiosity on");
    assert!(std::sync::Arc::ptr_eq(&again.light, &indirect.light));
    assert_eq!(stage.updates(), 1);
    let first = stage.update(&device, &frame([1.0, 1.0, 0.6])).expect("radiosity on");
    assert_eq!((stage.updates(), stage.frames_without()), (2, frames_without));
    // The direct light's points come in 4 slices (the default), one traced per update: the
    // frames after the move update again until all 4 are the new light's, then stop.
    assert_eq!(settings.direct_slices, 4);
    let mut moved = first.clone();
    for updates in [3, 4, 5, 5] {
        moved = stage.update(&device, &frame([1.0, 1.0, 0.6])).expect("radiosity on");
        assert_eq!(stage.updates(), updates);
    }
    // Nearer the floor, the floor is lit far more strongly (6x below the light), and the
    // bottom of a wall gets more of its bounce (measured: 1.19x).
    let wall = |l: &glrt::render::radiosity::transfer::IndirectLight| l.at(Vec3::new(0.0, 1.0, 0.25), Vec3::X);
    assert!(wall(&moved.light).x > 1.1 * wall(&indirect.light).x, "{} vs {}", wall(&moved.light), wall(&indirect.light));
    // The first update after the move, a quarter of the points lit by the new light, lies
    // between the two.
    let (old, partial, new) = (wall(&indirect.light).x, wall(&first.light).x, wall(&moved.light).x);
    assert!(old < partial && partial < new, "{old} {partial} {new}");

    // The matrix went to the cache: a new stage loads it (still on its thread: one frame without).
    let mut cached = RadiosityStage::new(settings, LightSettings::default()).with_cache_dir(cache.clone());
    assert!(cached.update(&device, &lit).is_none());
    let start = Instant::now();
    let light = loop {
        if let Some(indirect) = cached.update(&device, &lit) {
            break indirect.light;
        }
        assert!(start.elapsed() < Duration::from_secs(60), "loading never ended");
        std::thread::sleep(Duration::from_millis(5));
    };
    assert_eq!(light.at(Vec3::new(1.0, 1.0, 0.0), Vec3::Z), floor);
    stage.destroy(&device);
    cached.destroy(&device);
    let _ = std::fs::remove_dir_all(&cache);
}
