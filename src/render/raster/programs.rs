//! OpenGL 2.0 programs on the device: the layout of descriptor set 1 (the program's set of the
//! shader interface written in `translate::glsl`) and the shader modules of each
//! [`ShaderProgram`], created once per [`ShaderProgram::id`] and freed after
//! [`super::textures::KEEP_FRAMES`] presented frames without a draw using it (the pipelines
//! made with them go at the same time, see [`super::pipelines::Pipelines::end_frame`]).

use std::collections::HashMap;
use std::collections::hash_map::Entry;

use ash::vk;

use super::commands::SetKey;
use super::device::{Check, Device, Result};
use super::renderer::Recorder;
use super::textures::KEEP_FRAMES;
use crate::frame::program::{BUILTINS_BINDING, FIRST_SAMPLER_BINDING, MAX_SAMPLERS, ProgramDraw, ShaderProgram, UNIFORMS_BINDING};

/// Bindings of set 1: the built-in block, the uniform block and the sampler slots.
pub const BINDINGS: u32 = FIRST_SAMPLER_BINDING + MAX_SAMPLERS as u32;

/// The device side of one program.
pub struct ProgramModules {
    /// The vertex stage (`None`: the fixed-function one).
    pub vertex: Option<vk::ShaderModule>,
    /// The fragment stage (`None`: the fixed-function one).
    pub fragment: Option<vk::ShaderModule>,
    /// Generic attribute indices the vertex stage reads ([`super::ff::vertex::generic_indices`]).
    pub attributes: Vec<u32>,
    /// Presented-frame counter of the last draw that used it.
    used: u64,
}

/// The modules of the programs in use.
#[derive(Default)]
pub struct Programs {
    modules: HashMap<u64, ProgramModules>,
    /// Presented frames so far.
    frame: u64,
}

impl Programs {
    /// The modules of `program`, created on first use and marked used in this frame.
    pub fn get(&mut self, device: &Device, program: &ShaderProgram) -> Result<&ProgramModules> {
        let modules = match self.modules.entry(program.id) {
            Entry::Occupied(e) => e.into_mut(),
            Entry::Vacant(v) => v.insert(create(device, program)?),
        };
        modules.used = self.frame;
        Ok(modules)
    }

    /// The modules of the program `id`, if they exist.
    pub fn modules(&self, id: u64) -> Option<&ProgramModules> {
        self.modules.get(&id)
    }

    /// Counts a presented frame and frees the programs unused for [`KEEP_FRAMES`] frames
    /// (the GPU is done with them); returns their ids.
    pub fn end_frame(&mut self, device: &Device) -> Vec<u64> {
        self.frame += 1;
        let frame = self.frame;
        let old: Vec<u64> = self.modules.iter().filter(|(_, m)| m.used + KEEP_FRAMES < frame).map(|(&id, _)| id).collect();
        for id in &old {
            if let Some(m) = self.modules.remove(id) {
                destroy(device, &m);
            }
        }
        old
    }

    /// Programs on the device.
    pub fn len(&self) -> usize {
        self.modules.len()
    }

    /// Whether no program is on the device.
    pub fn is_empty(&self) -> bool {
        self.modules.is_empty()
    }

    /// Frees every module (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        for (_, m) in self.modules.drain() {
            destroy(device, &m);
        }
    }
}

/// Creates the layout of set 1: two dynamic storage buffers and [`MAX_SAMPLERS`] combined
/// image samplers, visible to both stages.
pub fn set_layout(device: &Device) -> Result<vk::DescriptorSetLayout> {
    let bindings: Vec<_> = (0..BINDINGS)
        .map(|b| {
            let buffer = b == BUILTINS_BINDING || b == UNIFORMS_BINDING;
            vk::DescriptorSetLayoutBinding::default()
                .binding(b)
                .descriptor_type(if buffer { vk::DescriptorType::STORAGE_BUFFER_DYNAMIC } else { vk::DescriptorType::COMBINED_IMAGE_SAMPLER })
                .descriptor_count(1)
                .stage_flags(vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT)
        })
        .collect();
    // Safety: valid create info on a live device; destroyed by the pipelines' `destroy`.
    unsafe { device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }
        .check("vkCreateDescriptorSetLayout")
}

/// Set 1 of a draw running `program`, with its dynamic offsets: the built-in and uniform
/// blocks uploaded to the frame's ring, the slot textures (uploaded beforehand with the
/// draw's) bound as [`super::textures::Textures::slot_bindings`] says. The program's modules
/// are made and marked used.
pub fn bind_set(rec: &mut Recorder<'_>, program: &ProgramDraw) -> Result<(vk::DescriptorSet, [u32; 2])> {
    rec.pipelines.use_program(rec.device, &program.program)?;
    let align = rec.device.properties.limits.min_storage_buffer_offset_alignment.max(16);
    // A buffer descriptor's range cannot be 0: an empty block is 16 zero bytes.
    let mut push = |bytes: &[u8]| {
        let padded: Vec<u8> = if bytes.is_empty() { vec![0; 16] } else { bytes.to_vec() };
        rec.ring.push(rec.device, &padded, align).map(|slice| (slice, padded.len() as u64))
    };
    let (builtins, builtins_size) = push(&program.builtins)?;
    let (uniforms, uniforms_size) = push(&program.uniforms)?;
    let images = rec.textures.slot_bindings(rec.device, &program.program.samplers, &program.textures)?;
    let key = SetKey {
        layout: rec.pipelines.program_set_layout,
        buffers: &[(builtins.buffer, builtins_size), (uniforms.buffer, uniforms_size)],
        images: &images,
    };
    let set = rec.descriptors.get(rec.device, &key)?;
    Ok((set, [builtins.offset as u32, uniforms.offset as u32]))
}

/// The modules of `program` (none made when one fails).
fn create(device: &Device, program: &ShaderProgram) -> Result<ProgramModules> {
    let vertex = program.vertex.as_deref().map(|code| module(device, code)).transpose()?;
    let fragment = match program.fragment.as_deref().map(|code| module(device, code)).transpose() {
        Ok(f) => f,
        Err(e) => {
            // Safety: the module was just created and never used.
            vertex.inspect(|&m| unsafe { device.raw.destroy_shader_module(m, None) });
            return Err(e);
        }
    };
    Ok(ProgramModules { vertex, fragment, attributes: super::ff::vertex::generic_indices(program), used: 0 })
}

fn module(device: &Device, code: &[u32]) -> Result<vk::ShaderModule> {
    // Safety: the SPIR-V comes from the GLSL translator's compiler (glslang).
    unsafe { device.raw.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(code), None) }.check("vkCreateShaderModule")
}

fn destroy(device: &Device, m: &ProgramModules) {
    for module in [m.vertex, m.fragment].into_iter().flatten() {
        // Safety: the GPU is done with every pipeline made from it (see `end_frame`).
        unsafe { device.raw.destroy_shader_module(module, None) };
    }
}
