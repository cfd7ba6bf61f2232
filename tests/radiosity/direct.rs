//! `shaders/radiosity/direct.comp` against analytic irradiance: a point light inside a closed
//! box (no shadows), a point light and a sun over a floor with a plate between (the plate's
//! shadow is exact: 0 where the whole patch is in it); the primary radiosity is emission plus
//! albedo times irradiance; and the product of the direct light fed to the gathering pass.

use std::sync::Arc;

use glam::Vec3;

use glrt::frame::world::StaticChunk;
use glrt::render::radiosity::gpu::direct::{Direct, MAX_LIGHTS, PatchLight};
use glrt::render::radiosity::patches::{self, Patches};
use glrt::render::radiosity::test_scenes::{closed_box, quad};
use glrt::render::raster::device::Device;
use glrt::render::trace::gpu_types::GpuLight;

use crate::lavapipe;

/// A point light of intensity `intensity` (white) at `at`.
fn point(at: Vec3, intensity: f32) -> GpuLight {
    GpuLight { position: at.extend(1.0).to_array(), radiance: [intensity, intensity, intensity, 0.0], spot: [0.0, 0.0, -1.0, -2.0], params: [0.0, 1.0, 0.0, 0.0] }
}

/// A sun of irradiance `irradiance` at normal incidence from direction `towards`.
fn sun(towards: Vec3, irradiance: f32) -> GpuLight {
    GpuLight { position: towards.normalize().extend(0.0).to_array(), radiance: [irradiance, irradiance, irradiance, 0.0], spot: [0.0, 0.0, -1.0, -2.0], params: [0.0, 1.0, 0.0, 0.0] }
}

/// The exact mean over patch `i`'s triangles of `irradiance(point, normal)`: each triangle cut
/// into 4^6 similar triangles, their centroids weighted by area.
fn exact_mean(p: &Patches, i: usize, irradiance: &dyn Fn(Vec3, Vec3) -> f32) -> f32 {
    fn cut(t: [Vec3; 3], depth: u32, f: &mut dyn FnMut([Vec3; 3])) {
        if depth == 0 {
            return f(t);
        }
        let [a, b, c] = t;
        let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
        for s in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            cut(s, depth - 1, f);
        }
    }
    let patch = &p.patches[i];
    let (mut sum, mut area) = (0.0f64, 0.0f64);
    for &t in &p.triangles[patch.triangles.clone()] {
        cut(t, 6, &mut |s| {
            let a = f64::from((s[1] - s[0]).cross(s[2] - s[0]).length() * 0.5);
            sum += a * f64::from(irradiance((s[0] + s[1] + s[2]) / 3.0, patch.normal));
            area += a;
        });
    }
    (sum / area) as f32
}

/// A point light's irradiance at `x` of normal `n`, unshadowed.
fn point_irradiance(light: Vec3, intensity: f32) -> impl Fn(Vec3, Vec3) -> f32 {
    move |x, n| {
        let d = light - x;
        (n.dot(d.normalize()).max(0.0)) * intensity / d.length_squared()
    }
}

/// The direct light of `patches` from `lights`, and the pass's wall time in ms (the first
/// update traces all the points, whatever the slices).
fn light(device: &Device, p: &Patches, lights: &[GpuLight]) -> (Vec<PatchLight>, f64) {
    let mut direct = Direct::new(device, p, 4).expect("the direct-light pass");
    let (out, time) = direct.run(device, lights).expect("a dispatch");
    direct.destroy(device);
    assert_eq!(out.len(), p.patches.len());
    (out, time.wall.as_secs_f64() * 1e3)
}

/// Largest relative error of the white irradiance against `expected`, over the patches `which`
/// selects; also checks the three channels are equal and primary = emission + albedo · E.
fn worst(p: &Patches, out: &[PatchLight], which: impl Fn(usize) -> bool, expected: impl Fn(usize) -> f32) -> (f32, usize) {
    let (mut worst, mut count) = (0.0f32, 0);
    for (i, l) in out.iter().enumerate() {
        let x = &p.patches[i];
        assert!((l.primary - (x.emission + x.albedo * l.irradiance)).abs().max_element() <= 1e-5 * l.primary.max_element().max(1.0), "patch {i}: {l:?}");
        assert!((l.irradiance.x - l.irradiance.y).abs() <= 1e-6 && (l.irradiance.x - l.irradiance.z).abs() <= 1e-6, "{l:?}");
        if which(i) {
            let e = expected(i);
            worst = worst.max((l.irradiance.x - e).abs() / e);
            count += 1;
        }
    }
    (worst, count)
}

#[test]
fn a_point_light_in_a_closed_box_gives_the_inverse_square_cosine_irradiance() {
    let device = lavapipe::select(Device::new);
    // The box [0, 2]³, patches of 0.5 (6 · 16), a light of intensity 10 at its centre.
    let p = closed_box(2.0, 0.5);
    assert_eq!(p.patches.len(), 96);
    let at = Vec3::splat(1.0);
    let (out, ms) = light(&device, &p, &[point(at, 10.0)]);
    let exact = point_irradiance(at, 10.0);
    let (err, count) = worst(&p, &out, |_| true, |i| exact_mean(&p, i, &exact));
    println!("closed box, 96 patches, point light: largest relative error {err:e} over {count} patches; {ms:.2} ms wall");
    // Measured: 1.4 %. The receiver points are the centroids of a patch's first triangles,
    // which sample the patch's area unevenly where the irradiance is curved.
    assert!(err < 0.02, "{err}");
    // The brightest patches face the light across 1 unit (E at the foot: 10).
    let brightest = out.iter().map(|l| l.irradiance.x).fold(0.0, f32::max);
    assert!(brightest > 7.0 && brightest < 10.0, "{brightest}");
}

/// The patches of a 4 × 4 floor at z = 0 facing up and a unit plate over [0.5, 1.5]² at
/// z = 0.5 facing up.
fn floor_and_plate() -> Patches {
    let floor = quad(1, Vec3::ZERO, Vec3::X * 4.0, Vec3::Y * 4.0);
    let plate = quad(2, Vec3::new(0.5, 0.5, 0.5), Vec3::X, Vec3::Y);
    patches::build(&[floor, plate], 0.5)
}

#[test]
fn a_plate_casts_an_exact_shadow_from_a_point_light_and_a_sun() {
    let device = lavapipe::select(Device::new);
    let p = floor_and_plate();
    let on_plate = |i: usize| p.patches[i].position.z > 0.25;
    let corners = |i: usize| p.triangles[p.patches[i].triangles.clone()].iter().flatten().copied().collect::<Vec<Vec3>>();
    let within = |i: usize, lo: f32, hi: f32| corners(i).iter().all(|c| c.x >= lo - 1e-4 && c.x <= hi + 1e-4 && c.y >= lo - 1e-4 && c.y <= hi + 1e-4);
    let outside = |i: usize, lo: f32, hi: f32| corners(i).iter().all(|c| c.x >= hi - 1e-4 || c.y >= hi - 1e-4) || corners(i).iter().all(|c| c.x <= lo + 1e-4 || c.y <= lo + 1e-4);

    // A point light at (2, 2, 1): the plate's shadow on the floor is [-1, 1]² (twice the
    // plate's offset from the light), so floor patches within [0, 1]² get nothing.
    let at = Vec3::new(2.0, 2.0, 1.0);
    let (out, ms) = light(&device, &p, &[point(at, 4.0)]);
    let exact = point_irradiance(at, 4.0);
    let shadowed: Vec<usize> = (0..out.len()).filter(|&i| !on_plate(i) && within(i, 0.0, 1.0)).collect();
    assert_eq!(shadowed.len(), 4);
    assert!(shadowed.iter().all(|&i| out[i].irradiance == Vec3::ZERO), "{:?}", shadowed.iter().map(|&i| out[i]).collect::<Vec<_>>());
    let lit = |i: usize| on_plate(i) || outside(i, -1.0, 1.0);
    let (err, count) = worst(&p, &out, lit, |i| exact_mean(&p, i, &exact));
    println!("floor and plate, {} patches, point light: {} patches in shadow at 0, largest relative error {err:e} over {count} lit patches; {ms:.2} ms wall", p.patches.len(), shadowed.len());
    assert!(count >= 60, "{count}");
    // Measured: 1.9 % (by the light's foot, where the irradiance curves most).
    assert!(err < 0.025, "{err}");

    // A sun from (1, 1, 2) (irradiance 3 at normal incidence): the plate's shadow is the plate
    // moved by (-0.25, -0.25): [0.25, 1.25]², so the floor patch [0.5, 1]² is dark, and every
    // floor patch off [0.25, 1.25]² gets 3 · cos = 3 · 2 / √6.
    let towards = Vec3::new(1.0, 1.0, 2.0);
    let (out, _) = light(&device, &p, &[sun(towards, 3.0)]);
    let cos = towards.normalize().z;
    let dark: Vec<usize> = (0..out.len()).filter(|&i| !on_plate(i) && within(i, 0.25, 1.25)).collect();
    assert_eq!(dark.len(), 1);
    assert_eq!(out[dark[0]].irradiance, Vec3::ZERO);
    let (err, count) = worst(&p, &out, |i| on_plate(i) || outside(i, 0.25, 1.25), |_| 3.0 * cos);
    println!("floor and plate, sun: largest relative error {err:e} over {count} lit patches");
    assert!(err < 1e-5, "{err}");
    assert_eq!(count, 59, "55 floor patches off the shadow's 9, and the plate's 4");
}

#[test]
fn emission_adds_to_the_primary_radiosity_and_lights_beyond_the_pass_are_dropped() {
    let device = lavapipe::select(Device::new);
    let mut lamp = quad(1, Vec3::ZERO, Vec3::X, Vec3::Y);
    Arc::get_mut(&mut lamp).map(|c: &mut StaticChunk| c.material.emissive = 2.0).expect("one owner");
    let p = patches::build(&[lamp], 0.5);
    assert!(p.patches.iter().all(|x| x.emission.min_element() > 0.0));
    // No lights: the primary radiosity is the emission alone.
    let (out, _) = light(&device, &p, &[]);
    for (l, x) in out.iter().zip(&p.patches) {
        assert_eq!((l.irradiance, l.primary), (Vec3::ZERO, x.emission));
    }
    // A light below the lamp's plane does not light its front.
    let (out, _) = light(&device, &p, &[point(Vec3::new(0.5, 0.5, -1.0), 5.0)]);
    assert!(out.iter().all(|l| l.irradiance == Vec3::ZERO));
    // MAX_LIGHTS strong lights below and 10 weak ones above: the weak are left out.
    let mut lights = vec![point(Vec3::new(0.5, 0.5, -1.0), 5.0); MAX_LIGHTS];
    lights.extend(vec![point(Vec3::new(0.5, 0.5, 1.0), 1e-3); 10]);
    let (out, _) = light(&device, &p, &lights);
    assert!(out.iter().all(|l| l.irradiance == Vec3::ZERO));
    // One strong light fewer: one weak light is in.
    let (out, _) = light(&device, &p, &lights[1..]);
    assert!(out.iter().all(|l| l.irradiance.x > 0.0 && l.irradiance.x < 1e-3), "{:?}", out[0]);
}

#[test]
fn updates_in_slices_of_points_reach_the_whole_direct_light_of_new_lights_after_one_update_per_slice() {
    let device = lavapipe::select(Device::new);
    // The floor and plate of the shadow test, a point light that moves from one side to the other.
    let p = floor_and_plate();
    let (before, after) = (point(Vec3::new(2.0, 2.0, 1.0), 4.0), point(Vec3::new(0.3, 3.0, 1.5), 6.0));
    let (whole, _) = light(&device, &p, &[after]);
    let differ = |a: &[PatchLight], b: &[PatchLight]| a.iter().zip(b).map(|(x, y)| (x.irradiance - y.irradiance).abs().max_element() / y.irradiance.max_element().max(1e-3)).fold(0.0f32, f32::max);
    for slices in [2, 4, 16] {
        let mut direct = Direct::new(&device, &p, slices).expect("the direct-light pass");
        direct.run(&device, &[before]).expect("a dispatch");
        assert!(direct.settled(), "the first update traces every point");
        // Its traversal work: every (patch, point, light) pair, each ray at least the root.
        let all = direct.work();
        assert_eq!(all.pairs, 4 * p.patches.len() as u64, "{all:?}");
        assert!(all.longest >= 1 && all.nodes >= u64::from(all.longest) && all.nodes >= all.pairs / 2, "{all:?}");
        // Two planes, a BLAS each under the TLAS: a ray enters few nodes (one BVH over all the
        // triangles took 30x more in a box of 4k patches, bench/radiosity.md).
        println!("{slices} slices: first update {all:?}");
        assert!(all.nodes <= 8 * all.pairs && all.longest <= 16, "{all:?}");
        let mut out = Vec::new();
        let mut pairs = 0;
        for k in 1..=slices {
            out = direct.run(&device, &[after]).expect("a dispatch").0;
            pairs += direct.work().pairs;
            assert_eq!(direct.settled(), k == slices, "{slices} slices, update {k}");
            if k < slices {
                assert!(differ(&out, &whole) > 0.05, "{slices} slices, update {k}: still partly the old light's");
            }
        }
        // The slices' pairs make every pair once.
        assert_eq!(pairs, all.pairs, "{slices} slices");
        // Each point the sum over the lights in the same order as tracing every point: equal
        // (measured: 0 difference).
        let d = differ(&out, &whole);
        println!("{slices} slices: after {slices} updates under the new light, largest relative difference from tracing every point {d:e}");
        assert!(d < 1e-5, "{d}");
        // The same lights again: still settled, the same light.
        let again = direct.run(&device, &[after]).expect("a dispatch").0;
        assert!(direct.settled() && differ(&again, &whole) < 1e-5);
        direct.destroy(&device);
    }
}
