//! The framebuffer the raster path draws into: two RGBA8 colour images (back and front
//! buffers, OpenGL 1.5 section 4.2.1) and a depth/stencil image of the drawable's size,
//! recreated when the size changes. Outputs show the front image; a swap copies the back
//! image into it ([`Target::copy_back_to_front`]). A single-buffered drawable only uses the
//! front image.
//!
//! Orientation: row 0 of the images is the **top** of the window (as a swapchain image or a
//! PNG wants it). OpenGL window coordinates grow upwards, so window row `y` is image row
//! `height - 1 - y`; draws get there through a negative viewport height (see
//! [`super::pipelines`]), and [`Target::vk_rect`] converts rectangles.
//!
//! Each image remembers its current layout; [`Target::transition`] records the barrier to a
//! new one (a full barrier: simple and correct across frames in flight, which share the
//! images and rely on the queue's submission order).

use ash::vk;

use super::device::{Device, Image, Result};
use crate::frame::ColorBuffer;

/// The colour format.
pub const COLOR_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

/// Which image of the target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    /// The back colour image.
    Color,
    /// The depth/stencil image.
    DepthStencil,
    /// The front colour image.
    Front,
}

impl Plane {
    /// The colour image of `buffer`.
    pub fn of(buffer: ColorBuffer) -> Plane {
        match buffer {
            ColorBuffer::Front => Plane::Front,
            ColorBuffer::Back => Plane::Color,
        }
    }
}

/// The colour and depth/stencil images.
pub struct Target {
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// The back colour image (RGBA8, [`COLOR_FORMAT`]).
    pub color: Image,
    /// The depth/stencil image ([`Device::depth_format`]).
    pub depth: Image,
    /// The front colour image (RGBA8).
    pub front: Image,
    layouts: [vk::ImageLayout; 3],
}

impl Target {
    /// Creates the images (contents undefined until the first clear: [`super::renderer`]
    /// clears them once after creation).
    pub fn new(device: &Device, size: [u32; 2]) -> Result<Target> {
        let [w, h] = [size[0].max(1), size[1].max(1)];
        let info = |format, usage| {
            vk::ImageCreateInfo::default()
                .image_type(vk::ImageType::TYPE_2D)
                .format(format)
                .extent(vk::Extent3D { width: w, height: h, depth: 1 })
                .mip_levels(1)
                .array_layers(1)
                .samples(vk::SampleCountFlags::TYPE_1)
                .tiling(vk::ImageTiling::OPTIMAL)
                .usage(usage)
        };
        let transfer = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::SAMPLED;
        let color_image = |name| {
            device.create_image(name, &info(COLOR_FORMAT, vk::ImageUsageFlags::COLOR_ATTACHMENT | transfer), vk::ImageViewType::TYPE_2D, vk::ImageAspectFlags::COLOR)
        };
        let color = color_image("glrt back colour")?;
        let front = match color_image("glrt front colour") {
            Ok(front) => front,
            Err(e) => {
                device.destroy_image(color);
                return Err(e);
            }
        };
        let depth = device.create_image(
            "glrt depth",
            &info(device.depth_format, vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | transfer),
            vk::ImageViewType::TYPE_2D,
            vk::ImageAspectFlags::DEPTH | vk::ImageAspectFlags::STENCIL,
        );
        match depth {
            Ok(depth) => Ok(Target { size: [w, h], color, depth, front, layouts: [vk::ImageLayout::UNDEFINED; 3] }),
            Err(e) => {
                device.destroy_image(color);
                device.destroy_image(front);
                Err(e)
            }
        }
    }

    /// Frees the images (the GPU must be done with them).
    pub fn destroy(self, device: &Device) {
        device.destroy_image(self.color);
        device.destroy_image(self.depth);
        device.destroy_image(self.front);
    }

    /// Records the swap of a double-buffered drawable: the back image is copied into the
    /// front image (the back image keeps its contents).
    pub fn copy_back_to_front(&mut self, device: &Device, cmd: vk::CommandBuffer) {
        self.transition(device, cmd, Plane::Color, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
        self.transition(device, cmd, Plane::Front, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        let layers = vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 };
        let copy = vk::ImageCopy {
            src_subresource: layers,
            src_offset: vk::Offset3D::default(),
            dst_subresource: layers,
            dst_offset: vk::Offset3D::default(),
            extent: vk::Extent3D { width: self.size[0], height: self.size[1], depth: 1 },
        };
        // Safety: the images are in the layouts named, of the same size; cmd is outside a pass.
        unsafe {
            device.raw.cmd_copy_image(cmd, self.color.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, self.front.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[copy])
        };
    }

    /// Records clearing the images (colour to transparent black, depth to 1, stencil to 0):
    /// a new target's contents are defined.
    pub fn clear_initial(&mut self, device: &Device, cmd: vk::CommandBuffer) {
        for plane in [Plane::Color, Plane::DepthStencil, Plane::Front] {
            self.transition(device, cmd, plane, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        }
        let range = |aspect_mask| vk::ImageSubresourceRange { aspect_mask, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 1 };
        // Safety: the images are in TRANSFER_DST_OPTIMAL; cmd is outside a rendering pass.
        unsafe {
            for image in [self.color.raw, self.front.raw] {
                device.raw.cmd_clear_color_image(
                    cmd,
                    image,
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    &vk::ClearColorValue { float32: [0.0; 4] },
                    &[range(vk::ImageAspectFlags::COLOR)],
                );
            }
            device.raw.cmd_clear_depth_stencil_image(
                cmd,
                self.depth.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &vk::ClearDepthStencilValue { depth: 1.0, stencil: 0 },
                &[range(Self::aspects(Plane::DepthStencil))],
            );
        }
    }

    /// The image of `plane`.
    pub fn image(&self, plane: Plane) -> &Image {
        match plane {
            Plane::Color => &self.color,
            Plane::DepthStencil => &self.depth,
            Plane::Front => &self.front,
        }
    }

    /// The aspects of `plane`.
    pub fn aspects(plane: Plane) -> vk::ImageAspectFlags {
        match plane {
            Plane::Color | Plane::Front => vk::ImageAspectFlags::COLOR,
            Plane::DepthStencil => vk::ImageAspectFlags::DEPTH | vk::ImageAspectFlags::STENCIL,
        }
    }

    /// The layout `plane` is in (after the commands recorded so far).
    pub fn layout(&self, plane: Plane) -> vk::ImageLayout {
        self.layouts[plane as usize]
    }

    /// Records a barrier moving `plane` to `layout` (nothing when already there and the
    /// layout is an attachment layout; transfer layouts always get the barrier so that
    /// consecutive copies are ordered).
    pub fn transition(&mut self, device: &Device, cmd: vk::CommandBuffer, plane: Plane, layout: vk::ImageLayout) {
        let old = self.layouts[plane as usize];
        let attachment = matches!(layout, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL | vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
        if old == layout && attachment {
            return;
        }
        let barrier = vk::ImageMemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
            .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            .dst_access_mask(vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE)
            .old_layout(old)
            .new_layout(layout)
            .image(self.image(plane).raw)
            .subresource_range(vk::ImageSubresourceRange {
                aspect_mask: Self::aspects(plane),
                base_mip_level: 0,
                level_count: 1,
                base_array_layer: 0,
                layer_count: 1,
            });
        let barriers = [barrier];
        let dependency = vk::DependencyInfo::default().image_memory_barriers(&barriers);
        // Safety: cmd is recording; the image belongs to the device.
        unsafe { device.raw.cmd_pipeline_barrier2(cmd, &dependency) };
        self.layouts[plane as usize] = layout;
    }

    /// The Vulkan rectangle (top-left origin) of the window rectangle `[x, y, w, h]`
    /// (bottom-left origin), clipped to the target; `None` when nothing remains.
    pub fn vk_rect(&self, rect: [i32; 4]) -> Option<vk::Rect2D> {
        window_to_image(self.size, rect)
    }
}

/// See [`Target::vk_rect`].
pub fn window_to_image(size: [u32; 2], [x, y, w, h]: [i32; 4]) -> Option<vk::Rect2D> {
    let (width, height) = (size[0] as i64, size[1] as i64);
    let x0 = (x as i64).clamp(0, width);
    let x1 = (x as i64 + w.max(0) as i64).clamp(0, width);
    let y0 = (y as i64).clamp(0, height);
    let y1 = (y as i64 + h.max(0) as i64).clamp(0, height);
    (x1 > x0 && y1 > y0).then(|| vk::Rect2D {
        offset: vk::Offset2D { x: x0 as i32, y: (height - y1) as i32 },
        extent: vk::Extent2D { width: (x1 - x0) as u32, height: (y1 - y0) as u32 },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_rectangles_flip_and_clip() {
        let r = window_to_image([64, 32], [0, 0, 10, 4]).unwrap();
        assert_eq!((r.offset.x, r.offset.y, r.extent.width, r.extent.height), (0, 28, 10, 4));
        let r = window_to_image([64, 32], [-5, 30, 100, 100]).unwrap();
        assert_eq!((r.offset.x, r.offset.y, r.extent.width, r.extent.height), (0, 0, 64, 2));
        assert!(window_to_image([64, 32], [70, 0, 5, 5]).is_none());
        assert!(window_to_image([64, 32], [0, 0, -1, 5]).is_none());
    }
}
