//! Where finished frames go besides the framebuffer: frame dumps (`GLRT_DUMP`), and the
//! presentation to a window (swapchain, or a copy put on the window with Xlib). Each is a
//! [`FrameOutput`] the renderer calls at three moments of a frame in flight.

use ash::vk;

use super::device::{Device, Result};
use super::renderer::Recorder;

/// Semaphores a frame's submission waits on and signals (for example a swapchain image's
/// acquire and render-finished semaphores).
#[derive(Default)]
pub struct SubmitSync {
    /// Semaphores waited on, with the stages that wait.
    pub wait: Vec<(vk::Semaphore, vk::PipelineStageFlags)>,
    /// Semaphores signalled when the frame's commands finish.
    pub signal: Vec<vk::Semaphore>,
}

impl SubmitSync {
    /// Adds `other`'s semaphores.
    pub fn extend(&mut self, other: SubmitSync) {
        self.wait.extend(other.wait);
        self.signal.extend(other.signal);
    }
}

/// A consumer of presented frames.
pub trait FrameOutput: Send {
    /// Records what the output needs at the end of frame `frame` (number) into the frame's
    /// command buffer (outside a rendering pass; the colour image is in `rec.target`), for
    /// frame-in-flight slot `slot`; returns the semaphores the submission must use.
    fn record(&mut self, rec: &mut Recorder<'_>, slot: usize, frame: u64) -> Result<SubmitSync>;

    /// The context was made current on `target`, or its size or swap interval changed
    /// ([`crate::frame::FrameSink::set_target`]).
    fn set_target(&mut self, _device: &Device, _target: crate::frame::Target) {}

    /// Called right after the submission of `slot` (for example to queue the present).
    fn submitted(&mut self, _device: &Device, _slot: usize) -> Result<()> {
        Ok(())
    }

    /// Called once the GPU finished `slot`'s submission (its fence signalled): read back
    /// what [`FrameOutput::record`] copied.
    fn completed(&mut self, _device: &Device, _slot: usize) {}

    /// Frees the output's Vulkan objects of `device`, which is replaced (it was lost): the
    /// output goes on with the next device, whose [`FrameOutput::set_target`] follows.
    fn release(&mut self, device: &Device);

    /// Frees the output's Vulkan objects (the GPU is idle) and ends it.
    fn destroy(&mut self, device: &Device) {
        self.release(device);
    }
}
