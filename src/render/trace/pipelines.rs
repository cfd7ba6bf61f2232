//! The compute tracer's Vulkan objects that do not change with the scene: the descriptor set
//! layout of [`super::bindings`] (storage buffers and the sky's cube map) and the two compute
//! pipelines (`pathtrace.comp`, `trace_resolve.comp`).

use ash::vk;

use super::bindings;
use crate::render::raster::device::{Check, Device, Error, Result};
use crate::render::raster::pipelines::shader_module;

/// Push constants of the compute pipelines: the sample a tracing dispatch traces (`pathtrace.comp`'s `Pass`).
pub const TRACE_PUSH_BYTES: u32 = 4;

include!(concat!(env!("OUT_DIR"), "/layouts/trace_push_constants.rs"));

/// The layouts and the compute pipelines.
pub struct TracePipelines {
    /// Set 0 of the compute pipelines.
    pub set_layout: vk::DescriptorSetLayout,
    /// Layout of the compute pipelines.
    pub layout: vk::PipelineLayout,
    /// The tracing pass.
    pub pathtrace: vk::Pipeline,
    /// The temporal pass and tone mapping.
    pub resolve: vk::Pipeline,
}

/// A descriptor set layout of `count` storage buffers visible to `stages`, then combined
/// image samplers at the bindings `samplers`.
pub(crate) fn descriptor_set_layout(device: &Device, count: u32, samplers: &[u32], stages: vk::ShaderStageFlags) -> Result<vk::DescriptorSetLayout> {
    let binding = |b, ty| vk::DescriptorSetLayoutBinding::default().binding(b).descriptor_type(ty).descriptor_count(1).stage_flags(stages);
    let bindings: Vec<_> = (0..count)
        .map(|b| binding(b, vk::DescriptorType::STORAGE_BUFFER))
        .chain(samplers.iter().map(|&b| binding(b, vk::DescriptorType::COMBINED_IMAGE_SAMPLER)))
        .collect();
    // Safety: valid create info.
    unsafe { device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }
        .check("vkCreateDescriptorSetLayout")
}

/// A compute pipeline of `layout` from the SPIR-V `spirv` (its entry point `main`).
pub(crate) fn compute_pipeline(device: &Device, layout: vk::PipelineLayout, spirv: &[u8]) -> Result<vk::Pipeline> {
    if crate::faults::fires(crate::faults::Fault::ShaderCompile) {
        return Err(Error::Vulkan("vkCreateComputePipelines", vk::Result::ERROR_INVALID_SHADER_NV));
    }
    let module = shader_module(device, spirv)?;
    let stage = vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::COMPUTE).module(module).name(c"main");
    let info = vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout);
    // Safety: the module and layout are alive; the module is destroyed after creation.
    let result = unsafe { device.raw.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) };
    // Safety: pipelines keep no reference to the module.
    unsafe { device.raw.destroy_shader_module(module, None) };
    match result {
        Ok(p) => Ok(p[0]),
        Err((_, r)) => Err(Error::Vulkan("vkCreateComputePipelines", r)),
    }
}

impl TracePipelines {
    /// Creates the layouts and the compute pipelines.
    pub fn new(device: &Device) -> Result<TracePipelines> {
        let set_layout = descriptor_set_layout(device, bindings::COUNT, &[bindings::SKY], vk::ShaderStageFlags::COMPUTE)?;
        let set_layouts = [set_layout];
        let trace_push = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::COMPUTE, offset: 0, size: TRACE_PUSH_BYTES }];
        // Safety (this block): valid create infos; objects are destroyed in `destroy`.
        let layout = unsafe {
            device.raw.create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts).push_constant_ranges(&trace_push), None)
        }
        .check("vkCreatePipelineLayout")?;
        let pathtrace = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.comp.spv")))?;
        let resolve = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_resolve.comp.spv")))?;
        Ok(TracePipelines { set_layout, layout, pathtrace, resolve })
    }

    /// Destroys everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once.
        unsafe {
            device.raw.destroy_pipeline(self.pathtrace, None);
            device.raw.destroy_pipeline(self.resolve, None);
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}
