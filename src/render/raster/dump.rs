//! `GLRT_DUMP=dir`: every presented frame is written to `dir/frame-NNNNN.png`. The colour
//! image is copied into a host buffer of the frame's slot when the frame is submitted, and
//! encoded once that slot's fence has signalled (no stall on the GPU). The image rows are
//! already top-down (see [`super::target`]), as PNG wants them.

use std::path::PathBuf;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::device::{Buffer, Device, Result};
use super::target::{Plane, Target};

/// A copy waiting for its frame to finish.
struct Pending {
    buffer: Buffer,
    size: [u32; 2],
    frame: u64,
}

/// The dump directory and the copies in flight, one per slot.
pub struct Dump {
    dir: PathBuf,
    pending: Vec<Option<Pending>>,
}

impl Dump {
    /// From `GLRT_DUMP` (creating the directory); `None` when unset or not creatable.
    pub fn from_env() -> Option<Dump> {
        let dir = PathBuf::from(std::env::var_os("GLRT_DUMP").filter(|d| !d.is_empty())?);
        if let Err(e) = std::fs::create_dir_all(&dir) {
            eprintln!("glrt: GLRT_DUMP={}: {e}; frames are not dumped", dir.display());
            return None;
        }
        Some(Dump { dir, pending: Vec::new() })
    }

    /// Records the copy of the colour image of frame `frame` for slot `slot`.
    pub fn record(&mut self, device: &Device, cmd: vk::CommandBuffer, target: &mut Target, slot: usize, frame: u64) -> Result<()> {
        if self.pending.len() <= slot {
            self.pending.resize_with(slot + 1, || None);
        }
        let [w, h] = target.size;
        let bytes = w as u64 * h as u64 * 4;
        let buffer = device.create_buffer("glrt dump", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?;
        target.transition(device, cmd, Plane::Color, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
        let copy = vk::BufferImageCopy {
            image_subresource: vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 },
            image_extent: vk::Extent3D { width: w, height: h, depth: 1 },
            ..Default::default()
        };
        // Safety: the image is in TRANSFER_SRC_OPTIMAL; the buffer holds the whole image.
        unsafe { device.raw.cmd_copy_image_to_buffer(cmd, target.color.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, buffer.raw, &[copy]) };
        if let Some(old) = self.pending[slot].replace(Pending { buffer, size: [w, h], frame }) {
            device.destroy_buffer(old.buffer);
        }
        Ok(())
    }

    /// Writes the PNG of slot `slot`'s frame (its fence has signalled).
    pub fn collect(&mut self, device: &Device, slot: usize) {
        let Some(mut p) = self.pending.get_mut(slot).and_then(Option::take) else { return };
        let path = self.dir.join(format!("frame-{:05}.png", p.frame));
        if let Err(e) = write_png(&path, p.size, p.buffer.mapped()) {
            eprintln!("glrt: writing {}: {e}", path.display());
        }
        device.destroy_buffer(p.buffer);
    }

    /// Frees the buffers (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        for p in self.pending.drain(..).flatten() {
            device.destroy_buffer(p.buffer);
        }
    }
}

/// Writes RGBA8 rows, top to bottom, as a PNG.
pub fn write_png(path: &std::path::Path, [w, h]: [u32; 2], rgba: &[u8]) -> std::io::Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(rgba).map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}
