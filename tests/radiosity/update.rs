//! The per-frame update (`radiosity::gpu::update`): the direct light of a point light in a
//! closed grey box fed to the product with the compressed k-bounce matrix, against the CPU's
//! product of the same primary radiosity, the dense matrix, and energy: in a closed box of
//! albedo ρ every bounce carries ρ of the light before it.

use glam::Vec3;

use glrt::render::radiosity::bounces::{colour_matrix, k_bounce};
use glrt::render::radiosity::compress::{LogRange, Reorder, compress};
use glrt::render::radiosity::reorder::Search;
use glrt::render::radiosity::gpu;
use glrt::render::radiosity::gpu::update::Update;
use glrt::render::radiosity::progress::Progress;
use glrt::render::radiosity::test_scenes::closed_box;
use glrt::render::raster::device::Device;
use glrt::render::trace::gpu_types::GpuLight;

use crate::lavapipe;

#[test]
fn a_point_light_in_a_grey_box_bounces_with_the_energy_of_k_bounces() {
    let device = lavapipe::select(Device::new);
    // The box [0, 2]³ in patches of 0.5 (96), albedo 0.5, a light of intensity 10 off centre.
    let mut p = closed_box(2.0, 0.5);
    let rho = 0.5;
    for x in &mut p.patches {
        x.albedo = Vec3::splat(rho);
    }
    let f = gpu::form_factors::compute(&device, &p, &mut |_, _| {}).expect("form factors");
    let albedo: Vec<Vec3> = p.patches.iter().map(|x| x.albedo).collect();
    let k = k_bounce(&colour_matrix(&f, &albedo), 3, Progress::Quiet);
    let m = compress(&k, 0.04, Reorder::seed(Search::SKETCH), LogRange::Fitted, Progress::Quiet);
    let light = GpuLight { position: [0.7, 1.2, 1.5, 1.0], radiance: [10.0, 10.0, 10.0, 0.0], spot: [0.0, 0.0, -1.0, -2.0], params: [0.0, 1.0, 0.0, 0.0] };
    let mut update = Update::new(&device, &p, &m, 1).expect("the update's passes");
    let (r, time) = update.run(&device, &[light]).expect("an update");
    update.destroy(&device);

    let primary: Vec<Vec3> = r.direct.iter().map(|l| l.primary).collect();
    assert!(primary.iter().all(|x| x.x > 0.0), "a convex box: every patch sees the light");
    // The product of the primary radiosity the direct pass gave, on the CPU.
    let cpu: Vec<Vec3> = m.decompress().apply(&primary).iter().zip(&primary).map(|(b, p)| *b + *p).collect();
    let dense: Vec<Vec3> = k.apply(&primary).iter().zip(&primary).map(|(b, p)| *b + *p).collect();
    let relative = |a: &[Vec3], b: &[Vec3]| a.iter().zip(b).map(|(x, y)| ((*x - *y).abs() / y.abs()).max_element()).fold(0.0f32, f32::max);
    let against_cpu = relative(&r.radiosity, &cpu);
    let against_dense = relative(&r.radiosity, &dense);
    // Energy: the area-weighted sum of the bounced light against ρ + ρ² + ρ³ of the primary.
    let area_sum = |v: &dyn Fn(usize) -> f32| (0..p.patches.len()).map(|i| f64::from(p.patches[i].area * v(i))).sum::<f64>();
    let emitted = area_sum(&|i| primary[i].x);
    let bounced = area_sum(&|i| r.radiosity[i].x - primary[i].x);
    let dense_bounced = area_sum(&|i| dense[i].x - primary[i].x);
    let expected = emitted * f64::from(rho + rho * rho + rho * rho * rho);
    println!(
        "grey box, 96 patches: GPU against the CPU's product {against_cpu:e}, against the dense matrix {against_dense:e}; bounced {bounced:.4} (dense {dense_bounced:.4}) against {expected:.4}; direct {:.2} ms, product {:.2} ms wall",
        time.direct.wall.as_secs_f64() * 1e3,
        time.gather.wall.as_secs_f64() * 1e3
    );
    // The device and texpresso decode BC1 a step apart at most (gather's test). Measured:
    // 7.7e-4.
    assert!(against_cpu < 1e-2, "{against_cpu}");
    // The dense matrix conserves energy as the form factors do (rows sum to 1 within 1e-3).
    // Measured: 55.49 against 55.33, +0.3 %.
    assert!((dense_bounced / expected - 1.0).abs() < 5e-3, "{dense_bounced} vs {expected}");
    // The compressed matrix's errors (bench/radiosity.md) largely cancel in the sum (measured:
    // 55.30, -0.07 %), less so per patch (measured: 2.5 % at most from the dense product).
    assert!((bounced / expected - 1.0).abs() < 0.02, "{bounced} vs {expected}");
    assert!(against_dense < 0.05, "{against_dense}");
}
