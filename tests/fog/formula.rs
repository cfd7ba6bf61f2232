//! `height_fog_amount` of `shaders/fog/height.glsl`, run on the GPU by a compute probe
//! (`tests/shaders/fog_probe.comp`), against the integral of the density
//! `rho0 · e^(−b · (O_z + t · D_z))` over the ray `t ∈ [0, S]` computed numerically in f64
//! (composite Simpson rule), for many random rays and the edge cases of the closed form:
//! horizontal rays (`D_z = 0` exactly), nearly horizontal ones (`|D_z|` from 1e−9 to 1e−3),
//! no falloff (`b = 0`), steep rays far below and above the origin.

use gpu_allocator::MemoryLocation;

use crate::lavapipe;
use glrt::render::raster::device::Device;

/// One segment: density, falloff, start height, direction's vertical component, length.
#[derive(Clone, Copy, Debug)]
struct Ray {
    rho0: f64,
    b: f64,
    o_z: f64,
    d_z: f64,
    s: f64,
}

/// The fog amount by Simpson's rule with `n` (even) intervals.
fn integrated(r: &Ray, n: usize) -> f64 {
    let density = |t: f64| r.rho0 * (-r.b * (r.o_z + t * r.d_z)).exp();
    let h = r.s / n as f64;
    let mut sum = density(0.0) + density(r.s);
    for i in 1..n {
        sum += density(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// A deterministic pseudo-random sequence in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The rays: random ones (unit directions, heights −20..40, falloffs up to 0.2, lengths up to 200), then the
/// edge cases.
fn rays() -> Vec<Ray> {
    let mut rng = Lcg(0xf06);
    let mut rays = Vec::new();
    for _ in 0..2000 {
        let d_z = rng.next() * 2.0 - 1.0;
        rays.push(Ray { rho0: 0.001 + rng.next() * 0.1, b: rng.next() * 0.2, o_z: rng.next() * 60.0 - 20.0, d_z, s: rng.next() * 200.0 });
    }
    for d_z in [0.0, 1e-9, -1e-9, 1e-7, -1e-6, 1e-5, -1e-4, 1e-3, -1e-3, 0.01] {
        for (o_z, s) in [(0.0, 1.0), (5.0, 50.0), (-3.0, 150.0), (12.0, 0.5)] {
            rays.push(Ray { rho0: 0.05, b: 0.3, o_z, d_z, s });
        }
    }
    for d_z in [0.0, 0.5, -1.0] {
        rays.push(Ray { rho0: 0.02, b: 0.0, o_z: 3.0, d_z, s: 40.0 });
    }
    rays.push(Ray { rho0: 0.01, b: 0.4, o_z: 60.0, d_z: -1.0, s: 80.0 });
    rays.push(Ray { rho0: 0.01, b: 0.4, o_z: -30.0, d_z: 1.0, s: 100.0 });
    rays
}

#[test]
fn closed_form_matches_numerical_integration() {
    let rays = rays();
    let queries: Vec<[f32; 8]> =
        rays.iter().map(|r| [r.rho0 as f32, r.b as f32, r.o_z as f32, (r.o_z + r.d_z * r.s) as f32, r.s as f32, 0.0, 0.0, 0.0]).collect();
    let spirv = lavapipe::probe::compile("tests/shaders/fog_probe.comp");
    let mut probe = lavapipe::probe::Probe::new(lavapipe::select(Device::new));
    let input = probe.buffer(bytemuck::cast_slice(&queries), MemoryLocation::CpuToGpu);
    let output = probe.buffer(&vec![0u8; rays.len() * 4], MemoryLocation::GpuToCpu);
    let bytes = probe.run(&spirv, &[(0, input), (1, output)], rays.len());
    probe.finish();
    let got: &[f32] = bytemuck::cast_slice(&bytes[..rays.len() * 4]);

    let (mut worst, mut worst_flat) = (0.0f64, 0.0f64);
    for (r, &f) in rays.iter().zip(got) {
        let want = integrated(r, 2000);
        // Relative to the amount, and absolute below what 8-bit colour shows.
        let error = (f as f64 - want).abs() / want.max(1e-3);
        assert!(error < 2e-5, "{r:?}: GPU {f}, integrated {want}");
        worst = worst.max(error);
        if r.d_z.abs() <= 1e-3 {
            worst_flat = worst_flat.max(error);
        }
    }
    eprintln!("{} rays: largest relative error {worst:.2e} ({worst_flat:.2e} for |D_z| <= 1e-3)", rays.len());
}
