//! Copies a window rectangle of the colour, depth or stencil image into host memory and
//! converts it to what [`crate::frame::FrameSink::read_pixels`] returns: one `[f32; 4]` per
//! pixel, rows bottom to top; colour as RGBA in [0, 1], depth in [0, 1] and stencil as its
//! integer value in the first component. Pixels of the rectangle outside the window are 0
//! (their values are undefined in OpenGL, section 4.3.2).

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::device::{Buffer, Device, Result};
use super::target::{Plane, Target};
use crate::frame::ColorBuffer;
use crate::frame::pixels::PixelBuffer;

/// Largest rectangle read back, in pixels.
const MAX_PIXELS: u64 = 1 << 26;

/// What a texel of the copied aspect holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Texel {
    /// RGBA8.
    Rgba8,
    /// 24-bit unorm depth in the low bits of 32.
    Depth24,
    /// 32-bit float depth.
    Depth32,
    /// 8-bit stencil.
    Stencil8,
}

impl Texel {
    fn size(self) -> u64 {
        if self == Texel::Stencil8 { 1 } else { 4 }
    }

    fn decode(self, b: &[u8]) -> [f32; 4] {
        match self {
            Texel::Rgba8 => [b[0], b[1], b[2], b[3]].map(|v| v as f32 / 255.0),
            Texel::Depth24 => {
                let v = u32::from_le_bytes([b[0], b[1], b[2], b[3]]) & 0xff_ffff;
                [v as f32 / 0xff_ffff as f32, 0.0, 0.0, 0.0]
            }
            Texel::Depth32 => [f32::from_le_bytes([b[0], b[1], b[2], b[3]]), 0.0, 0.0, 0.0],
            Texel::Stencil8 => [b[0] as f32, 0.0, 0.0, 0.0],
        }
    }
}

/// A recorded copy, read once the command buffer has run.
pub struct Readback {
    buffer: Buffer,
    texel: Texel,
    /// Requested rectangle (window coordinates).
    rect: [i32; 4],
    /// The part of it inside the image, in window coordinates: x0, y0, width, height.
    inside: [i64; 4],
}

impl Readback {
    /// Records the copy of `rect` (window coordinates) of `buffer` (colour from the image of
    /// `color`) into host memory, resolved when multisampled ([`Target::readable`]); `None`
    /// when the rectangle is too large. Ends with the image read in `TRANSFER_SRC_OPTIMAL`.
    pub fn record(device: &Device, cmd: vk::CommandBuffer, target: &mut Target, buffer: PixelBuffer, color: ColorBuffer, rect: [i32; 4]) -> Result<Option<Readback>> {
        let [_, _, w, h] = rect;
        if w <= 0 || h <= 0 || (w as u64) * (h as u64) > MAX_PIXELS {
            return Ok(None);
        }
        let (plane, aspect, texel) = match buffer {
            PixelBuffer::Color => (Plane::of(color), vk::ImageAspectFlags::COLOR, Texel::Rgba8),
            PixelBuffer::Depth => {
                let t = if device.depth_format == vk::Format::D24_UNORM_S8_UINT { Texel::Depth24 } else { Texel::Depth32 };
                (Plane::DepthStencil, vk::ImageAspectFlags::DEPTH, t)
            }
            PixelBuffer::Stencil => (Plane::DepthStencil, vk::ImageAspectFlags::STENCIL, Texel::Stencil8),
        };
        let region = target.vk_rect(rect);
        let inside = match region {
            Some(r) => {
                let x0 = r.offset.x as i64;
                let y0 = target.size[1] as i64 - r.offset.y as i64 - r.extent.height as i64;
                [x0, y0, r.extent.width as i64, r.extent.height as i64]
            }
            None => [0; 4],
        };
        let bytes = (inside[2] * inside[3]) as u64 * texel.size();
        let host = device.create_buffer("glrt read-back", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?;
        if let Some(r) = region {
            let image = target.readable(device, cmd, plane);
            let copy = vk::BufferImageCopy {
                buffer_offset: 0,
                buffer_row_length: 0,
                buffer_image_height: 0,
                image_subresource: vk::ImageSubresourceLayers { aspect_mask: aspect, mip_level: 0, base_array_layer: 0, layer_count: 1 },
                image_offset: vk::Offset3D { x: r.offset.x, y: r.offset.y, z: 0 },
                image_extent: vk::Extent3D { width: r.extent.width, height: r.extent.height, depth: 1 },
            };
            // Safety: the image is in TRANSFER_SRC_OPTIMAL, the region inside it, the buffer
            // large enough.
            unsafe { device.raw.cmd_copy_image_to_buffer(cmd, image, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, host.raw, &[copy]) };
            let barrier = [vk::MemoryBarrier2::default()
                .src_stage_mask(vk::PipelineStageFlags2::ALL_TRANSFER)
                .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
                .dst_stage_mask(vk::PipelineStageFlags2::HOST)
                .dst_access_mask(vk::AccessFlags2::HOST_READ)];
            // Safety: cmd is recording outside a rendering pass.
            unsafe { device.raw.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&barrier)) };
        }
        Ok(Some(Readback { buffer: host, texel, rect, inside }))
    }

    /// The pixels, once the copy ran (frees the host buffer).
    pub fn finish(mut self, device: &Device) -> Vec<[f32; 4]> {
        let [x, y, w, h] = self.rect.map(|v| v as i64);
        let [ix, iy, iw, ih] = self.inside;
        let size = self.texel.size() as usize;
        let mut out = vec![[0.0; 4]; (w * h) as usize];
        let data = self.buffer.mapped();
        // The buffer's rows are top to bottom (image order): buffer row r is window row
        // iy + ih - 1 - r.
        for r in 0..ih {
            let wy = iy + ih - 1 - r;
            let out_row = (wy - y) as usize;
            for c in 0..iw {
                let src = ((r * iw + c) as usize) * size;
                if let Some(texel) = data.get(src..src + size) {
                    out[out_row * w as usize + (ix - x + c) as usize] = self.texel.decode(texel);
                }
            }
        }
        device.destroy_buffer(self.buffer);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texels_decode() {
        assert_eq!(Texel::Rgba8.decode(&[255, 0, 51, 255]), [1.0, 0.0, 0.2, 1.0]);
        assert_eq!(Texel::Depth24.decode(&[0xff, 0xff, 0xff, 0x07])[0], 1.0);
        assert_eq!(Texel::Depth32.decode(&0.25f32.to_le_bytes())[0], 0.25);
        assert_eq!(Texel::Stencil8.decode(&[7])[0], 7.0);
    }
}
