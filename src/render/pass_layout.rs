//! The layouts of a pass whose shaders read one descriptor set and push constants: the set
//! layout of its bindings and the pipeline layout over it, made and destroyed together (the
//! ambient occlusion's passes, `radiosity::gpu::pass`).

use ash::vk;

use crate::render::raster::device::{Check, Device, Result};

/// A descriptor set layout and the pipeline layout of that one set and the push constants.
#[derive(Clone, Copy, Debug)]
pub struct PassLayout {
    /// The layout of set 0.
    pub set: vk::DescriptorSetLayout,
    /// The pipeline layout.
    pub pipeline: vk::PipelineLayout,
}

impl PassLayout {
    /// The layouts of `bindings` (binding number, descriptor type; one descriptor each) and
    /// `push` bytes of push constants (none when 0), all visible to `stage`.
    pub fn new(device: &Device, bindings: &[(u32, vk::DescriptorType)], stage: vk::ShaderStageFlags, push: u32) -> Result<PassLayout> {
        let bindings: Vec<_> = bindings.iter().map(|&(b, ty)| vk::DescriptorSetLayoutBinding::default().binding(b).descriptor_type(ty).descriptor_count(1).stage_flags(stage)).collect();
        // Safety: valid create info; destroyed in `destroy`.
        let set = unsafe { device.raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }.check("vkCreateDescriptorSetLayout")?;
        let sets = [set];
        let ranges = [vk::PushConstantRange { stage_flags: stage, offset: 0, size: push }];
        let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&sets).push_constant_ranges(if push > 0 { &ranges[..] } else { &[] });
        // Safety: valid create info; destroyed in `destroy` (the set layout here on failure).
        match unsafe { device.raw.create_pipeline_layout(&info, None) }.check("vkCreatePipelineLayout") {
            Ok(pipeline) => Ok(PassLayout { set, pipeline }),
            Err(e) => {
                // Safety: nothing uses the set layout yet.
                unsafe { device.raw.destroy_descriptor_set_layout(set, None) };
                Err(e)
            }
        }
    }

    /// `count` dynamic storage buffers at bindings 0, 1, …: the bindings of a pass whose
    /// buffers the frame's descriptor sets hold.
    pub fn dynamic_storage(count: u32) -> Vec<(u32, vk::DescriptorType)> {
        (0..count).map(|b| (b, vk::DescriptorType::STORAGE_BUFFER_DYNAMIC)).collect()
    }

    /// Destroys both layouts (no pipeline or command may use them any more).
    pub fn destroy(&self, device: &Device) {
        // Safety: see above; null handles are ignored.
        unsafe {
            device.raw.destroy_pipeline_layout(self.pipeline, None);
            device.raw.destroy_descriptor_set_layout(self.set, None);
        }
    }
}
