//! `shaders/radiosity/gather.comp` against the CPU: the product of the compressed k-bounce
//! matrix (its BC1 image decoded by the device) with the patches' primary radiosity equals
//! `P + decompress() · P`; and its time per product for a synthetic matrix of
//! `GLRT_RADIOSITY_GATHER_PATCHES` patches (default 1024; the GPU target is 16,384).

use glam::Vec3;

use glrt::render::radiosity::bounces::{colour_matrix, k_bounce};
use glrt::render::radiosity::compress::{LogRange, Reorder, compress};
use glrt::render::radiosity::reorder::Search;
use glrt::render::radiosity::gpu::gather::{Gather, synthetic};
use glrt::render::radiosity::progress::Progress;
use glrt::render::radiosity::test_scenes::unit_box;
use glrt::render::raster::device::Device;

use crate::lavapipe;

#[test]
fn the_product_from_the_bc1_image_equals_the_cpu_product() {
    let device = lavapipe::select(Device::new);
    let (p, f) = unit_box();
    // A grey box, redder on the floor; one emitting ceiling patch and a little light on all.
    let albedo: Vec<Vec3> = p.patches.iter().map(|x| if x.normal.z > 0.5 { Vec3::new(0.8, 0.3, 0.2) } else { Vec3::splat(0.5) }).collect();
    let m = compress(&k_bounce(&colour_matrix(f, &albedo), 3, Progress::Quiet), 0.04, Reorder::seed(Search::SKETCH), LogRange::Fitted, Progress::Quiet);
    let lamp = p.patches.iter().position(|x| x.normal.z < -0.5).expect("a ceiling patch");
    let primary: Vec<Vec3> = (0..p.patches.len()).map(|i| if i == lamp { Vec3::splat(10.0) } else { Vec3::new(0.01, 0.02, 0.03) * (i % 7) as f32 }).collect();

    let expected: Vec<Vec3> = m.decompress().apply(&primary).iter().zip(&primary).map(|(b, p)| *b + *p).collect();
    let mut gather = Gather::new(&device, &m).expect("the gathering pass");
    let (got, time) = gather.run(&device, &primary).expect("a product");
    // The same pass again with other light: the host input is rewritten.
    let doubled: Vec<Vec3> = primary.iter().map(|x| *x * 2.0).collect();
    let (twice, _) = gather.run(&device, &doubled).expect("a product");
    gather.destroy(&device);

    let largest = expected.iter().map(|v| v.max_element()).fold(0.0f32, f32::max);
    let worst = got.iter().zip(&expected).map(|(g, e)| ((*g - *e).abs() / e.abs().max(Vec3::splat(1e-3))).max_element()).fold(0.0f32, f32::max);
    let worst_twice = twice.iter().zip(&got).map(|(t, g)| (*t - *g * 2.0).abs().max_element()).fold(0.0f32, f32::max);
    println!("96 patches: largest radiosity {largest}, largest relative difference GPU vs CPU {worst:e}, doubled light off by {worst_twice:e}; {time:?}");
    assert!(largest > 10.0);
    // The device decodes BC1's interpolated colours in floating point from the 5- and 6-bit
    // end points, texpresso in integers from end points widened to 8 bits: a texel's code may
    // differ by one step (a factor e^(shift/254), 4 % at a shift of 10) where the two round
    // differently. Measured: 5.8e-3 at most over the 96 patches.
    assert!(worst < 1.0e-2, "{worst}");
    assert!(worst_twice < 1.0e-4 * largest, "{worst_twice}");
}

#[test]
fn the_product_of_a_large_matrix_is_timed() {
    let n: usize = std::env::var("GLRT_RADIOSITY_GATHER_PATCHES").ok().and_then(|v| v.parse().ok()).unwrap_or(1024);
    let device = lavapipe::select(Device::new);
    let m = synthetic(n, 0x9e37_79b9_7f4a_7c15);
    let per_row = n / 25;
    assert_eq!((m.sparse.len(), m.texture.bytes()), (n * per_row, n.div_ceil(4).pow(2) * 8));
    let primary = vec![Vec3::ONE; n];
    let mut gather = Gather::new(&device, &m).expect("the gathering pass");
    let mut times = Vec::new();
    let mut out = Vec::new();
    for _ in 0..5 {
        let (b, t) = gather.run(&device, &primary).expect("a product");
        times.push(t);
        out = b;
    }
    gather.destroy(&device);
    let wall = times.iter().map(|t| t.wall.as_secs_f64() * 1e3).fold(f64::INFINITY, f64::min);
    let gpu = times.iter().filter_map(|t| t.gpu).min().map(|d| format!("{:.3} ms", d.as_secs_f64() * 1e3)).unwrap_or_else(|| "not timed (no timestamps)".to_owned());
    println!("{n} patches ({} bytes of BC1, {} exact entries): best of 5 products, wall {wall:.3} ms, GPU {gpu} ({})", m.texture.bytes(), m.sparse.len(), device.name());
    // Every row gathers something: the primary light itself plus its exact entries.
    assert!(out.iter().all(|b| b.min_element() >= 1.0 + per_row as f32 * 1.0e-3 * 0.999), "{:?}", &out[..4]);
}
