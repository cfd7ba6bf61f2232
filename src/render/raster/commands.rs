//! Command recording for one frame in flight: a command pool and buffer, the fence of its last
//! submission, its upload [`Ring`] and descriptor pools. [`Slot::begin`] waits for the
//! slot's previous submission, so memory of a slot is reused only once the GPU is done.

use std::hash::{BuildHasher, Hash, Hasher};

use ash::vk;
use rustc_hash::{FxBuildHasher, FxHashMap};

use super::device::{Check, Device, Result};
use super::output::SubmitSync;
use super::ff::shader_interface::BINDING_COUNT;
use super::upload::Ring;

/// Descriptor sets per pool.
const SETS_PER_POOL: u32 = 256;

/// What a descriptor set holds: dynamic storage buffers at bindings `0..` (the buffer and the
/// range the shaders read; the offsets are dynamic), then combined image samplers at the
/// bindings after them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SetKey<'a> {
    /// The set's layout.
    pub layout: vk::DescriptorSetLayout,
    /// Buffer and range of each storage buffer binding.
    pub buffers: &'a [(vk::Buffer, u64)],
    /// Image view and sampler of each sampler binding.
    pub images: &'a [(vk::ImageView, vk::Sampler)],
}

/// A [`SetKey`] kept by [`Descriptors`].
struct OwnedSetKey {
    layout: vk::DescriptorSetLayout,
    buffers: Vec<(vk::Buffer, u64)>,
    images: Vec<(vk::ImageView, vk::Sampler)>,
}

impl OwnedSetKey {
    fn of(key: &SetKey<'_>) -> OwnedSetKey {
        OwnedSetKey { layout: key.layout, buffers: key.buffers.to_vec(), images: key.images.to_vec() }
    }

    fn is(&self, key: &SetKey<'_>) -> bool {
        self.layout == key.layout && self.buffers == key.buffers && self.images == key.images
    }
}

/// Descriptor pools of one frame in flight, reset together when the frame is reused; sets
/// with the same contents are shared within the frame.
pub struct Descriptors {
    pools: Vec<vk::DescriptorPool>,
    /// Pool being allocated from.
    current: usize,
    /// The frame's sets by the FxHash of their key (keys of equal hashes side by side), so a
    /// lookup hashes and compares borrowed slices and allocates nothing.
    sets: FxHashMap<u64, Vec<(OwnedSetKey, vk::DescriptorSet)>>,
    /// The set `get` returned last, which consecutive draws often share.
    last: Option<(OwnedSetKey, vk::DescriptorSet)>,
}

impl Descriptors {
    fn new() -> Descriptors {
        Descriptors { pools: Vec::new(), current: 0, sets: FxHashMap::default(), last: None }
    }

    fn reset(&mut self, device: &Device) -> Result<()> {
        for &pool in &self.pools {
            // Safety: the frame that used the sets is finished (the slot fence signalled).
            unsafe { device.raw.reset_descriptor_pool(pool, vk::DescriptorPoolResetFlags::empty()) }.check("vkResetDescriptorPool")?;
        }
        self.current = 0;
        self.sets.clear();
        self.last = None;
        Ok(())
    }

    /// The set holding `key`.
    pub fn get(&mut self, device: &Device, key: &SetKey<'_>) -> Result<vk::DescriptorSet> {
        if let Some((last, set)) = &self.last
            && last.is(key)
        {
            return Ok(*set);
        }
        let mut hasher = FxBuildHasher.build_hasher();
        key.hash(&mut hasher);
        let hash = hasher.finish();
        if let Some(&(_, set)) = self.sets.get(&hash).and_then(|same| same.iter().find(|(k, _)| k.is(key))) {
            self.remember(key, set);
            return Ok(set);
        }
        let set = self.allocate(device, key.layout)?;
        let buffers: Vec<_> = key.buffers.iter().map(|&(buffer, range)| [vk::DescriptorBufferInfo { buffer, offset: 0, range }]).collect();
        let images: Vec<_> = key
            .images
            .iter()
            .map(|&(view, sampler)| [vk::DescriptorImageInfo { sampler, image_view: view, image_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL }])
            .collect();
        let mut writes = Vec::with_capacity(buffers.len() + images.len());
        for (i, buffer) in buffers.iter().enumerate() {
            writes.push(
                vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(i as u32)
                    .descriptor_type(vk::DescriptorType::STORAGE_BUFFER_DYNAMIC)
                    .buffer_info(buffer),
            );
        }
        for (i, image) in images.iter().enumerate() {
            writes.push(
                vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding((buffers.len() + i) as u32)
                    .descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
                    .image_info(image),
            );
        }
        // Safety: every handle in the writes is alive for the frame.
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
        self.sets.entry(hash).or_default().push((OwnedSetKey::of(key), set));
        self.remember(key, set);
        Ok(set)
    }

    /// Makes `set` (holding `key`) the last one returned, reusing the vectors of the previous.
    fn remember(&mut self, key: &SetKey<'_>, set: vk::DescriptorSet) {
        match &mut self.last {
            Some((last, last_set)) => {
                last.layout = key.layout;
                last.buffers.clear();
                last.buffers.extend_from_slice(key.buffers);
                last.images.clear();
                last.images.extend_from_slice(key.images);
                *last_set = set;
            }
            None => self.last = Some((OwnedSetKey::of(key), set)),
        }
    }

    fn allocate(&mut self, device: &Device, layout: vk::DescriptorSetLayout) -> Result<vk::DescriptorSet> {
        loop {
            if let Some(&pool) = self.pools.get(self.current) {
                let layouts = [layout];
                let info = vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&layouts);
                // Safety: pool and layout are alive.
                match unsafe { device.raw.allocate_descriptor_sets(&info) } {
                    Ok(sets) => return Ok(sets[0]),
                    Err(vk::Result::ERROR_OUT_OF_POOL_MEMORY | vk::Result::ERROR_FRAGMENTED_POOL) => self.current += 1,
                    Err(e) => return Err(super::device::Error::Vulkan("vkAllocateDescriptorSets", e)),
                }
                continue;
            }
            let sizes = [
                vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER_DYNAMIC, descriptor_count: SETS_PER_POOL * 2 },
                vk::DescriptorPoolSize { ty: vk::DescriptorType::COMBINED_IMAGE_SAMPLER, descriptor_count: SETS_PER_POOL * (BINDING_COUNT - 1) },
            ];
            let info = vk::DescriptorPoolCreateInfo::default().max_sets(SETS_PER_POOL).pool_sizes(&sizes);
            // Safety: valid create info.
            let pool = unsafe { device.raw.create_descriptor_pool(&info, None) }.check("vkCreateDescriptorPool")?;
            self.pools.push(pool);
            self.current = self.pools.len() - 1;
        }
    }

    fn destroy(&mut self, device: &Device) {
        for pool in self.pools.drain(..) {
            // Safety: the GPU is idle.
            unsafe { device.raw.destroy_descriptor_pool(pool, None) };
        }
    }
}

/// One frame in flight.
pub struct Slot {
    pool: vk::CommandPool,
    /// The command buffer being recorded (valid between [`Slot::begin`] and [`Slot::submit`]).
    pub cmd: vk::CommandBuffer,
    fence: vk::Fence,
    /// Whether work of this slot was submitted and not yet waited for.
    pending: bool,
    /// Vertices, indices and uniforms of the frame.
    pub ring: Ring,
    /// Descriptor sets of the frame.
    pub descriptors: Descriptors,
}

impl Slot {
    /// Creates the pool, command buffer and fence.
    pub fn new(device: &Device) -> Result<Slot> {
        let d = &device.raw;
        // Safety (this block): valid create infos; the objects are destroyed in `destroy`.
        unsafe {
            let pool = d
                .create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(device.queue_family), None)
                .check("vkCreateCommandPool")?;
            let info = vk::CommandBufferAllocateInfo::default().command_pool(pool).level(vk::CommandBufferLevel::PRIMARY).command_buffer_count(1);
            let cmd = d.allocate_command_buffers(&info).check("vkAllocateCommandBuffers")?[0];
            let fence = d.create_fence(&vk::FenceCreateInfo::default(), None).check("vkCreateFence")?;
            Ok(Slot { pool, cmd, fence, pending: false, ring: Ring::default(), descriptors: Descriptors::new() })
        }
    }

    /// Waits for the slot's previous submission (if any) to finish. Returns whether there was
    /// one (so its results, such as a frame dump, can be read).
    pub fn wait(&mut self, device: &Device) -> Result<bool> {
        if !self.pending {
            return Ok(false);
        }
        // Safety: the fence was submitted with the slot's last work.
        unsafe {
            device.raw.wait_for_fences(&[self.fence], true, u64::MAX).check("vkWaitForFences")?;
            device.raw.reset_fences(&[self.fence]).check("vkResetFences")?;
        }
        self.pending = false;
        Ok(true)
    }

    /// Starts recording (the previous submission must have been waited for: [`Slot::wait`]).
    /// The first command is a full memory barrier, so this frame's work is ordered after the
    /// previous frames' on the shared framebuffer images.
    pub fn begin(&mut self, device: &Device) -> Result<()> {
        self.ring.reset();
        self.descriptors.reset(device)?;
        // Safety: the slot's previous work finished; the pool is externally synchronised by
        // the renderer's `&mut`.
        unsafe {
            device.raw.reset_command_pool(self.pool, vk::CommandPoolResetFlags::empty()).check("vkResetCommandPool")?;
            let info = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            device.raw.begin_command_buffer(self.cmd, &info).check("vkBeginCommandBuffer")?;
            let barrier = [vk::MemoryBarrier2::default()
                .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
                .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
                .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
                .dst_access_mask(vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE)];
            device.raw.cmd_pipeline_barrier2(self.cmd, &vk::DependencyInfo::default().memory_barriers(&barrier));
        }
        Ok(())
    }

    /// Ends recording and submits with the semaphores of `sync`, signalling the slot's fence
    /// ([`Slot::wait`] waits for it).
    pub fn submit(&mut self, device: &Device, sync: &SubmitSync) -> Result<()> {
        let buffers = [self.cmd];
        let (wait_semaphores, wait_stages): (Vec<_>, Vec<_>) = sync.wait.iter().copied().unzip();
        let submit = [vk::SubmitInfo::default()
            .command_buffers(&buffers)
            .wait_semaphores(&wait_semaphores)
            .wait_dst_stage_mask(&wait_stages)
            .signal_semaphores(&sync.signal)];
        if crate::faults::fires(crate::faults::Fault::DeviceLost) {
            return Err(super::device::Error::Vulkan("vkQueueSubmit", vk::Result::ERROR_DEVICE_LOST));
        }
        // Safety: the command buffer is recording; the fence is unsignalled (reset in `wait`).
        unsafe {
            device.raw.end_command_buffer(self.cmd).check("vkEndCommandBuffer")?;
            device.raw.queue_submit(device.queue, &submit, self.fence).check("vkQueueSubmit")?;
        }
        self.pending = true;
        Ok(())
    }

    /// Frees everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        self.ring.destroy(device);
        self.descriptors.destroy(device);
        // Safety: the GPU is idle; each object is destroyed once.
        unsafe {
            device.raw.destroy_fence(self.fence, None);
            device.raw.destroy_command_pool(self.pool, None);
        }
    }
}
