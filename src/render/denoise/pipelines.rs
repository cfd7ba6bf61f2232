//! The denoiser's Vulkan objects that do not change with the frame: the layout of its
//! descriptor sets ([`super::shader_constants`]'s bindings, all storage buffers), the push
//! constants of a pass ([`DenoisePass`]) and the compute pipelines of the five passes, each
//! with the specular channel or without it (the specialisation constant `SPECULAR_CONSTANT`):
//! with `[denoise] specular = false` no pass holds the channel's code, and the à-trous
//! iterations past the first `SPECULAR_ITERATIONS` run without it either way.

use ash::vk;
use bytemuck::{Pod, Zeroable};

use super::shader_constants::{BINDING_COUNT, SPECULAR_CONSTANT};
use crate::render::raster::device::{Check, Device, Result};
use crate::render::trace::pipelines::{completed, descriptor_set_layout, specialised_compute_pipeline};

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
    /// Temporal gradients per stratum (`gradient.comp`), with the specular channel's where
    /// the denoiser has it (as the passes below but `atrous`).
    pub gradient: vk::Pipeline,
    /// Temporal accumulation with reprojection (`temporal.comp`).
    pub temporal: vk::Pipeline,
    /// Spatial variance of young histories (`variance.comp`).
    pub variance: vk::Pipeline,
    /// One à-trous iteration without the specular channel (`atrous.comp`).
    pub atrous: vk::Pipeline,
    /// One of the first `SPECULAR_ITERATIONS` à-trous iterations with the specular channel
    /// (null without it).
    pub atrous_specular: vk::Pipeline,
    /// Remodulation and tone mapping (`modulate.comp`).
    pub modulate: vk::Pipeline,
}

impl DenoisePipelines {
    /// Creates the layouts and pipelines, the passes with the specular channel where
    /// `specular`.
    pub fn new(device: &Device, specular: bool) -> Result<DenoisePipelines> {
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
            atrous_specular: vk::Pipeline::null(),
            modulate: vk::Pipeline::null(),
        };
        // The constants of a pass with the specular channel or without it.
        let with = |on: bool| {
            let mut constants = [0; SPECULAR_CONSTANT as usize + 1];
            constants[SPECULAR_CONSTANT as usize] = u32::from(on);
            constants
        };
        let make = |pipelines: &mut DenoisePipelines| {
            let pass = |spirv: &[u8], on: bool| specialised_compute_pipeline(device, layout, spirv, &with(on));
            let atrous: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/atrous.comp.spv"));
            pipelines.gradient = pass(include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/gradient.comp.spv")), specular)?;
            pipelines.temporal = pass(include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/temporal.comp.spv")), specular)?;
            pipelines.variance = pass(include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/variance.comp.spv")), specular)?;
            pipelines.atrous = pass(atrous, false)?;
            if specular {
                pipelines.atrous_specular = pass(atrous, true)?;
            }
            pipelines.modulate = pass(include_bytes!(concat!(env!("OUT_DIR"), "/shaders/denoise/modulate.comp.spv")), specular)?;
            Ok(())
        };
        completed(device, pipelines, make, DenoisePipelines::destroy)
    }

    /// Destroys everything (the GPU must be idle); null handles are skipped by Vulkan.
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once (null handles are ignored).
        unsafe {
            for p in [self.gradient, self.temporal, self.variance, self.atrous, self.atrous_specular, self.modulate] {
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
