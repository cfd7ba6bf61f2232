//! The CPU reference path tracer (`tests/pathtrace/reference_tracer.rs`) checked against physics it
//! must reproduce before the GPU path tracer is compared with it: the white furnace, Lambert's
//! cosine law, inverse-square point lights, the form factor of a rectangular emitter, a spherical
//! emitter, the bounce series of a glowing enclosure, and colour bleeding in the Cornell box.
//!
//! Run `cargo test --test pathtrace reference:: -- --ignored` to write
//! `target/reference-cornell.png` and `target/reference-cornell-point.png` for eyeballing.

use crate::reference_tracer;

use std::f64::consts::PI;

use glam::DVec3;
use reference_tracer::*;

/// Asserts `|actual − expected| ≤ k·error + abs` per channel.
fn assert_within(what: &str, actual: DVec3, expected: DVec3, error: DVec3, k: f64, abs: f64) {
    let diff = (actual - expected).abs();
    let bound = error * k + DVec3::splat(abs);
    assert!(diff.cmple(bound).all(), "{what}: {actual} vs expected {expected} (standard error {error}, bound {bound})");
}

/// Mean and standard error of `n` single-path estimates along one ray.
fn ray_estimate(scene: &Scene, origin: DVec3, dir: DVec3, settings: &Settings, n: u32) -> (DVec3, DVec3) {
    let mut rng = Pcg32::new(settings.seed, 0);
    let (mut sum, mut sum_sq) = (DVec3::ZERO, DVec3::ZERO);
    for _ in 0..n {
        let l = scene.radiance(origin, dir, settings, &mut rng);
        sum += l;
        sum_sq += l * l;
    }
    let n = f64::from(n);
    let mean = sum / n;
    (mean, ((sum_sq - sum * mean) / (n - 1.0) / n).max(DVec3::ZERO).powf(0.5))
}

#[test]
fn pcg32_matches_the_published_sequence() {
    // pcg32-demo of pcg-c-basic: pcg32_srandom_r(&rng, 42, 54).
    let mut rng = Pcg32::new(42, 54);
    let got: Vec<u32> = (0..6).map(|_| rng.next_u32()).collect();
    assert_eq!(got, [0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e]);
    let mean = (0..100_000).map(|_| rng.next_f64()).sum::<f64>() / 100_000.0;
    assert!((mean - 0.5).abs() < 0.003, "mean of uniform numbers {mean}");
}

#[test]
fn srgb_round_trips_and_has_the_standard_midpoint() {
    for i in 0..=255 {
        let c = f64::from(i) / 255.0;
        assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-12, "{c}");
    }
    assert!((srgb_to_linear(0.5) - 0.214041).abs() < 1e-6);
}

#[test]
fn pixel_zero_is_the_bottom_left_and_the_frustum_is_gluperspective() {
    let camera = Camera::perspective(90.0, 2.0, 1.0, 10.0);
    let d = camera.pixel_center(4, 2, 0, 0);
    assert!(d.x < 0.0 && d.y < 0.0 && d.z < 0.0, "{d}");
    let corner = camera.direction(1.0, 1.0);
    let expected = DVec3::new(2.0, 1.0, -1.0).normalize();
    assert!((corner - expected).length() < 1e-12, "{corner} vs {expected}");
}

#[test]
fn white_furnace_every_pixel_is_the_environment() {
    let scene = white_furnace();
    for bounces in [0, 3] {
        let image = scene.render(&Settings::new(24, 24, 8, bounces));
        for y in 0..24 {
            for x in 0..24 {
                let what = format!("bounces {bounces}, pixel ({x}, {y})");
                assert_within(&what, image.at(x, y), DVec3::ONE, image.error_at(x, y), 3.0, 1e-9);
            }
        }
    }
    // Albedo 0.5: the sphere reflects half the sky, the background stays 1.
    let mut grey = white_furnace();
    grey.surfaces[0].albedo = DVec3::splat(0.5);
    let settings = Settings::new(1, 1, 2, 3);
    let (l, e) = ray_estimate(&grey, DVec3::ZERO, DVec3::NEG_Z, &settings, 16);
    assert_within("grey sphere", l, DVec3::splat(0.5), e, 3.0, 1e-9);
}

#[test]
fn white_furnace_holds_for_the_tessellated_sphere() {
    // Any convex surface of albedo 1 works; this one can be drawn through GL as it is.
    let mut scene = white_furnace();
    let faces = tessellate_sphere(DVec3::new(0.0, 0.0, -3.0), 1.0, 12, 6);
    assert_eq!(faces.len(), 72);
    for face in &faces {
        let (corners, centroid) = match *face {
            Shape::Triangle(t) => (vec![t[0], t[1], t[2]], (t[0] + t[1] + t[2]) / 3.0),
            Shape::Quad(q) => (q.to_vec(), (q[0] + q[1] + q[2] + q[3]) / 4.0),
            Shape::Sphere { .. } => unreachable!("faces are flat"),
        };
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        assert!(normal.dot(centroid - DVec3::new(0.0, 0.0, -3.0)) > 0.0, "{face:?} faces inwards");
        if let [a, _, _, d] = corners[..] {
            assert!(normal.dot(d - a).abs() < 1e-12, "{face:?} is not planar");
        }
    }
    scene.surfaces = faces.into_iter().map(|shape| Surface::new("facet", shape, DVec3::ONE)).collect();
    let image = scene.render(&Settings::new(16, 16, 4, 3));
    let lit = (0..16).filter(|&y| scene.intersect(DVec3::ZERO, scene.camera.pixel_center(16, 16, 8, y), 1e9).is_some());
    assert!(lit.count() > 4, "the sphere is in view");
    for y in 0..16 {
        for x in 0..16 {
            let what = format!("pixel ({x}, {y})");
            assert_within(&what, image.at(x, y), DVec3::ONE, image.error_at(x, y), 3.0, 1e-9);
        }
    }
}

#[test]
fn lit_plane_follows_lamberts_cosine_law() {
    let albedo = DVec3::new(0.8, 0.5, 0.2);
    let irradiance = DVec3::new(PI, 2.0, 1.0);
    for degrees in [0.0, 30.0, 60.0, 85.0, 120.0] {
        let theta = f64::to_radians(degrees);
        let image = lit_plane(theta, albedo, irradiance).render(&Settings::new(8, 8, 2, 2));
        // Light from behind (120°) lights the back face only, which the eye does not see.
        let expected = albedo / PI * irradiance * theta.cos().max(0.0);
        for y in 0..8 {
            for x in 0..8 {
                let what = format!("{degrees}°, pixel ({x}, {y})");
                assert_within(&what, image.at(x, y), expected, DVec3::ZERO, 0.0, 1e-12);
            }
        }
    }
}

#[test]
fn sun_disc_gives_the_irradiance_of_a_delta_light() {
    let albedo = DVec3::splat(0.6);
    let mut scene = lit_plane(0.0, albedo, DVec3::ONE);
    scene.lights = vec![Light::Directional { towards: DVec3::Z, irradiance: DVec3::ONE, angular_radius: 0.4 }];
    let image = scene.render(&Settings::new(8, 8, 64, 0));
    let all: Vec<_> = (0..8).flat_map(|y| (0..8).map(move |x| (x, y))).collect();
    let (mean, error) = image.region_mean(&all);
    assert!(error.x > 0.0 && error.x < 1e-3, "standard error {error}");
    assert_within("disc of 0.4 rad", mean, albedo / PI, error, 4.0, 0.0);
}

#[test]
fn point_light_follows_the_inverse_square_law() {
    let albedo = DVec3::splat(0.7);
    let intensity = DVec3::new(3.0, 2.0, 1.0);
    let mut scene = lit_plane(0.0, albedo, DVec3::ZERO);
    scene.lights = vec![Light::Point { position: DVec3::new(0.0, 0.0, -1.0), intensity }];
    let settings = Settings::new(1, 1, 2, 0);
    // On the plane z = −2: right below the light (d = 1, cos 1), and at x = 1 (d = √2, cos 1/√2).
    for (target, geometry) in [(DVec3::new(0.0, 0.0, -2.0), 1.0), (DVec3::new(1.0, 0.0, -2.0), 0.5f64.sqrt() / 2.0)] {
        let origin = DVec3::new(0.3, 0.2, -1.5);
        let mut rng = Pcg32::new(1, 0);
        let l = scene.radiance(origin, (target - origin).normalize(), &settings, &mut rng);
        assert_within(&format!("at {target}"), l, albedo / PI * intensity * geometry, DVec3::ZERO, 0.0, 1e-12);
    }
}

/// Form factor from a point to a parallel rectangle `a × b` at distance `c` with one corner
/// right above the point.
fn corner_form_factor(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

#[test]
fn rectangular_emitter_matches_its_form_factor() {
    // A 1 × 0.6 emitter 0.5 in front of the lit plane (z = −2), facing it: as a quad, then as
    // two triangles. Its front faces −z (towards the plane): corners counter-clockwise from there.
    let albedo = DVec3::splat(0.5);
    let emission = DVec3::new(4.0, 2.0, 1.0);
    let [a, b, c, d] = [(-0.5, -0.3), (-0.5, 0.3), (0.5, 0.3), (0.5, -0.3)].map(|(x, y)| DVec3::new(x, y, -1.5));
    let expected = albedo * emission * 4.0 * corner_form_factor(0.5, 0.3, 0.5);
    for shapes in [vec![Shape::Quad([a, b, c, d])], vec![Shape::Triangle([a, b, c]), Shape::Triangle([a, c, d])]] {
        let mut scene = lit_plane(0.0, albedo, DVec3::ZERO);
        scene.lights.clear();
        for shape in shapes {
            scene.surfaces.push(Surface { name: "emitter", shape, albedo: DVec3::ZERO, emission });
        }
        let settings = Settings::new(1, 1, 2, 0);
        // Look at the plane right below the emitter's centre from between the two.
        let (l, error) = ray_estimate(&scene, DVec3::new(0.0, 0.0, -1.9), DVec3::NEG_Z, &settings, 20_000);
        assert!(error.x < 0.01 * l.x, "standard error {error} of {l}");
        assert_within("rectangle", l, expected, error, 4.0, 0.0);
        // Seen from behind, the emitter neither emits nor lights anything in front of it.
        let (back, _) = ray_estimate(&scene, DVec3::new(0.0, 0.0, -1.0), DVec3::NEG_Z, &settings, 4);
        assert_eq!(back, DVec3::ZERO);
    }
}

#[test]
fn spherical_emitter_lights_like_a_point_of_intensity_pi_r2_le() {
    // A sphere of radius r and radiance Le wholly above the horizon gives E = π Le r² cosθ / d².
    let albedo = DVec3::splat(0.8);
    let emission = DVec3::new(1.0, 2.0, 3.0);
    let mut scene = lit_plane(0.0, albedo, DVec3::ZERO);
    scene.lights.clear();
    let sphere = Shape::Sphere { center: DVec3::new(0.0, 0.0, -1.0), radius: 0.2 };
    scene.surfaces.push(Surface { name: "ball", shape: sphere, albedo: DVec3::ZERO, emission });
    let settings = Settings::new(1, 1, 2, 0);
    for target in [DVec3::new(0.0, 0.0, -2.0), DVec3::new(0.5, 0.0, -2.0)] {
        let to_light = DVec3::new(0.0, 0.0, -1.0) - target;
        let expected = albedo * emission * 0.04 * to_light.normalize().z / to_light.length_squared();
        let origin = DVec3::new(0.3, -0.4, -1.9);
        // Uniform area sampling wastes the far half of the sphere: more samples.
        let (l, error) = ray_estimate(&scene, origin, (target - origin).normalize(), &settings, 80_000);
        assert!(error.x < 0.01 * l.x, "standard error {error} of {l}");
        assert_within(&format!("at {target}"), l, expected, error, 4.0, 0.0);
    }
}

#[test]
fn glowing_box_sums_the_bounce_series() {
    let (rho, emission) = (0.5, 1.0);
    let scene = glowing_box(rho, emission);
    let all: Vec<_> = (0..8).flat_map(|y| (0..8).map(move |x| (x, y))).collect();
    for (bounces, roulette_from) in [(0, None), (1, None), (3, None), (60, Some(2))] {
        let settings = Settings { roulette_from, ..Settings::new(8, 8, 48, bounces) };
        let (mean, error) = scene.render(&settings).region_mean(&all);
        let expected: f64 = (0..=bounces + 1).map(|k| emission * rho.powi(k as i32)).sum();
        assert!(error.x < 0.01 * expected, "standard error {error}");
        assert_within(&format!("{bounces} bounces"), mean, DVec3::splat(expected), error, 4.0, 0.0);
    }
}

/// Mean red/green ratio over the pixels that see only floor at `x < -0.5`, and only floor at `x > 0.5`.
fn floor_red_green(scene: &Scene, image: &Image) -> (f64, f64) {
    let floor = scene.surfaces.iter().position(|s| s.name == "floor").expect("a floor");
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for y in 0..image.height {
        for x in 0..image.width {
            // The whole pixel (its corners and centre) must see the floor, or the box filter
            // mixes in the walls.
            let points = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)].map(|(dx, dy)| {
                let (sx, sy) = ((x as f64 + dx) / image.width as f64, (y as f64 + dy) / image.height as f64);
                scene.intersect(DVec3::ZERO, scene.camera.direction(sx, sy), f64::INFINITY)
            });
            if points.iter().all(|hit| hit.is_some_and(|h| h.surface == floor && h.point.x < -0.5)) {
                left.push((x, y));
            } else if points.iter().all(|hit| hit.is_some_and(|h| h.surface == floor && h.point.x > 0.5)) {
                right.push((x, y));
            }
        }
    }
    assert!(left.len() >= 4 && right.len() >= 4, "floor pixels near the walls: {} and {}", left.len(), right.len());
    let ratio = |pixels: &[(usize, usize)]| {
        let (mean, _) = image.region_mean(pixels);
        mean.x / mean.y
    };
    (ratio(&left), ratio(&right))
}

#[test]
fn cornell_box_bleeds_red_and_green_onto_the_floor() {
    for light in [CornellLight::Area, CornellLight::Point] {
        let scene = cornell_box(light);
        // Direct light only: the white floor under a white light stays exactly grey.
        let direct = scene.render(&Settings::new(32, 32, 4, 0));
        let (left, right) = floor_red_green(&scene, &direct);
        assert!((left - 1.0).abs() < 1e-12 && (right - 1.0).abs() < 1e-12, "{light:?}: direct {left} {right}");
        // With bounces, the red wall tints the floor next to it, the green wall the other side.
        let bounced = scene.render(&Settings::new(32, 32, 24, 3));
        let (left, right) = floor_red_green(&scene, &bounced);
        assert!(left > 1.1 && right < 0.9, "{light:?}: floor red/green {left} near red, {right} near green");
    }
}

#[test]
#[ignore = "writes target/reference-cornell*.png for eyeballing (one to two minutes in a debug build on 2 cores)"]
fn save_cornell_png() {
    let target = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).parent().expect("target dir").to_path_buf();
    for (light, name) in [(CornellLight::Area, "reference-cornell.png"), (CornellLight::Point, "reference-cornell-point.png")] {
        let settings = Settings { roulette_from: Some(3), ..Settings::new(96, 96, 96, 16) };
        let path = target.join(name);
        cornell_box(light).render(&settings).save_png(&path).expect("PNG written");
        println!("{}", path.display());
    }
}
