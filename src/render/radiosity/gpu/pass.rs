//! A compute pass run outside the frame loop, dispatch after dispatch with the CPU waiting
//! for each (the precompute's form factors, the per-patch product): read-only storage buffers
//! and at most one 2D image (a BC1 matrix) uploaded once into device memory through staging
//! buffers, host-visible storage buffers the caller writes before a dispatch, one
//! host-visible storage buffer the dispatches write and the caller reads after each, push
//! constants, and one descriptor set (set 0, the tracer's set number, so that
//! `trace/bvh.glsl` binds as in the tracer), its layouts a [`PassLayout`]. On devices whose
//! timestamps time compute work ([`pass_times::supported`]: GPUs, not CPU devices), each
//! dispatch is timed.

use std::time::{Duration, Instant};

use ash::vk;
use gpu_allocator::MemoryLocation;

use crate::render::pass_layout::PassLayout;
use crate::render::pass_times::{self, SlotStamps};
use crate::render::raster::device::{Buffer, Check, Device, Image, Result};
use crate::render::trace::pipelines::compute_pipeline;

/// How long one dispatch took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DispatchTime {
    /// On the GPU (timestamps), where the device times compute work.
    pub gpu: Option<Duration>,
    /// On the CPU's clock: submission to the fence.
    pub wall: Duration,
}

/// A 2D image a pass samples: one level of `format` (block-compressed formats allowed).
pub struct ImageInput<'a> {
    /// Its binding (a combined image sampler, nearest filtering).
    pub binding: u32,
    /// Its format.
    pub format: vk::Format,
    /// Width and height in texels.
    pub size: [u32; 2],
    /// Its bytes, rows of texels (or blocks) tightly packed.
    pub bytes: &'a [u8],
}

/// What a pass reads and writes.
pub struct Inputs<'a> {
    /// Read-only storage buffers: binding and bytes.
    pub storage: Vec<(u32, &'a [u8])>,
    /// Storage buffers the caller writes before each dispatch ([`ComputePass::host_input`]):
    /// binding and bytes.
    pub host: Vec<(u32, u64)>,
    /// The image, if any.
    pub image: Option<ImageInput<'a>>,
    /// The output storage buffer: binding and bytes.
    pub output: (u32, u64),
    /// Bytes of the push constants.
    pub push_bytes: u32,
}

/// The pass's Vulkan objects.
pub struct ComputePass {
    buffers: Vec<Buffer>,
    host: Vec<Buffer>,
    image: Option<Image>,
    sampler: vk::Sampler,
    output: Buffer,
    /// Two timestamps around each dispatch, on devices that time compute work.
    timestamps: Option<SlotStamps>,
    layout: PassLayout,
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
            host: Vec::new(),
            image: None,
            sampler: vk::Sampler::null(),
            output,
            timestamps: None,
            layout: PassLayout { set: vk::DescriptorSetLayout::null(), pipeline: vk::PipelineLayout::null() },
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
        let bindings: Vec<u32> = inputs.storage.iter().map(|(b, _)| *b).chain(inputs.host.iter().map(|(b, _)| *b)).chain([inputs.output.0]).collect();
        let layout_bindings: Vec<_> = bindings
            .iter()
            .map(|&b| (b, vk::DescriptorType::STORAGE_BUFFER))
            .chain(inputs.image.as_ref().map(|i| (i.binding, vk::DescriptorType::COMBINED_IMAGE_SAMPLER)))
            .collect();
        self.layout = PassLayout::new(device, &layout_bindings, vk::ShaderStageFlags::COMPUTE, inputs.push_bytes)?;
        self.timestamps = SlotStamps::new(device, 2, 1)?;
        // Safety (this function): valid create infos of live objects; everything made is
        // recorded in `self`, whose `destroy` frees it after the GPU is done.
        unsafe {
            let set_layouts = [self.layout.set];
            self.pipeline = compute_pipeline(device, self.layout.pipeline, spirv)?;
            let sizes = [
                vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: bindings.len() as u32 },
                vk::DescriptorPoolSize { ty: vk::DescriptorType::COMBINED_IMAGE_SAMPLER, descriptor_count: 1 },
            ];
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
            if inputs.image.is_some() {
                let info = vk::SamplerCreateInfo::default()
                    .mag_filter(vk::Filter::NEAREST)
                    .min_filter(vk::Filter::NEAREST)
                    .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
                    .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
                    .unnormalized_coordinates(false);
                self.sampler = raw.create_sampler(&info, None).check("vkCreateSampler")?;
            }
        }
        for (_, bytes) in &inputs.host {
            self.host.push(device.create_buffer("radiosity host input", *bytes, vk::BufferUsageFlags::STORAGE_BUFFER, MemoryLocation::CpuToGpu)?);
        }
        self.upload(device, inputs)?;
        let infos: Vec<[vk::DescriptorBufferInfo; 1]> =
            self.buffers.iter().chain(&self.host).chain([&self.output]).map(|b| [vk::DescriptorBufferInfo::default().buffer(b.raw).range(vk::WHOLE_SIZE)]).collect();
        let image_info = self.image.as_ref().map(|i| [vk::DescriptorImageInfo { sampler: self.sampler, image_view: i.view, image_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL }]);
        let mut writes: Vec<_> = bindings
            .iter()
            .zip(&infos)
            .map(|(&binding, info)| vk::WriteDescriptorSet::default().dst_set(self.set).dst_binding(binding).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info))
            .collect();
        if let (Some(input), Some(info)) = (&inputs.image, &image_info) {
            writes.push(vk::WriteDescriptorSet::default().dst_set(self.set).dst_binding(input.binding).descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER).image_info(info));
        }
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
            if let Some(input) = &inputs.image {
                let info = vk::ImageCreateInfo::default()
                    .image_type(vk::ImageType::TYPE_2D)
                    .format(input.format)
                    .extent(vk::Extent3D { width: input.size[0], height: input.size[1], depth: 1 })
                    .mip_levels(1)
                    .array_layers(1)
                    .samples(vk::SampleCountFlags::TYPE_1)
                    .tiling(vk::ImageTiling::OPTIMAL)
                    .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST)
                    .initial_layout(vk::ImageLayout::UNDEFINED);
                self.image = Some(device.create_image("radiosity matrix", &info, vk::ImageViewType::TYPE_2D, vk::ImageAspectFlags::COLOR)?);
                let mut s = device.create_buffer("radiosity staging", input.bytes.len() as u64, vk::BufferUsageFlags::TRANSFER_SRC, MemoryLocation::CpuToGpu)?;
                s.mapped()[..input.bytes.len()].copy_from_slice(input.bytes);
                staging.push(s);
            }
            let image = self.image.as_ref().zip(inputs.image.as_ref()).map(|(i, input)| (i.raw, input.size));
            self.submit(device, |raw, cmd| {
                if let (Some((image, size)), Some(s)) = (image, staging.last()) {
                    record_image_upload(raw, cmd, s.raw, image, size);
                }
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

    /// The bytes of the `k`-th host input, for the next dispatch.
    pub fn host_input(&mut self, k: usize) -> &mut [u8] {
        self.host[k].mapped()
    }

    /// The GPU time of the last dispatch, on devices that time compute work.
    pub fn last_dispatch_time(&self, device: &Device) -> Option<Duration> {
        // Both queries were written by the last dispatch, which was waited for.
        let ticks = self.timestamps.as_ref()?.read(device, 0)?;
        Some(Duration::from_secs_f64(pass_times::seconds(device, ticks[0], ticks[1])))
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
        let (pipeline, layout, set) = (self.pipeline, self.layout.pipeline, self.set);
        let stamps = self.timestamps.as_ref().map(|t| t.frame(0));
        self.submit(device, |raw, cmd| {
            let barrier = [vk::MemoryBarrier::default().src_access_mask(vk::AccessFlags::SHADER_WRITE).dst_access_mask(vk::AccessFlags::HOST_READ)];
            // Safety: recording with live objects.
            unsafe {
                raw.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
                raw.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, layout, 0, &[set], &[]);
                raw.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::COMPUTE, 0, push);
                if let Some(stamps) = stamps {
                    stamps.write(device, cmd, 0, vk::PipelineStageFlags2::TOP_OF_PIPE);
                }
                raw.cmd_dispatch(cmd, groups[0], groups[1], groups[2]);
                if let Some(stamps) = stamps {
                    stamps.write(device, cmd, 1, vk::PipelineStageFlags2::COMPUTE_SHADER);
                }
                raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::PipelineStageFlags::HOST, vk::DependencyFlags::empty(), &barrier, &[], &[]);
            }
        })
    }

    /// One dispatch as [`ComputePass::run`] does, and how long it took.
    pub fn run_timed(&mut self, device: &Device, push: &[u8], groups: [u32; 3]) -> Result<DispatchTime> {
        let start = Instant::now();
        self.run(device, push, groups)?;
        let wall = start.elapsed();
        Ok(DispatchTime { gpu: self.last_dispatch_time(device), wall })
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
            device.raw.destroy_sampler(self.sampler, None);
            device.raw.destroy_command_pool(self.command_pool, None);
            device.raw.destroy_descriptor_pool(self.descriptor_pool, None);
            device.raw.destroy_pipeline(self.pipeline, None);
        }
        self.layout.destroy(device);
        if let Some(stamps) = self.timestamps {
            stamps.destroy(device);
        }
        for b in self.buffers.into_iter().chain(self.host) {
            device.destroy_buffer(b);
        }
        if let Some(image) = self.image {
            device.destroy_image(image);
        }
        device.destroy_buffer(self.output);
    }
}

/// Records the copy of `staging` into the whole of `image` (one level of `size`), with the
/// layout transitions around it: undefined, transfer destination, read by compute shaders.
fn record_image_upload(raw: &ash::Device, cmd: vk::CommandBuffer, staging: vk::Buffer, image: vk::Image, size: [u32; 2]) {
    let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 1 };
    let to_transfer = vk::ImageMemoryBarrier::default()
        .image(image)
        .subresource_range(range)
        .old_layout(vk::ImageLayout::UNDEFINED)
        .new_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
        .dst_access_mask(vk::AccessFlags::TRANSFER_WRITE);
    let to_read = vk::ImageMemoryBarrier::default()
        .image(image)
        .subresource_range(range)
        .old_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
        .new_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
        .src_access_mask(vk::AccessFlags::TRANSFER_WRITE)
        .dst_access_mask(vk::AccessFlags::SHADER_READ);
    let region = vk::BufferImageCopy::default()
        .image_subresource(vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 })
        .image_extent(vk::Extent3D { width: size[0], height: size[1], depth: 1 });
    // Safety: recording; the buffer holds the whole level and the image is alive.
    unsafe {
        raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::TOP_OF_PIPE, vk::PipelineStageFlags::TRANSFER, vk::DependencyFlags::empty(), &[], &[], &[to_transfer]);
        raw.cmd_copy_buffer_to_image(cmd, staging, image, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[region]);
        raw.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::TRANSFER, vk::PipelineStageFlags::COMPUTE_SHADER, vk::DependencyFlags::empty(), &[], &[], &[to_read]);
    }
}
