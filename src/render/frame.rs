//! The Vulkan renderer ([`Renderer`], the [`FrameSink`] of a context): one [`Frame`] in, one
//! image out, as a sequence of stages that `Renderer::record` runs top to bottom (kajiya's
//! `world_render_passes.rs` is the model, DESIGN.md "The frame in the renderer"):
//!
//! 1. raster composite, first part ([`Raster::record`]): the clears, pixel operations and
//!    raster draws placed before the first traced draw (the sky), in program order;
//! 2. upload and acceleration structures ([`RayTracer::build`]) of the traced draws and the
//!    static world;
//! 3. trace ([`RayTracer::trace`]): the G-buffer and radiance;
//! 4. resolve ([`RayTracer::resolve`]): temporal filter and tone mapping;
//! 5. composite ([`Composite::record`]): the traced colour and depth into the framebuffer, at
//!    the place of the first traced draw;
//! 6. raster composite, the rest: the draws after it (translucent, overlay) over the traced
//!    image, depth-tested against its depth; the passes of traced surfaces (draws of class
//!    `Layer` the tracer evaluates, [`Surfaces`]) are not rasterized;
//! 7. present ([`Raster::present`]: back to front at a swap, the outputs, submission) or read
//!    back ([`Raster::read`]).
//!
//! Without a [`RayTracer`] (raster mode) steps 2 to 5 are left out and every draw is
//! rasterized. Denoising (issue 20) and radiosity (issue 19) are stages between 3 and 4.
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
use crate::render::raster::device::{Device, Error, Result};
use crate::render::raster::dump::Dump;
use crate::render::raster::output::FrameOutput;
use crate::render::raster::renderer::{FRAMES_IN_FLIGHT, Raster, Recorder};
use crate::render::trace::composite::Composite;
use crate::render::trace::settings::Settings;
use crate::render::trace::surfaces::Surfaces;
use crate::render::trace::{self, RayTracer};

/// The Vulkan renderer: owns the stages of a frame.
pub struct Renderer {
    /// Command recording, framebuffers, and the raster stages (clears, pixel operations,
    /// raster draws, present, read-back).
    raster: Raster,
    /// The path-tracing stages, when the mode traces.
    tracing: Option<Tracing>,
    /// Set after a device error: frames are dropped.
    failed: bool,
}

/// The path-tracing stages: a ray-tracing back end and the composite of its image.
struct Tracing {
    backend: Box<dyn RayTracer>,
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
        Ok(Renderer { raster: Raster::new()?, tracing: None, failed: false })
    }

    /// Path traces the traced draws of the next frames with `settings`, with the back end
    /// [`trace::backend`] chooses for the device; the other draws stay rasterized around them.
    pub fn enable_tracing(&mut self, settings: Settings) -> Result<()> {
        if self.tracing.is_none() {
            let device = self.raster.device();
            self.tracing = Some(Tracing { backend: trace::backend(device, settings, FRAMES_IN_FLIGHT)?, composite: Composite::new(device)? });
        }
        Ok(())
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
        // Raster composite up to the traced image's place: clears, pixel operations, draws.
        self.raster.record(frame, traced_at, &rasterized)?;
        // The traced stages, once per frame, in place of the first traced draw.
        if let Some(tracing) = &mut self.tracing
            && let Some(surfaces) = &surfaces
            && let Some(at) = traced_at
            && self.raster.recorded_draws(frame) == at
        {
            let mut rec = self.raster.recorder_into(None, frame.size)?;
            tracing.record(&mut rec, frame, surfaces, &frame.draws[at])?;
            self.raster.skip_draw(frame, at);
        }
        // Raster composite, the rest: the draws after it (glass, HUD), over the traced image
        // and depth-tested against its depth.
        self.raster.record(frame, None, &rasterized)
    }

    /// Renders the rest of `frame` and submits it for presentation.
    fn finish(&mut self, frame: &Frame) -> Result<()> {
        self.record(frame)?;
        self.raster.present(frame)
    }

    /// Renders `frame` so far and reads `rect` of `buffer` back.
    fn read(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Result<Option<Vec<[f32; 4]>>> {
        self.record(frame)?;
        self.raster.read(frame, buffer, rect)
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
    /// (the window's framebuffer, at the place of `camera`, the first traced draw).
    fn record(&mut self, rec: &mut Recorder<'_>, frame: &Frame, surfaces: &Surfaces, camera: &Draw) -> Result<()> {
        // Upload and acceleration structures.
        let scene = self.backend.build(rec, frame, surfaces, camera)?;
        // Trace: the G-buffer and radiance (nothing when no geometry is on the GPU yet).
        let Some(radiance) = self.backend.trace(rec, &scene)? else { return Ok(()) };
        // Denoising (issue 20) and radiosity (issue 19) come here, as stages on `radiance`.
        // Resolve: temporal filter, tone mapping.
        let image = self.backend.resolve(rec, radiance)?;
        // Composite: the traced colour and depth into the framebuffer.
        self.composite.record(rec, &image)
    }

    /// Frees the stages' GPU objects (the GPU must be idle) and logs the back end's totals.
    fn destroy(&mut self, device: &Device) {
        self.backend.destroy(device);
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
        self.raster.set_target(target);
    }

    /// After a part of a frame ([`FrameEnd::Part`]), once the part is dropped, frees the
    /// texture versions that no frame references any more.
    fn present(&mut self, frame: Frame) {
        if self.failed {
            return;
        }
        let part = frame.end == FrameEnd::Part;
        let mut result = self.finish(&frame);
        drop(frame);
        if part && result.is_ok() {
            result = self.raster.release_unreferenced_textures();
        }
        if let Err(e) = result {
            self.fail(e);
        }
    }

    fn occlusion_counter_bits(&self) -> u32 {
        self.raster.occlusion_counter_bits()
    }

    /// Waits for the frame in flight that ended `frame` when the result is not known yet.
    fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
        match self.raster.occlusion_result(frame, query) {
            Ok(count) => count,
            Err(e) => {
                self.fail(e);
                None
            }
        }
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        if self.failed {
            return None;
        }
        match self.read(frame, buffer, rect) {
            Ok(pixels) => pixels,
            Err(e) => {
                self.fail(e);
                None
            }
        }
    }
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
        if let Some(mut tracing) = self.tracing.take() {
            tracing.destroy(device);
        }
    }
}
