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
//! Neither reference has the depth bias δ nor the blur: they are the occlusion itself, so the error
//! states everything the screen-space estimate changes (depth-buffer visibility instead of
//! rays, the range check, the bias, the finite kernel and noise tile, the blur across edges).
//!
//! The scenes: the box and the open plane of `main.rs` (both references), and the last frame
//! of the demo's capture (`tests/fixtures/demo.glrtcap`) replayed (the kernel reference, every
//! second pixel), its occlusion the ratio of the frame drawn with and without it, its
//! reference traced over the triangles of its opaque 3D draws.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use glam::{Affine3A, Vec3, Vec4};
use glrt::frame::pixels::PixelBuffer;
use glrt::frame::{Frame, FrameSink, Target, Topology};
use glrt::render::ao::settings::AoSettings;
use glrt::render::frame::Renderer;
use glrt::render::trace::bvh::cpu::{self, Instance, Scene};
use glrt::render::trace::bvh::{Blas, Layout, Tlas};
use glrt::replay::{self, reader::Capture};

use super::images::Image;
use super::{HUD, SIZE, context, lavapipe, modelview, quads, render, settings};

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

/// The box's or the plane's triangles in eye space (after the camera's pitch).
fn triangles(walls: bool) -> Vec<[Vec3; 3]> {
    let eye = |p: [f32; 3]| modelview().transform_point3(Vec3::from(p));
    quads(walls).into_iter().flat_map(|q| [[eye(q[0]), eye(q[1]), eye(q[2])], [eye(q[0]), eye(q[2]), eye(q[3])]]).collect()
}

/// The reference occlusion of every pixel (rows bottom up) of a `size` image of eye-space
/// `triangles` whose pixel (x, y) looks from the eye along `ray(x, y)`, for `s`'s radius and
/// kernel size, under `distribution` from `count` directions; `None` where the pixel sees no
/// surface.
fn traced(triangles: &[[Vec3; 3]], size: [i32; 2], ray: impl Fn(i32, i32) -> Vec3, s: &AoSettings, distribution: Distribution, count: usize) -> Vec<Option<f64>> {
    let blas = Blas::build(triangles, Layout::Binary);
    let tlas = Tlas::build(&[blas.bounds], Layout::Binary);
    let instances = [Instance::new(&Affine3A::IDENTITY, 0, 0, false)];
    let scene = Scene { tlas: &tlas.nodes, blas_nodes: &blas.nodes, triangles: &blas.triangles, instances: &instances };
    let m = s.samples as usize;
    let scales: Vec<f32> = (0..m).map(|i| (i as f32 / m as f32).powi(2) * 0.9 + 0.1).collect();
    let directions = directions(distribution, count);
    let mut out = Vec::with_capacity((size[0] * size[1]) as usize);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let ray = ray(x, y);
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

/// The reference occlusion of the box (`walls`) or the open plane, per pixel.
fn reference(walls: bool, distribution: Distribution) -> Vec<Option<f64>> {
    // The frustum's sides are at ±0.1 at the near plane 0.1.
    let ndc = |i: i32| (i as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0;
    traced(&triangles(walls), [SIZE, SIZE], |x, y| Vec3::new(ndc(x), ndc(y), -1.0), &settings(), distribution, DIRECTIONS)
}

/// The errors of raster occlusion against a reference over pixels that have both.
struct Errors {
    pixels: usize,
    mean: f64,
    largest: f64,
    /// The share of pixels off by more than 0.1.
    above_tenth: f64,
    /// Mean occlusion of the raster image and of the reference over those pixels.
    means: [f64; 2],
}

/// The errors of `raster` against `reference`, per pixel (`None`: not compared).
fn errors(raster: &[Option<f64>], reference: &[Option<f64>]) -> Errors {
    let pairs: Vec<(f64, f64)> = raster.iter().zip(reference).filter_map(|(a, r)| Some(((*a)?, (*r)?))).collect();
    let n = pairs.len() as f64;
    Errors {
        pixels: pairs.len(),
        mean: pairs.iter().map(|(a, r)| (a - r).abs()).sum::<f64>() / n,
        largest: pairs.iter().map(|(a, r)| (a - r).abs()).fold(0.0, f64::max),
        above_tenth: pairs.iter().filter(|(a, r)| (a - r).abs() > 0.1).count() as f64 / n,
        means: [pairs.iter().map(|p| p.0).sum::<f64>() / n, pairs.iter().map(|p| p.1).sum::<f64>() / n],
    }
}

/// Writes the unoccluded fraction of `raster` and of `reference` (rows bottom up, `width`
/// wide) side by side, grey (white unoccluded), dark blue where not compared, as
/// `ao/<name>.png` under the test's scratch directory; returns its path.
fn save_pair(name: &str, width: usize, raster: &[Option<f64>], reference: &[Option<f64>]) -> PathBuf {
    let colour = |o: &Option<f64>| {
        o.map_or([30, 40, 110], |o| {
            let v = ((1.0 - o) * 255.0).round().clamp(0.0, 255.0) as u8;
            [v; 3]
        })
    };
    let height = raster.len() / width;
    let mut rgb = Vec::with_capacity(width * height * 2 * 3);
    for row in (0..height).rev() {
        let both = raster[row * width..][..width].iter().chain(&reference[row * width..][..width]);
        rgb.extend(both.flat_map(colour));
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("ao");
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join(format!("{name}.png"));
    Image { width: 2 * width, height, rgb }.save_png(&path);
    path
}

/// Prints the errors of `raster` against each of `references` (kernel, then cosine if
/// given) and saves the image pair against the first.
fn report<const N: usize>(name: &str, width: usize, raster: &[Option<f64>], references: [&[Option<f64>]; N]) -> [Errors; N] {
    let path = save_pair(name, width, raster, references[0]);
    let errors = references.map(|r| errors(raster, r));
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

/// The raster occlusion of the box or the plane against both references.
fn compare(name: &str, walls: bool) -> [Errors; 2] {
    let image = render(&mut context(Some(settings())), walls);
    // Every pixel but the HUD square's: `1 − value / 255`.
    let raster: Vec<Option<f64>> = image
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let (x, y) = ((i % SIZE as usize) as i32, (i / SIZE as usize) as i32);
            let hud = (HUD.0..HUD.1).contains(&x) && (HUD.0..HUD.1).contains(&y);
            (!hud).then(|| 1.0 - f64::from(v) / 255.0)
        })
        .collect();
    report(name, SIZE as usize, &raster, [&reference(walls, Distribution::Kernel), &reference(walls, Distribution::Cosine)])
}

#[test]
fn the_open_plane_matches_the_traced_occlusion() {
    let [kernel, cosine] = compare("plane", false);
    assert!(kernel.pixels > (SIZE * SIZE / 3) as usize, "the floor fills the lower half: {}", kernel.pixels);
    assert!(kernel.means[1] < 1e-6 && cosine.means[1] < 1e-6, "nothing occludes an open plane: {:?} {:?}", kernel.means, cosine.means);
    // Also far away at grazing angles, where one pixel spans more depth than the bias (0.018
    // on average and up to 0.18 when samples met the depth of the pixel's centre; 0 now).
    assert!(kernel.mean < 0.001 && kernel.largest < 0.02, "mean {} largest {}", kernel.mean, kernel.largest);
}

#[test]
fn the_box_matches_the_traced_occlusion() {
    let [kernel, cosine] = compare("box", true);
    assert!(kernel.pixels > (SIZE * SIZE * 9 / 10) as usize, "the box fills the view: {}", kernel.pixels);
    assert!(kernel.means[1] > 0.02, "the box is occluded: {:?}", kernel.means);
    // 0.0104 measured (largest 0.22, along the walls' edges and the image border).
    assert!(kernel.mean < 0.012 && kernel.largest < 0.3, "against the kernel reference: mean {} largest {}", kernel.mean, kernel.largest);
    // The cosine-weighted occlusion within R is a larger quantity (full-length rays), which
    // the kernel's short samples see only in part.
    assert!(cosine.mean < 0.16 && cosine.means[1] > kernel.means[1], "against the cosine reference: {} {:?}", cosine.mean, cosine.means);
}

/// What a replay presents: its frames and the drawable.
#[derive(Clone, Default)]
struct Kept(Arc<Mutex<(Vec<Frame>, Option<Target>)>>);

impl FrameSink for Kept {
    fn present(&mut self, frame: Frame) {
        self.0.lock().unwrap().0.push(frame);
    }

    fn set_target(&mut self, target: Target) {
        self.0.lock().unwrap().1 = Some(target);
    }
}

/// The occlusion of the demo's scene, in its units (as `bench/aofog.sh` sets it).
fn demo_settings() -> AoSettings {
    AoSettings { enabled: true, samples: 64, radius: 0.6, bias: 0.02, blur: 3 }
}

/// `frame` drawn by a new renderer into `target`, with occlusion `ao` (`None`: off); RGBA,
/// rows bottom up.
fn draw(frame: &Frame, target: Target, ao: Option<AoSettings>) -> Vec<[f32; 4]> {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    if let Some(ao) = ao {
        renderer.enable_ambient_occlusion(ao).expect("the occlusion's pipelines");
    }
    renderer.set_target(target);
    let [w, h] = frame.size.map(|v| v as i32);
    renderer.read_pixels(frame, PixelBuffer::Color, [0, 0, w, h]).expect("the frame's pixels")
}

#[test]
fn a_replayed_demo_frame_matches_the_traced_occlusion() {
    let capture = Capture::open(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/demo.glrtcap")).expect("the demo's capture");
    let kept = Kept::default();
    let sink = kept.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    replay::run(&capture, &options).expect("replay");
    let (mut frames, target) = std::mem::take(&mut *kept.0.lock().unwrap());
    let (mut frame, target) = (frames.pop().expect("a frame"), target.expect("a drawable"));
    let (at, camera) = glrt::render::ao::place(&frame).map(|(at, camera)| (at, camera.clone())).expect("opaque 3D draws");
    // What is drawn after the occlusion (glass, HUD bar, HUD text) is left out, so that
    // every pixel's occlusion is the ratio of the two images.
    for draw in &mut frame.draws[at..] {
        draw.indices.clear();
        draw.edge_masks.clear();
    }
    frame.pixels.retain(|op| op.before_draw < at);
    let plain = draw(&frame, target, None);
    let occluded = draw(&frame, target, Some(demo_settings()));
    // Every second pixel on both axes (the reference takes minutes unoptimised): the
    // occlusion where the plain pixel is bright enough for the ratio (8-bit rounding below
    // 0.008 of it).
    let [w, h] = frame.size.map(|v| v as i32);
    let [cw, ch] = [w / 2, h / 2];
    let raster: Vec<Option<f64>> = (0..cw * ch)
        .map(|i| {
            let px = ((i / cw * 2) * w + i % cw * 2) as usize;
            let (p, o) = (plain[px], occluded[px]);
            let k = (0..3).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap_or(0);
            (p[k] >= 0.25).then(|| 1.0 - f64::from(o[k] / p[k]).min(1.0))
        })
        .collect();
    // The opaque 3D draws' triangles in eye space.
    let triangles: Vec<[Vec3; 3]> = frame.draws[..at]
        .iter()
        .filter(|d| glrt::render::ao::occluded(d) && d.topology == Topology::Triangles)
        .flat_map(|d| {
            let eye = |i: u32| {
                let p = d.modelview * Vec4::from(d.vertices.position[i as usize]);
                p.truncate() / p.w
            };
            d.indices.chunks_exact(3).map(move |t| [eye(t[0]), eye(t[1]), eye(t[2])])
        })
        .collect();
    let inverse = camera.projection.inverse();
    let [vx, vy, vw, vh] = camera.state.viewport.map(|v| v as f32);
    let ray = |x: i32, y: i32| {
        let ndc = [((2 * x) as f32 + 0.5 - vx) / vw * 2.0 - 1.0, ((2 * y) as f32 + 0.5 - vy) / vh * 2.0 - 1.0];
        let near = inverse * Vec4::new(ndc[0], ndc[1], -1.0, 1.0);
        near.truncate() / near.w
    };
    let kernel = traced(&triangles, [cw, ch], ray, &demo_settings(), Distribution::Kernel, DIRECTIONS);
    let [kernel] = report("demo", cw as usize, &raster, [&kernel]);
    eprintln!("demo: frame {} of {w}x{h}, every second pixel, {} triangles", frame.number, triangles.len());
    assert!(kernel.pixels > (cw * ch / 2) as usize, "most pixels compared: {}", kernel.pixels);
    assert!(kernel.means[1] > 0.002, "the room is occluded somewhere: {:?}", kernel.means);
    // 0.004 measured, 0.8 % of pixels off by > 0.1 (0.033 and 6.8 % when walls and floor
    // seen at grazing angles were darkened), and as much occlusion as traced.
    assert!(kernel.mean < 0.008 && kernel.above_tenth < 0.02, "against the kernel reference: mean {} above 0.1 {}", kernel.mean, kernel.above_tenth);
    assert!((kernel.means[0] - kernel.means[1]).abs() < 0.002, "mean occlusion raster / traced {:?}", kernel.means);
}
