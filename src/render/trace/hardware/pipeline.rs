//! The hardware tracer's ray-tracing pipeline and its shader binding table: the ray generation
//! shader `pathtrace.rgen` (the compute tracer's path integrator, `trace/path.glsl`, over
//! `trace/hardware.glsl`'s traversal), one miss shader and one triangle hit group (closest hit,
//! and the alpha test as any hit), on the tracing pipelines' layout
//! ([`crate::render::trace::pipelines`]).

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::render::raster::device::{Buffer, Check, Device, Error, Result};
use crate::render::raster::pipelines::shader_module;

/// The shader binding table: one record per group, in a host-visible buffer.
pub struct ShaderTable {
    ext: ash::khr::ray_tracing_pipeline::Device,
    buffer: Buffer,
    raygen: vk::StridedDeviceAddressRegionKHR,
    miss: vk::StridedDeviceAddressRegionKHR,
    hit: vk::StridedDeviceAddressRegionKHR,
}

/// Rounds `n` up to a multiple of `alignment` (a power of two).
fn align_up(n: u64, alignment: u64) -> u64 {
    n.div_ceil(alignment) * alignment
}

/// Creates the ray-tracing pipeline on `layout` and its shader binding table.
pub fn create(device: &Device, layout: vk::PipelineLayout) -> Result<(vk::Pipeline, ShaderTable)> {
    if crate::faults::fires(crate::faults::Fault::ShaderCompile) {
        return Err(Error::Vulkan("vkCreateRayTracingPipelinesKHR", vk::Result::ERROR_INVALID_SHADER_NV));
    }
    let ext = ash::khr::ray_tracing_pipeline::Device::new(&device.instance, &device.raw);
    let sources: [(vk::ShaderStageFlags, &[u8]); 4] = [
        (vk::ShaderStageFlags::RAYGEN_KHR, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.rgen.spv"))),
        (vk::ShaderStageFlags::MISS_KHR, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.rmiss.spv"))),
        (vk::ShaderStageFlags::CLOSEST_HIT_KHR, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.rchit.spv"))),
        (vk::ShaderStageFlags::ANY_HIT_KHR, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.rahit.spv"))),
    ];
    let mut modules = Vec::new();
    for (_, spirv) in &sources {
        match shader_module(device, spirv) {
            Ok(m) => modules.push(m),
            Err(e) => {
                // Safety: unused modules.
                modules.iter().for_each(|&m| unsafe { device.raw.destroy_shader_module(m, None) });
                return Err(e);
            }
        }
    }
    let stages: Vec<vk::PipelineShaderStageCreateInfo> =
        sources.iter().zip(&modules).map(|((stage, _), &module)| vk::PipelineShaderStageCreateInfo::default().stage(*stage).module(module).name(c"main")).collect();
    let general = |shader| {
        vk::RayTracingShaderGroupCreateInfoKHR::default()
            .ty(vk::RayTracingShaderGroupTypeKHR::GENERAL)
            .general_shader(shader)
            .closest_hit_shader(vk::SHADER_UNUSED_KHR)
            .any_hit_shader(vk::SHADER_UNUSED_KHR)
            .intersection_shader(vk::SHADER_UNUSED_KHR)
    };
    let groups = [
        general(0),
        general(1),
        vk::RayTracingShaderGroupCreateInfoKHR::default()
            .ty(vk::RayTracingShaderGroupTypeKHR::TRIANGLES_HIT_GROUP)
            .general_shader(vk::SHADER_UNUSED_KHR)
            .closest_hit_shader(2)
            .any_hit_shader(3)
            .intersection_shader(vk::SHADER_UNUSED_KHR),
    ];
    let info = vk::RayTracingPipelineCreateInfoKHR::default().stages(&stages).groups(&groups).max_pipeline_ray_recursion_depth(1).layout(layout);
    // Safety: valid create info; the modules are destroyed after creation.
    let result = unsafe { ext.create_ray_tracing_pipelines(vk::DeferredOperationKHR::null(), vk::PipelineCache::null(), &[info], None) };
    // Safety: pipelines keep no reference to their modules.
    modules.iter().for_each(|&m| unsafe { device.raw.destroy_shader_module(m, None) });
    let pipeline = match result {
        Ok(p) => p[0],
        Err((_, r)) => return Err(Error::Vulkan("vkCreateRayTracingPipelinesKHR", r)),
    };
    match ShaderTable::new(device, ext, pipeline, groups.len() as u32) {
        Ok(table) => Ok((pipeline, table)),
        Err(e) => {
            // Safety: unused pipeline.
            unsafe { device.raw.destroy_pipeline(pipeline, None) };
            Err(e)
        }
    }
}

impl ShaderTable {
    /// The table of `pipeline`'s `groups` groups: ray generation, miss, hit group, each in its
    /// own region.
    fn new(device: &Device, ext: ash::khr::ray_tracing_pipeline::Device, pipeline: vk::Pipeline, groups: u32) -> Result<ShaderTable> {
        let mut properties = vk::PhysicalDeviceRayTracingPipelinePropertiesKHR::default();
        let mut all = vk::PhysicalDeviceProperties2::default().push_next(&mut properties);
        // Safety: the device has VK_KHR_ray_tracing_pipeline.
        unsafe { device.instance.get_physical_device_properties2(device.physical, &mut all) };
        let handle = properties.shader_group_handle_size as usize;
        let stride = align_up(handle as u64, u64::from(properties.shader_group_handle_alignment.max(1)));
        let base = u64::from(properties.shader_group_base_alignment.max(1));
        let region = align_up(stride, base);
        // Safety: the pipeline has `groups` groups.
        let handles = unsafe { ext.get_ray_tracing_shader_group_handles(pipeline, 0, groups, handle * groups as usize) }.check("vkGetRayTracingShaderGroupHandlesKHR")?;
        let usage = vk::BufferUsageFlags::SHADER_BINDING_TABLE_KHR | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS;
        let mut buffer = device.create_buffer("glrt shader binding table", region * u64::from(groups) + base, usage, MemoryLocation::CpuToGpu)?;
        // Safety: the buffer has SHADER_DEVICE_ADDRESS usage.
        let address = unsafe { device.raw.get_buffer_device_address(&vk::BufferDeviceAddressInfo::default().buffer(buffer.raw)) };
        let start = align_up(address, base);
        let mapped = buffer.mapped();
        for g in 0..groups as usize {
            let at = (start - address) as usize + g * region as usize;
            mapped[at..at + handle].copy_from_slice(&handles[g * handle..(g + 1) * handle]);
        }
        let at = |g: u64| vk::StridedDeviceAddressRegionKHR { device_address: start + g * region, stride, size: stride };
        // The ray generation region's stride must equal its size.
        let raygen = vk::StridedDeviceAddressRegionKHR { stride: region, size: region, ..at(0) };
        Ok(ShaderTable { ext, buffer, raygen, miss: at(1), hit: at(2) })
    }

    /// Records a launch of `width` x `height` ray generation invocations (pipeline and set
    /// bound).
    ///
    /// # Safety
    /// `cmd` is recording outside a rendering pass with the pipeline and its set bound.
    pub unsafe fn trace(&self, cmd: vk::CommandBuffer, width: u32, height: u32) {
        let callable = vk::StridedDeviceAddressRegionKHR::default();
        // Safety: per the function's contract.
        unsafe { self.ext.cmd_trace_rays(cmd, &self.raygen, &self.miss, &self.hit, &callable, width, height, 1) };
    }

    /// Frees the table (the GPU must be idle).
    pub fn destroy(self, device: &Device) {
        device.destroy_buffer(self.buffer);
    }
}
