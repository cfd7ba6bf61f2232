//! The Cornell box of issue 6: the compute path tracer on lavapipe, converged by accumulation,
//! against the independent CPU path tracer of `tests/pathtrace/reference_tracer.rs` (f64, std and
//! glam only, no code shared with `shaders/`).
//!
//! The scene is the reference's [`cornell_box`] lit by its point light, drawn through the GL
//! API quad by quad from the reference's own surfaces, so both trace the same geometry: each
//! quad a lit `GL_QUADS` draw with its normal and a diffuse material colour, the light a white
//! positional `GL_LIGHT0` whose quadratic attenuation `k2 = π / I` converts to the reference's
//! intensity `I` exactly (`src/render/trace/lights.rs`), the clear colour black. The materials
//! are the same too: the GL colour of an albedo `ρ` is its 8-bit sRGB encoding (the precision
//! the tracer keeps), and the reference takes the albedo that byte decodes to.
//!
//! Both render `SIZE`² pixels with `BOUNCES` bounces, one convention on both sides: `B`
//! bounces after the primary hit, next-event estimation at each of the `B + 1` vertices. The
//! tracer traces `GPU_SPP` samples per frame for `GPU_FRAMES` frames, accumulated, and writes
//! 8-bit sRGB (tone mapping off, exposure 0), decoded here to linear radiance; the reference
//! traces `CPU_SAMPLES` per pixel.
//!
//! # The error bound
//!
//! Pixels whose whole footprint (corners and centre) sees one quad are grouped by that quad;
//! pixels the reference puts above 0.8 (near the clip at 1: the ceiling above the light) are
//! left out. For each region of at least `MIN_PIXELS` pixels, and for all of them together,
//! the two means must satisfy, per channel,
//!
//! `|gpu − cpu| ≤ 4·√(σ_cpu² + σ_gpu² + σ_8bit²) + 0.5 %·cpu`
//!
//! - `σ_cpu`: the reference's standard error of the region mean (from its per-pixel sample
//!   variances);
//! - `σ_gpu = σ_cpu·√(CPU_SAMPLES / (GPU_SPP·GPU_FRAMES))`: the tracer's, the same estimator
//!   with fewer samples;
//! - `σ_8bit`: the 8-bit rounding of the tracer's output, uniform within half a step `h` of
//!   each pixel (the pixels' own noise, larger than a step, dithers it): `√(Σ h²/3) / n`;
//! - 0.5 %: an allowance for what is not noise (single precision, each frame's first sample
//!   through the pixel centre).
//!
//! Measured (debug build; lavapipe and both tracers are deterministic, so every run on one
//! machine gives these numbers): every region within 1.9 standard errors of the reference, at
//! most 1.4 % apart (2.3 % on the short block's dark front face, whose bound is 20 %); all 774
//! pixels within 0.3 %, against a bound of 1.8 % to 2.1 %. Floor red/green beside the red
//! wall 1.22 (reference 1.26), beside the green wall 0.76 (0.77). The bound catches a wrong
//! number of bounces: the tracer with 2 bounces reads all pixels 4.0 % to 6.3 % dark (20 σ),
//! the floor up to 8 %; with 4 bounces 1.6 % to 3.6 % bright (11 σ). The tracer as it was before it
//! dispatched each sample on its own read them 6.2 % to 6.5 % dark, the tall block's front
//! 20 % (lavapipe's loop limit, src/render/trace/compute.rs).
//!
//! The test takes 25 s of CPU time, three quarters of it the tracer's: about 15 s on 2 idle
//! cores (estimated), 60 s measured on 2 cores shared with other builds.

use crate::reference_tracer;

use crate::lavapipe;

use glam::DVec3;
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::translate::{Context, dispatch, gl};
use reference_tracer::{CornellLight, Hit, Image, Light, Scene, Shape, cornell_box, linear_to_srgb, srgb_to_linear};

/// Image width and height, both sides.
const SIZE: usize = 32;
/// Indirect bounces after the primary hit, both sides.
const BOUNCES: u32 = 3;
/// The tracer's samples per pixel in one frame: above what one shader invocation could trace
/// on lavapipe before the tracer dispatched each sample on its own (src/render/trace/compute.rs).
const GPU_SPP: u32 = 64;
/// Frames the tracer accumulates.
const GPU_FRAMES: u32 = 2;
/// The reference's samples per pixel (it traces a sample about 3 times faster than lavapipe).
const CPU_SAMPLES: u32 = 256;
/// Regions smaller than this are not compared.
const MIN_PIXELS: usize = 6;
/// Pixels the reference puts above this (in any channel) are left out: the tracer's noise
/// could clip them at 1.
const CLIP: f64 = 0.8;

/// The 8-bit sRGB code of linear albedo component `a`.
fn albedo_code(a: f64) -> u8 {
    (linear_to_srgb(a) * 255.0).round() as u8
}

/// The reference's point-lit Cornell box with every albedo replaced by the one its 8-bit GL
/// colour decodes to.
fn scene() -> Scene {
    let mut scene = cornell_box(CornellLight::Point);
    for s in &mut scene.surfaces {
        s.albedo = DVec3::from_array(s.albedo.to_array().map(|a| srgb_to_linear(f64::from(albedo_code(a)) / 255.0)));
    }
    scene
}

/// Draws `scene`'s point lights and quads (lit, a Lambertian material of each quad's albedo)
/// through GL. The modelview is the identity: GL's eye space is the reference's space.
fn draw(ctx: &mut Context, scene: &Scene) {
    unsafe {
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        let [Light::Point { position, intensity }] = scene.lights[..] else { panic!("one point light") };
        let p = [position.x as f32, position.y as f32, position.z as f32, 1.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, p.as_ptr());
        // A white light of quadratic attenuation k2 has intensity π / k2 (lights.rs).
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_CONSTANT_ATTENUATION, 0.0);
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_LINEAR_ATTENUATION, 0.0);
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_QUADRATIC_ATTENUATION, (std::f64::consts::PI / intensity.x) as f32);
        let black = [0.0f32, 0.0, 0.0, 1.0];
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, black.as_ptr());
        for surface in &scene.surfaces {
            let Shape::Quad(corners) = surface.shape else { panic!("{} is not a quad", surface.name) };
            let [r, g, b] = surface.albedo.to_array().map(|a| f32::from(albedo_code(a)) / 255.0);
            dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, [r, g, b, 1.0].as_ptr());
            let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
            dispatch::glBegin(ctx, gl::GL_QUADS);
            dispatch::glNormal3f(ctx, n.x as f32, n.y as f32, n.z as f32);
            for c in corners {
                dispatch::glVertex3f(ctx, c.x as f32, c.y as f32, c.z as f32);
            }
            dispatch::glEnd(ctx);
        }
    }
}

/// The tracer's accumulated image of `scene` with `bounces`: linear radiance per pixel, row 0
/// the bottom.
fn gpu_image(scene: &Scene, bounces: u32) -> Vec<DVec3> {
    let settings = Settings { spp: GPU_SPP, bounces, accumulate: GPU_FRAMES, tonemap: Tonemap::Clamp, exposure: 0.0, ..Settings::default() };
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    renderer.enable_tracing(settings).expect("the tracer's pipelines");
    let mut ctx = lavapipe::context_on(renderer);
    let size = SIZE as i32;
    ctx.bind_drawable(size, size);
    let c = scene.camera;
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, size, size);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glFrustum(&mut ctx, c.left, c.right, c.bottom, c.top, c.near, c.far);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(&mut ctx);
    }
    let e = scene.environment.to_array().map(|v| linear_to_srgb(v) as f32);
    for _ in 0..GPU_FRAMES {
        unsafe {
            dispatch::glClearColor(&mut ctx, e[0], e[1], e[2], 1.0);
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
            dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        }
        draw(&mut ctx, scene);
        ctx.end_frame();
    }
    let mut out = vec![[0u8; 4]; SIZE * SIZE];
    unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, size, size, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out.iter().map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into()).map(|c| srgb_to_linear(c / 255.0))).collect()
}

/// Half an 8-bit sRGB step around linear value `v`, in linear units.
fn half_step(v: f64) -> f64 {
    let code = (linear_to_srgb(v) * 255.0).round();
    let at = |c: f64| srgb_to_linear(c.clamp(0.0, 255.0) / 255.0);
    (at(code + 0.5) - at(code - 0.5)) / 2.0
}

/// What pixel `(x, y)` sees when its whole footprint (corners and centre) sees one surface:
/// the hit through its centre.
fn footprint(scene: &Scene, x: usize, y: usize) -> Option<Hit> {
    let hits = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)].map(|(dx, dy)| {
        let (sx, sy) = ((x as f64 + dx) / SIZE as f64, (y as f64 + dy) / SIZE as f64);
        scene.intersect(DVec3::ZERO, scene.camera.direction(sx, sy), f64::INFINITY)
    });
    let centre = hits[4]?;
    hits.iter().all(|h| h.is_some_and(|h| h.surface == centre.surface)).then_some(centre)
}

/// Pixels that all see one quad of the scene (or, for `"all"`, any).
struct Region {
    name: String,
    pixels: Vec<(usize, usize)>,
}

/// Per quad of `scene` seen by at least `MIN_PIXELS` whole pixels that `reference` puts below
/// `CLIP`, those pixels; then all of them as one region.
fn regions(scene: &Scene, reference: &Image) -> Vec<Region> {
    let mut by_surface: Vec<Vec<(usize, usize)>> = vec![Vec::new(); scene.surfaces.len()];
    for y in 0..SIZE {
        for x in 0..SIZE {
            if let Some(hit) = footprint(scene, x, y)
                && reference.at(x, y).max_element() < CLIP
            {
                by_surface[hit.surface].push((x, y));
            }
        }
    }
    let mut regions: Vec<Region> = by_surface
        .into_iter()
        .enumerate()
        .filter(|(_, pixels)| pixels.len() >= MIN_PIXELS)
        .map(|(i, pixels)| {
            // A block is several quads of one name: 0 its top, 1 to 4 its sides.
            let name = scene.surfaces[i].name;
            let quads: Vec<usize> = (0..scene.surfaces.len()).filter(|&j| scene.surfaces[j].name == name).collect();
            Region { name: if quads.len() > 1 { format!("{name} {}", i - quads[0]) } else { name.into() }, pixels }
        })
        .collect();
    regions.push(Region { name: "all".into(), pixels: regions.iter().flat_map(|r| r.pixels.iter().copied()).collect() });
    regions
}

/// Per channel: the tracer's region mean, the reference's, and the bound on their difference
/// (module doc).
struct Comparison {
    gpu: DVec3,
    cpu: DVec3,
    sigma: DVec3,
    bound: DVec3,
}

fn compare(region: &Region, gpu: &[DVec3], cpu: &Image) -> Comparison {
    let n = region.pixels.len() as f64;
    let gpu_mean = region.pixels.iter().map(|&(x, y)| gpu[y * SIZE + x]).sum::<DVec3>() / n;
    let (cpu_mean, cpu_error) = cpu.region_mean(&region.pixels);
    let gpu_error = cpu_error * (f64::from(CPU_SAMPLES) / f64::from(GPU_SPP * GPU_FRAMES)).sqrt();
    let rounding = region.pixels.iter().map(|&(x, y)| gpu[y * SIZE + x].map(|v| half_step(v).powi(2) / 3.0)).sum::<DVec3>().powf(0.5) / n;
    let sigma = (cpu_error * cpu_error + gpu_error * gpu_error + rounding * rounding).powf(0.5);
    Comparison { gpu: gpu_mean, cpu: cpu_mean, sigma, bound: sigma * 4.0 + cpu_mean * 0.005 }
}

/// Red over green of the floor's mean radiance where the floor is nearer the red wall
/// (`x < -0.5`) and nearer the green wall (`x > 0.5`), from the pixels that see only floor.
fn floor_red_green(scene: &Scene, image: &dyn Fn(usize, usize) -> DVec3) -> (f64, f64) {
    let floor = scene.surfaces.iter().position(|s| s.name == "floor").expect("a floor");
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for y in 0..SIZE {
        for x in 0..SIZE {
            match footprint(scene, x, y) {
                Some(hit) if hit.surface == floor && hit.point.x < -0.5 => left.push(image(x, y)),
                Some(hit) if hit.surface == floor && hit.point.x > 0.5 => right.push(image(x, y)),
                _ => {}
            }
        }
    }
    assert!(left.len() >= 4 && right.len() >= 4, "floor pixels near the walls: {} and {}", left.len(), right.len());
    let ratio = |pixels: &[DVec3]| {
        let sum: DVec3 = pixels.iter().sum();
        sum.x / sum.y
    };
    (ratio(&left), ratio(&right))
}

/// The tracer's accumulated image matches the reference region by region and as a whole
/// within the bound of the module doc, and both bleed colour: the floor beside the red wall
/// is redder than beside the green one.
#[test]
fn cornell_box_matches_the_reference() {
    let scene = scene();
    let cpu = scene.render(&reference_tracer::Settings::new(SIZE, SIZE, CPU_SAMPLES, BOUNCES));
    let gpu = gpu_image(&scene, BOUNCES);

    let mut failures = Vec::new();
    for region in regions(&scene, &cpu) {
        let c = compare(&region, &gpu, &cpu);
        let percent = |v: DVec3| (v / c.cpu * 100.0).to_array().map(|p| format!("{p:+.2}%")).join(" ");
        println!(
            "{:>14} {:>3} px: tracer {:.4} reference {:.4}, difference {} ({:.1} σ), bound {}",
            region.name,
            region.pixels.len(),
            c.gpu,
            c.cpu,
            percent(c.gpu - c.cpu),
            ((c.gpu - c.cpu).abs() / c.sigma).max_element(),
            percent(c.bound).replace('+', "±"),
        );
        if !(c.gpu - c.cpu).abs().cmple(c.bound).all() {
            failures.push(format!("{}: tracer {:.4} against reference {:.4}, bound {:.4}", region.name, c.gpu, c.cpu, c.bound));
        }
    }
    assert!(failures.is_empty(), "regions outside the bound:\n{}", failures.join("\n"));

    let tracer = floor_red_green(&scene, &|x, y| gpu[y * SIZE + x]);
    let reference = floor_red_green(&scene, &|x, y| cpu.at(x, y));
    for (side, (red_side, green_side)) in [("tracer", tracer), ("reference", reference)] {
        println!("{side}: floor red/green {red_side:.3} beside the red wall, {green_side:.3} beside the green wall");
        assert!(red_side > 1.1 && green_side < 0.9, "{side}: floor red/green {red_side} beside the red wall, {green_side} beside the green wall");
    }
}
