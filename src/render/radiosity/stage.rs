//! The renderer's radiosity stage (`[radiosity] enabled`), for raster and traced frames: the static
//! world's patches and compressed k-bounce matrix, built once per static world (the form
//! factors and the k-bounce matrix on the device, else on the CPU: [`OnDevice`]; the matrix from the disk cache when it has it,
//! [`precompute::load_or_build`]), then per frame the update on the device
//! ([`Update`]: direct light from the frame's lights, then the product) whenever the lights
//! or the world changed, and after a change of the lights until the direct light's slices of
//! points are all the new lights' ([`Update::settled`]), and its [`IndirectLight`] for the raster draws ([`super::transfer`])
//! or the tracer ([`crate::render::trace::radiosity`]).
//!
//! The precompute of a new static world runs on a thread of its own, with a Vulkan device of
//! its own for the form factors (the renderer's queue is never shared): the frames meanwhile
//! are drawn without radiosity (raster: GL's ambient term; traced: the paths' own bounces), then
//! it switches on; stderr says both, with the frames drawn without it. `radiosity_wait` makes
//! the frame that meets the world wait for it instead (tests, comparisons). The memory budget
//! bounds the precompute's size ([`precompute::patches_within_budget`]). A stage that fails
//! (device memory, a shader) says so once and stops: raster frames keep GL's ambient term,
//! traced paths their bounces.
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

use glam::{Mat4, Vec3};

use super::bounces;
use super::form_factors::{self, FormFactors};
use super::gpu::update::Update;
use super::matrix::ColourMatrix;
use super::patches::Patches;
use super::precompute::{self, StaticRadiosity, Steps};
use super::progress::Progress;
use super::settings::Settings;
use super::lights::same_lights;
use super::transfer::IndirectLight;
use crate::frame::Frame;
use crate::frame::world::StaticChunk;
use crate::render::raster::device::Device;
use crate::render::trace::gpu_types::GpuLight;
use crate::render::trace::lights::LightSettings;

/// The static world the stage holds, and its last update.
struct World {
    /// Ids of the chunks it was built from, sorted.
    chunks: Vec<u64>,
    patches: Patches,
    update: Update,
    /// The lights of the last update and its result.
    last: Option<(Vec<GpuLight>, Arc<IndirectLight>)>,
}

/// A static world whose matrix is being precomputed on its own thread.
struct Pending {
    /// Ids of its chunks, sorted.
    chunks: Vec<u64>,
    thread: JoinHandle<StaticRadiosity>,
    start: Instant,
    /// Frames drawn without radiosity while it runs.
    frames_without: u64,
}

/// What the stage holds.
enum Held {
    Nothing,
    Pending(Pending),
    Ready(Box<World>),
}

/// The radiosity stage.
pub struct RadiosityStage {
    settings: Settings,
    lights: LightSettings,
    /// The disk cache's directory ([`crate::config::cache_dir`] unless told otherwise).
    cache: PathBuf,
    held: Held,
    /// Frames drawn without radiosity while a precompute ran, over the stage's life.
    frames_without: u64,
    /// Updates run on the device (direct light and product), over the stage's life.
    updates: u64,
    /// Set after a failure: the stage does nothing more.
    failed: bool,
}

/// A frame's indirect light and the frame's eye-to-world transform.
#[derive(Clone, Debug)]
pub struct FrameIndirect {
    /// The patches' indirect light (world frame).
    pub light: Arc<IndirectLight>,
    /// Inverse of the frame's recovered view.
    pub eye_to_world: Mat4,
}

impl RadiosityStage {
    /// A stage with `settings`, the frame's lights read as the tracer reads them (`lights`).
    pub fn new(settings: Settings, lights: LightSettings) -> RadiosityStage {
        RadiosityStage { settings, lights, cache: crate::config::cache_dir(), held: Held::Nothing, frames_without: 0, updates: 0, failed: false }
    }

    /// The stage with its matrices cached under `dir` instead.
    pub fn with_cache_dir(self, dir: PathBuf) -> RadiosityStage {
        RadiosityStage { cache: dir, ..self }
    }

    /// Frames drawn without radiosity because its precompute was running.
    pub fn frames_without(&self) -> u64 {
        self.frames_without
    }

    /// Updates run on the device (direct light and product): one per frame whose lights or
    /// static world changed.
    pub fn updates(&self) -> u64 {
        self.updates
    }

    /// The indirect light of `frame`: none without a static world or a recovered view, while
    /// the precompute runs, or after a failure.
    pub fn update(&mut self, device: &Device, frame: &Frame) -> Option<FrameIndirect> {
        if self.failed || frame.static_world.is_empty() {
            return None;
        }
        let view = frame.view.as_ref()?;
        match self.try_update(device, frame) {
            Ok(light) => light.map(|light| FrameIndirect { light, eye_to_world: view.view.inverse() }),
            Err(e) => {
                eprintln!("glrt: radiosity stopped: {e}; the static world keeps GL's ambient light (raster) or traced bounces");
                self.failed = true;
                if let Held::Ready(world) = std::mem::replace(&mut self.held, Held::Nothing) {
                    world.update.destroy(device);
                }
                None
            }
        }
    }

    fn try_update(&mut self, device: &Device, frame: &Frame) -> crate::render::raster::device::Result<Option<Arc<IndirectLight>>> {
        let mut chunks: Vec<u64> = frame.static_world.iter().map(|c| c.id).collect();
        chunks.sort_unstable();
        let held_chunks = match &self.held {
            Held::Nothing => None,
            Held::Pending(p) => Some(&p.chunks),
            Held::Ready(w) => Some(&w.chunks),
        };
        if held_chunks != Some(&chunks) {
            // A precompute of an older world runs on to its end, unused.
            if let Held::Ready(old) = std::mem::replace(&mut self.held, Held::Nothing) {
                old.update.destroy(device);
            }
            eprintln!("glrt: radiosity: a new static world: precomputing its matrix on a thread of its own; frames are drawn without radiosity until it is ready");
            let world: Vec<Arc<StaticChunk>> = frame.static_world.to_vec();
            let (settings, cache) = (self.settings, self.cache.clone());
            let thread = std::thread::Builder::new().name("glrt-radiosity".into()).spawn(move || precompute_on_own_device(&world, &settings, &cache));
            match thread {
                Ok(thread) => self.held = Held::Pending(Pending { chunks, thread, start: Instant::now(), frames_without: 0 }),
                Err(e) => {
                    eprintln!("glrt: radiosity: no thread for the precompute ({e}): computing it in this frame");
                    let r = precompute_on_own_device(&frame.static_world, &self.settings, &self.cache);
                    let Some(world) = self.world_of(device, chunks, r, Instant::now(), 0)? else { return Ok(None) };
                    self.held = Held::Ready(world);
                }
            }
        }
        if let Held::Pending(pending) = &mut self.held {
            if !(self.settings.wait || pending.thread.is_finished()) {
                pending.frames_without += 1;
                self.frames_without += 1;
                return Ok(None);
            }
            let Held::Pending(pending) = std::mem::replace(&mut self.held, Held::Nothing) else { unreachable!("matched above") };
            let Ok(r) = pending.thread.join() else {
                self.failed = true;
                eprintln!("glrt: radiosity stopped: its precompute panicked; the static world keeps GL's ambient light (raster) or traced bounces");
                return Ok(None);
            };
            let Some(world) = self.world_of(device, pending.chunks, r, pending.start, pending.frames_without)? else { return Ok(None) };
            self.held = Held::Ready(world);
        }
        let Held::Ready(world) = &mut self.held else { return Ok(None) };
        let lights = super::lights::of_frame(frame, &self.lights);
        if let Some((last, light)) = &world.last
            && same_lights(last, &lights)
            && world.update.settled()
        {
            return Ok(Some(light.clone()));
        }
        let (r, _) = world.update.run(device, &lights)?;
        self.updates += 1;
        let primary: Vec<Vec3> = r.direct.iter().map(|l| l.primary).collect();
        let light = Arc::new(IndirectLight::new(&world.patches, &r.radiosity, &primary));
        world.last = Some((lights, light.clone()));
        Ok(Some(light))
    }

    /// The world of a finished precompute `r` on `device`, saying what it took; `None`, and
    /// radiosity stopped, when the world has no patches (more surface orientations than the
    /// budget holds: [`precompute::patches_within_budget`]'s note says so).
    fn world_of(&mut self, device: &Device, chunks: Vec<u64>, r: StaticRadiosity, start: Instant, frames_without: u64) -> crate::render::raster::device::Result<Option<Box<World>>> {
        for note in &r.notes {
            eprintln!("glrt: radiosity: {note}");
        }
        if r.patches.patches.is_empty() {
            eprintln!("glrt: radiosity stopped: the static world has no patches; it keeps GL's ambient light (raster) or traced bounces");
            self.failed = true;
            return Ok(None);
        }
        let how = if r.loaded { "loaded" } else { "computed" };
        eprintln!(
            "glrt: radiosity: {} patches, matrix {how} in {:.1} s; radiosity on ({frames_without} frames were drawn without it)",
            r.patches.patches.len(),
            start.elapsed().as_secs_f64()
        );
        let update = Update::new(device, &r.patches, &r.matrix, self.settings.direct_slices)?;
        Ok(Some(Box::new(World { chunks, patches: r.patches, update, last: None })))
    }

    /// Frees the device's objects (the device idle).
    pub fn destroy(&mut self, device: &Device) {
        if let Held::Ready(world) = std::mem::replace(&mut self.held, Held::Nothing) {
            world.update.destroy(device);
        }
    }
}

/// The precompute of `world` (the matrix of the disk cache under `cache` when it has it), the
/// heavy steps on a Vulkan device of this thread's own (the renderer's queue is not shared),
/// else the CPU.
fn precompute_on_own_device(world: &[Arc<StaticChunk>], settings: &Settings, cache: &Path) -> StaticRadiosity {
    let device = Device::new().map_err(|e| eprintln!("glrt: radiosity: no Vulkan device of its own for the form factors and the k-bounce matrix ({e}): they are computed on the CPU")).ok();
    precompute::load_or_build(world, settings, Some(cache), &mut OnDevice(device.as_ref()))
}

/// The precompute's heavy steps on a Vulkan device (the form factors, the k-bounce matrix),
/// each on the CPU without one or when the device fails, with a message saying why; their
/// progress on stderr ([`Progress::Stderr`]). On a CPU device (lavapipe) the k-bounce matrix
/// is the CPU's: its blocked product on every core is about 10x faster than the device's
/// compute there (bench/radiosity.md, session 21).
pub struct OnDevice<'a>(pub Option<&'a Device>);

impl<'a> OnDevice<'a> {
    /// The device the k-bounce matrix is computed on: a GPU, not a CPU device.
    pub fn product_device(&self) -> Option<&'a Device> {
        self.0.filter(|d| d.properties.device_type != ash::vk::PhysicalDeviceType::CPU)
    }
}

impl Steps for OnDevice<'_> {
    fn form_factors(&mut self, p: &Patches) -> FormFactors {
        let n = p.patches.len();
        if let Some(device) = self.0 {
            let stage = Progress::Stderr.stage(&format!("form factors of {n} patches on {} (once per static world; the matrix is cached)", device.name()), n as u64, "rows");
            let mut counted = 0;
            let result = super::gpu::form_factors::compute(device, p, &mut |done, _| {
                stage.add(done.saturating_sub(counted) as u64);
                counted = counted.max(done);
            });
            stage.finish();
            match result {
                Ok(f) => return f,
                Err(e) => eprintln!("glrt: radiosity: form factors on {} failed ({e}): computing them on the CPU", device.name()),
            }
        }
        let stage = Progress::Stderr.stage(&format!("form factors of {n} patches on the CPU"), 1, "matrix");
        let f = form_factors::compute(p);
        stage.finish();
        f
    }

    fn k_bounce(&mut self, colour: &ColourMatrix, k: u32, progress: Progress) -> ColourMatrix {
        if let Some(device) = self.product_device() {
            match super::gpu::product::k_bounce(device, colour, k, progress) {
                Ok(m) => return m,
                Err(e) => eprintln!("glrt: radiosity: the k-bounce matrix on {} failed ({e}): computing it on the CPU", device.name()),
            }
        }
        bounces::k_bounce(colour, k, progress)
    }
}
