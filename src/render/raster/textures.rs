//! Textures on the GPU: the image of each [`TextureRef`] content version, uploaded once and
//! kept while draws use it, samplers cached by their state, and the 1×1 white textures that
//! fill unused bindings (see the `ff` module doc).

use ash::vk;

use super::device::{Check, Device, Image, Result};
use super::pipelines::BINDINGS;

/// The white textures of unused 2D, 3D and cube bindings and their sampler.
pub struct Textures {
    white: Option<[Image; 3]>,
    sampler: vk::Sampler,
}

impl Textures {
    /// Creates the default sampler (the white images are made on first use, in a frame).
    pub fn new(device: &Device) -> Result<Textures> {
        let info = vk::SamplerCreateInfo::default().max_lod(vk::LOD_CLAMP_NONE);
        // Safety: valid create info.
        let sampler = unsafe { device.raw.create_sampler(&info, None) }.check("vkCreateSampler")?;
        Ok(Textures { white: None, sampler })
    }

    /// Image views and samplers of bindings 1.. for a draw; records the creation of the white
    /// textures into `cmd` the first time (outside a rendering pass).
    pub fn bindings(&mut self, device: &Device, cmd: vk::CommandBuffer) -> Result<[(vk::ImageView, vk::Sampler); BINDINGS as usize - 1]> {
        if self.white.is_none() {
            self.white = Some(create_white(device, cmd)?);
        }
        let views = self.white.as_ref().map(|w| [w[0].view, w[1].view, w[2].view]).unwrap_or_default();
        let per_kind = super::ff::MAX_UNITS;
        Ok(std::array::from_fn(|i| (views[i / per_kind], self.sampler)))
    }

    /// Whether [`Textures::bindings`] would record commands (so the caller ends rendering).
    pub fn needs_upload(&self) -> bool {
        self.white.is_none()
    }

    /// Frees everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        if let Some(white) = self.white.take() {
            for image in white {
                device.destroy_image(image);
            }
        }
        // Safety: the GPU is idle.
        unsafe { device.raw.destroy_sampler(self.sampler, None) };
    }
}

/// The 1×1 white 2D, 3D and cube textures, cleared to white in `cmd` and left shader-readable.
fn create_white(device: &Device, cmd: vk::CommandBuffer) -> Result<[Image; 3]> {
    let base = vk::ImageCreateInfo::default()
        .format(vk::Format::R8G8B8A8_UNORM)
        .extent(vk::Extent3D { width: 1, height: 1, depth: 1 })
        .mip_levels(1)
        .array_layers(1)
        .samples(vk::SampleCountFlags::TYPE_1)
        .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST);
    let d2 = device.create_image("glrt white 2D", &base.image_type(vk::ImageType::TYPE_2D), vk::ImageViewType::TYPE_2D, vk::ImageAspectFlags::COLOR)?;
    let d3 = device.create_image("glrt white 3D", &base.image_type(vk::ImageType::TYPE_3D), vk::ImageViewType::TYPE_3D, vk::ImageAspectFlags::COLOR)?;
    let cube_info = base.image_type(vk::ImageType::TYPE_2D).array_layers(6).flags(vk::ImageCreateFlags::CUBE_COMPATIBLE);
    let cube = device.create_image("glrt white cube", &cube_info, vk::ImageViewType::CUBE, vk::ImageAspectFlags::COLOR)?;
    for (image, layers) in [(&d2, 1), (&d3, 1), (&cube, 6)] {
        let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: layers };
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::UNDEFINED, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        // Safety: the image is in TRANSFER_DST_OPTIMAL.
        unsafe {
            device.raw.cmd_clear_color_image(
                cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &vk::ClearColorValue { float32: [1.0; 4] },
                &[range],
            )
        };
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    }
    Ok([d2, d3, cube])
}

/// Records a full barrier moving `range` of `image` between layouts.
pub fn image_barrier(device: &Device, cmd: vk::CommandBuffer, image: vk::Image, range: vk::ImageSubresourceRange, old: vk::ImageLayout, new: vk::ImageLayout) {
    let barrier = [vk::ImageMemoryBarrier2::default()
        .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
        .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
        .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
        .dst_access_mask(vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE)
        .old_layout(old)
        .new_layout(new)
        .image(image)
        .subresource_range(range)];
    // Safety: cmd is recording; the image is alive.
    unsafe { device.raw.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().image_memory_barriers(&barrier)) };
}
