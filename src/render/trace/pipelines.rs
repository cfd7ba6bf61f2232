//! The tracers' Vulkan objects that do not change with the scene: the descriptor set layout of
//! [`super::bindings`] (storage buffers and the sky's cube map, and for the hardware tracer
//! the top-level acceleration structure), the tracing pipeline (`pathtrace.comp` over wide
//! BVHs or `pathtrace_binary.comp` over binary ones, or the hardware tracer's ray-tracing
//! pipeline, [`super::hardware::pipeline`]) and the resolve pass
//! (`trace_resolve.comp`).

use ash::vk;

use super::bindings;
use super::bvh::Layout;
use crate::render::raster::device::{Check, Device, Error, Result};
use crate::render::raster::pipelines::shader_module;
use super::hardware::pipeline::ShaderTable;

/// Push constants of the compute pipelines: the sample a tracing dispatch traces and whether
/// it is the gradient pass (`pathtrace.comp`'s `Pass`).
pub const TRACE_PUSH_BYTES: u32 = 8;

include!(concat!(env!("OUT_DIR"), "/layouts/trace_push_constants.rs"));

/// The layouts and the pipelines.
pub struct TracePipelines {
    /// Set 0 of the pipelines.
    pub set_layout: vk::DescriptorSetLayout,
    /// Layout of the pipelines.
    pub layout: vk::PipelineLayout,
    /// The tracing pass: a compute pipeline, or with [`TracePipelines::table`] a ray-tracing one.
    pub pathtrace: vk::Pipeline,
    /// The hardware tracer's shader binding table.
    pub table: Option<ShaderTable>,
    /// The temporal pass and tone mapping.
    pub resolve: vk::Pipeline,
}

/// The ray-tracing stages.
const RAY_TRACING_STAGES: vk::ShaderStageFlags = vk::ShaderStageFlags::from_raw(
    vk::ShaderStageFlags::RAYGEN_KHR.as_raw() | vk::ShaderStageFlags::CLOSEST_HIT_KHR.as_raw() | vk::ShaderStageFlags::ANY_HIT_KHR.as_raw() | vk::ShaderStageFlags::MISS_KHR.as_raw(),
);

/// A descriptor set layout of `count` storage buffers visible to `stages`, then combined
/// image samplers at the bindings `samplers`, then acceleration structures at the bindings
/// `structures`.
pub(crate) fn descriptor_set_layout(device: &Device, count: u32, samplers: &[u32], structures: &[u32], stages: vk::ShaderStageFlags) -> Result<vk::DescriptorSetLayout> {
    let binding = |b, ty| vk::DescriptorSetLayoutBinding::default().binding(b).descriptor_type(ty).descriptor_count(1).stage_flags(stages);
    let bindings: Vec<_> = (0..count)
        .map(|b| binding(b, vk::DescriptorType::STORAGE_BUFFER))
        .chain(samplers.iter().map(|&b| binding(b, vk::DescriptorType::COMBINED_IMAGE_SAMPLER)))
        .chain(structures.iter().map(|&b| binding(b, vk::DescriptorType::ACCELERATION_STRUCTURE_KHR)))
        .collect();
    // Safety: valid create info.
    unsafe { device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }
        .check("vkCreateDescriptorSetLayout")
}

/// `objects` once `make` has created the rest of their handles; where it fails, `destroy`
/// destroys what it made (the others are null, which Vulkan skips) and its error is returned.
pub(crate) fn completed<T>(device: &Device, mut objects: T, make: impl FnOnce(&mut T) -> Result<()>, destroy: impl FnOnce(&mut T, &Device)) -> Result<T> {
    match make(&mut objects) {
        Ok(()) => Ok(objects),
        Err(e) => {
            destroy(&mut objects, device);
            Err(e)
        }
    }
}

/// A compute pipeline of `layout` from the SPIR-V `spirv` (its entry point `main`).
pub(crate) fn compute_pipeline(device: &Device, layout: vk::PipelineLayout, spirv: &[u8]) -> Result<vk::Pipeline> {
    specialised_compute_pipeline(device, layout, spirv, &[])
}

/// [`compute_pipeline`] with the specialisation constants `constants`: the 32-bit value of
/// `constant_id` k at index k (a bool is 0 or 1).
pub(crate) fn specialised_compute_pipeline(device: &Device, layout: vk::PipelineLayout, spirv: &[u8], constants: &[u32]) -> Result<vk::Pipeline> {
    if crate::faults::fires(crate::faults::Fault::ShaderCompile) {
        return Err(Error::Vulkan("vkCreateComputePipelines", vk::Result::ERROR_INVALID_SHADER_NV));
    }
    let module = shader_module(device, spirv)?;
    let entries: Vec<vk::SpecializationMapEntry> = (0..constants.len() as u32).map(|i| vk::SpecializationMapEntry { constant_id: i, offset: 4 * i, size: 4 }).collect();
    let specialization = vk::SpecializationInfo::default().map_entries(&entries).data(bytemuck::cast_slice(constants));
    let stage = vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::COMPUTE).module(module).name(c"main").specialization_info(&specialization);
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
    /// Creates the layouts and the pipelines: with `hardware`, the ray-tracing pipeline
    /// (the device has [`Device::ray_tracing`]) and its acceleration-structure binding;
    /// without, the compute pipeline traversing BVHs of layout `bvh`.
    pub fn new(device: &Device, hardware: bool, bvh: Layout) -> Result<TracePipelines> {
        let (stages, structures): (_, &[u32]) =
            if hardware { (vk::ShaderStageFlags::COMPUTE | RAY_TRACING_STAGES, &[bindings::ACCELERATION]) } else { (vk::ShaderStageFlags::COMPUTE, &[]) };
        let set_layout = descriptor_set_layout(device, bindings::COUNT, &[bindings::SKY], structures, stages)?;
        let set_layouts = [set_layout];
        let push_stages = if hardware { vk::ShaderStageFlags::COMPUTE | vk::ShaderStageFlags::RAYGEN_KHR } else { vk::ShaderStageFlags::COMPUTE };
        let trace_push = [vk::PushConstantRange { stage_flags: push_stages, offset: 0, size: TRACE_PUSH_BYTES }];
        // Safety (this block): valid create infos; objects are destroyed in `destroy`.
        let layout = unsafe {
            device.raw.create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts).push_constant_ranges(&trace_push), None)
        }
        .check("vkCreatePipelineLayout")?;
        let pipelines = TracePipelines { set_layout, layout, pathtrace: vk::Pipeline::null(), table: None, resolve: vk::Pipeline::null() };
        let make = |pipelines: &mut TracePipelines| {
            if hardware {
                let (pipeline, table) = super::hardware::pipeline::create(device, layout)?;
                pipelines.pathtrace = pipeline;
                pipelines.table = Some(table);
            } else {
                let spirv: &[u8] = match bvh {
                    Layout::Wide => include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.comp.spv")),
                    Layout::Binary => include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace_binary.comp.spv")),
                };
                pipelines.pathtrace = compute_pipeline(device, layout, spirv)?;
            }
            pipelines.resolve = compute_pipeline(device, layout, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_resolve.comp.spv")))?;
            Ok(())
        };
        completed(device, pipelines, make, TracePipelines::destroy)
    }

    /// The bind point of [`TracePipelines::pathtrace`].
    pub fn trace_bind_point(&self) -> vk::PipelineBindPoint {
        if self.table.is_some() { vk::PipelineBindPoint::RAY_TRACING_KHR } else { vk::PipelineBindPoint::COMPUTE }
    }

    /// Destroys everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        if let Some(table) = self.table.take() {
            table.destroy(device);
        }
        // Safety: the GPU is done with them; each is destroyed once (null handles are ignored).
        unsafe {
            device.raw.destroy_pipeline(self.pathtrace, None);
            device.raw.destroy_pipeline(self.resolve, None);
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}
