//! The Vulkan renderer ([`Renderer`], the [`FrameSink`] of a context): one [`Frame`] in, one
//! image out, as a sequence of stages that `Renderer::record` runs top to bottom (kajiya's
//! `world_render_passes.rs` is the model, DESIGN.md "The frame in the renderer"):
//!
//! 1. raster composite, first part ([`Raster::record`]): the clears, pixel operations and
//!    raster draws placed before the first traced draw (the sky), in program order;
//! 2. upload and acceleration structures ([`RayTracer::build`]) of the traced draws and the
//!    static world;
//! 3. trace ([`RayTracer::trace`]): the G-buffer and radiance;
//! 4. denoise ([`Denoiser::record`], A-SVGF, when enabled) or else resolve
//!    ([`RayTracer::resolve`]: the tracer's temporal filter), then tone mapping;
//! 5. composite ([`Composite::record`]): the traced colour and depth into the framebuffer, at
//!    the place of the first traced draw, fogged by the height fog ([`crate::render::fog`],
//!    which the raster draws apply per fragment);
//! 6. raster composite, the rest: the draws after it (translucent, overlay) over the traced
//!    image, depth-tested against its depth; the passes of traced surfaces (draws of class
//!    `Layer` the tracer evaluates, [`Surfaces`]) are not rasterized;
//! 7. present ([`Raster::present`]: back to front at a swap, the HUD over it when on
//!    ([`crate::render::hud`]), the outputs, submission) or read back ([`Raster::read`]).
//!
//! Without a [`RayTracer`] (raster mode) steps 2 to 5 are left out and every draw is
//! rasterized; ambient occlusion ([`AmbientOcclusion`], when enabled) then runs once, after
//! the last opaque 3D draw ([`crate::render::ao::place`]). Radiosity ([`RadiosityStage`], when
//! enabled) runs before step 1, once per frame: its indirect light goes to the raster draws of
//! the static world, or to step 2 (the path's first diffuse bounce on the static world).
//!
//! Failures degrade (DESIGN.md, "Files, variables, conventions"), each said once on stderr:
//! tracing stages that cannot be created or fail in a frame (a shader the driver cannot
//! compile, GPU memory) leave the renderer rasterizing every draw; a lost device is replaced
//! once by a new one (rasterizing; the frame that was being drawn is drawn again on it, from
//! the `Frame`, which holds every texture's content; images drawn in earlier frames, such as
//! framebuffer objects' textures, start black); any other error, or a second lost device,
//! stops drawing: frames are dropped and read-backs are black.
//!
//! A frame read back before its end (`glReadPixels`, pixel copies) is recorded in parts: each
//! call of `Renderer::record` goes on where the last one stopped ([`Raster::recorded_draws`]),
//! so the traced stages run once per frame, when the recording first passes the traced place.
//! A long frame that `translate` submits in parts ([`FrameEnd::Part`]) arrives as several
//! frames, each drawn over what the one before left in the framebuffers (the traced stages
//! run in each part that has traced draws).

use crate::frame::pixels::PixelBuffer;
use crate::frame::{Draw, Frame, FrameEnd};
use crate::frame::FrameSink;
use crate::frame::storage::StoragePool;
use crate::render::ao::AmbientOcclusion;
use crate::render::ao::settings::AoSettings;
use crate::render::denoise::Denoiser;
use crate::render::denoise::settings::DenoiseSettings;
use crate::render::fog::settings::FogSettings;
use crate::render::hud::canvas::Canvas;
use crate::render::hud::{Display, FrameInfo, Hud};
use crate::render::radiosity::settings::Settings as RadiositySettings;
use crate::render::radiosity::stage::{FrameIndirect, RadiosityStage};
use crate::render::raster::device::{Device, Error, Result};
use crate::render::raster::dump::Dump;
use crate::render::raster::output::FrameOutput;
use crate::render::raster::renderer::{FRAMES_IN_FLIGHT, Raster, Recorder};
use crate::render::trace::composite::Composite;
use crate::render::trace::lights::LightSettings;
use crate::render::trace::settings::Settings;
use crate::render::trace::shader_constants::{FRAME_GRADIENTS, FRAME_SPECULAR};
use crate::render::trace::surfaces::Surfaces;
use crate::render::trace::{self, RayTracer};

/// The Vulkan renderer: owns the stages of a frame.
pub struct Renderer {
    /// Command recording, framebuffers, and the raster stages (clears, pixel operations,
    /// raster draws, present, read-back).
    raster: Raster,
    /// The path-tracing stages, when the mode traces.
    tracing: Option<Tracing>,
    /// Tracing stages that failed, freed when the GPU is idle (frames in flight may use them).
    retired: Option<Tracing>,
    /// Set after a device error: frames are dropped.
    failed: bool,
    /// Whether the device was lost and replaced already (it is replaced once).
    replaced: bool,
    /// The drawable of the last [`FrameSink::set_target`], for a replacement device.
    target: Option<crate::frame::Target>,
    /// The HUD, when `GLRT_HUD` asks for it.
    hud: Option<Hud>,
    /// Ambient occlusion of raster frames, when enabled.
    ao: Option<AmbientOcclusion>,
    /// The number of the last frame that got ambient occlusion (it runs once per frame).
    occluded_frame: Option<u64>,
    /// Radiosity, when enabled: the indirect light of raster frames' static draws and of the
    /// path tracer's first diffuse bounce on the static world.
    radiosity: Option<RadiosityStage>,
    /// The number of the last frame whose indirect light was found (once per frame).
    radiosity_frame: Option<u64>,
    /// That frame's indirect light.
    indirect: Option<FrameIndirect>,
    /// The storage of the draws of frames drawn, for the context to fill again.
    spent: StoragePool,
}

/// The path-tracing stages: a ray-tracing back end, the denoiser (when enabled) and the
/// composite of its image.
struct Tracing {
    backend: Box<dyn RayTracer>,
    denoiser: Option<Denoiser>,
    composite: Composite,
}

impl Renderer {
    /// Creates the renderer on the device chosen by `GLRT_DEVICE` (see [`Device::new`]),
    /// rasterizing, dumping frames where `GLRT_DUMP` says and presenting them to the window.
    pub fn new() -> Result<Renderer> {
        Renderer::with_dump(Dump::from_env())
    }

    /// Creates the renderer on the device chosen by `GLRT_DEVICE`, rasterizing, dumping frames
    /// to `dump` and presenting them to the window, if any.
    pub fn with_dump(dump: Option<Dump>) -> Result<Renderer> {
        let mut renderer = Renderer::without_outputs()?;
        if let Some(dump) = dump {
            renderer.add_output(Box::new(dump));
        }
        renderer.add_output(Box::new(crate::render::present::window_output::WindowOutput::new()));
        Ok(renderer)
    }

    /// Creates the renderer with no [`FrameOutput`]: frames stay in the framebuffer.
    pub fn without_outputs() -> Result<Renderer> {
        let hud = Display::of_process().hud.then(Hud::default);
        Ok(Renderer { raster: Raster::new()?, tracing: None, retired: None, failed: false, replaced: false, target: None, hud, ao: None, occluded_frame: None, radiosity: None, radiosity_frame: None, indirect: None, spent: StoragePool::default() })
    }

    /// Path traces the traced draws of the next frames with `settings`, with the back end
    /// [`trace::backend`] chooses for the device; the other draws stay rasterized around them.
    pub fn enable_tracing(&mut self, settings: Settings) -> Result<()> {
        if self.tracing.is_none() {
            let device = self.raster.device();
            let mut backend = trace::backend(device, settings, FRAMES_IN_FLIGHT)?;
            match Composite::new(device) {
                Ok(composite) => self.tracing = Some(Tracing { backend, denoiser: None, composite }),
                Err(e) => {
                    backend.destroy(device);
                    return Err(e);
                }
            }
        }
        Ok(())
    }

    /// Denoises the traced frames with `settings` ([`Denoiser`]) in place of the back end's
    /// temporal filter; nothing without tracing.
    pub fn enable_denoising(&mut self, settings: DenoiseSettings) -> Result<()> {
        if let Some(tracing) = &mut self.tracing
            && tracing.denoiser.is_none()
        {
            tracing.denoiser = Some(Denoiser::new(self.raster.device(), settings)?);
        }
        Ok(())
    }

    /// Fogs the next frames with the height fog of `settings` ([`crate::render::fog`]), in
    /// both modes.
    pub fn set_fog(&mut self, settings: FogSettings) {
        self.raster.set_fog(settings);
    }

    /// Gives the next raster frames ambient occlusion with `settings` ([`AmbientOcclusion`]);
    /// frames that are path traced get none.
    pub fn enable_ambient_occlusion(&mut self, settings: AoSettings) -> Result<()> {
        if self.ao.is_none() {
            self.ao = Some(AmbientOcclusion::new(self.raster.device(), settings)?);
        }
        Ok(())
    }

    /// Lights the static world of the next frames with radiosity ([`RadiosityStage`] with
    /// `settings`, the frame's lights read as the tracer's `lights` settings say): raster
    /// frames' static draws, and traced frames' paths at their first diffuse bounce on it.
    pub fn enable_radiosity(&mut self, settings: RadiositySettings, lights: LightSettings) {
        if self.radiosity.is_none() {
            self.radiosity = Some(RadiosityStage::new(settings, lights));
        }
    }

    /// The ray-tracing back end, when tracing is enabled (statistics: rays, scenes, frames).
    pub fn tracer(&self) -> Option<&dyn RayTracer> {
        self.tracing.as_ref().map(|t| &*t.backend)
    }

    /// The raster stage (statistics: pipelines, programs, textures).
    pub fn raster(&self) -> &Raster {
        &self.raster
    }

    /// The device.
    pub fn device(&self) -> &Device {
        self.raster.device()
    }

    /// Adds a consumer of presented frames (presentation, dumps), called in the order added.
    pub fn add_output(&mut self, output: Box<dyn FrameOutput>) {
        self.raster.add_output(output);
    }

    /// Records what of `frame` is not recorded yet: the stages of the module doc, in order.
    fn record(&mut self, frame: &Frame) -> Result<()> {
        // The traced surfaces (bases and their passes): neither is rasterized when tracing.
        let surfaces = self.tracing.as_ref().map(|_| Surfaces::of(frame));
        let traced_at = surfaces.as_ref().and_then(Surfaces::first);
        let rasterized = |index: usize| !surfaces.as_ref().is_some_and(|s| s.is_traced(index));
        // Where ambient occlusion goes in a raster frame that has not had it yet.
        let occlusion_at = (self.tracing.is_none() && self.ao.is_some() && self.occluded_frame != Some(frame.number))
            .then(|| crate::render::ao::place(frame).map(|(at, _)| at))
            .flatten();
        // Radiosity's indirect light of the frame, once, before its draws: the raster draws'
        // or the tracer's.
        if self.radiosity_frame != Some(frame.number) {
            self.radiosity_frame = Some(frame.number);
            self.indirect = match &mut self.radiosity {
                Some(stage) => stage.update(self.raster.device(), frame),
                None => None,
            };
            self.raster.set_indirect(self.indirect.clone().filter(|_| self.tracing.is_none()));
        }
        // Raster composite up to the traced image's (or the occlusion's) place: clears, pixel
        // operations, draws.
        self.raster.record(frame, traced_at.or(occlusion_at), &rasterized)?;
        // The traced stages, once per frame, in place of the first traced draw.
        if let Some(tracing) = &mut self.tracing
            && let Some(surfaces) = &surfaces
            && let Some(at) = traced_at
            && self.raster.recorded_draws(frame) == at
        {
            let mut rec = self.raster.recorder_into(None, frame.size)?;
            let traced = tracing.record(&mut rec, frame, surfaces, &frame.draws[at], self.indirect.as_ref());
            self.raster.skip_draw(frame, at);
            match traced {
                Err(e @ Error::Vulkan(_, ash::vk::Result::ERROR_DEVICE_LOST)) => return Err(e),
                Err(e) => {
                    eprintln!("glrt: path tracing stopped: {e}; frames are rasterized from now on");
                    self.retired = self.tracing.take();
                }
                Ok(()) => {}
            }
        }
        // Ambient occlusion of a raster frame, once, after its last opaque 3D draw.
        if self.tracing.is_none()
            && let Some(ao) = &mut self.ao
            && let Some((at, camera)) = crate::render::ao::place(frame)
            && self.raster.recorded_draws(frame) <= at
            && self.occluded_frame != Some(frame.number)
        {
            self.raster.record(frame, Some(at), &rasterized)?;
            self.occluded_frame = Some(frame.number);
            let mut rec = self.raster.recorder_into(None, frame.size)?;
            ao.record(&mut rec, camera)?;
        }
        // Raster composite, the rest: the draws after it (glass, HUD), over the traced image
        // and depth-tested against its depth.
        self.raster.record(frame, None, &rasterized)
    }

    /// Renders the rest of `frame` and submits it for presentation.
    fn finish(&mut self, frame: &Frame) -> Result<()> {
        self.record(frame)?;
        let hud = self.hud_panel(frame);
        self.raster.present(frame, hud.as_ref())
    }

    /// The HUD's panel of `frame`, at a swap when the HUD is on.
    fn hud_panel(&mut self, frame: &Frame) -> Option<Canvas> {
        let hud = self.hud.as_mut().filter(|_| frame.end == FrameEnd::Swap)?;
        let tracer = self.tracing.as_ref().map(|t| &*t.backend);
        let mode = tracer.map_or_else(|| "raster".to_owned(), |t| format!("pathtrace ({})", t.name()));
        let info = FrameInfo {
            mode: &mode,
            device: &self.raster.device().name(),
            classes: &frame.stats.classes,
            rays: tracer.map(|t| t.statistics().rays.total()),
        };
        Some(hud.frame(&info))
    }

    /// Renders `frame` so far and reads `rect` of `buffer` back.
    fn read(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Result<Option<Vec<[f32; 4]>>> {
        self.record(frame)?;
        self.raster.read(frame, buffer, rect)
    }

    /// Runs `op`; after a lost device, once per renderer, replaces the device
    /// ([`Renderer::replace_device`]) and runs `op` again; `None` when it failed (said once,
    /// and the renderer stopped).
    fn attempt<T>(&mut self, mut op: impl FnMut(&mut Renderer) -> Result<T>) -> Option<T> {
        if self.failed {
            return None;
        }
        let e = match op(self) {
            Ok(v) => return Some(v),
            Err(e) => e,
        };
        if !self.replaced && matches!(e, Error::Vulkan(_, ash::vk::Result::ERROR_DEVICE_LOST)) {
            self.replaced = true;
            match self.replace_device() {
                Ok(()) => {
                    eprintln!("glrt: the Vulkan device was lost ({e}); rendering goes on, rasterized, on a new device");
                    match op(self) {
                        Ok(v) => return Some(v),
                        Err(e) => self.fail(e),
                    }
                }
                Err(new) => self.fail(Error::NoDevice(format!("the device was lost ({e}) and no new one could be made ({new})"))),
            }
            return None;
        }
        self.fail(e);
        None
    }

    /// Moves the renderer to a new device, rasterizing: the outputs and the drawable go over;
    /// the old device's stages are freed.
    fn replace_device(&mut self) -> Result<()> {
        let mut old = std::mem::replace(&mut self.raster, Raster::new()?);
        let outputs = old.take_outputs();
        for mut tracing in [self.tracing.take(), self.retired.take()].into_iter().flatten() {
            tracing.destroy(old.device());
        }
        if let Some(mut ao) = self.ao.take() {
            ao.destroy(old.device());
        }
        if let Some(mut radiosity) = self.radiosity.take() {
            radiosity.destroy(old.device());
        }
        drop(old);
        for output in outputs {
            self.raster.add_output(output);
        }
        if let Some(target) = self.target {
            self.raster.set_target(target);
        }
        Ok(())
    }

    /// Reports `e` once; frames are dropped from now on.
    fn fail(&mut self, e: Error) {
        if !self.failed {
            eprintln!("glrt: the Vulkan renderer stopped: {e}; frames are no longer drawn");
        }
        self.failed = true;
    }
}

impl Tracing {
    /// Records the traced stages of `frame`, whose traced surfaces are `surfaces`, into `rec`
    /// (the window's framebuffer, at the place of `camera`, the first traced draw), with
    /// radiosity's `indirect` light when there is one.
    fn record(&mut self, rec: &mut Recorder<'_>, frame: &Frame, surfaces: &Surfaces, camera: &Draw, indirect: Option<&FrameIndirect>) -> Result<()> {
        // Upload and acceleration structures.
        let mut scene = self.backend.build(rec, frame, surfaces, camera, indirect)?;
        if self.denoiser.as_ref().is_some_and(Denoiser::wants_gradient_samples) {
            scene.frame.flags[0] |= FRAME_GRADIENTS;
        }
        if self.denoiser.as_ref().is_some_and(Denoiser::wants_specular_channel) {
            scene.frame.flags[0] |= FRAME_SPECULAR;
        }
        // Trace: the G-buffer and radiance (nothing when no geometry is on the GPU yet).
        let Some(radiance) = self.backend.trace(rec, &scene)? else { return Ok(()) };
        // Denoise (A-SVGF), or resolve (the tracer's temporal filter); tone mapping.
        let image = match &mut self.denoiser {
            Some(denoiser) => denoiser.record(rec, &scene.frame, &radiance)?,
            None => self.backend.resolve(rec, radiance)?,
        };
        // Composite: the traced colour and depth into the framebuffer, fogged.
        self.composite.record(rec, &image, camera)
    }

    /// Frees the stages' GPU objects (the GPU must be idle) and logs the back end's totals.
    fn destroy(&mut self, device: &Device) {
        self.backend.destroy(device);
        if let Some(denoiser) = &mut self.denoiser {
            denoiser.destroy(device);
        }
        self.composite.destroy(device);
        let totals = &self.backend.statistics().totals;
        if totals.frames > 0 {
            log::info!("{}", totals.summary());
        }
    }
}

impl FrameSink for Renderer {
    /// Also takes the drawable's sample count and destination alpha (see
    /// [`Raster::set_target`]).
    fn set_target(&mut self, target: crate::frame::Target) {
        self.target = Some(target);
        self.raster.set_target(target);
    }

    /// After a part of a frame ([`FrameEnd::Part`]), once the part is dropped (but for its
    /// draws' storage, kept for the context), frees the texture versions that no frame
    /// references any more.
    fn present(&mut self, frame: Frame) {
        let part = frame.end == FrameEnd::Part;
        let finished = self.attempt(|r| r.finish(&frame)).is_some();
        self.spent.keep_frame(frame);
        if part && finished {
            self.attempt(|r| r.raster.release_unreferenced_textures());
        }
    }

    fn occlusion_counter_bits(&self) -> u32 {
        self.raster.occlusion_counter_bits()
    }

    /// Only the path tracer needs them (rasterized, they are culled).
    fn keeps_culled_triangles(&self) -> bool {
        self.tracing.is_some()
    }

    fn spent_storage(&mut self) -> Option<&mut StoragePool> {
        Some(&mut self.spent)
    }

    /// The path tracer reads classes (what it traces, layers, lights, the static world), the
    /// HUD its draws per class, radiosity the static world, its draws and the view;
    /// rasterizing alone reads none.
    fn reads_classes(&self) -> bool {
        self.tracing.is_some() || self.hud.is_some() || self.radiosity.is_some()
    }

    /// Waits for the frame in flight that ended `frame` when the result is not known yet.
    fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
        self.attempt(|r| r.raster.occlusion_result(frame, query)).flatten()
    }

    /// Black (zero depth and stencil) once the renderer stopped.
    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.attempt(|r| r.read(frame, buffer, rect)).unwrap_or_else(|| Some(black(buffer, rect)))
    }
}

/// What a stopped renderer reads back: `rect` of black opaque colour, or of zero depth or
/// stencil.
fn black(buffer: PixelBuffer, [_, _, w, h]: [i32; 4]) -> Vec<[f32; 4]> {
    let value = match buffer {
        PixelBuffer::Color => [0.0, 0.0, 0.0, 1.0],
        PixelBuffer::Depth | PixelBuffer::Stencil => [0.0; 4],
    };
    vec![value; w.max(0) as usize * h.max(0) as usize]
}

impl Drop for Renderer {
    /// Waits for the GPU and frees the tracing stages; the raster stage, which holds the
    /// device, is dropped after.
    fn drop(&mut self) {
        if let Err(e) = self.raster.wait_all() {
            log::warn!("glrt: waiting for the GPU at shutdown: {e}");
        }
        let device = self.raster.device();
        let _ = device.wait_idle();
        for mut tracing in [self.tracing.take(), self.retired.take()].into_iter().flatten() {
            tracing.destroy(device);
        }
        if let Some(ao) = &mut self.ao {
            ao.destroy(device);
        }
        if let Some(radiosity) = &mut self.radiosity {
            radiosity.destroy(device);
        }
    }
}
