//! `shaders/radiosity/form_factors.comp` against the CPU form factors
//! (`render::radiosity::form_factors`, the same method in f64): entry by entry on scenes with
//! and without occluders, and against Howell's analytic values and the white furnace.

use std::time::Instant;

use glam::Vec3;

use glrt::render::radiosity::form_factors::{self, FormFactors};
use glrt::render::radiosity::gpu;
use glrt::render::radiosity::patches::{self, Patches};
use glrt::render::radiosity::test_scenes::{closed_box, quad};
use glrt::render::raster::device::Device;

use crate::lavapipe;

/// The GPU's and the CPU's form factors of `p`, and how many progress reports came.
fn both(device: &Device, p: &Patches) -> (FormFactors, FormFactors, usize) {
    let mut reports = Vec::new();
    let start = Instant::now();
    let gpu = gpu::form_factors::compute(device, p, &mut |done, n| reports.push((done, n))).expect("GPU form factors");
    let gpu_time = start.elapsed();
    let start = Instant::now();
    let cpu = form_factors::compute(p);
    println!("{} patches: GPU {:.2} s, CPU {:.2} s", p.patches.len(), gpu_time.as_secs_f64(), start.elapsed().as_secs_f64());
    let n = p.patches.len();
    assert_eq!(reports.last(), Some(&(n, n)));
    assert!(reports.windows(2).all(|w| w[0].0 < w[1].0), "{reports:?}");
    (gpu, cpu, reports.len())
}

/// Largest difference between the two matrices' entries, and the entries that differ by more
/// than `tolerance`.
fn compare(a: &FormFactors, b: &FormFactors, tolerance: f32) -> (f32, usize) {
    assert_eq!(a.n, b.n);
    let diffs: Vec<f32> = a.values.iter().zip(&b.values).map(|(x, y)| (x - y).abs()).collect();
    (diffs.iter().copied().fold(0.0, f32::max), diffs.iter().filter(|&&d| d > tolerance).count())
}

/// The form factor from the patches whose normals pass `receivers` (as one surface:
/// area-weighted) to those whose normals pass `sources`.
fn surface_form_factor(p: &Patches, f: &FormFactors, receivers: impl Fn(Vec3) -> bool, sources: impl Fn(Vec3) -> bool) -> f32 {
    let (mut sum, mut area) = (0.0, 0.0);
    for (i, r) in p.patches.iter().enumerate().filter(|(_, r)| receivers(r.normal)) {
        let row: f32 = p.patches.iter().enumerate().filter(|(_, s)| sources(s.normal)).map(|(j, _)| f.row(i)[j]).sum();
        sum += r.area * row;
        area += r.area;
    }
    sum / area
}

#[test]
fn gpu_form_factors_equal_the_cpu_reference_and_the_analytic_values() {
    let device = lavapipe::select(Device::new);

    // Parallel unit squares one apart: 0.19982 (Howell's catalogue, C-11).
    let floor = quad(1, Vec3::ZERO, Vec3::X, Vec3::Y);
    let ceiling = quad(2, Vec3::Z, Vec3::Y, Vec3::X);
    let p = patches::build(&[floor.clone(), ceiling.clone()], 0.125);
    let (gpu, cpu, _) = both(&device, &p);
    let (max, off) = compare(&gpu, &cpu, 1.0e-5);
    let parallel = surface_form_factor(&p, &gpu, |n| n.z > 0.5, |n| n.z < -0.5);
    println!("parallel squares: GPU {parallel}, largest difference from the CPU {max:e}, {off} entries off by more than 1e-5");
    assert!((parallel - 0.19982).abs() < 1.0e-3, "parallel {parallel}");
    assert!(max < 1.0e-5, "{max}");

    // A plate between them: visibility rays through the BVH decide most entries.
    let plate = quad(3, Vec3::new(0.25, 0.25, 0.5), Vec3::Y * 0.5, Vec3::X * 0.5);
    let p = patches::build(&[floor, ceiling, plate], 0.125);
    let (gpu, cpu, _) = both(&device, &p);
    let occluded = cpu.values.iter().zip(&gpu.values).filter(|(c, g)| **c > 0.0 && **g > 0.0).count();
    let (max, off) = compare(&gpu, &cpu, 1.0e-5);
    println!("occluded squares: largest difference {max:e}, {off} of {} entries off by more than 1e-5 ({occluded} nonzero)", cpu.values.len());
    // A visibility ray that grazes an edge may decide differently in f32 on the two sides: a
    // quarter of one entry's share at most, on a few entries.
    assert!(off * 1000 < cpu.values.len(), "{off}");
    let row_sums = |f: &FormFactors| -> f32 { (0..f.n).map(|i| f.row(i).iter().sum::<f32>()).sum() };
    assert!((row_sums(&gpu) - row_sums(&cpu)).abs() < 1.0e-3 * row_sums(&cpu), "{} vs {}", row_sums(&gpu), row_sums(&cpu));

    // White furnace: every row of a closed box sums to 1.
    let p = closed_box(1.0, 0.25);
    let (gpu, cpu, _) = both(&device, &p);
    let (max, _) = compare(&gpu, &cpu, 1.0e-5);
    let worst = (0..gpu.n).map(|i| (gpu.row(i).iter().sum::<f32>() - 1.0).abs()).fold(0.0, f32::max);
    println!("closed box: largest |row sum - 1| {worst:e}, largest difference from the CPU {max:e}");
    assert!(worst < 1.0e-3, "{worst}");
    assert!(max < 1.0e-5, "{max}");
}
