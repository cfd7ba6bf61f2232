//! Graphics pipelines, created once per [`PipelineKey`] and cached: the stages (the
//! fixed-function shaders, or an OpenGL 2.0 program's in their place, see [`super::programs`]),
//! the shader specialisation ([`ff::ShaderKey`]), the topology, the polygon mode, and the part of the
//! raster state Vulkan bakes into a pipeline (blend factors and equation, logic op, depth
//! test/function/write, stencil functions and operations, colour mask, culling and front face,
//! whether polygon offset applies, and the multisample state: sample count, sample mask,
//! alpha to coverage and to one, see [`super::multisample`]).
//!
//! Dynamic state (set per draw by [`super::renderer`]): viewport, scissor, line width, depth
//! bias, blend constants, stencil reference and compare/write masks.
//!
//! Conventions:
//! - **y flip**: the viewport has a negative height (Vulkan 1.1 core), so GL window
//!   coordinates (y up) land in images whose row 0 is the top of the window (see
//!   [`super::target`]). Vulkan's winding is defined as seen on screen (its area formula
//!   carries a minus sign for the downward y), and the flipped viewport shows the image as GL
//!   does, so GL's windings map unchanged ([`front_face`]; `tests/raster/draws.rs` checks it).
//! - **depth**: `ff.vert` maps GL clip depth [-w, w] to Vulkan's [0, w]; the viewport's
//!   depth range is GL's `glDepthRange`.
//! - **logic op**: used when the device has `logicOp` (lavapipe and NVIDIA do); otherwise the
//!   draw is drawn without it and a warning is logged once.
//! - Polygon offset applies to triangle batches as [`ff::Batch::polygon_offset`] says.
//! - **Programs**: one pipeline layout serves every pipeline: set 0 the fixed-function set,
//!   set 1 the programs' ([`super::programs::set_layout`]). A program's vertex stage adds
//!   vertex binding 1, the generic attributes it reads ([`ff::vertex::pack_generic`]) at the
//!   locations of the `translate::glsl` contract; its pipelines draw points and lines with
//!   Vulkan's topologies and polygon modes (`fillModeNonSolid`, see [`ff::native`]).
//!
//! The cache is bounded: past [`CACHED_PIPELINES`] pipelines, those no draw used in the last
//! [`IDLE_SUBMISSIONS`] submissions are destroyed at the next submission (a pipeline costs
//! megabytes on lavapipe, and a program that changes its blend state for every draw, such as
//! piglit's `gl-1.0-blend-func`, would otherwise keep one per state it ever used). Pipelines
//! in use every frame are never evicted, whatever their number.

use std::collections::{HashMap, HashSet};

use ash::vk;

use super::conv;
use super::device::{Check, Device, Error, Result};
use super::ff;
use super::ff::shader_interface::{BINDING_COUNT, BINDING_SAMPLER_2D, BINDING_SAMPLER_3D, BINDING_SAMPLER_CUBE, BINDING_UNIFORMS};
use crate::render::texenv::codes::MAX_UNITS;
use super::multisample::{self, SampleState};
use super::programs::{self, Programs};
use super::target::COLOR_FORMAT;
use crate::frame::program::{GENERIC_ATTRIBUTE_LOCATION, ShaderProgram};
use crate::frame::state::{Face, RasterState, Stencil, StencilFaces, Winding};

/// Pipelines the cache keeps before it evicts idle ones.
pub const CACHED_PIPELINES: usize = 16;

/// Submissions without use after which a pipeline is idle: more than the submissions in flight
/// ([`super::renderer::FRAMES_IN_FLIGHT`]), so the GPU is done with an idle pipeline.
pub const IDLE_SUBMISSIONS: u64 = 8;

// Set 0 (see the `ff` module doc): the uniform block, then the 2D, 3D and cube samplers of
// each unit, [`BINDING_COUNT`] in all; the descriptor code relies on that order.
const _: () = assert!(
    BINDING_UNIFORMS == 0
        && BINDING_SAMPLER_2D == 1
        && BINDING_SAMPLER_3D == BINDING_SAMPLER_2D + MAX_UNITS as u32
        && BINDING_SAMPLER_CUBE == BINDING_SAMPLER_3D + MAX_UNITS as u32
        && BINDING_COUNT == BINDING_SAMPLER_CUBE + MAX_UNITS as u32
);

/// Binding of the 2D/3D/cube sampler of unit `unit`.
pub fn sampler_binding(kind: SamplerKind, unit: usize) -> u32 {
    let first = match kind {
        SamplerKind::D2 => BINDING_SAMPLER_2D,
        SamplerKind::D3 => BINDING_SAMPLER_3D,
        SamplerKind::Cube => BINDING_SAMPLER_CUBE,
    };
    first + unit as u32
}

/// The sampler types of the texture bindings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SamplerKind {
    /// `sampler2D` (2D and 1D textures).
    D2 = 0,
    /// `sampler3D`.
    D3 = 1,
    /// `samplerCube`.
    Cube = 2,
}

/// What selects a pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PipelineKey {
    /// Shader specialisation.
    pub shader: ff::ShaderKey,
    /// Primitive topology.
    pub topology: vk::PrimitiveTopology,
    /// Polygon mode (`FILL` but for triangles a program's vertex stage draws as lines or
    /// points).
    pub polygon_mode: vk::PolygonMode,
    /// The program whose stages replace the fixed-function ones ([`ShaderProgram::id`]).
    pub program: Option<u64>,
    /// Fixed per-fragment state.
    pub fixed: FixedState,
    /// How the vertices are laid out (the vertex input state).
    pub vertex_format: ff::VertexFormat,
}

/// The raster state baked into a pipeline, as Vulkan values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FixedState {
    /// Factors (src rgb, dst rgb, src alpha, dst alpha) and operations (rgb, alpha), when
    /// blending.
    pub blend: Option<([vk::BlendFactor; 4], [vk::BlendOp; 2])>,
    /// Logic operation, when enabled and supported.
    pub logic_op: Option<vk::LogicOp>,
    /// Depth comparison, when the depth test is on.
    pub depth_test: Option<vk::CompareOp>,
    /// Depth writes (only with the depth test on, section 4.1.6).
    pub depth_write: bool,
    /// Stencil comparison and fail, depth-fail, pass operations of the rasterizer's front and
    /// back faces, when the test is on.
    pub stencil: Option<[[i32; 4]; 2]>,
    /// Colour write mask.
    pub color_mask: vk::ColorComponentFlags,
    /// Culled faces.
    pub cull: vk::CullModeFlags,
    /// Front-face winding in framebuffer coordinates.
    pub front_face: vk::FrontFace,
    /// Depth bias on.
    pub depth_bias: bool,
    /// Samples, sample mask and alpha-to-coverage/one ([`SampleState::SINGLE`] from
    /// [`FixedState::new`]; the renderer sets the pass's).
    pub samples: SampleState,
}

/// GL front-face winding as Vulkan sees it through the y-flipped viewport (the same).
pub fn front_face(w: Winding) -> vk::FrontFace {
    match w {
        Winding::Ccw => vk::FrontFace::COUNTER_CLOCKWISE,
        Winding::Cw => vk::FrontFace::CLOCKWISE,
    }
}

impl FixedState {
    /// The fixed state of `state` for a batch whose rasterizer culls `cull`, applies the
    /// polygon offset as depth bias when `depth_bias` and tests `stencil`
    /// ([`super::ff::Batch::cull`], [`super::ff::Batch::polygon_offset`] and
    /// [`super::ff::Batch::stencil`]: the CPU already culled or expanded the rest);
    /// `logic_op_supported` says whether the device has the `logicOp` feature.
    pub fn new(state: &RasterState, cull: Option<Face>, depth_bias: bool, stencil: Option<StencilFaces>, logic_op_supported: bool) -> FixedState {
        let blend = state.blend.map(|b| {
            let factors = [b.src_rgb, b.dst_rgb, b.src_alpha, b.dst_alpha].map(conv::blend_factor);
            (factors, [b.equation_rgb, b.equation_alpha].map(conv::blend_op))
        });
        let logic_op = state.logic_op.filter(|_| logic_op_supported).map(conv::logic_op);
        let face = |s: Stencil| {
            [conv::compare(s.func).as_raw(), conv::stencil_op(s.fail).as_raw(), conv::stencil_op(s.depth_fail).as_raw(), conv::stencil_op(s.depth_pass).as_raw()]
        };
        let stencil = stencil.map(|s| [face(s.front), face(s.back)]);
        let mut color_mask = vk::ColorComponentFlags::empty();
        for (on, bit) in state.color_mask.iter().zip([
            vk::ColorComponentFlags::R,
            vk::ColorComponentFlags::G,
            vk::ColorComponentFlags::B,
            vk::ColorComponentFlags::A,
        ]) {
            if *on {
                color_mask |= bit;
            }
        }
        let cull = match cull {
            Some(Face::Front) => vk::CullModeFlags::FRONT,
            Some(Face::Back) => vk::CullModeFlags::BACK,
            Some(Face::FrontAndBack) => vk::CullModeFlags::FRONT_AND_BACK,
            None => vk::CullModeFlags::NONE,
        };
        FixedState {
            blend,
            logic_op,
            depth_test: state.depth_test.map(conv::compare),
            depth_write: state.depth_test.is_some() && state.depth_write,
            stencil,
            color_mask,
            cull,
            front_face: front_face(state.front_face),
            depth_bias,
            samples: SampleState::SINGLE,
        }
    }
}

/// The descriptor layouts, pipeline layout, shader modules and the pipeline cache.
pub struct Pipelines {
    /// Layout of descriptor set 0.
    pub set_layout: vk::DescriptorSetLayout,
    /// Layout of descriptor set 1 (programs).
    pub program_set_layout: vk::DescriptorSetLayout,
    /// The pipeline layout.
    pub layout: vk::PipelineLayout,
    /// The fixed-function stages (vertex, fragment) with every varying.
    full: [vk::ShaderModule; 2],
    /// The fixed-function stages of lean keys ([`ff::ShaderKey::lean`]).
    lean: [vk::ShaderModule; 2],
    programs: Programs,
    depth_format: vk::Format,
    /// Each pipeline with the submission that last used it.
    cache: HashMap<PipelineKey, (vk::Pipeline, u64)>,
    /// Submissions so far ([`Pipelines::end_submission`]).
    submissions: u64,
    /// Keys whose pipeline the driver could not create: their draws are skipped.
    failed: HashSet<PipelineKey>,
}

impl Pipelines {
    /// Creates the layouts and shader modules.
    pub fn new(device: &Device) -> Result<Pipelines> {
        let d = &device.raw;
        let bindings: Vec<_> = (0..BINDING_COUNT)
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b)
                    .descriptor_type(if b == 0 {
                        vk::DescriptorType::STORAGE_BUFFER_DYNAMIC
                    } else {
                        vk::DescriptorType::COMBINED_IMAGE_SAMPLER
                    })
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT)
            })
            .collect();
        // Safety (this block): valid create infos on a live device; objects destroyed in `destroy`.
        unsafe {
            let set_layout = d
                .create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None)
                .check("vkCreateDescriptorSetLayout")?;
            let program_set_layout = programs::set_layout(device)?;
            let sets = [set_layout, program_set_layout];
            let layout = d
                .create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&sets), None)
                .check("vkCreatePipelineLayout")?;
            let full = [shader_module(device, ff::vertex_spirv(false))?, shader_module(device, ff::fragment_spirv(false))?];
            let lean = [shader_module(device, ff::vertex_spirv(true))?, shader_module(device, ff::fragment_spirv(true))?];
            Ok(Pipelines {
                set_layout,
                program_set_layout,
                layout,
                full,
                lean,
                programs: Programs::default(),
                depth_format: device.depth_format,
                cache: HashMap::new(),
                submissions: 0,
                failed: HashSet::new(),
            })
        }
    }

    /// Makes the shader modules of `program` (once per program) and marks them used in this
    /// frame; pipelines of keys naming it can then be made.
    pub fn use_program(&mut self, device: &Device, program: &ShaderProgram) -> Result<()> {
        self.programs.get(device, program).map(|_| ())
    }

    /// Counts a presented frame: programs unused for [`super::textures::KEEP_FRAMES`] frames
    /// are freed with their pipelines.
    pub fn end_frame(&mut self, device: &Device) {
        let dead = self.programs.end_frame(device);
        if dead.is_empty() {
            return;
        }
        self.cache.retain(|key, &mut (p, _)| {
            let keep = key.program.is_none_or(|id| !dead.contains(&id));
            if !keep {
                // Safety: the GPU is done with it (unused for more frames than are in flight).
                unsafe { device.raw.destroy_pipeline(p, None) };
            }
            keep
        });
    }

    /// Programs whose shader modules are on the device.
    pub fn program_count(&self) -> usize {
        self.programs.len()
    }

    /// The pipeline of `key`, created on first use (a key naming a program needs
    /// [`Pipelines::use_program`] first). `None` when the driver cannot create it (a shader it
    /// fails to compile, no memory for it): the draws of that key are skipped, which is said
    /// once, and the key is not tried again. A lost device is an error.
    pub fn get(&mut self, device: &Device, key: &PipelineKey) -> Result<Option<vk::Pipeline>> {
        if let Some((p, used)) = self.cache.get_mut(key) {
            *used = self.submissions;
            return Ok(Some(*p));
        }
        if self.failed.contains(key) {
            return Ok(None);
        }
        match self.create(device, key) {
            Ok(pipeline) => {
                self.cache.insert(*key, (pipeline, self.submissions));
                log::debug!("raster pipeline {} created: {key:?}", self.cache.len());
                Ok(Some(pipeline))
            }
            Err(e @ Error::Vulkan(_, vk::Result::ERROR_DEVICE_LOST)) => Err(e),
            Err(e) => {
                if self.failed.is_empty() {
                    eprintln!("glrt: a raster pipeline cannot be created ({e}); the draws that need it are not drawn");
                }
                log::debug!("raster pipeline failed: {key:?}");
                self.failed.insert(*key);
                Ok(None)
            }
        }
    }

    /// Counts a submission of the commands recorded so far; past [`CACHED_PIPELINES`]
    /// pipelines, destroys those idle for [`IDLE_SUBMISSIONS`] submissions (see the module
    /// doc).
    pub fn end_submission(&mut self, device: &Device) {
        self.submissions += 1;
        if self.cache.len() <= CACHED_PIPELINES {
            return;
        }
        let now = self.submissions;
        self.cache.retain(|_, &mut (p, used)| {
            let keep = used + IDLE_SUBMISSIONS > now;
            if !keep {
                // Safety: no submission the GPU may still run used it (see IDLE_SUBMISSIONS).
                unsafe { device.raw.destroy_pipeline(p, None) };
            }
            keep
        });
    }

    /// Pipelines created so far.
    pub fn len(&self) -> usize {
        self.cache.len()
    }

    /// Whether no pipeline was created yet.
    pub fn is_empty(&self) -> bool {
        self.cache.is_empty()
    }

    fn create(&self, device: &Device, key: &PipelineKey) -> Result<vk::Pipeline> {
        let words = key.shader.words;
        let entries: Vec<_> = (0..words.len() as u32)
            .map(|i| vk::SpecializationMapEntry { constant_id: i, offset: 4 * i, size: 4 })
            .collect();
        let data = super::upload::bytemuck_free::bytes(&words);
        let spec = vk::SpecializationInfo::default().map_entries(&entries).data(data);
        let program = match key.program {
            Some(id) => Some(self.programs.modules(id).ok_or_else(|| Error::Memory(format!("program {id} has no shader modules")))?),
            None => None,
        };
        // A program's stages pair with the full fixed-function ones, whose varyings its
        // generated code writes and reads.
        let [ff_vertex, ff_fragment] = if program.is_none() && key.shader.lean() { self.lean } else { self.full };
        let vertex = program.and_then(|p| p.vertex).unwrap_or(ff_vertex);
        let fragment = program.and_then(|p| p.fragment).unwrap_or(ff_fragment);
        let stages = [
            vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::VERTEX).module(vertex).name(c"main").specialization_info(&spec),
            vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::FRAGMENT).module(fragment).name(c"main").specialization_info(&spec),
        ];
        let format = key.vertex_format;
        let mut vertex_bindings: Vec<_> = format
            .bindings()
            .into_iter()
            .map(|(binding, stride)| vk::VertexInputBindingDescription { binding, stride, input_rate: vk::VertexInputRate::VERTEX })
            .collect();
        let mut attributes: Vec<_> = format
            .attributes()
            .iter()
            .map(|a| vk::VertexInputAttributeDescription {
                location: a.location,
                binding: a.binding,
                format: match a.format {
                    ff::compact::InputFormat::Float(n) => {
                        [vk::Format::R32_SFLOAT, vk::Format::R32G32_SFLOAT, vk::Format::R32G32B32_SFLOAT, vk::Format::R32G32B32A32_SFLOAT][(n.clamp(1, 4) - 1) as usize]
                    }
                    ff::compact::InputFormat::Unorm8x4 => vk::Format::R8G8B8A8_UNORM,
                },
                offset: a.offset,
            })
            .collect();
        // Generic attributes of a program's vertex stage: vec4s at binding 1, in the order of
        // its attribute list.
        let generic = program.filter(|p| p.vertex.is_some()).map_or(&[][..], |p| &p.attributes[..]);
        if !generic.is_empty() {
            vertex_bindings.push(vk::VertexInputBindingDescription { binding: 1, stride: 16 * generic.len() as u32, input_rate: vk::VertexInputRate::VERTEX });
            attributes.extend(generic.iter().enumerate().map(|(k, &index)| vk::VertexInputAttributeDescription {
                location: GENERIC_ATTRIBUTE_LOCATION + index - 1,
                binding: 1,
                format: vk::Format::R32G32B32A32_SFLOAT,
                offset: 16 * k as u32,
            }));
        }
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&vertex_bindings)
            .vertex_attribute_descriptions(&attributes);
        let assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(key.topology);
        let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
        let f = &key.fixed;
        let raster = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(key.polygon_mode)
            .cull_mode(f.cull)
            .front_face(f.front_face)
            .depth_bias_enable(f.depth_bias)
            .line_width(1.0);
        let sample_mask = [f.samples.mask];
        let multisample = vk::PipelineMultisampleStateCreateInfo::default()
            .rasterization_samples(multisample::flags(f.samples.samples))
            .sample_mask(&sample_mask)
            .alpha_to_coverage_enable(f.samples.alpha_to_coverage)
            .alpha_to_one_enable(f.samples.alpha_to_one);
        let stencil_face = |s: [i32; 4]| vk::StencilOpState {
            fail_op: vk::StencilOp::from_raw(s[1]),
            pass_op: vk::StencilOp::from_raw(s[3]),
            depth_fail_op: vk::StencilOp::from_raw(s[2]),
            compare_op: vk::CompareOp::from_raw(s[0]),
            ..Default::default()
        };
        let [front, back] = f.stencil.map_or([vk::StencilOpState::default(); 2], |s| s.map(stencil_face));
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(f.depth_test.is_some())
            .depth_write_enable(f.depth_write)
            .depth_compare_op(f.depth_test.unwrap_or(vk::CompareOp::ALWAYS))
            .stencil_test_enable(f.stencil.is_some())
            .front(front)
            .back(back);
        let (blend_on, [src, dst, src_a, dst_a], [op, op_a]) = match f.blend {
            Some((factors, ops)) => (true, factors, ops),
            None => (false, [vk::BlendFactor::ONE, vk::BlendFactor::ZERO, vk::BlendFactor::ONE, vk::BlendFactor::ZERO], [vk::BlendOp::ADD; 2]),
        };
        let attachments = [vk::PipelineColorBlendAttachmentState {
            blend_enable: blend_on.into(),
            src_color_blend_factor: src,
            dst_color_blend_factor: dst,
            color_blend_op: op,
            src_alpha_blend_factor: src_a,
            dst_alpha_blend_factor: dst_a,
            alpha_blend_op: op_a,
            color_write_mask: f.color_mask,
        }];
        let blend = vk::PipelineColorBlendStateCreateInfo::default()
            .logic_op_enable(f.logic_op.is_some())
            .logic_op(f.logic_op.unwrap_or(vk::LogicOp::COPY))
            .attachments(&attachments);
        let dynamic_states = [
            vk::DynamicState::VIEWPORT,
            vk::DynamicState::SCISSOR,
            vk::DynamicState::LINE_WIDTH,
            vk::DynamicState::DEPTH_BIAS,
            vk::DynamicState::BLEND_CONSTANTS,
            vk::DynamicState::STENCIL_COMPARE_MASK,
            vk::DynamicState::STENCIL_WRITE_MASK,
            vk::DynamicState::STENCIL_REFERENCE,
        ];
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
            .layout(self.layout);
        create_for_target(&device.raw, self.depth_format, info)
    }

    /// Destroys every pipeline and layout (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        // Safety: the GPU is done with them; each is destroyed once.
        unsafe {
            for (_, (p, _)) in self.cache.drain() {
                device.raw.destroy_pipeline(p, None);
            }
            self.programs.destroy(device);
            for module in self.full.into_iter().chain(self.lean) {
                device.raw.destroy_shader_module(module, None);
            }
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
            device.raw.destroy_descriptor_set_layout(self.program_set_layout, None);
        }
    }
}

pub(crate) fn shader_module(device: &Device, spirv: &[u8]) -> Result<vk::ShaderModule> {
    let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    // Safety: the SPIR-V was produced by the build's shader compiler.
    unsafe { device.raw.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&words), None) }.check("vkCreateShaderModule")
}

/// Creates a graphics pipeline drawing into the raster target (dynamic rendering: the RGBA8
/// colour image and a depth/stencil image of `depth_format`) from `info`, whose states and
/// layout are set.
pub(crate) fn create_for_target(device: &ash::Device, depth_format: vk::Format, info: vk::GraphicsPipelineCreateInfo) -> Result<vk::Pipeline> {
    let color_formats = [COLOR_FORMAT];
    let mut rendering = vk::PipelineRenderingCreateInfo::default()
        .color_attachment_formats(&color_formats)
        .depth_attachment_format(depth_format)
        .stencil_attachment_format(depth_format);
    let info = info.push_next(&mut rendering);
    if crate::faults::fires(crate::faults::Fault::ShaderCompile) {
        return Err(Error::Vulkan("vkCreateGraphicsPipelines", vk::Result::ERROR_INVALID_SHADER_NV));
    }
    // Safety: every object `info` refers to is alive (the caller's states); the formats are the
    // target's.
    match unsafe { device.create_graphics_pipelines(vk::PipelineCache::null(), &[info], None) } {
        Ok(p) => Ok(p[0]),
        Err((_, r)) => Err(Error::Vulkan("vkCreateGraphicsPipelines", r)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::state::{Blend, BlendEquation, BlendFactor};

    #[test]
    fn fixed_state_follows_gl_rules() {
        let mut state = RasterState { depth_write: true, ..RasterState::default() };
        assert!(!FixedState::new(&state, None, false, None, true).depth_write, "no depth writes without the test");
        state.depth_test = Some(crate::frame::state::CompareFunc::Less);
        let f = FixedState::new(&state, None, false, None, true);
        assert!(f.depth_write);
        assert_eq!(f.depth_test, Some(vk::CompareOp::LESS));
        assert_eq!(FixedState::new(&state, Some(Face::Back), false, None, true).cull, vk::CullModeFlags::BACK);
        assert_eq!(FixedState::new(&state, None, false, None, true).cull, vk::CullModeFlags::NONE);
        assert!(FixedState::new(&state, None, true, None, true).depth_bias);
        state.blend = Some(Blend {
            src_rgb: BlendFactor::SrcAlpha,
            dst_rgb: BlendFactor::OneMinusSrcAlpha,
            equation_alpha: BlendEquation::Max,
            ..Blend::default()
        });
        let (factors, ops) = FixedState::new(&state, None, false, None, true).blend.unwrap();
        assert_eq!(factors[..2], [vk::BlendFactor::SRC_ALPHA, vk::BlendFactor::ONE_MINUS_SRC_ALPHA]);
        assert_eq!(ops, [vk::BlendOp::ADD, vk::BlendOp::MAX]);
        state.logic_op = Some(crate::frame::state::LogicOp::Xor);
        assert_eq!(FixedState::new(&state, None, false, None, true).logic_op, Some(vk::LogicOp::XOR));
        assert_eq!(FixedState::new(&state, None, false, None, false).logic_op, None);
    }

    #[test]
    fn sampler_bindings_follow_the_ff_contract() {
        assert_eq!(sampler_binding(SamplerKind::D2, 0), 1);
        assert_eq!(sampler_binding(SamplerKind::D3, 1), 6);
        assert_eq!(sampler_binding(SamplerKind::Cube, 3), 12);
        assert_eq!(BINDING_COUNT, 13);
    }
}
