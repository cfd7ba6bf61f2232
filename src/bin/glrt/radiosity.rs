//! `glrt radiosity FILE`: replays a capture without drawing and runs the radiosity precompute
//! on the static world of its last frame with the `[radiosity]` settings (`glrt.toml`,
//! `GLRT_*`): times, sizes and errors as Markdown (`glrt::render::radiosity::precompute`),
//! then the per-frame update with the renderer's compressed matrix timed on the device as
//! `--matrix` does. With `--baked`, the static world includes the draws whose light is baked
//! (`glrt::translate::classify::baked_world`: a Quake-3 map's). With `--matrix`, only the compressed matrix the renderer uses, read from the disk cache
//! when it holds it, else computed and written there; it says which and how long it took,
//! then times the per-frame update on the device (`radiosity::gpu::update`: the patches' direct
//! light under the last frame's lights, then the product with the matrix).
//!
//! The form factors and the k-bounce matrix are computed on the Vulkan device (`GLRT_DEVICE`)
//! with a progress bar; without one, or when it fails, on the CPU, with a message saying why.
//! `--precompute N` times the stages after the form factors, and the peak memory, on a
//! synthetic closed box of about N patches.

use std::sync::Arc;
use std::time::Instant;

use glam::Vec3;

use glrt::frame::FrameSink;
use glrt::render::radiosity;
use glrt::render::radiosity::compress::CompressedMatrix;
use glrt::render::radiosity::gpu::gather::synthetic;
use glrt::render::radiosity::gpu::update::{Update, UpdateTime};
use glrt::render::radiosity::patches::Patches;
use glrt::render::radiosity::precompute::{self, Steps};
use glrt::render::radiosity::settings::{DENSE_BYTES_PER_ENTRY, Settings};
use glrt::render::radiosity::stage::OnDevice;
use glrt::render::radiosity::bounces::colour_matrix;
use glrt::render::radiosity::compress::{self, REORDER_PASSES, Reorder, compress};
use glrt::render::radiosity::matrix::ColourMatrix;
use glrt::render::radiosity::progress::Progress;
use glrt::render::radiosity::reorder::Search;
use glrt::render::radiosity::test_scenes::{closed_box, disc_form_factors, shuffled_order};
use glrt::render::raster::device::Device;
use glrt::render::trace::gpu_types::GpuLight;
use glrt::render::trace::lights::LightSettings;
use glrt::replay::{self, reader::Capture};
use glrt::translate::classify::baked_world::BakedWorld;


/// What [`run`] keeps of the frames presented.
#[derive(Default)]
struct Seen {
    /// The static world of the last frame, with the baked world's chunks when there is one.
    chunks: Vec<Arc<glrt::frame::world::StaticChunk>>,
    /// The last frame's lights in the world frame.
    lights: Vec<GpuLight>,
    /// With `--baked`: the baked static draws of every frame so far.
    baked: Option<BakedWorld>,
}

/// The sink that fills [`Seen`].
#[derive(Clone, Default)]
struct LastWorld(Arc<parking_lot::Mutex<Seen>>);

impl FrameSink for LastWorld {
    fn present(&mut self, frame: glrt::frame::Frame) {
        let lights = radiosity::lights::of_frame(&frame, &LightSettings::of(&glrt::render::trace::settings::Settings::of_process()));
        let mut seen = self.0.lock();
        let mut chunks = frame.static_world.to_vec();
        if let Some(baked) = &mut seen.baked {
            baked.add(&frame);
            chunks.extend(baked.chunks().iter().cloned());
        }
        (seen.chunks, seen.lights) = (chunks, lights);
    }
}

/// Runs the precompute (or with `matrix_only`, builds or loads the renderer's matrix) on
/// `capture`'s last static world and prints what it measured; with `baked`, the world
/// includes the static draws whose light is baked ([`BakedWorld`]), which a game's radiosity
/// leaves out.
pub fn run(capture: &Capture, matrix_only: bool, baked: bool) -> Result<(), String> {
    let world = LastWorld::default();
    world.0.lock().baked = baked.then(BakedWorld::default);
    let sink = world.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    replay::run(capture, &options)?;
    let Seen { chunks, lights, .. } = std::mem::take(&mut *world.0.lock());
    if chunks.is_empty() {
        let hint = if baked { "" } else { " (--baked takes the draws whose light is baked too)" };
        return Err(format!("radiosity: the capture's last frame has no static world{hint}"));
    }
    if baked {
        eprintln!("glrt: radiosity: {} chunks of {} triangles, baked draws included", chunks.len(), chunks.iter().map(|c| c.triangles()).sum::<usize>());
    }
    let settings = Settings::of_process();
    let device = Device::new().map_err(|e| eprintln!("glrt: no Vulkan device for the form factors ({e}): they are computed on the CPU")).ok();
    if !matrix_only {
        let report = precompute::run(&chunks, &settings, &mut OnDevice(device.as_ref())).map_err(|e| format!("radiosity: {e}"))?;
        print!("{}", report.markdown());
        if let Some(device) = &device {
            println!("\nthe renderer's compressed matrix ({} bytes) under the last frame's {} lights:", report.matrix.bytes(), lights.len());
            time_updates(device, &report.patches, &report.matrix, &lights);
        }
        return Ok(());
    }
    let start = Instant::now();
    let r = precompute::load_or_build(&chunks, &settings, Some(&glrt::config::cache_dir()), &mut OnDevice(device.as_ref()));
    for note in &r.notes {
        eprintln!("glrt: {note}");
    }
    let file = r.cache_file.as_ref().map_or_else(String::new, |f| f.display().to_string());
    let how = if r.loaded { format!("loaded from {file}") } else { format!("computed, written to {file}") };
    println!("{} patches, compressed matrix {} bytes: {how} in {:.3} s", r.patches.patches.len(), r.matrix.bytes(), start.elapsed().as_secs_f64());
    if let Some(device) = &device {
        println!("{} lights in the last frame", lights.len());
        time_updates(device, &r.patches, &r.matrix, &lights);
    }
    Ok(())
}

/// `glrt radiosity --synthetic N`: the per-frame update timed on the device, for the inside
/// of a closed box of about `n` patches of size 1 lit by four point lights, with
/// [`synthetic`]'s matrix of that many patches.
pub fn time_synthetic(n: usize) -> Result<(), String> {
    let device = Device::new().map_err(|e| format!("radiosity: no Vulkan device: {e}"))?;
    let side = ((n as f64 / 6.0).sqrt().round() as usize).max(1) as f32;
    let p = closed_box(side, 1.0);
    let n = p.patches.len();
    let m = synthetic(n, 0x9e37_79b9_7f4a_7c15);
    println!("synthetic: the inside of a box of side {side}, {n} patches; matrix of {} bytes of BC1, {} exact entries", m.texture.bytes(), m.sparse.len());
    let light = |x: f32, y: f32| GpuLight {
        position: [x * side, y * side, 0.5 * side, 1.0],
        radiance: [side * side; 4],
        spot: [0.0, 0.0, -1.0, -2.0],
        params: [0.0, 1.0, 0.0, 0.0],
    };
    time_updates(&device, &p, &m, &[light(0.25, 0.25), light(0.75, 0.25), light(0.25, 0.75), light(0.75, 0.75)]);
    Ok(())
}

/// `glrt radiosity --precompute N`: the precompute's stages after the real form factors
/// timed for the inside of a closed box of about `n` patches of size 1, albedo 0.5, with
/// [`disc_form_factors`]: the colour matrix, the k-bounce matrix on the Vulkan device
/// (`GLRT_DEVICE`; on the CPU without one, on a CPU device, or when the matrix does not fit
/// it: [`OnDevice`]) and the
/// compression; each stage's progress on stderr ([`Progress::Stderr`]), then the stage times
/// and the process's peak resident memory after each. Refused, with the budget's message,
/// when the dense matrices exceed `radiosity_budget_mb`. With `orderings`, then
/// [`compare_orderings`] on the k-bounce matrix.
pub fn time_precompute(n: usize, orderings: bool) -> Result<(), String> {
    let settings = Settings::of_process();
    let side = ((n as f64 / 6.0).sqrt().round() as usize).max(1) as f32;
    let patches = 6 * (side as usize).pow(2);
    let dense = patches * patches * DENSE_BYTES_PER_ENTRY;
    if patches > settings.max_patches() {
        return Err(format!(
            "radiosity: {patches} patches need {} MiB of dense matrices (colour and k-bounce, 3 channels of f32 each), past the budget of {} MiB \
             (radiosity_budget_mb, GLRT_RADIOSITY_BUDGET_MB): at most {} patches; a static world this large gets larger patches",
            dense >> 20,
            settings.budget_mb,
            settings.max_patches()
        ));
    }
    let device = Device::new().map_err(|e| eprintln!("glrt: no Vulkan device for the k-bounce matrix ({e}): it is computed on the CPU")).ok();
    let mut p = closed_box(side, 1.0);
    for patch in &mut p.patches {
        patch.albedo = Vec3::splat(0.5);
    }
    let mut stages: Vec<(&str, f64, u64)> = Vec::new();
    let mut timed = |name, start: Instant| stages.push((name, start.elapsed().as_secs_f64(), peak_resident_bytes()));
    let start = Instant::now();
    let f = disc_form_factors(&p);
    timed("disc form factors (CPU)", start);
    let start = Instant::now();
    let albedo: Vec<Vec3> = p.patches.iter().map(|x| x.albedo).collect();
    let colour = colour_matrix(&f, &albedo);
    drop(f);
    timed("colour matrix", start);
    let start = Instant::now();
    let mut steps = OnDevice(device.as_ref());
    let on = steps.product_device().map_or_else(|| "the CPU".to_owned(), |d| d.name());
    let k = steps.k_bounce(&colour, settings.bounces, Progress::Stderr);
    drop(colour);
    timed("k-bounce matrix", start);
    let start = Instant::now();
    let m = compress(&k, settings.top_share, precompute::reorder_of(&settings), precompute::RANGE, Progress::Stderr);
    timed("compression (reordering, BC1)", start);
    println!(
        "precompute of {patches} patches (a box of side {side}), k = {}, the k-bounce matrix on {on} ({} CPU threads); dense matrices {} MiB, compressed {} bytes:",
        settings.bounces,
        rayon::current_num_threads(),
        dense >> 20,
        m.bytes()
    );
    println!("| stage | s | peak resident memory after it, MiB |\n| --- | ---: | ---: |");
    for (name, seconds, peak) in &stages {
        println!("| {name} | {seconds:.2} | {} |", peak >> 20);
    }
    println!("| all | {:.2} | |", stages.iter().map(|s| s.1).sum::<f64>());
    if orderings {
        compare_orderings(&k, settings.top_share);
    }
    Ok(())
}

/// Compresses `k` (top share `top_share`, [`precompute::RANGE`]) with each reordering — none,
/// the exact and the sketched search ([`Search::SKETCH`]) with 1 and 2 passes, and sketches
/// of fewer and more positions or one candidate with 2 passes — of its patches
/// in their order and shuffled ([`shuffled_order`]), and prints a Markdown table of each
/// one's errors, bytes and time (the seed's table, `bench/radiosity.md`); each pass's time is
/// on stderr.
fn compare_orderings(k: &ColourMatrix, top_share: f32) {
    let total: f64 = k.channels.iter().flatten().map(|&x| f64::from(x)).sum();
    println!("\n| patches | search | passes | mean error | max error | summed error | summed / sum of entries | compressed bytes | s |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let shuffled = k.permuted(&shuffled_order(k.n, 0x5eed));
    for (patches, m) in [("as built", k), ("shuffled", &shuffled)] {
        let sketch = |samples, candidates| Search::Sketch { samples, candidates };
        let runs = [
            (Search::Exact, 0),
            (Search::Exact, 1),
            (Search::Exact, REORDER_PASSES),
            (Search::SKETCH, 1),
            (Search::SKETCH, REORDER_PASSES),
            (sketch(64, 16), REORDER_PASSES),
            (sketch(256, 1), REORDER_PASSES),
            (sketch(1024, 16), REORDER_PASSES),
        ];
        for (search, passes) in runs {
            let start = Instant::now();
            let c = compress(m, top_share, Reorder { passes, search }, precompute::RANGE, Progress::Stderr);
            let seconds = start.elapsed().as_secs_f64();
            let e = compress::errors(m, &c.decompress());
            let name = match (passes, search) {
                (0, _) => "none".to_owned(),
                (_, Search::Exact) => "exact".to_owned(),
                (_, Search::Sketch { samples, candidates }) => format!("sketch ({samples} positions, {candidates} candidates)"),
            };
            println!("| {patches} | {name} | {passes} | {:.3e} | {:.4} | {:.4} | {:.4} | {} | {seconds:.2} |", e.mean, e.max, e.sum, e.sum / total.max(f64::MIN_POSITIVE), c.bytes());
        }
    }
}

/// The process's peak resident memory in bytes (`VmHWM` of `/proc/self/status`; 0 where it
/// cannot be read).
fn peak_resident_bytes() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// [`UPDATES`] per-frame updates of `patches` with matrix `m` under `lights` on `device`, the
/// direct light in the settings' slices of points (`radiosity_direct_slices`); prints the
/// times of the first (all the points), the best of the others' (one slice each) and what the
/// last one gave.
fn time_updates(device: &Device, patches: &Patches, m: &CompressedMatrix, lights: &[GpuLight]) {
    let slices = Settings::of_process().direct_slices;
    let result = Update::new(device, patches, m, slices).and_then(|mut update| {
        let runs: Result<Vec<_>, _> = (0..UPDATES).map(|_| update.run(device, lights)).collect();
        update.destroy(device);
        runs
    });
    let runs = match result {
        Ok(runs) => runs,
        Err(e) => return eprintln!("glrt: the per-frame update on {} failed: {e}", device.name()),
    };
    let times: Vec<UpdateTime> = runs.iter().map(|(_, t)| *t).collect();
    let line = |what: &str, times: &[UpdateTime]| {
        let best = |f: &dyn Fn(&UpdateTime) -> Option<std::time::Duration>| times.iter().filter_map(f).map(|d| d.as_secs_f64() * 1e3).fold(f64::INFINITY, f64::min);
        let gpu = |f: &dyn Fn(&UpdateTime) -> Option<std::time::Duration>| {
            let t = best(f);
            if t.is_finite() { format!("{t:.3} ms on the GPU") } else { "no GPU timestamps".to_owned() }
        };
        let w = times[times.len() - 1].direct_work;
        println!(
            "{what}: direct light {:.3} ms wall ({}), product {:.3} ms wall ({}); the last one's shadow rays: {} (patch, point, light) pairs, {:.1} BVH nodes visited a pair, {} by the longest ray",
            best(&|t| Some(t.direct.wall)),
            gpu(&|t| t.direct.gpu),
            best(&|t| Some(t.gather.wall)),
            gpu(&|t| t.gather.gpu),
            w.pairs,
            w.nodes as f64 / w.pairs.max(1) as f64,
            w.longest,
        );
    };
    println!("per-frame update on {}, direct-light slices: {slices}", device.name());
    line("first update (all the points)", &times[..1]);
    line(&format!("next updates (one slice each), best of {}", UPDATES - 1), &times[1..]);
    if let Some((r, _)) = runs.last() {
        let mean = |v: &mut dyn Iterator<Item = Vec3>| v.fold(Vec3::ZERO, |a, b| a + b) / r.radiosity.len().max(1) as f32;
        let irradiance = mean(&mut r.direct.iter().map(|l| l.irradiance));
        let primary = mean(&mut r.direct.iter().map(|l| l.primary));
        let radiosity = mean(&mut r.radiosity.iter().copied());
        println!("mean over the patches: direct irradiance {irradiance:.4}, primary radiosity {primary:.4}, radiosity {radiosity:.4}");
    }
}

/// Updates [`time_updates`] times.
const UPDATES: usize = 10;
