//! The k-bounce matrix on the GPU (`radiosity::gpu::product`, `shaders/radiosity/product.comp`)
//! against the CPU's (`radiosity::bounces::k_bounce`), on matrices whose sides are not
//! multiples of the pass's tile, so that the tiles' edges are covered.

use glam::Vec3;

use glrt::render::radiosity::bounces::k_bounce;
use glrt::render::radiosity::gpu::product;
use glrt::render::radiosity::matrix::ColourMatrix;
use glrt::render::radiosity::progress::Progress;
use glrt::render::raster::device::Device;

use crate::lavapipe;

/// A colour matrix of side `n` whose rows sum to at most 0.9 per channel: xorshift entries,
/// a quarter of them 0 (as occluded pairs are).
fn colour_matrix(n: usize, seed: u64) -> ColourMatrix {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut m = ColourMatrix::zeros(n);
    for i in 0..n {
        for j in 0..n {
            let v = Vec3::new(next(), next(), next());
            m.set(i, j, if next() < 0.25 { Vec3::ZERO } else { v * (1.8 / n as f32) });
        }
    }
    m
}

#[test]
fn the_gpu_k_bounce_matrix_equals_the_cpu_one_to_float_rounding() {
    let device = lavapipe::select(Device::new);
    for (n, k) in [(1, 3), (70, 1), (70, 3), (131, 4)] {
        let colour = colour_matrix(n, 0x2545_f491_4f6c_dd1d ^ n as u64);
        let cpu = k_bounce(&colour, k, Progress::Quiet);
        let gpu = product::k_bounce(&device, &colour, k, Progress::Quiet).expect("the product on the device");
        assert_eq!(gpu.n, n);
        let largest = cpu.channels.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
        let worst = (0..3).flat_map(|c| cpu.channels[c].iter().zip(&gpu.channels[c]).map(|(a, b)| (a - b).abs())).fold(0.0f32, f32::max);
        println!("n = {n}, k = {k}: largest entry {largest:.4e}, largest difference GPU − CPU {worst:.3e}");
        assert!(largest > 0.0);
        // f32 sums of n terms in the same order; a GPU may fuse the multiplies and adds: a few
        // ulps of the largest entry (measured on lavapipe, which does not: 0). k = 1 copies
        // the colour matrix: exact.
        assert!(worst <= 1e-6 * largest, "n = {n}, k = {k}: {worst} against {largest}");
        if k == 1 {
            assert_eq!(gpu, cpu);
        }
    }
}
