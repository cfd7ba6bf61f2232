//! The raster occlusion against ray-traced ambient occlusion of the same pixels (issue 23:
//! "against the path tracer's converged ambient occlusion of the same scene").
//!
//! The path tracer has no occlusion output: no `GLRT_*` setting makes it trace occlusion within
//! a radius (lit by a uniform sky with no bounce it would show the cosine-weighted visibility
//! of the sky, an occlusion of unbounded reach, and through its tone curve). So the reference
//! is traced here, on the CPU, through glrt's own BVH (`render::trace::bvh`: built and
//! traversed as the compute tracer does) over the scene's triangles, the ones the test draws.
//! Per pixel: the surface seen through the pixel centre (the point whose depth the raster
//! pass reads) and its geometric normal; then `DIRECTIONS` directions over the hemisphere,
//! each one closest-hit ray of reach R from the point, so each pixel's value is converged (a
//! quasi-random Halton set, the same for every pixel). Two references:
//! - **kernel**: the samples distributed as the seed's kernel (`render::ao::kernel`):
//!   directions `normalize(x, y, z)` for `x, y` uniform in [−1, 1] and `z` in [0, 1], turned
//!   by a uniform angle about the normal (the noise tile's rotations, all of them), at lengths
//!   `ρ · s_i · R` for `ρ` uniform in [0, 1] and the kernel's scales `s_i = 0.1 + 0.9 (i/m)²`;
//!   a sample is occluded when a surface lies between the point and it. A direction whose
//!   closest hit is at distance `h` hides the share `mean_i max(0, 1 − h / (s_i R))` of its
//!   samples (exactly, over `ρ`). This is the quantity the screen-space pass estimates.
//! - **cosine**: cosine-weighted hemisphere visibility within R (the occlusion an ambient
//!   occlusion ray of a path tracer gives): the share of directions whose ray hits within R.
//!
//! Neither has the depth bias δ nor the blur: they are the occlusion itself, so the error
//! states everything the screen-space estimate changes (depth-buffer visibility instead of
//! rays, the range check, the bias, the finite kernel and noise tile, the blur across edges).

use std::path::PathBuf;

use glam::{Affine3A, Vec3};
use glrt::render::trace::bvh::cpu::{self, Instance, Scene};
use glrt::render::trace::bvh::{Blas, Tlas};

use super::images::Image;
use super::{HUD, SIZE, context, modelview, quads, render, settings};

/// Directions traced per pixel: references of 1024 differ from these by 0.0006 (kernel) and
/// 0.003 (cosine) on average over the box's pixels, 0.013 and 0.022 at most.
const DIRECTIONS: usize = 256;

/// Which distribution of samples the reference occlusion takes (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Distribution {
    Kernel,
    Cosine,
}

/// The `i`-th element of the radical inverse sequence in `base` (Halton), in [0, 1).
fn halton(mut i: usize, base: usize) -> f32 {
    let (mut f, mut r) = (1.0f64, 0.0f64);
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r as f32
}

/// `count` tangent-space directions of `distribution` (z along the normal).
fn directions(distribution: Distribution, count: usize) -> Vec<Vec3> {
    (1..=count)
        .map(|i| match distribution {
            Distribution::Kernel => {
                let d = Vec3::new(halton(i, 2) * 2.0 - 1.0, halton(i, 3) * 2.0 - 1.0, halton(i, 5)).normalize_or(Vec3::Z);
                let (sin, cos) = (halton(i, 7) * std::f32::consts::TAU).sin_cos();
                Vec3::new(d.x * cos - d.y * sin, d.x * sin + d.y * cos, d.z)
            }
            Distribution::Cosine => {
                let (r, phi) = (halton(i, 2).sqrt(), halton(i, 3) * std::f32::consts::TAU);
                Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).max(0.0).sqrt())
            }
        })
        .collect()
}

/// The scene's triangles in eye space (after the camera's pitch).
fn triangles(walls: bool) -> Vec<[Vec3; 3]> {
    let eye = |p: [f32; 3]| modelview().transform_point3(Vec3::from(p));
    quads(walls).into_iter().flat_map(|q| [[eye(q[0]), eye(q[1]), eye(q[2])], [eye(q[0]), eye(q[2]), eye(q[3])]]).collect()
}

/// The reference occlusion of every pixel (rows bottom up) of the scene with or without
/// `walls`, under `distribution`, from `count` directions; `None` where the pixel sees no
/// surface.
fn reference(walls: bool, distribution: Distribution, count: usize) -> Vec<Option<f64>> {
    let blas = Blas::build(&triangles(walls));
    let tlas = Tlas::build(&[blas.bounds]);
    let instances = [Instance::new(&Affine3A::IDENTITY, 0, 0, false)];
    let scene = Scene { tlas: &tlas.nodes, blas_nodes: &blas.nodes, triangles: &blas.triangles, instances: &instances };
    let s = settings();
    let m = s.samples as usize;
    let scales: Vec<f32> = (0..m).map(|i| (i as f32 / m as f32).powi(2) * 0.9 + 0.1).collect();
    let directions = directions(distribution, count);
    let ndc = |i: i32| (i as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0;
    let mut out = Vec::with_capacity((SIZE * SIZE) as usize);
    for y in 0..SIZE {
        for x in 0..SIZE {
            // The frustum's sides are at ±0.1 at the near plane 0.1.
            let ray = Vec3::new(ndc(x), ndc(y), -1.0);
            let Some(hit) = cpu::closest(&scene, Vec3::ZERO, ray, 0.0, f32::INFINITY, |_, _, _| true) else {
                out.push(None);
                continue;
            };
            let t = &blas.triangles[hit.triangle as usize];
            let mut n = Vec3::from(t.e1).cross(Vec3::from(t.e2)).normalize();
            let p = ray * hit.t;
            if n.dot(-p) < 0.0 {
                n = -n;
            }
            let tangent = n.any_orthonormal_vector();
            let bitangent = n.cross(tangent);
            let origin = p + n * 1e-4;
            let hidden: f64 = directions
                .iter()
                .map(|d| {
                    let dir = tangent * d.x + bitangent * d.y + n * d.z;
                    let Some(h) = cpu::closest(&scene, origin, dir, 0.0, s.radius, |_, _, _| true).map(|h| h.t) else { return 0.0 };
                    match distribution {
                        Distribution::Cosine => 1.0,
                        Distribution::Kernel => scales.iter().map(|&k| f64::from((1.0 - h / (k * s.radius)).max(0.0))).sum::<f64>() / m as f64,
                    }
                })
                .sum();
            out.push(Some(hidden / count as f64));
        }
    }
    out
}

/// The errors of the raster occlusion `1 − image / 255` against `reference` over the pixels
/// that see a surface (the HUD square left out).
struct Errors {
    pixels: usize,
    mean: f64,
    largest: f64,
    /// The share of pixels off by more than 0.1.
    above_tenth: f64,
    /// Mean occlusion of the raster image and of the reference over those pixels.
    means: [f64; 2],
}

fn errors(image: &[u8], reference: &[Option<f64>]) -> Errors {
    let hud = |i: usize| {
        let (x, y) = ((i % SIZE as usize) as i32, (i / SIZE as usize) as i32);
        (HUD.0..HUD.1).contains(&x) && (HUD.0..HUD.1).contains(&y)
    };
    let pairs: Vec<(f64, f64)> = (0..image.len()).filter(|&i| !hud(i)).filter_map(|i| reference[i].map(|r| (1.0 - f64::from(image[i]) / 255.0, r))).collect();
    let n = pairs.len() as f64;
    Errors {
        pixels: pairs.len(),
        mean: pairs.iter().map(|(a, r)| (a - r).abs()).sum::<f64>() / n,
        largest: pairs.iter().map(|(a, r)| (a - r).abs()).fold(0.0, f64::max),
        above_tenth: pairs.iter().filter(|(a, r)| (a - r).abs() > 0.1).count() as f64 / n,
        means: [pairs.iter().map(|p| p.0).sum::<f64>() / n, pairs.iter().map(|p| p.1).sum::<f64>() / n],
    }
}

/// Writes the unoccluded fraction of `image` and of `reference` side by side (grey, white
/// unoccluded, black where the reference sees nothing) as `ao/<name>.png` under the test's
/// scratch directory; returns its path.
fn save_pair(name: &str, image: &[u8], reference: &[Option<f64>]) -> PathBuf {
    let size = SIZE as usize;
    let mut rgb = Vec::with_capacity(size * size * 2 * 3);
    for row in (0..size).rev() {
        let raster = image[row * size..][..size].iter().copied();
        let traced = reference[row * size..][..size].iter().map(|r| r.map_or(0, |o| ((1.0 - o) * 255.0).round() as u8));
        rgb.extend(raster.chain(traced).flat_map(|v| [v; 3]));
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("ao");
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join(format!("{name}.png"));
    Image { width: 2 * size, height: size, rgb }.save_png(&path);
    path
}

/// The raster occlusion of the scene with or without `walls` against both references; saves
/// the image pair against the kernel reference. Returns the errors (kernel, cosine).
fn compare(name: &str, walls: bool) -> [Errors; 2] {
    let image = render(&mut context(Some(settings())), walls);
    let kernel = reference(walls, Distribution::Kernel, DIRECTIONS);
    let cosine = reference(walls, Distribution::Cosine, DIRECTIONS);
    let path = save_pair(name, &image, &kernel);
    let errors = [errors(&image, &kernel), errors(&image, &cosine)];
    for (e, against) in errors.iter().zip(["kernel", "cosine"]) {
        eprintln!(
            "{name}: raster against the traced {against} reference over {} pixels: mean absolute error {:.4}, largest {:.3}, {:.1} % off by > 0.1; mean occlusion {:.4} (raster) / {:.4} (traced)",
            e.pixels,
            e.mean,
            e.largest,
            e.above_tenth * 100.0,
            e.means[0],
            e.means[1]
        );
    }
    eprintln!("{name}: images (raster | traced kernel reference) in {}", path.display());
    errors
}

#[test]
fn the_open_plane_matches_the_traced_occlusion() {
    let [kernel, cosine] = compare("plane", false);
    assert!(kernel.pixels > (SIZE * SIZE / 3) as usize, "the floor fills the lower half: {}", kernel.pixels);
    assert!(kernel.means[1] < 1e-6 && cosine.means[1] < 1e-6, "nothing occludes an open plane: {:?} {:?}", kernel.means, cosine.means);
    // The floor far away, seen at grazing angles, is darkened a little (up to 0.18).
    assert!(kernel.mean < 0.025 && kernel.largest < 0.25, "mean {} largest {}", kernel.mean, kernel.largest);
}

#[test]
fn the_box_matches_the_traced_occlusion() {
    let [kernel, cosine] = compare("box", true);
    assert!(kernel.pixels > (SIZE * SIZE * 9 / 10) as usize, "the box fills the view: {}", kernel.pixels);
    assert!(kernel.means[1] > 0.02, "the box is occluded: {:?}", kernel.means);
    assert!(kernel.mean < 0.02, "mean absolute error against the kernel reference {}", kernel.mean);
    // The cosine-weighted occlusion within R is a larger quantity (full-length rays), which
    // the kernel's short samples see only in part.
    assert!(cosine.mean < 0.16 && cosine.means[1] > kernel.means[1], "against the cosine reference: {} {:?}", cosine.mean, cosine.means);
}
