//! The renderer's radiosity stage (`[radiosity] enabled`), for raster and traced frames: the static
//! world's patches and compressed k-bounce matrix, built once per static world (the form
//! factors on the device, else on the CPU; the matrix from the disk cache when it has it,
//! [`precompute::load_or_build`]), then per frame the update on the device
//! ([`Update`]: direct light from the frame's lights, then the product) whenever the lights
//! or the world changed, and its [`IndirectLight`] for the raster draws ([`super::transfer`])
//! or the tracer ([`crate::render::trace::radiosity`]).
//!
//! The precompute blocks the frame that meets a new static world (said once on stderr, with
//! its time); the memory budget bounds its size ([`precompute::patches_within_budget`]). A
//! stage that fails (device memory, a shader) says so once and stops: raster frames keep GL's
//! ambient term, traced paths their bounces.

use std::sync::Arc;
use std::time::Instant;

use glam::{Mat4, Vec3};

use super::form_factors::{self, FormFactors};
use super::gpu::update::Update;
use super::patches::Patches;
use super::precompute;
use super::progress::Progress;
use super::settings::Settings;
use super::transfer::IndirectLight;
use crate::frame::Frame;
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

/// The radiosity stage.
pub struct RadiosityStage {
    settings: Settings,
    lights: LightSettings,
    world: Option<World>,
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
        RadiosityStage { settings, lights, world: None, failed: false }
    }

    /// The indirect light of `frame`: none without a static world or a recovered view, or
    /// after a failure.
    pub fn update(&mut self, device: &Device, frame: &Frame) -> Option<FrameIndirect> {
        if self.failed || frame.static_world.is_empty() {
            return None;
        }
        let view = frame.view.as_ref()?;
        match self.try_update(device, frame) {
            Ok(light) => Some(FrameIndirect { light, eye_to_world: view.view.inverse() }),
            Err(e) => {
                eprintln!("glrt: radiosity stopped: {e}; the static world keeps GL's ambient light (raster) or traced bounces");
                self.failed = true;
                if let Some(world) = self.world.take() {
                    world.update.destroy(device);
                }
                None
            }
        }
    }

    fn try_update(&mut self, device: &Device, frame: &Frame) -> crate::render::raster::device::Result<Arc<IndirectLight>> {
        let mut chunks: Vec<u64> = frame.static_world.iter().map(|c| c.id).collect();
        chunks.sort_unstable();
        if self.world.as_ref().is_none_or(|w| w.chunks != chunks) {
            if let Some(old) = self.world.take() {
                old.update.destroy(device);
            }
            let start = Instant::now();
            let r = precompute::load_or_build(&frame.static_world, &self.settings, Some(&crate::config::cache_dir()), &mut |p| form_factors_on(Some(device), p));
            for note in &r.notes {
                eprintln!("glrt: radiosity: {note}");
            }
            let how = if r.loaded { "loaded" } else { "computed" };
            eprintln!("glrt: radiosity: {} patches, matrix {how} in {:.1} s", r.patches.patches.len(), start.elapsed().as_secs_f64());
            let update = Update::new(device, &r.patches, &r.matrix)?;
            self.world = Some(World { chunks, patches: r.patches, update, last: None });
        }
        let world = self.world.as_mut().expect("built above");
        let lights = super::lights::of_frame(frame, &self.lights);
        if let Some((last, light)) = &world.last
            && *last == lights
        {
            return Ok(light.clone());
        }
        let (r, _) = world.update.run(device, &lights)?;
        let primary: Vec<Vec3> = r.direct.iter().map(|l| l.primary).collect();
        let light = Arc::new(IndirectLight::new(&world.patches, &r.radiosity, &primary));
        world.last = Some((lights, light.clone()));
        Ok(light)
    }

    /// Frees the device's objects (the device idle).
    pub fn destroy(&mut self, device: &Device) {
        if let Some(world) = self.world.take() {
            world.update.destroy(device);
        }
    }
}

/// The form factors of `p` on `device`, or on the CPU when there is none or it fails, with
/// their progress on stderr ([`Progress::Stderr`]).
pub fn form_factors_on(device: Option<&Device>, p: &Patches) -> FormFactors {
    let n = p.patches.len();
    if let Some(device) = device {
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
