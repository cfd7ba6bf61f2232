//! `glrt radiosity FILE`: replays a capture without drawing and runs the radiosity precompute
//! on the static world of its last frame with the `[radiosity]` settings (`glrt.toml`,
//! `GLRT_*`): times, sizes and errors as Markdown (`glrt::render::radiosity::precompute`).
//! With `--matrix`, only the compressed matrix the renderer uses, read from the disk cache
//! when it holds it, else computed and written there; it says which and how long it took,
//! then times the per-frame product on the device (`radiosity::gpu::gather`).
//!
//! The form factors are computed on the Vulkan device (`GLRT_DEVICE`) with a progress bar;
//! without one, or when it fails, on the CPU, with a message saying why.

use std::sync::Arc;
use std::time::Instant;

use glam::Vec3;

use glrt::frame::FrameSink;
use glrt::render::radiosity::form_factors::{self, FormFactors};
use glrt::render::radiosity::compress::CompressedMatrix;
use glrt::render::radiosity::gpu::gather::{Gather, synthetic};
use glrt::render::radiosity::gpu::pass::DispatchTime;
use glrt::render::radiosity::patches::Patches;
use glrt::render::radiosity::precompute;
use glrt::render::radiosity::settings::Settings;
use glrt::render::raster::device::Device;
use glrt::replay::{self, reader::Capture};

use crate::progress::counted;

/// Keeps the static world of the last frame presented.
#[derive(Clone, Default)]
struct LastWorld(Arc<parking_lot::Mutex<Vec<Arc<glrt::frame::world::StaticChunk>>>>);

impl FrameSink for LastWorld {
    fn present(&mut self, frame: glrt::frame::Frame) {
        *self.0.lock() = frame.static_world.to_vec();
    }
}

/// The form factors of `p` on `device` when there is one and it succeeds, else on the CPU;
/// says where and how long on stderr.
fn form_factors_on(device: &Option<Device>, p: &Patches) -> FormFactors {
    let n = p.patches.len();
    let start = Instant::now();
    if let Some(device) = device {
        let bar = counted("form factors", "rows", || n as u64);
        let result = glrt::render::radiosity::gpu::form_factors::compute(device, p, &mut |done, _| bar.set_position(done as u64));
        bar.finish_and_clear();
        match result {
            Ok(f) => {
                eprintln!("glrt: form factors of {n} patches on {}: {:.2} s", device.name(), start.elapsed().as_secs_f64());
                return f;
            }
            Err(e) => eprintln!("glrt: form factors on {} failed ({e}): computing them on the CPU", device.name()),
        }
    }
    let f = form_factors::compute(p);
    eprintln!("glrt: form factors of {n} patches on the CPU: {:.2} s", start.elapsed().as_secs_f64());
    f
}

/// Runs the precompute (or with `matrix_only`, builds or loads the renderer's matrix) on
/// `capture`'s last static world and prints what it measured.
pub fn run(capture: &Capture, matrix_only: bool) -> Result<(), String> {
    let world = LastWorld::default();
    let sink = world.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    replay::run(capture, &options)?;
    let chunks = world.0.lock().clone();
    if chunks.is_empty() {
        return Err("radiosity: the capture's last frame has no static world".to_owned());
    }
    let settings = Settings::of_process();
    let device = Device::new().map_err(|e| eprintln!("glrt: no Vulkan device for the form factors ({e}): they are computed on the CPU")).ok();
    if !matrix_only {
        print!("{}", precompute::run(&chunks, &settings, &mut |p| form_factors_on(&device, p)).markdown());
        return Ok(());
    }
    let start = Instant::now();
    let r = precompute::load_or_build(&chunks, &settings, Some(&glrt::config::cache_dir()), &mut |p| form_factors_on(&device, p));
    for note in &r.notes {
        eprintln!("glrt: {note}");
    }
    let file = r.cache_file.as_ref().map_or_else(String::new, |f| f.display().to_string());
    let how = if r.loaded { format!("loaded from {file}") } else { format!("computed, written to {file}") };
    println!("{} patches, compressed matrix {} bytes: {how} in {:.3} s", r.patches.patches.len(), r.matrix.bytes(), start.elapsed().as_secs_f64());
    if let Some(device) = &device {
        let primary: Vec<Vec3> = r.patches.patches.iter().map(|p| p.emission + Vec3::ONE).collect();
        time_products(device, &r.matrix, &primary);
    }
    Ok(())
}

/// `glrt radiosity --synthetic N`: the per-frame product of [`synthetic`]'s matrix of `n`
/// patches timed on the device.
pub fn time_synthetic(n: usize) -> Result<(), String> {
    let device = Device::new().map_err(|e| format!("radiosity: no Vulkan device: {e}"))?;
    let m = synthetic(n, 0x9e37_79b9_7f4a_7c15);
    println!("synthetic matrix: {n} patches, {} bytes of BC1, {} exact entries", m.texture.bytes(), m.sparse.len());
    time_products(&device, &m, &vec![Vec3::ONE; n]);
    Ok(())
}

/// Products the renderer's per-frame update timed: [`PRODUCTS`] of `m` with `primary` on
/// `device`; prints the best times.
fn time_products(device: &Device, m: &CompressedMatrix, primary: &[Vec3]) {
    let times = Gather::new(device, m).and_then(|mut gather| {
        let times: Result<Vec<DispatchTime>, _> = (0..PRODUCTS).map(|_| gather.run(device, primary).map(|(_, t)| t)).collect();
        gather.destroy(device);
        times
    });
    match times {
        Ok(times) => {
            let best = |f: &dyn Fn(&DispatchTime) -> Option<f64>| times.iter().filter_map(f).fold(f64::INFINITY, f64::min);
            let gpu = best(&|t| t.gpu.map(|d| d.as_secs_f64() * 1e3));
            let gpu = if gpu.is_finite() { format!("{gpu:.3} ms on the GPU") } else { "no GPU timestamps on this device".to_owned() };
            println!("per-frame product on {}: best of {PRODUCTS}: {:.3} ms wall, {gpu}", device.name(), best(&|t| Some(t.wall.as_secs_f64() * 1e3)));
        }
        Err(e) => eprintln!("glrt: the per-frame product on {} failed: {e}", device.name()),
    }
}

/// Products [`time_products`] times.
const PRODUCTS: usize = 10;
