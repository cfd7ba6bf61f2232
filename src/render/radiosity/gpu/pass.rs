//! A compute pass run outside the frame loop, dispatch after dispatch with the CPU waiting
//! for each (the precompute's form factors): read-only storage buffers uploaded once into
//! device memory through staging buffers, one host-visible storage buffer the dispatches
//! write and the caller reads after each, push constants, and one descriptor set (set 0, the
//! tracer's set number, so that `trace/bvh.glsl` binds as in the tracer).

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::render::raster::device::{Buffer, Check, Device, Result};
use crate::render::trace::pipelines::compute_pipeline;

/// What a pass reads and writes.
pub struct Inputs<'a> {
    /// Read-only storage buffers: binding and bytes.
    pub storage: Vec<(u32, &'a [u8])>,
    /// The output storage buffer: binding and bytes.
    pub output: (u32, u64),
    /// Bytes of the push constants.
    pub push_bytes: u32,
}

/// The pass's Vulkan objects.
pub struct ComputePass {
    buffers: Vec<Buffer>,
    output: Buffer,
    set_layout: vk::DescriptorSetLayout,
    layout: vk::PipelineLayout,
    pipeline: vk::Pipeline,
    descriptor_pool: vk::DescriptorPool,
    set: vk::DescriptorSet,
    command_pool: vk::CommandPool,
    command: vk::CommandBuffer,
    fence: vk::Fence,
}

impl ComputePass {
    /// Creates the pass of the compute shader `spirv` over `inputs` and uploads them.
    pub fn new(device: &Device, spirv: &[u8], inputs: &Inputs) -> Result<ComputePass> {
        let output = device.create_buffer("radiosity output", inputs.output.1, vk::BufferUsageFlags::STORAGE_BUFFER, MemoryLocation::GpuToCpu)?;
        let mut pass = ComputePass {
            buffers: Vec::new(),
            output,
            set_layout: vk::DescriptorSetLayout::null(),
            layout: vk::PipelineLayout::null(),
            pipeline: vk::Pipeline::null(),
            descriptor_pool: vk::DescriptorPool::null(),
            set: vk::DescriptorSet::null(),
            command_pool: vk::CommandPool::null(),
            command: vk::CommandBuffer::null(),
            fence: vk::Fence::null(),
        };
        match pass.create(device, spirv, inputs) {
            Ok(()) => Ok(pass),
            Err(e) => {
                pass.destroy(device);
                Err(e)
            }
        }
    }

    /// Creates the objects and uploads the inputs (on failure, `destroy` frees what was made).
    fn create(&mut self, device: &Device, spirv: &[u8], inputs: &Inputs) -> Result<()> {
        let raw = &device.raw;
        let bindings: Vec<u32> = inputs.storage.iter().map(|(b, _)| *b).chain([inputs.output.0]).collect();
        let layout_bindings: Vec<_> = bindings
            .iter()
            .map(|&b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b)
                    .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        // Safety (this function): valid create infos of live objects; everything made is
        // recorded in `self`, whose `destroy` frees it after the GPU is done.
        unsafe {
            self.set_layout = raw.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings), None).check("vkCreateDescriptorSetLayout")?;
            let set_layouts = [self.set_layout];
            let push = [vk::PushConstantRange { stage_flags: vk::ShaderStageFlags::COMPUTE, offset: 0, size: inputs.push_bytes }];
            self.layout = raw
                .create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts).push_constant_ranges(&push), None)
                .check("vkCreatePipelineLayout")?;
            self.pipeline = compute_pipeline(device, self.layout, spirv)?;
            let sizes = [vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: bindings.len() as u32 }];
            self.descriptor_pool = raw.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(1).pool_sizes(&sizes), None).check("vkCreateDescriptorPool")?;
            self.set = raw
                .allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(self.descriptor_pool).set_layouts(&set_layouts))
                .check("vkAllocateDescriptorSets")?[0];
            self.command_pool = raw
                .create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(device.queue_family).flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER), None)
                .check("vkCreateCommandPool")?;
            self.command = raw
                .allocate_command_buffers(&vk::CommandBufferAllocateInfo::default().command_pool(self.command_pool).level(vk::CommandBufferLevel::PRIMARY).command_buffer_count(1))
                .check("vkAllocateCommandBuffers")?[0];
            self.fence = raw.create_fence(&vk::FenceCreateInfo::default(), None).check("vkCreateFence")?;
        }
        self.upload(device, inputs)?;
        let infos: Vec<[vk::DescriptorBufferInfo; 1]> =
            self.buffers.iter().chain([&self.output]).map(|b| [vk::DescriptorBufferInfo::default().buffer(b.raw).range(vk::WHOLE_SIZE)]).collect();
        let writes: Vec<_> = bindings
            .iter()
            .zip(&infos)
            .map(|(&binding, info)| vk::WriteDescriptorSet::default().dst_set(self.set).dst_binding(binding).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info))
            .collect();
        // Safety: the set and buffers are alive and no command uses the set yet.
        unsafe { raw.update_descriptor_sets(&writes, &[]) };
        Ok(())
    }

    /// Copies the inputs into device-local buffers through staging buffers, and waits.
    fn upload(&mut self, device: &Device, inputs: &Inputs) -> Result<()> {
        let mut staging = Vec::new();
        let result = (|| {
            for (_, bytes) in &inputs.storage {
                let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
                self.buffers.push(device.create_buffer("radiosity input", bytes.len() as u64, usage, MemoryLocation::GpuOnly)?);
                let mut s = device.create_buffer("radiosity staging", bytes.len() as u64, vk::BufferUsageFlags::TRANSFER_SRC, MemoryLocation::CpuToGpu)?;
                s.mapped()[..bytes.len()].copy_from_slice(bytes);
                staging.push(s);
            }
            self.submit(device, |raw, cmd| {
                for ((s, b), (_, bytes)) in staging.iter().zip(&self.buffers).zip(&inputs.storage) {
                    let region = [vk::BufferCopy { src_offset: 0, dst_offset: 0, size: bytes.len().max(4) as u64 }];
                    // Safety: both buffers are alive and large enough.
                    unsafe { raw.cmd_copy_buffer(cmd, s.raw, b.raw, &region) };
                }
                let barrier = [vk::MemoryBarrier::default().src_access_mask(vk::AccessFlags::TRANSFER_WRITE).dst_access_mask(vk::AccessFlags::SHADER_READ)];
                // Safety: recording.
                unsafe { raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::TRANSFER, vk::PipelineStageFlags::COMPUTE_SHADER, vk::DependencyFlags::empty(), &barrier, &[], &[]) };
            })
        })();
        for s in staging {
            device.destroy_buffer(s);
        }
        result
    }

    /// Records `record` into the command buffer, submits it and waits for it.
    fn submit(&self, device: &Device, record: impl FnOnce(&ash::Device, vk::CommandBuffer)) -> Result<()> {
        let raw = &device.raw;
        let commands = [self.command];
        // Safety: the command buffer is not in use (the last submission was waited for); the
        // fence is reset before reuse.
        unsafe {
            raw.begin_command_buffer(self.command, &vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT)).check("vkBeginCommandBuffer")?;
            record(raw, self.command);
            raw.end_command_buffer(self.command).check("vkEndCommandBuffer")?;
            raw.reset_fences(&[self.fence]).check("vkResetFences")?;
            raw.queue_submit(device.queue, &[vk::SubmitInfo::default().command_buffers(&commands)], self.fence).check("vkQueueSubmit")?;
            raw.wait_for_fences(&[self.fence], true, u64::MAX).check("vkWaitForFences")
        }
    }

    /// One dispatch of `groups` with the push constants `push`; waits for it.
    pub fn run(&mut self, device: &Device, push: &[u8], groups: [u32; 3]) -> Result<()> {
        let (pipeline, layout, set) = (self.pipeline, self.layout, self.set);
        self.submit(device, |raw, cmd| {
            let barrier = [vk::MemoryBarrier::default().src_access_mask(vk::AccessFlags::SHADER_WRITE).dst_access_mask(vk::AccessFlags::HOST_READ)];
            // Safety: recording with live objects.
            unsafe {
                raw.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
                raw.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, layout, 0, &[set], &[]);
                raw.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::COMPUTE, 0, push);
                raw.cmd_dispatch(cmd, groups[0], groups[1], groups[2]);
                raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::PipelineStageFlags::HOST, vk::DependencyFlags::empty(), &barrier, &[], &[]);
            }
        })
    }

    /// The output buffer's bytes as the last dispatch left them.
    pub fn output(&mut self) -> &[u8] {
        self.output.mapped()
    }

    /// Destroys everything (no submission is pending: each was waited for).
    pub fn destroy(self, device: &Device) {
        // Safety: the GPU is done with every object; null handles are ignored.
        unsafe {
            device.raw.destroy_fence(self.fence, None);
            device.raw.destroy_command_pool(self.command_pool, None);
            device.raw.destroy_descriptor_pool(self.descriptor_pool, None);
            device.raw.destroy_pipeline(self.pipeline, None);
            device.raw.destroy_pipeline_layout(self.layout, None);
            device.raw.destroy_descriptor_set_layout(self.set_layout, None);
        }
        for b in self.buffers {
            device.destroy_buffer(b);
        }
        device.destroy_buffer(self.output);
    }
}
