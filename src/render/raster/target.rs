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
//!
//! A multisampled drawable (`GLX_SAMPLES` n, see [`super::multisample`]) has n-sample colour
//! and depth/stencil images, and two single-sampled resolve images. Everything that reads
//! pixels (read-back, `glCopyPixels`, accumulation, presentation, dumps) goes through
//! [`Target::readable`], which resolves first: colour is the average of the samples
//! (`vkCmdResolveImage`, the "resolved" colour of OpenGL 1.5 section 4.3.2); depth and stencil
//! have no combined value in OpenGL, and glrt reads sample 0 (a rendering pass whose
//! depth/stencil resolve mode is `SAMPLE_ZERO`, a mode every Vulkan 1.2 device supports).
//!
//! A drawable without destination alpha (an RGB GLX configuration, [`Target::alpha`] false)
//! keeps the RGBA8 images, with alpha 1 in every pixel from the start: the initial clear and
//! every colour clear write alpha 1, and no pipeline writes alpha (the renderer takes `A` out
//! of each draw's colour write mask; pixel operations draw through the same pipelines). So
//! destination alpha reads as 1 wherever it is used, as OpenGL 1.5 section 4.1.8 wants for a
//! framebuffer without alpha bitplanes: the blend factors `GL_DST_ALPHA`,
//! `GL_ONE_MINUS_DST_ALPHA` and `GL_SRC_ALPHA_SATURATE` (the device reads the stored 1),
//! read-back, `glCopyPixels`, `glCopyTexImage`, accumulation and presentation (they all read
//! the images). One format for both kinds keeps every copy, resolve and presenter path the
//! same; substituting blend factors instead would leave read-back and copies to patch.

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
    /// Samples per pixel of the three images.
    pub samples: u32,
    /// Whether the drawable has destination alpha; without it alpha stays 1 (module doc).
    pub alpha: bool,
    layouts: [vk::ImageLayout; 3],
    /// The single-sampled images reads go through when `samples` > 1.
    resolved: Option<Resolved>,
}

/// The resolve images of a multisampled target, and their layouts.
struct Resolved {
    /// RGBA8: the averaged back or front image.
    color: Image,
    /// Depth/stencil: sample 0.
    depth: Image,
    layouts: [vk::ImageLayout; 2],
}

impl Target {
    /// Creates the images with `samples` samples per pixel (1, or a count of
    /// [`super::device::Features::sample_counts`]), with or without destination `alpha`;
    /// contents are undefined until the first clear: [`super::renderer`] clears them once
    /// after creation.
    pub fn new(device: &Device, size: [u32; 2], samples: u32, alpha: bool) -> Result<Target> {
        let [w, h] = [size[0].max(1), size[1].max(1)];
        let info = |format, usage, samples| {
            vk::ImageCreateInfo::default()
                .image_type(vk::ImageType::TYPE_2D)
                .format(format)
                .extent(vk::Extent3D { width: w, height: h, depth: 1 })
                .mip_levels(1)
                .array_layers(1)
                .samples(super::multisample::flags(samples))
                .tiling(vk::ImageTiling::OPTIMAL)
                .usage(usage)
        };
        let mut transfer = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
        if samples <= 1 {
            transfer |= vk::ImageUsageFlags::SAMPLED;
        }
        let color_usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | transfer;
        let depth_usage = vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | transfer;
        let depth_aspects = Self::aspects(Plane::DepthStencil);
        // Each image is freed if a later one fails.
        let mut made: Vec<Image> = Vec::new();
        let mut make = |name, format, usage, samples, aspects| match device.create_image(name, &info(format, usage, samples), vk::ImageViewType::TYPE_2D, aspects) {
            Ok(image) => {
                made.push(image);
                Ok(())
            }
            Err(e) => {
                made.drain(..).for_each(|i| device.destroy_image(i));
                Err(e)
            }
        };
        make("glrt back colour", COLOR_FORMAT, color_usage, samples, vk::ImageAspectFlags::COLOR)?;
        make("glrt front colour", COLOR_FORMAT, color_usage, samples, vk::ImageAspectFlags::COLOR)?;
        make("glrt depth", device.depth_format, depth_usage, samples, depth_aspects)?;
        if samples > 1 {
            // Attachment usage: the resolve images get views, like every image.
            let resolve = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
            make("glrt resolved colour", COLOR_FORMAT, resolve | vk::ImageUsageFlags::COLOR_ATTACHMENT, 1, vk::ImageAspectFlags::COLOR)?;
            make("glrt resolved depth", device.depth_format, resolve | vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT, 1, depth_aspects)?;
        }
        let mut images = made.into_iter();
        let (Some(color), Some(front), Some(depth)) = (images.next(), images.next(), images.next()) else { unreachable!("made above") };
        let resolved = match (images.next(), images.next()) {
            (Some(color), Some(depth)) => Some(Resolved { color, depth, layouts: [vk::ImageLayout::UNDEFINED; 2] }),
            _ => None,
        };
        Ok(Target { size: [w, h], color, depth, front, samples: samples.max(1), alpha, layouts: [vk::ImageLayout::UNDEFINED; 3], resolved })
    }

    /// Frees the images (the GPU must be done with them).
    pub fn destroy(self, device: &Device) {
        device.destroy_image(self.color);
        device.destroy_image(self.depth);
        device.destroy_image(self.front);
        if let Some(r) = self.resolved {
            device.destroy_image(r.color);
            device.destroy_image(r.depth);
        }
    }

    /// Records what makes the pixels of `plane` readable by transfers and returns the
    /// single-sampled image that holds them, in `TRANSFER_SRC_OPTIMAL`: the plane's own image,
    /// or for a multisampled target its resolve (see the module doc). Outside a rendering
    /// pass.
    pub fn readable(&mut self, device: &Device, cmd: vk::CommandBuffer, plane: Plane) -> vk::Image {
        let Some(mut resolved) = self.resolved.take() else {
            self.transition(device, cmd, plane, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
            return self.image(plane).raw;
        };
        let [width, height] = self.size;
        let out = match plane {
            Plane::Color | Plane::Front => {
                self.transition(device, cmd, plane, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
                resolved.transition(device, cmd, 0, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
                let layers = vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 };
                let region = vk::ImageResolve {
                    src_subresource: layers,
                    src_offset: vk::Offset3D::default(),
                    dst_subresource: layers,
                    dst_offset: vk::Offset3D::default(),
                    extent: vk::Extent3D { width, height, depth: 1 },
                };
                // Safety: both images are in the layouts named, of the same size and format;
                // cmd is outside a rendering pass.
                unsafe {
                    device.raw.cmd_resolve_image(
                        cmd,
                        self.image(plane).raw,
                        vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                        resolved.color.raw,
                        vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                        &[region],
                    )
                };
                resolved.transition(device, cmd, 0, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
                resolved.color.raw
            }
            Plane::DepthStencil => {
                let layout = vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
                self.transition(device, cmd, plane, layout);
                resolved.transition(device, cmd, 1, layout);
                let attachment = vk::RenderingAttachmentInfo::default()
                    .image_view(self.depth.view)
                    .image_layout(layout)
                    .resolve_mode(vk::ResolveModeFlags::SAMPLE_ZERO)
                    .resolve_image_view(resolved.depth.view)
                    .resolve_image_layout(layout)
                    .load_op(vk::AttachmentLoadOp::LOAD)
                    .store_op(vk::AttachmentStoreOp::STORE);
                let info = vk::RenderingInfo::default()
                    .render_area(vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width, height } })
                    .layer_count(1)
                    .depth_attachment(&attachment)
                    .stencil_attachment(&attachment);
                // Safety: the attachments are in the layouts named; cmd is outside a pass; the
                // pass only resolves.
                unsafe {
                    device.raw.cmd_begin_rendering(cmd, &info);
                    device.raw.cmd_end_rendering(cmd);
                }
                resolved.transition(device, cmd, 1, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
                resolved.depth.raw
            }
        };
        self.resolved = Some(resolved);
        out
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

    /// Records copying an RGBA8 picture of `size` (rows top to bottom, at `offset` in
    /// `buffer`) over the top-left corner of the front image, clipped to it; after
    /// [`Target::copy_back_to_front`] (the HUD, [`crate::render::hud`]). A multisampled front
    /// image cannot be written by a copy: nothing is recorded for it.
    pub fn copy_to_front(&mut self, device: &Device, cmd: vk::CommandBuffer, buffer: vk::Buffer, offset: u64, size: [u32; 2]) {
        if self.samples > 1 {
            return;
        }
        self.transition(device, cmd, Plane::Front, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        let copy = vk::BufferImageCopy {
            buffer_offset: offset,
            buffer_row_length: size[0],
            buffer_image_height: size[1],
            image_subresource: vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 },
            image_offset: vk::Offset3D::default(),
            image_extent: vk::Extent3D { width: size[0].min(self.size[0]), height: size[1].min(self.size[1]), depth: 1 },
        };
        // Safety: the front image is single-sampled and in TRANSFER_DST_OPTIMAL; the buffer
        // holds `size` RGBA8 texels from `offset`; the region lies inside both; outside a pass.
        unsafe { device.raw.cmd_copy_buffer_to_image(cmd, buffer, self.front.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[copy]) };
    }

    /// Records clearing the images (colour to transparent black, or opaque black without
    /// destination alpha; depth to 1, stencil to 0): a new target's contents are defined.
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
                    &vk::ClearColorValue { float32: self.stored_color([0.0; 4]) },
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

    /// The value the colour images store for `color`: alpha is 1 without destination alpha.
    pub fn stored_color(&self, [r, g, b, a]: [f32; 4]) -> [f32; 4] {
        [r, g, b, if self.alpha { a } else { 1.0 }]
    }

    /// The colour write mask `mask` leaves on the images: alpha is never written without
    /// destination alpha.
    pub fn color_write_mask(&self, mask: vk::ColorComponentFlags) -> vk::ColorComponentFlags {
        if self.alpha { mask } else { mask & !vk::ColorComponentFlags::A }
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
        barrier(device, cmd, self.image(plane).raw, Self::aspects(plane), old, layout);
        self.layouts[plane as usize] = layout;
    }

    /// The Vulkan rectangle (top-left origin) of the window rectangle `[x, y, w, h]`
    /// (bottom-left origin), clipped to the target; `None` when nothing remains.
    pub fn vk_rect(&self, rect: [i32; 4]) -> Option<vk::Rect2D> {
        window_to_image(self.size, rect)
    }
}

impl Resolved {
    /// [`Target::transition`] for resolve image `index` (0 colour, 1 depth/stencil).
    fn transition(&mut self, device: &Device, cmd: vk::CommandBuffer, index: usize, layout: vk::ImageLayout) {
        let (image, plane) = if index == 0 { (&self.color, Plane::Color) } else { (&self.depth, Plane::DepthStencil) };
        barrier(device, cmd, image.raw, Target::aspects(plane), self.layouts[index], layout);
        self.layouts[index] = layout;
    }
}

/// Records the barrier moving `image` from `old` to `layout` (nothing when already there and
/// the layout is an attachment layout; transfer layouts always get the barrier so that
/// consecutive copies are ordered).
fn barrier(device: &Device, cmd: vk::CommandBuffer, image: vk::Image, aspect_mask: vk::ImageAspectFlags, old: vk::ImageLayout, layout: vk::ImageLayout) {
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
        .image(image)
        .subresource_range(vk::ImageSubresourceRange { aspect_mask, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 1 });
    let barriers = [barrier];
    let dependency = vk::DependencyInfo::default().image_memory_barriers(&barriers);
    // Safety: cmd is recording; the image belongs to the device.
    unsafe { device.raw.cmd_pipeline_barrier2(cmd, &dependency) };
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
