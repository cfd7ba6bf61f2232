//! Rendering: draws [`crate::frame::Frame`]s with Vulkan. The Vulkan renderer is
//! [`frame::Renderer`], a [`FrameSink`] (defined in [`crate::frame`], the interface between the
//! layers): a frame's stages in order, read top to bottom there; [`raster`] provides the command
//! recording and the raster stages (clears, pixel operations, draws in program order,
//! read-back, present), [`trace`] the path-tracing stages behind one back-end trait
//! ([`trace::RayTracer`]), [`denoise`] the A-SVGF stage after tracing, [`fog`] the height fog
//! of both modes, [`ao`] the ambient occlusion of raster mode, [`radiosity`] the static
//! world's global illumination (raster mode's indirect light so far), [`present`] the window,
//! and [`hud`] the panel of frame times drawn over the image; [`pass_layout`] and
//! [`pass_times`] are the layouts and GPU timing of those stages' passes. [`default_sink`]
//! chooses the renderer of the mode (`GLRT_MODE`); [`devices`] lists the machine's Vulkan
//! devices with the mode each would get ([`rendering_on`]).

pub mod ao;
pub mod devices;
pub mod frame;
#[macro_use]
pub mod shader_abi;
pub mod denoise;
pub mod fog;
pub mod frame_log;
pub mod frames_from;
pub mod frames_repeated;
pub mod hud;
pub mod pass_layout;
pub mod pass_times;
pub mod present;
pub mod radiosity;
pub mod raster;
pub mod texenv;
pub mod trace;

use crate::frame::{FrameSink, NullSink};

pub use present::{FrameImage, Presenter};

/// The sink a new context presents to, behind the frame log when `GLRT_FRAME_LOG` is set (see
/// [`frame_log`]): the Vulkan renderer of the mode [`Mode::of_process`] chooses when a device
/// is available, else the [`NullSink`] (with one message on stderr saying why).
pub fn default_sink() -> Box<dyn FrameSink> {
    frame_log::wrap_from_env(renderer_from_env())
}

/// The sink of a replay that writes frames as PNG (`glrt replay --out`): the Vulkan renderer
/// (of the mode `GLRT_MODE` chooses; a mode without a renderer still gets pixels, rasterized),
/// drawing and writing frames `first` and later to `dir/frame-NNNNN.png` (see [`raster::dump`];
/// the earlier ones run for their state only, [`frames_from`]), behind the frame log as in
/// [`default_sink`]. The error says why no frames could be written (no Vulkan device,
/// directory not writable).
pub fn dumping_sink(dir: &std::path::Path, first: u64) -> Result<Box<dyn FrameSink>, String> {
    let dump = raster::dump::Dump::new(dir.to_path_buf(), first)?;
    let renderer = renderer_for_mode(Some(dump)).map_err(|e| e.to_string())?;
    Ok(frame_log::wrap_from_env(Box::new(frames_from::FramesFrom::new(first, Box::new(renderer)))))
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

/// How frames are rendered on a device of `device_type`, with or without ray-tracing
/// pipelines (`ray_tracing`), under `GLRT_MODE` (unset: path traced on a GPU, rasterized on a
/// CPU) and the tracer setting.
pub fn rendering_on(device_type: ash::vk::PhysicalDeviceType, ray_tracing: bool) -> devices::Rendering {
    let cpu = device_type == ash::vk::PhysicalDeviceType::CPU;
    let tracer = trace::backend_name(ray_tracing, trace::settings::Settings::of_process().tracer, None);
    match Mode::of_process() {
        Ok(Mode::PathTrace) => devices::Rendering::PathTrace { tracer },
        Ok(Mode::Default) if cpu => devices::Rendering::Raster { by_default: true },
        Ok(Mode::Default) => devices::Rendering::PathTrace { tracer },
        Ok(Mode::Raster) => devices::Rendering::Raster { by_default: false },
        Err(_) => devices::Rendering::NotDrawn,
    }
}

/// The Vulkan renderer, path tracing when the mode says so on its device (rasterizing, with a
/// message, when the tracing stages cannot be made).
fn renderer_for_mode(dump: Option<raster::dump::Dump>) -> raster::device::Result<frame::Renderer> {
    let mut renderer = frame::Renderer::with_dump(dump)?;
    renderer.set_fog(fog::settings::FogSettings::of_process());
    let rendering = rendering_on(renderer.device().properties.device_type, renderer.device().ray_tracing);
    if rendering == (devices::Rendering::Raster { by_default: true }) {
        log::info!("glrt: the Vulkan device is a CPU: rasterizing (GLRT_MODE=pathtrace traces anyway, at seconds per frame)");
    }
    let ao = ao::settings::AoSettings::of_process();
    if ao.enabled
        && !matches!(rendering, devices::Rendering::PathTrace { .. })
        && let Err(e) = renderer.enable_ambient_occlusion(ao)
    {
        eprintln!("glrt: ambient occlusion is not available: {e}");
    }
    let radiosity = radiosity::settings::Settings::of_process();
    if radiosity.enabled {
        renderer.enable_radiosity(radiosity, trace::lights::LightSettings::of(&trace::settings::Settings::of_process()));
    }
    if matches!(rendering, devices::Rendering::PathTrace { .. }) {
        match renderer.enable_tracing(trace::settings::Settings::of_process()) {
            Err(e) => eprintln!("glrt: path tracing is not available: {e}; frames are rasterized"),
            Ok(()) => {
                let denoise = denoise::settings::DenoiseSettings::of_process();
                if denoise.enabled
                    && let Err(e) = renderer.enable_denoising(denoise)
                {
                    eprintln!("glrt: denoising is not available: {e}; the tracer's temporal filter resolves its frames");
                }
            }
        }
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
