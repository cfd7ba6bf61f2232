//! The composite: draws a [`TracedImage`] into the raster framebuffer with its depth (thesis
//! 4.3.6), a full-screen triangle (`trace_composite.vert`, `trace_composite.frag`). Pixels
//! whose primary ray hit take the traced colour and depth (depth test LEQUAL, so raster draws
//! made earlier and nearer stay); pixels whose ray missed keep what the framebuffer holds.
//! The translucent and overlay draws after it are depth-tested against the traced depth. Each
//! hit is fogged there by the height fog ([`crate::render::fog`]) as a raster fragment at its
//! place would be. The
//! image's layout is the same for every back end, so this stage belongs to none of them.

use std::collections::HashMap;

use ash::vk;

use super::TracedImage;
use super::gpu_types::OUTPUT_SAMPLE_BYTES;
use crate::frame::Draw;
use crate::render::fog::GpuHeightFog;
use crate::render::raster::commands::SetKey;
use crate::render::raster::device::{Check, Device, Result};
use crate::render::raster::multisample;
use crate::render::raster::pipelines::{create_for_target, shader_module};
use crate::render::raster::renderer::Recorder;

/// Push constants: traced size and framebuffer size.
const PUSH_BYTES: u32 = 16;

include!(concat!(env!("OUT_DIR"), "/layouts/trace_composite.rs"));

/// The composite's layouts, shaders and pipelines (one per sample count of the framebuffer).
pub struct Composite {
    /// Set 0: binding 0, the traced image's samples, binding 1 the height fog's block
    /// ([`GpuHeightFog`]), dynamic storage buffers, so the frame's descriptor sets hold them
    /// ([`crate::render::raster::commands::Descriptors`]).
    set_layout: vk::DescriptorSetLayout,
    layout: vk::PipelineLayout,
    vertex: vk::ShaderModule,
    fragment: vk::ShaderModule,
    pipelines: HashMap<u32, vk::Pipeline>,
}

impl Composite {
    /// Creates the layouts and shader modules.
    pub fn new(device: &Device) -> Result<Composite> {
        let binding = [0, 1].map(|b| {
            vk::DescriptorSetLayoutBinding::default()
                .binding(b)
                .descriptor_type(vk::DescriptorType::STORAGE_BUFFER_DYNAMIC)
                .descriptor_count(1)
                .stage_flags(vk::ShaderStageFlags::FRAGMENT)
        });
        let push = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::FRAGMENT, offset: 0, size: PUSH_BYTES }];
        // Safety (this block): valid create infos; the objects are destroyed in `destroy`.
        let (set_layout, layout) = unsafe {
            let set_layout =
                device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&binding), None).check("vkCreateDescriptorSetLayout")?;
            let sets = [set_layout];
            let layout = device
                .raw
                .create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&sets).push_constant_ranges(&push), None)
                .check("vkCreatePipelineLayout")?;
            (set_layout, layout)
        };
        Ok(Composite {
            set_layout,
            layout,
            vertex: shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_composite.vert.spv")))?,
            fragment: shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_composite.frag.spv")))?,
            pipelines: HashMap::new(),
        })
    }

    /// Records drawing `image` over the whole of `rec`'s framebuffer (scaled to its size), its
    /// hits fogged as `camera` (the first traced draw) places them when the frame is fogged
    /// ([`Recorder::fog`]).
    pub fn record(&mut self, rec: &mut Recorder<'_>, image: &TracedImage, camera: &Draw) -> Result<()> {
        let pipeline = self.pipeline(rec.device, rec.target.samples)?;
        let bytes = image.size[0] as u64 * image.size[1] as u64 * OUTPUT_SAMPLE_BYTES;
        let fog = rec.fog.map_or_else(GpuHeightFog::default, |f| f.for_draw(camera, rec.target.size[1]));
        let align = rec.device.properties.limits.min_storage_buffer_offset_alignment.max(16);
        let fog = rec.ring.push(rec.device, bytemuck::bytes_of(&fog), align)?;
        let fog_bytes = size_of::<GpuHeightFog>() as u64;
        let key = SetKey { layout: self.set_layout, buffers: &[(image.output, bytes), (fog.buffer, fog_bytes)], images: &[] };
        let set = rec.descriptors.get(rec.device, &key)?;
        rec.begin_rendering();
        let [w, h] = rec.target.size;
        let (d, cmd) = (&rec.device.raw, rec.cmd);
        let sizes: [u32; 4] = [image.size[0], image.size[1], w, h];
        // Safety: inside the rendering pass on the framebuffer; the image's buffer lives until
        // the frame finishes and was made readable by fragment shaders.
        unsafe {
            d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::GRAPHICS, pipeline);
            d.cmd_set_viewport(cmd, 0, &[vk::Viewport { x: 0.0, y: 0.0, width: w as f32, height: h as f32, min_depth: 0.0, max_depth: 1.0 }]);
            d.cmd_set_scissor(cmd, 0, &[vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width: w, height: h } }]);
            d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::GRAPHICS, self.layout, 0, &[set], &[0, fog.offset as u32]);
            d.cmd_push_constants(cmd, self.layout, vk::ShaderStageFlags::FRAGMENT, 0, bytemuck::cast_slice(&sizes));
            d.cmd_draw(cmd, 3, 1, 0, 0);
        }
        rec.forget_state();
        Ok(())
    }

    /// The pipeline for a framebuffer of `samples` samples: a full-screen triangle writing
    /// colour (all channels) and depth (test LEQUAL), leaving stencil alone.
    fn pipeline(&mut self, device: &Device, samples: u32) -> Result<vk::Pipeline> {
        if let Some(&p) = self.pipelines.get(&samples) {
            return Ok(p);
        }
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(true)
            .depth_write_enable(true)
            .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL);
        let attachment = vk::PipelineColorBlendAttachmentState::default().color_write_mask(vk::ColorComponentFlags::RGBA);
        let pipeline = full_screen_pipeline(device, self.layout, [self.vertex, self.fragment], samples, depth, attachment)?;
        self.pipelines.insert(samples, pipeline);
        Ok(pipeline)
    }

    /// Destroys everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once.
        unsafe {
            for (_, p) in self.pipelines.drain() {
                device.raw.destroy_pipeline(p, None);
            }
            device.raw.destroy_shader_module(self.vertex, None);
            device.raw.destroy_shader_module(self.fragment, None);
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

/// A graphics pipeline of `layout` drawing a full-screen triangle (the vertex shader
/// `trace_composite.vert`, no vertex input) into the raster framebuffer of `samples` samples,
/// with the depth and stencil state `depth`, the blending of `attachment`, and a dynamic
/// viewport and scissor; also used by the ambient occlusion's pass ([`crate::render::ao`]).
pub(crate) fn full_screen_pipeline(
    device: &Device,
    layout: vk::PipelineLayout,
    [vertex, fragment]: [vk::ShaderModule; 2],
    samples: u32,
    depth: vk::PipelineDepthStencilStateCreateInfo<'_>,
    attachment: vk::PipelineColorBlendAttachmentState,
) -> Result<vk::Pipeline> {
    let stages = [
        vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::VERTEX).module(vertex).name(c"main"),
        vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::FRAGMENT).module(fragment).name(c"main"),
    ];
    let vertex_input = vk::PipelineVertexInputStateCreateInfo::default();
    let assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(vk::PrimitiveTopology::TRIANGLE_LIST);
    let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
    let raster = vk::PipelineRasterizationStateCreateInfo::default().polygon_mode(vk::PolygonMode::FILL).cull_mode(vk::CullModeFlags::NONE).line_width(1.0);
    let multisample = vk::PipelineMultisampleStateCreateInfo::default().rasterization_samples(multisample::flags(samples));
    let attachments = [attachment];
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
        .layout(layout);
    create_for_target(&device.raw, device.depth_format, info)
}
