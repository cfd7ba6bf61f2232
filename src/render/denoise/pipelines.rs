//! The denoiser's Vulkan objects that do not change with the frame: the layout of its
//! descriptor sets ([`super::shader_constants`]'s bindings, all storage buffers), the push
//! constants of a pass ([`DenoisePass`]) and the five compute pipelines.

use ash::vk;
use bytemuck::{Pod, Zeroable};

use super::shader_constants::BINDING_COUNT;
use crate::render::raster::device::{Check, Device, Result};
use crate::render::trace::pipelines::{completed, compute_pipeline, descriptor_set_layout};

/// Push constants of every pass (`DenoisePass` of `shaders/denoise/common.glsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DenoisePass {
    /// Exposure multiplier, history cap (frames), tone-mapping knee, frames of a moving
    /// camera's history.
    pub params: [f32; 4],
    /// Traced width and height, `FLAG_*` bits, the à-trous step in pixels.
    pub size: [u32; 4],
    /// Record offsets (in pixels) into the signal: read, written.
    pub signal: [u32; 2],
    /// Record offsets (in pixels) into the specular signal: read, written.
    pub specular: [u32; 2],
}

/// Bytes of [`DenoisePass`].
pub const PASS_BYTES: u32 = size_of::<DenoisePass>() as u32;

include!(concat!(env!("OUT_DIR"), "/layouts/denoise_gpu_types.rs"));

/// The layouts and pipelines.
pub struct DenoisePipelines {
    /// The layout of both descriptor sets (one per frame parity).
    pub set_layout: vk::DescriptorSetLayout,
    /// Layout of every pass.
    pub layout: vk::PipelineLayout,
    /// Temporal gradients per stratum (`gradient.comp`).
    pub gradient: vk::Pipeline,
    /// Temporal accumulation with reprojection (`temporal.comp`).
    pub temporal: vk::Pipeline,
    /// Spatial variance of young histories (`variance.comp`).
    pub variance: vk::Pipeline,
    /// One à-trous iteration (`atrous.comp`).
    pub atrous: vk::Pipeline,
    /// Remodulation and tone mapping (`modulate.comp`).
    pub modulate: vk::Pipeline,
}

impl DenoisePipelines {
    /// Creates the layouts and pipelines.
    pub fn new(device: &Device) -> Result<DenoisePipelines> {
        let set_layout = descriptor_set_layout(device, BINDING_COUNT, &[], &[], vk::ShaderStageFlags::COMPUTE)?;
        let set_layouts = [set_layout];
        let push = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::COMPUTE, offset: 0, size: PASS_BYTES }];
        // Safety: valid create info; destroyed in `destroy`.
        let layout = unsafe { device.raw.create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts).push_constant_ranges(&push), None) }
            .check("vkCreatePipelineLayout")?;
        let pipelines = DenoisePipelines {
            set_layout,
            layout,
            gradient: vk::Pipeline::null(),
            temporal: vk::Pipeline::null(),
            variance: vk::Pipeline::null(),
            atrous: vk::Pipeline::null(),
            modulate: vk::Pipeline::null(),
        };
        let make = |pipelines: &mut DenoisePipelines| {
            pipelines.gradient = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/gradient.comp.spv")))?;
            pipelines.temporal = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/temporal.comp.spv")))?;
            pipelines.variance = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/variance.comp.spv")))?;
            pipelines.atrous = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/atrous.comp.spv")))?;
            pipelines.modulate = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/modulate.comp.spv")))?;
            Ok(())
        };
        completed(device, pipelines, make, DenoisePipelines::destroy)
    }

    /// Destroys everything (the GPU must be idle); null handles are skipped by Vulkan.
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once (null handles are ignored).
        unsafe {
            for p in [self.gradient, self.temporal, self.variance, self.atrous, self.modulate] {
                device.raw.destroy_pipeline(p, None);
            }
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

/// Per-pixel bytes of one frame's history light (`HistoryLight` of `denoise/common.glsl`).
pub const HISTORY_LIGHT_BYTES: u64 = 16;
/// Per-pixel bytes of one frame's luminance means, variances and traced luminances
/// (`HistoryMoments`).
pub const HISTORY_MOMENTS_BYTES: u64 = 12;
/// Per-pixel bytes of one frame's surfaces (`Guide`).
pub const GUIDE_BYTES: u64 = 8;
/// Per-pixel bytes of one frame's specular history (`HistorySpecular`).
pub const HISTORY_SPECULAR_BYTES: u64 = 16;
/// Bytes of one stratum's temporal gradients (`Gradient` of `denoise/common.glsl`).
pub const GRADIENT_BYTES: u64 = 12;
/// Per-pixel bytes of the spatial passes' signal (`Signal`).
pub const SIGNAL_BYTES: u64 = 16;
/// Per-pixel bytes of the specular signal (`SpecularSignal`).
pub const SPECULAR_SIGNAL_BYTES: u64 = 8;
