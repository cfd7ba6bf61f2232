//! Compute probes: a test shader (`tests/shaders/*.comp`, compiled here with
//! `glslangValidator` against `shaders/` and the generated headers) run once over storage
//! buffers on the test's device, so GLSL shared with the renderer is tested on its own.

use std::path::Path;
use std::process::Command;

use ash::vk;
use gpu_allocator::MemoryLocation;

use glrt::render::raster::device::{Buffer, Device};

/// Compiles the compute shader at `path` (relative to the crate root) to SPIR-V words.
pub fn compile(path: &str) -> Vec<u32> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let name = Path::new(path).file_stem().and_then(|s| s.to_str()).unwrap_or("probe");
    let out = std::env::temp_dir().join(format!("glrt-{name}-{}.spv", std::process::id()));
    let status = Command::new("glslangValidator")
        .args(["-V", "--target-env", "vulkan1.1"])
        .arg(format!("-I{}", root.join("shaders").display()))
        .arg(concat!("-I", env!("OUT_DIR"), "/glsl"))
        .arg(root.join(path))
        .arg("-o")
        .arg(&out)
        .output()
        .expect("glslangValidator runs");
    assert!(status.status.success(), "{path}: {}", String::from_utf8_lossy(&status.stdout));
    let bytes = std::fs::read(&out).expect("the SPIR-V file");
    let _ = std::fs::remove_file(&out);
    ash::util::read_spv(&mut std::io::Cursor::new(bytes)).expect("SPIR-V words")
}

/// Storage buffers and the probe pipeline; everything created is destroyed by `finish`.
pub struct Probe {
    device: Device,
    buffers: Vec<Buffer>,
}

impl Probe {
    /// A probe on `device`, with no buffers yet.
    pub fn new(device: Device) -> Probe {
        Probe { device, buffers: Vec::new() }
    }

    /// A host-visible storage buffer holding `bytes` (at least 16 bytes).
    pub fn buffer(&mut self, bytes: &[u8], location: MemoryLocation) -> usize {
        let size = bytes.len().max(16) as u64;
        let mut b = self.device.create_buffer("probe", size, vk::BufferUsageFlags::STORAGE_BUFFER, location).expect("a buffer");
        b.mapped()[..bytes.len()].copy_from_slice(bytes);
        self.buffers.push(b);
        self.buffers.len() - 1
    }

    /// Runs the probe over `queries` with `bound` buffers at (binding, buffer index); returns
    /// the results buffer's bytes.
    pub fn run(&mut self, spirv: &[u32], bound: &[(u32, usize)], queries: usize) -> Vec<u8> {
        let d = &self.device.raw;
        let stage = vk::ShaderStageFlags::COMPUTE;
        let layout_bindings: Vec<_> = bound.iter().map(|&(b, _)| vk::DescriptorSetLayoutBinding::default().binding(b).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).descriptor_count(1).stage_flags(stage)).collect();
        // Safety: valid create infos; every object is destroyed below after the queue is idle.
        unsafe {
            let set_layout = d.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings), None).unwrap();
            let sizes = [vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: bound.len() as u32 }];
            let pool = d.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(1).pool_sizes(&sizes), None).unwrap();
            let set = d.allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&[set_layout])).unwrap()[0];
            let infos: Vec<_> = bound.iter().map(|&(_, i)| [vk::DescriptorBufferInfo { buffer: self.buffers[i].raw, offset: 0, range: vk::WHOLE_SIZE }]).collect();
            let writes: Vec<_> = bound.iter().zip(&infos).map(|(&(b, _), info)| vk::WriteDescriptorSet::default().dst_set(set).dst_binding(b).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info)).collect();
            d.update_descriptor_sets(&writes, &[]);
            let pipeline_layout = d.create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&[set_layout]), None).unwrap();
            let module = d.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(spirv), None).unwrap();
            let stage_info = vk::PipelineShaderStageCreateInfo::default().stage(stage).module(module).name(c"main");
            let pipeline = d.create_compute_pipelines(vk::PipelineCache::null(), &[vk::ComputePipelineCreateInfo::default().stage(stage_info).layout(pipeline_layout)], None).map_err(|(_, e)| e).unwrap()[0];
            let command_pool = d.create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(self.device.queue_family), None).unwrap();
            let cmd = d.allocate_command_buffers(&vk::CommandBufferAllocateInfo::default().command_pool(command_pool).command_buffer_count(1)).unwrap()[0];
            d.begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default()).unwrap();
            d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
            d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, pipeline_layout, 0, &[set], &[]);
            d.cmd_dispatch(cmd, queries.div_ceil(64) as u32, 1, 1);
            let barrier = [vk::MemoryBarrier::default().src_access_mask(vk::AccessFlags::SHADER_WRITE).dst_access_mask(vk::AccessFlags::HOST_READ)];
            d.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::PipelineStageFlags::HOST, vk::DependencyFlags::empty(), &barrier, &[], &[]);
            d.end_command_buffer(cmd).unwrap();
            let fence = d.create_fence(&vk::FenceCreateInfo::default(), None).unwrap();
            d.queue_submit(self.device.queue, &[vk::SubmitInfo::default().command_buffers(&[cmd])], fence).unwrap();
            d.wait_for_fences(&[fence], true, u64::MAX).unwrap();
            d.destroy_fence(fence, None);
            d.destroy_command_pool(command_pool, None);
            d.destroy_pipeline(pipeline, None);
            d.destroy_shader_module(module, None);
            d.destroy_pipeline_layout(pipeline_layout, None);
            d.destroy_descriptor_pool(pool, None);
            d.destroy_descriptor_set_layout(set_layout, None);
        }
        let results = bound.last().map(|&(_, i)| i).expect("a results buffer");
        self.buffers[results].mapped().to_vec()
    }

    /// Frees the buffers.
    pub fn finish(self) {
        for b in self.buffers {
            self.device.destroy_buffer(b);
        }
    }
}
