//! Rendering: consumes [`Frame`]s. The Vulkan back ends come here; for now the sinks that keep
//! frames for tests and for programs run without a renderer.

#[macro_use]
pub mod shader_abi;
pub mod frame_log;
pub mod present;
pub mod raster;
pub mod texenv;
pub mod trace;

use std::sync::Arc;

use parking_lot::Mutex;

use crate::frame::Frame;
use crate::frame::pixels::PixelBuffer;

pub use present::{FrameImage, Presenter, Surface, Target, XDrawable};

/// Receives each finished frame.
pub trait FrameSink: Send {
    /// Takes the frame that `glXSwapBuffers` (or a read-back) ended.
    fn present(&mut self, frame: Frame);

    /// Where the next frames go: called when a context is made current on a drawable and when
    /// that drawable's size changes (only then: the target differs from the previous one).
    /// The default ignores it (sinks that keep frames in memory).
    fn set_target(&mut self, _target: Target) {}

    /// Samples that passed for occlusion query `query` of frame number `frame` (listed in
    /// that frame's [`Frame::occlusion_queries`]), once that frame was presented; `None` while
    /// unknown. A renderer whose [`FrameSink::occlusion_counter_bits`] is not 0 must answer
    /// every query of a presented frame eventually. The default counts nothing.
    fn occlusion_result(&mut self, _frame: u64, _query: u32) -> Option<u64> {
        None
    }

    /// Bits of the renderer's sample counter (`GL_QUERY_COUNTER_BITS`); 0 when it does not
    /// count samples (the default).
    fn occlusion_counter_bits(&self) -> u32 {
        0
    }
    /// Renders `frame` so far (it is not ended) and reads the rectangle `rect` (x, y, width,
    /// height, window coordinates) of `buffer`: RGBA for colour, the value in the first
    /// component for depth and stencil; rows bottom to top. `None` when the sink cannot
    /// render (the caller leaves the client's memory untouched).
    fn read_pixels(&mut self, _frame: &Frame, _buffer: PixelBuffer, _rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        None
    }
}

/// Drops frames, keeping only how many were presented (used when no renderer is available).
#[derive(Default)]
pub struct NullSink {
    /// Frames presented so far.
    pub presented: u64,
}

impl FrameSink for NullSink {
    fn present(&mut self, _frame: Frame) {
        self.presented += 1;
    }
}

/// Keeps every frame in a shared list, for tests.
#[derive(Clone, Default)]
pub struct RecordingSink {
    /// The frames presented so far.
    pub frames: Arc<Mutex<Vec<Frame>>>,
}

impl FrameSink for RecordingSink {
    fn present(&mut self, frame: Frame) {
        self.frames.lock().push(frame);
    }
}

/// The sink a new context presents to, behind the frame log when `GLRT_FRAME_LOG` is set (see
/// [`frame_log`]): the Vulkan renderer of the mode [`Mode::of_process`] chooses when a device
/// is available, else the [`NullSink`] (with one message on stderr saying why).
pub fn default_sink() -> Box<dyn FrameSink> {
    frame_log::wrap_from_env(renderer_from_env())
}

/// The sink of a replay that writes frames as PNG (`glrt replay --out`): the Vulkan renderer
/// (of the mode `GLRT_MODE` chooses; a mode without a renderer still gets pixels, rasterized),
/// writing frames `first` and later to `dir/frame-NNNNN.png` (see [`raster::dump`]), behind
/// the frame log as in [`default_sink`]. The error says why no frames could be written (no
/// Vulkan device, directory not writable).
pub fn dumping_sink(dir: &std::path::Path, first: u64) -> Result<Box<dyn FrameSink>, String> {
    let dump = raster::dump::Dump::new(dir.to_path_buf(), first)?;
    let renderer = renderer_for_mode(Some(dump)).map_err(|e| e.to_string())?;
    Ok(frame_log::wrap_from_env(Box::new(renderer)))
}

/// How frames are rendered, from `GLRT_MODE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// `raster`: everything rasterized.
    Raster,
    /// `pathtrace`: the traced classes path traced, the others rasterized around them.
    PathTrace,
    /// Unset or empty: path traced on a GPU; rasterized on a CPU device (lavapipe), where the
    /// compute tracer takes seconds per frame.
    Default,
}

impl Mode {
    /// The mode `GLRT_MODE` names; `Err` with the value when it names a mode without a renderer.
    fn of_process() -> Result<Mode, String> {
        match std::env::var("GLRT_MODE").unwrap_or_default().as_str() {
            "" => Ok(Mode::Default),
            "raster" => Ok(Mode::Raster),
            "pathtrace" => Ok(Mode::PathTrace),
            other => Err(other.to_owned()),
        }
    }
}

/// The Vulkan renderer, path tracing when the mode says so on its device.
fn renderer_for_mode(dump: Option<raster::dump::Dump>) -> raster::device::Result<raster::renderer::Renderer> {
    let mut renderer = raster::renderer::Renderer::with_dump(dump)?;
    let cpu = renderer.device().properties.device_type == ash::vk::PhysicalDeviceType::CPU;
    let traced = match Mode::of_process() {
        Ok(Mode::PathTrace) => true,
        Ok(Mode::Default) if cpu => {
            log::info!("glrt: the Vulkan device is a CPU: rasterizing (GLRT_MODE=pathtrace traces anyway, at seconds per frame)");
            false
        }
        Ok(Mode::Default) => true,
        Ok(Mode::Raster) | Err(_) => false,
    };
    if traced {
        renderer.enable_tracing(trace::settings::Settings::of_process())?;
    }
    Ok(renderer)
}

/// The sample counts above 1 that the renderer of [`default_sink`] draws multisampled
/// framebuffers with (what GLX offers as multisampled configurations): those of the Vulkan
/// device, probed once per process; none when frames are not drawn.
pub fn multisample_counts() -> &'static [u32] {
    if Mode::of_process().is_err() { &[] } else { raster::multisample::probe() }
}

/// The renderer `GLRT_MODE` asks for, or the [`NullSink`].
fn renderer_from_env() -> Box<dyn FrameSink> {
    if let Err(mode) = Mode::of_process() {
        eprintln!("glrt: GLRT_MODE={mode} has no renderer yet; frames are not drawn");
        return Box::new(NullSink::default());
    }
    match renderer_for_mode(raster::dump::Dump::from_env()) {
        Ok(renderer) => Box::new(renderer),
        Err(e) => {
            eprintln!("glrt: {e}; frames are not drawn");
            Box::new(NullSink::default())
        }
    }
}
