//! The tracer's Vulkan objects that do not change with the scene: the descriptor set layout
//! of [`super::bindings`] (storage buffers and the sky's cube map), the two compute pipelines
//! (`pathtrace.comp`, `trace_resolve.comp`) and the composite's graphics pipelines (one per
//! sample count of the framebuffer it draws into).

use std::collections::HashMap;

use ash::vk;

use super::bindings;
use crate::render::raster::device::{Check, Device, Error, Result};
use crate::render::raster::multisample;
use crate::render::raster::pipelines::{create_for_target, shader_module};

/// Push constants of the composite: traced size and framebuffer size (`trace_composite.frag`'s
/// `Sizes`).
pub const COMPOSITE_PUSH_BYTES: u32 = 16;

/// Push constants of the compute pipelines: the sample a tracing dispatch traces (`pathtrace.comp`'s `Pass`).
pub const TRACE_PUSH_BYTES: u32 = 4;

include!(concat!(env!("OUT_DIR"), "/layouts/trace_push_constants.rs"));

/// Layouts, compute pipelines and composite pipelines.
pub struct TracePipelines {
    /// Set 0 of the compute pipelines.
    pub set_layout: vk::DescriptorSetLayout,
    /// Layout of the compute pipelines.
    pub layout: vk::PipelineLayout,
    /// The tracing pass.
    pub pathtrace: vk::Pipeline,
    /// The temporal pass and tone mapping.
    pub resolve: vk::Pipeline,
    /// Set 0 of the composite (binding 0: the output buffer).
    pub composite_set_layout: vk::DescriptorSetLayout,
    /// Layout of the composite.
    pub composite_layout: vk::PipelineLayout,
    composite_vertex: vk::ShaderModule,
    composite_fragment: vk::ShaderModule,
    /// Composite pipelines by sample count.
    composite: HashMap<u32, vk::Pipeline>,
}

/// A descriptor set layout of `count` storage buffers visible to `stages`, then combined
/// image samplers at the bindings `samplers`.
fn descriptor_set_layout(device: &Device, count: u32, samplers: &[u32], stages: vk::ShaderStageFlags) -> Result<vk::DescriptorSetLayout> {
    let binding = |b, ty| vk::DescriptorSetLayoutBinding::default().binding(b).descriptor_type(ty).descriptor_count(1).stage_flags(stages);
    let bindings: Vec<_> = (0..count)
        .map(|b| binding(b, vk::DescriptorType::STORAGE_BUFFER))
        .chain(samplers.iter().map(|&b| binding(b, vk::DescriptorType::COMBINED_IMAGE_SAMPLER)))
        .collect();
    // Safety: valid create info.
    unsafe { device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }
        .check("vkCreateDescriptorSetLayout")
}

fn compute_pipeline(device: &Device, layout: vk::PipelineLayout, spirv: &[u8]) -> Result<vk::Pipeline> {
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
        let composite_set_layout = descriptor_set_layout(device, 1, &[], vk::ShaderStageFlags::FRAGMENT)?;
        let composite_sets = [composite_set_layout];
        let push = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::FRAGMENT, offset: 0, size: COMPOSITE_PUSH_BYTES }];
        let composite_layout = unsafe {
            device.raw.create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&composite_sets).push_constant_ranges(&push), None)
        }
        .check("vkCreatePipelineLayout")?;
        Ok(TracePipelines {
            set_layout,
            layout,
            pathtrace,
            resolve,
            composite_set_layout,
            composite_layout,
            composite_vertex: shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_composite.vert.spv")))?,
            composite_fragment: shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_composite.frag.spv")))?,
            composite: HashMap::new(),
        })
    }

    /// The composite pipeline for a framebuffer of `samples` samples: a full-screen triangle
    /// writing colour (all channels) and depth (test LEQUAL), leaving stencil alone.
    pub fn composite(&mut self, device: &Device, samples: u32) -> Result<vk::Pipeline> {
        if let Some(&p) = self.composite.get(&samples) {
            return Ok(p);
        }
        let stages = [
            vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::VERTEX).module(self.composite_vertex).name(c"main"),
            vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::FRAGMENT).module(self.composite_fragment).name(c"main"),
        ];
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default();
        let assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(vk::PrimitiveTopology::TRIANGLE_LIST);
        let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
        let raster = vk::PipelineRasterizationStateCreateInfo::default().polygon_mode(vk::PolygonMode::FILL).cull_mode(vk::CullModeFlags::NONE).line_width(1.0);
        let multisample = vk::PipelineMultisampleStateCreateInfo::default().rasterization_samples(multisample::flags(samples));
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(true)
            .depth_write_enable(true)
            .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL);
        let attachments = [vk::PipelineColorBlendAttachmentState::default().color_write_mask(vk::ColorComponentFlags::RGBA)];
        let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&attachments);
        let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
        let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
        let info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&assembly)
            .viewport_state(&viewport)
            .rasterization_state(&raster)
            .multisample_state(&multisample)
            .depth_stencil_state(&depth)
            .color_blend_state(&blend)
            .dynamic_state(&dynamic)
            .layout(self.composite_layout);
        let pipeline = create_for_target(&device.raw, device.depth_format, info)?;
        self.composite.insert(samples, pipeline);
        Ok(pipeline)
    }

    /// Destroys everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once.
        unsafe {
            for (_, p) in self.composite.drain() {
                device.raw.destroy_pipeline(p, None);
            }
            device.raw.destroy_pipeline(self.pathtrace, None);
            device.raw.destroy_pipeline(self.resolve, None);
            device.raw.destroy_shader_module(self.composite_vertex, None);
            device.raw.destroy_shader_module(self.composite_fragment, None);
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_pipeline_layout(self.composite_layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
            device.raw.destroy_descriptor_set_layout(self.composite_set_layout, None);
        }
    }
}
