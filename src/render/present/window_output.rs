//! The raster renderer's presentation: a [`FrameOutput`] that shows each finished frame on the
//! context's [`Target`] through a [`Presenter`].
//!
//! At the end of a frame ([`FrameOutput::record`]) the colour image (rows top to bottom, see
//! `raster::target`) is left in `TRANSFER_SRC_OPTIMAL` for the swapchain's blit, or, on the
//! Xlib path, copied into a host buffer. Right after the frame's submission
//! ([`FrameOutput::submitted`]) the presenter shows it: the swapchain's blit is submitted
//! behind the frame on the same queue (queue order and the blit's barrier order them); the
//! Xlib path waits for the queue and puts the pixels on the window, so the frame is on screen
//! when `glXSwapBuffers` returns (a program drawing one frame and then waiting for events must
//! see it).

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::swapchain::{Gpu, Source};
use super::{FrameImage, Presenter};
use crate::frame::Target;
use crate::render::raster::device::{Buffer, Device, Result};
use crate::render::raster::output::{FrameOutput, SubmitSync};
use crate::render::raster::renderer::Recorder;
use crate::render::raster::target::Plane;

/// What the end of the frame prepared for [`FrameOutput::submitted`].
enum Prepared {
    /// The colour image, ready for a blit.
    Image(Source),
    /// The colour image copied into a host-visible buffer.
    Pixels(Source, Buffer),
}

/// Shows the renderer's frames on the context's drawable.
#[derive(Default)]
pub struct WindowOutput {
    presenter: Option<Presenter>,
    prepared: Option<Prepared>,
}

impl WindowOutput {
    /// No target yet: frames stay off-screen until [`FrameOutput::set_target`].
    pub fn new() -> WindowOutput {
        WindowOutput::default()
    }
}

/// The renderer's device as the swapchain needs it, when it can present.
fn gpu_of(device: &Device) -> Option<Gpu> {
    device.swapchain.then(|| Gpu {
        entry: device.entry.clone(),
        instance: device.instance.clone(),
        physical: device.physical,
        device: device.raw.clone(),
        queue_family: device.queue_family,
        queue: device.queue,
    })
}

/// A prepared frame handed to the presenter: the read-back waits for the queue.
struct Rendered<'a> {
    device: &'a Device,
    prepared: &'a mut Prepared,
}

impl FrameImage for Rendered<'_> {
    fn source(&self) -> Source {
        match &*self.prepared {
            Prepared::Image(s) | Prepared::Pixels(s, _) => *s,
        }
    }

    fn read_rgba(&mut self) -> Option<Vec<u8>> {
        let Prepared::Pixels(source, buffer) = self.prepared else { return None };
        self.device.wait_idle().map_err(|e| log::warn!("present: waiting for the frame: {e}")).ok()?;
        let bytes = source.size[0] as usize * source.size[1] as usize * 4;
        buffer.mapped().get(..bytes).map(<[u8]>::to_vec)
    }
}

impl FrameOutput for WindowOutput {
    fn set_target(&mut self, device: &Device, target: Target) {
        let gpu = gpu_of(device);
        match self.presenter.as_mut() {
            // Safety: the target's display is the application's, live while it is current; the
            // device outlives the presenter (destroyed in `destroy`).
            Some(p) => unsafe { p.retarget(target, gpu.as_ref()) },
            None => self.presenter = Some(unsafe { Presenter::new(target, gpu.as_ref()) }),
        }
    }

    fn record(&mut self, rec: &mut Recorder<'_>, _slot: usize, _frame: u64) -> Result<SubmitSync> {
        let Some(presenter) = &self.presenter else { return Ok(SubmitSync::default()) };
        if !presenter.shows_frames() {
            return Ok(SubmitSync::default());
        }
        let (device, cmd, target) = (rec.device, rec.cmd, &mut *rec.target);
        let front = target.readable(device, cmd, Plane::Front);
        let source = Source { image: front, layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL, size: target.size, bottom_up: false };
        let prepared = if presenter.needs_pixels() {
            let [w, h] = target.size;
            let bytes = w as u64 * h as u64 * 4;
            let buffer = device.create_buffer("glrt present", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?;
            let copy = vk::BufferImageCopy {
                image_subresource: vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 },
                image_extent: vk::Extent3D { width: w, height: h, depth: 1 },
                ..Default::default()
            };
            // Safety: the image is in TRANSFER_SRC_OPTIMAL; the buffer holds the whole image.
            unsafe { device.raw.cmd_copy_image_to_buffer(cmd, front, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, buffer.raw, &[copy]) };
            Prepared::Pixels(source, buffer)
        } else {
            Prepared::Image(source)
        };
        if let Some(Prepared::Pixels(_, old)) = self.prepared.replace(prepared) {
            device.destroy_buffer(old);
        }
        Ok(SubmitSync::default())
    }

    fn submitted(&mut self, device: &Device, _slot: usize) -> Result<()> {
        let (Some(presenter), Some(mut prepared)) = (self.presenter.as_mut(), self.prepared.take()) else { return Ok(()) };
        // Safety: the frame's commands (rendering the image) were just submitted to the
        // device's queue, which this thread alone uses.
        unsafe { presenter.show(&mut Rendered { device, prepared: &mut prepared }) };
        if let Prepared::Pixels(_, buffer) = prepared {
            // `show` waited for the queue before reading it.
            let _ = device.wait_idle();
            device.destroy_buffer(buffer);
        }
        Ok(())
    }

    fn release(&mut self, device: &Device) {
        if let Some(Prepared::Pixels(_, buffer)) = self.prepared.take() {
            device.destroy_buffer(buffer);
        }
        self.presenter = None;
    }
}
