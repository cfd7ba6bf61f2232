//! Vulkan presentation on the application's X window: a `VK_KHR_xlib_surface` surface made
//! from its `Display*` and `Window`, a `VK_KHR_swapchain` swapchain, and each frame the
//! renderer's off-screen colour image blitted onto the acquired swapchain image (a blit, not a
//! copy: it converts to the swapchain's format, often B8G8R8A8, and flips OpenGL's bottom-up
//! rows).
//!
//! The surface is checked with `vkGetPhysicalDeviceSurfaceSupportKHR` for the renderer's queue
//! family; when it cannot present (an NVIDIA GPU with Xvfb) or anything here fails, the caller
//! falls back to [`super::xlib::XlibPresenter`] with a read-back. `VK_ERROR_OUT_OF_DATE_KHR`,
//! `VK_SUBOPTIMAL_KHR` and resizes ([`SwapchainPresenter::resize`]) recreate the swapchain; an
//! acquisition found out of date is tried again on the new one, so the frame still shows.
//! The swap interval picks the present mode: 0 is `IMMEDIATE` (else `MAILBOX`), any other value
//! `FIFO` (intervals above 1 are shown as 1: Vulkan has no frame skipping).
//!
//! Synchronisation: the blit is submitted on the renderer's queue after its rendering, so
//! submission order and the barrier below order them; frames in flight are bounded by
//! [`FRAMES_IN_FLIGHT`] fences.

use std::ffi::CStr;

use ash::vk;

use super::display_epoch;
use crate::frame::XDrawable;

/// Instance extensions a presenting renderer enables (when the loader offers them all).
pub const INSTANCE_EXTENSIONS: [&CStr; 2] = [ash::khr::surface::NAME, ash::khr::xlib_surface::NAME];

/// The device extension a presenting renderer enables (when the device offers it).
pub const DEVICE_EXTENSION: &CStr = ash::khr::swapchain::NAME;

/// Command buffers (and acquire semaphores) cycled through.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// How long an acquire may wait before the frame is dropped (a stuck window system must not
/// hang the program): one second.
const ACQUIRE_TIMEOUT_NS: u64 = 1_000_000_000;

/// Which of `available` instance extensions to enable for presentation: all of
/// [`INSTANCE_EXTENSIONS`] or none.
pub fn instance_extensions(available: &[vk::ExtensionProperties]) -> Vec<&'static CStr> {
    let has = |name: &CStr| available.iter().any(|e| e.extension_name_as_c_str() == Ok(name));
    if INSTANCE_EXTENSIONS.iter().all(|n| has(n)) { INSTANCE_EXTENSIONS.to_vec() } else { Vec::new() }
}

/// The renderer's Vulkan objects a swapchain presents with. The instance must have
/// [`INSTANCE_EXTENSIONS`] and the device [`DEVICE_EXTENSION`] enabled.
#[derive(Clone)]
pub struct Gpu {
    /// The loader.
    pub entry: ash::Entry,
    /// The instance.
    pub instance: ash::Instance,
    /// The renderer's physical device.
    pub physical: vk::PhysicalDevice,
    /// The renderer's device.
    pub device: ash::Device,
    /// The family of `queue`.
    pub queue_family: u32,
    /// The queue the renderer submits its frames to; presentation uses it too.
    pub queue: vk::Queue,
}

/// The rendered image to show.
#[derive(Clone, Copy, Debug)]
pub struct Source {
    /// The renderer's colour image (usage must include `TRANSFER_SRC`; its format must support
    /// `BLIT_SRC` with optimal tiling).
    pub image: vk::Image,
    /// Its layout when presentation starts, restored when the blit is done.
    pub layout: vk::ImageLayout,
    /// Its width and height.
    pub size: [u32; 2],
    /// Rows stored bottom to top (OpenGL's window coordinates without a flipped viewport):
    /// the blit turns them upright.
    pub bottom_up: bool,
}

/// What happened to a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Presented {
    /// It was queued for presentation.
    Shown,
    /// Nothing to show now (a zero-sized or minimised window, an acquire timeout).
    Skipped,
}

/// Why a swapchain cannot be used: the caller presents with Xlib instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unusable {
    /// The surface cannot be presented to from the renderer's queue family, or has no format
    /// glrt can blit to.
    Unsupported,
    /// A Vulkan call failed.
    Failed(vk::Result),
}

impl From<vk::Result> for Unusable {
    fn from(r: vk::Result) -> Unusable {
        Unusable::Failed(r)
    }
}

/// A swapchain and what recreating it needs.
struct Chain {
    handle: vk::SwapchainKHR,
    images: Vec<vk::Image>,
    /// Signalled when the blit to each image is done; waited for by its presentation.
    blitted: Vec<vk::Semaphore>,
    format: vk::Format,
    extent: vk::Extent2D,
    mode: vk::PresentModeKHR,
}

/// Presents the renderer's frames on one X window through a Vulkan swapchain.
pub struct SwapchainPresenter {
    gpu: Gpu,
    surface_fns: ash::khr::surface::Instance,
    swapchain_fns: ash::khr::swapchain::Device,
    surface: vk::SurfaceKHR,
    /// The window's display and its [`display_epoch`] when the surface was made: once the
    /// application closed the display, the window system's objects are abandoned, not
    /// destroyed (destroying them would use the closed connection).
    display: usize,
    epoch: u64,
    chain: Option<Chain>,
    /// The window's size as last told (used when the surface leaves the extent to glrt).
    size: [u32; 2],
    interval: u32,
    /// Recreate before the next acquire (resized, suboptimal, out of date, new interval).
    stale: bool,
    pool: vk::CommandPool,
    commands: [vk::CommandBuffer; FRAMES_IN_FLIGHT],
    acquired: [vk::Semaphore; FRAMES_IN_FLIGHT],
    done: [vk::Fence; FRAMES_IN_FLIGHT],
    frame: usize,
}

// Safety: Vulkan handles are plain values; the Xlib display behind the surface is only used
// by the thread presenting (see the module documentation of `present`).
unsafe impl Send for SwapchainPresenter {}

impl SwapchainPresenter {
    /// A presenter for `window` of `size` pixels with swap interval `interval`.
    ///
    /// # Safety
    /// `window`'s display is the application's live display; `gpu` is live and outlives the
    /// presenter, with the extensions documented on [`Gpu`] enabled.
    pub unsafe fn new(gpu: &Gpu, window: XDrawable, size: [u32; 2], interval: u32) -> Result<SwapchainPresenter, Unusable> {
        let surface_fns = ash::khr::surface::Instance::new(&gpu.entry, &gpu.instance);
        let xlib_fns = ash::khr::xlib_surface::Instance::new(&gpu.entry, &gpu.instance);
        let info = vk::XlibSurfaceCreateInfoKHR::default().dpy(window.display).window(window.drawable as vk::Window);
        // Safety (all): as documented; every object is destroyed on failure (by `Drop` once
        // `presenter` exists).
        unsafe {
            let surface = xlib_fns.create_xlib_surface(&info, None)?;
            let supported = surface_fns.get_physical_device_surface_support(gpu.physical, gpu.queue_family, surface);
            if supported != Ok(true) {
                surface_fns.destroy_surface(surface, None);
                return Err(supported.err().map_or(Unusable::Unsupported, Unusable::Failed));
            }
            let device = &gpu.device;
            let pool_info = vk::CommandPoolCreateInfo::default()
                .queue_family_index(gpu.queue_family)
                .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
            let pool = match device.create_command_pool(&pool_info, None) {
                Ok(p) => p,
                Err(e) => {
                    surface_fns.destroy_surface(surface, None);
                    return Err(e.into());
                }
            };
            let mut presenter = SwapchainPresenter {
                gpu: gpu.clone(),
                swapchain_fns: ash::khr::swapchain::Device::new(&gpu.instance, &gpu.device),
                surface_fns,
                surface,
                display: window.display as usize,
                epoch: display_epoch(window.display as usize),
                chain: None,
                size,
                interval,
                stale: true,
                pool,
                commands: [vk::CommandBuffer::null(); FRAMES_IN_FLIGHT],
                acquired: [vk::Semaphore::null(); FRAMES_IN_FLIGHT],
                done: [vk::Fence::null(); FRAMES_IN_FLIGHT],
                frame: 0,
            };
            let alloc = vk::CommandBufferAllocateInfo::default()
                .command_pool(pool)
                .level(vk::CommandBufferLevel::PRIMARY)
                .command_buffer_count(FRAMES_IN_FLIGHT as u32);
            let buffers = device.allocate_command_buffers(&alloc)?;
            presenter.commands.copy_from_slice(&buffers);
            for i in 0..FRAMES_IN_FLIGHT {
                presenter.acquired[i] = device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None)?;
                let signalled = vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED);
                presenter.done[i] = device.create_fence(&signalled, None)?;
            }
            presenter.recreate()?;
            Ok(presenter)
        }
    }

    /// The window is now `size` pixels, or its swap interval changed: the swapchain is
    /// recreated before the next frame.
    pub fn resize(&mut self, size: [u32; 2], interval: u32) {
        if size != self.size || interval != self.interval {
            self.size = size;
            self.interval = interval;
            self.stale = true;
        }
    }

    /// The swapchain's format and extent, once it exists (for logs and tests).
    pub fn format(&self) -> Option<(vk::Format, [u32; 2])> {
        self.chain.as_ref().map(|c| (c.format, [c.extent.width, c.extent.height]))
    }

    /// The swapchain's present mode, once it exists (for logs and tests).
    pub fn present_mode(&self) -> Option<vk::PresentModeKHR> {
        self.chain.as_ref().map(|c| c.mode)
    }

    /// Shows `source` on the window: acquire, blit (scaled if the window's size changed since
    /// the frame was rendered), present. `Err` when presenting failed for good (the caller
    /// switches to Xlib).
    ///
    /// # Safety
    /// `source.image` is a live image of the presenter's device whose rendering was submitted
    /// to the presenter's queue; nothing else uses the queue during the call.
    pub unsafe fn present(&mut self, source: &Source) -> Result<Presented, Unusable> {
        if !self.display_open() {
            return Err(Unusable::Unsupported);
        }
        // Safety (all): as documented.
        unsafe {
            let frame = self.frame;
            self.gpu.device.wait_for_fences(&[self.done[frame]], true, u64::MAX)?;
            let Some(index) = self.acquire(frame)? else { return Ok(Presented::Skipped) };
            let Some(chain) = self.chain.as_ref() else { return Ok(Presented::Skipped) };
            let device = &self.gpu.device;
            let cmd = self.commands[frame];
            device.reset_command_buffer(cmd, vk::CommandBufferResetFlags::empty())?;
            device.begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT))?;
            record_blit(device, cmd, source, chain.images[index], chain.extent);
            device.end_command_buffer(cmd)?;
            device.reset_fences(&[self.done[frame]])?;
            let waits = [self.acquired[frame]];
            let stages = [vk::PipelineStageFlags::TRANSFER];
            let signals = [chain.blitted[index]];
            let cmds = [cmd];
            let submit = vk::SubmitInfo::default()
                .wait_semaphores(&waits)
                .wait_dst_stage_mask(&stages)
                .command_buffers(&cmds)
                .signal_semaphores(&signals);
            device.queue_submit(self.gpu.queue, &[submit], self.done[frame])?;
            self.frame = (frame + 1) % FRAMES_IN_FLIGHT;
            let swapchains = [chain.handle];
            let indices = [index as u32];
            let info = vk::PresentInfoKHR::default().wait_semaphores(&signals).swapchains(&swapchains).image_indices(&indices);
            match self.swapchain_fns.queue_present(self.gpu.queue, &info) {
                Ok(suboptimal) => self.stale |= suboptimal,
                Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => self.stale = true,
                Err(e) => return Err(e.into()),
            }
            Ok(Presented::Shown)
        }
    }

    /// Acquires the next image of the swapchain with the semaphore of frame slot `frame`,
    /// recreating the swapchain first when it is stale. A swapchain found out of date (the
    /// window changed since) is recreated and the acquisition tried once more, so the frame is
    /// not lost; `None` when there is nothing to present to (a zero-sized window, an acquire
    /// timeout, out of date twice).
    ///
    /// # Safety
    /// The presenter's objects are live; slot `frame`'s last blit is done.
    unsafe fn acquire(&mut self, frame: usize) -> Result<Option<usize>, Unusable> {
        for _ in 0..2 {
            // Safety (all): as documented.
            unsafe {
                if self.stale {
                    self.recreate()?;
                }
                let Some(chain) = self.chain.as_ref() else { return Ok(None) };
                let acquire = if crate::faults::fires(crate::faults::Fault::OutOfDate) {
                    Err(vk::Result::ERROR_OUT_OF_DATE_KHR)
                } else {
                    self.swapchain_fns.acquire_next_image(chain.handle, ACQUIRE_TIMEOUT_NS, self.acquired[frame], vk::Fence::null())
                };
                match acquire {
                    Ok((index, suboptimal)) => {
                        self.stale |= suboptimal;
                        return Ok(Some(index as usize));
                    }
                    Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                        log::info!("present: the swapchain is out of date: recreating it");
                        self.stale = true;
                    }
                    Err(vk::Result::TIMEOUT | vk::Result::NOT_READY) => return Ok(None),
                    Err(e) => return Err(e.into()),
                }
            }
        }
        Ok(None)
    }

    /// Whether the application's display is still open.
    fn display_open(&self) -> bool {
        display_epoch(self.display) == self.epoch
    }

    /// Builds the swapchain for the surface's current extent (none while it is zero-sized),
    /// replacing the old one.
    ///
    /// # Safety
    /// The presenter's objects are live.
    unsafe fn recreate(&mut self) -> Result<(), Unusable> {
        let (gpu, fns) = (&self.gpu, &self.surface_fns);
        // Safety (all): the presenter's objects are live; the old chain is idle once our
        // fences are signalled and is destroyed after its replacement exists.
        unsafe {
            gpu.device.wait_for_fences(&self.done, true, u64::MAX)?;
            let caps = fns.get_physical_device_surface_capabilities(gpu.physical, self.surface)?;
            let formats = fns.get_physical_device_surface_formats(gpu.physical, self.surface)?;
            let modes = fns.get_physical_device_surface_present_modes(gpu.physical, self.surface)?;
            let format = pick_format(&formats, |f| {
                let props = gpu.instance.get_physical_device_format_properties(gpu.physical, f);
                props.optimal_tiling_features.contains(vk::FormatFeatureFlags::BLIT_DST)
            })
            .ok_or(Unusable::Unsupported)?;
            if !caps.supported_usage_flags.contains(vk::ImageUsageFlags::TRANSFER_DST) {
                return Err(Unusable::Unsupported);
            }
            let extent = if caps.current_extent.width == u32::MAX {
                vk::Extent2D {
                    width: self.size[0].clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                    height: self.size[1].clamp(caps.min_image_extent.height, caps.max_image_extent.height),
                }
            } else {
                caps.current_extent
            };
            let old = self.chain.take();
            self.stale = false;
            if extent.width == 0 || extent.height == 0 {
                self.destroy_chain(old);
                return Ok(());
            }
            let count = match caps.max_image_count {
                0 => caps.min_image_count + 1,
                max => (caps.min_image_count + 1).min(max),
            };
            let alpha = [vk::CompositeAlphaFlagsKHR::OPAQUE, vk::CompositeAlphaFlagsKHR::INHERIT]
                .into_iter()
                .find(|a| caps.supported_composite_alpha.contains(*a))
                .unwrap_or(vk::CompositeAlphaFlagsKHR::from_raw(caps.supported_composite_alpha.as_raw() & caps.supported_composite_alpha.as_raw().wrapping_neg()));
            let mode = present_mode(self.interval, &modes);
            log::info!("present: swapchain {}x{} {:?} {mode:?}", extent.width, extent.height, format.format);
            let info = vk::SwapchainCreateInfoKHR::default()
                .surface(self.surface)
                .min_image_count(count)
                .image_format(format.format)
                .image_color_space(format.color_space)
                .image_extent(extent)
                .image_array_layers(1)
                .image_usage(vk::ImageUsageFlags::TRANSFER_DST)
                .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
                .pre_transform(caps.current_transform)
                .composite_alpha(alpha)
                .present_mode(mode)
                .clipped(true)
                .old_swapchain(old.as_ref().map_or(vk::SwapchainKHR::null(), |c| c.handle));
            let created = self.swapchain_fns.create_swapchain(&info, None);
            self.destroy_chain(old);
            let handle = created?;
            let mut chain = Chain { handle, images: Vec::new(), blitted: Vec::new(), format: format.format, extent, mode };
            let result = (|| {
                chain.images = self.swapchain_fns.get_swapchain_images(handle)?;
                for _ in 0..chain.images.len() {
                    chain.blitted.push(self.gpu.device.create_semaphore(&vk::SemaphoreCreateInfo::default(), None)?);
                }
                Ok(())
            })();
            self.chain = Some(chain);
            result.map_err(Unusable::Failed)
        }
    }

    /// Destroys a swapchain no longer in use (the queue is idle: its semaphores may still be
    /// waited on by a presentation, which `queue_wait_idle` completes); only abandoned when the
    /// display is closed.
    ///
    /// # Safety
    /// The chain belongs to this presenter.
    unsafe fn destroy_chain(&self, chain: Option<Chain>) {
        let Some(chain) = chain else { return };
        // Safety: as documented.
        unsafe {
            let _ = self.gpu.device.queue_wait_idle(self.gpu.queue);
            for s in chain.blitted {
                self.gpu.device.destroy_semaphore(s, None);
            }
            if self.display_open() {
                self.swapchain_fns.destroy_swapchain(chain.handle, None);
            }
        }
    }
}

impl Drop for SwapchainPresenter {
    fn drop(&mut self) {
        // Safety: every object was created by this presenter; the fences and the queue are
        // waited for before anything is destroyed (null handles are ignored by Vulkan).
        unsafe {
            let device = &self.gpu.device;
            let live: Vec<vk::Fence> = self.done.iter().copied().filter(|f| *f != vk::Fence::null()).collect();
            if !live.is_empty() {
                let _ = device.wait_for_fences(&live, true, u64::MAX);
            }
            let chain = self.chain.take();
            self.destroy_chain(chain);
            for i in 0..FRAMES_IN_FLIGHT {
                device.destroy_semaphore(self.acquired[i], None);
                device.destroy_fence(self.done[i], None);
            }
            device.destroy_command_pool(self.pool, None);
            if self.display_open() {
                self.surface_fns.destroy_surface(self.surface, None);
            }
        }
    }
}

/// A UNORM 8-bit format when the surface offers one (OpenGL 1.x colours are written as they
/// are, without sRGB encoding), else the first non-sRGB, else the first; only formats that
/// `blittable` accepts.
fn pick_format(formats: &[vk::SurfaceFormatKHR], blittable: impl Fn(vk::Format) -> bool) -> Option<vk::SurfaceFormatKHR> {
    let usable: Vec<vk::SurfaceFormatKHR> = formats.iter().copied().filter(|f| blittable(f.format)).collect();
    let preferred = [vk::Format::B8G8R8A8_UNORM, vk::Format::R8G8B8A8_UNORM, vk::Format::A8B8G8R8_UNORM_PACK32];
    let srgb = [vk::Format::B8G8R8A8_SRGB, vk::Format::R8G8B8A8_SRGB, vk::Format::A8B8G8R8_SRGB_PACK32];
    preferred
        .iter()
        .find_map(|p| usable.iter().find(|f| f.format == *p))
        .or_else(|| usable.iter().find(|f| !srgb.contains(&f.format)))
        .or_else(|| usable.first())
        .copied()
}

/// The present mode for swap interval `interval` among `modes` (FIFO always exists).
fn present_mode(interval: u32, modes: &[vk::PresentModeKHR]) -> vk::PresentModeKHR {
    let wanted: &[vk::PresentModeKHR] =
        if interval == 0 { &[vk::PresentModeKHR::IMMEDIATE, vk::PresentModeKHR::MAILBOX] } else { &[] };
    wanted.iter().copied().find(|m| modes.contains(m)).unwrap_or(vk::PresentModeKHR::FIFO)
}

/// Records: source to `TRANSFER_SRC`, swapchain image to `TRANSFER_DST`, the blit (flipped for
/// bottom-up sources), swapchain image to `PRESENT_SRC`, source back to its layout.
///
/// # Safety
/// `cmd` is recording; the images are live.
unsafe fn record_blit(device: &ash::Device, cmd: vk::CommandBuffer, src: &Source, dst: vk::Image, extent: vk::Extent2D) {
    let range = vk::ImageSubresourceRange::default().aspect_mask(vk::ImageAspectFlags::COLOR).level_count(1).layer_count(1);
    let barrier = |image, old, new, src_access, dst_access| {
        vk::ImageMemoryBarrier::default()
            .image(image)
            .old_layout(old)
            .new_layout(new)
            .src_access_mask(src_access)
            .dst_access_mask(dst_access)
            .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
            .subresource_range(range)
    };
    let before = [
        barrier(
            src.image,
            src.layout,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            vk::AccessFlags::MEMORY_WRITE,
            vk::AccessFlags::TRANSFER_READ,
        ),
        barrier(dst, vk::ImageLayout::UNDEFINED, vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::AccessFlags::empty(), vk::AccessFlags::TRANSFER_WRITE),
    ];
    let after = [
        barrier(dst, vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::PRESENT_SRC_KHR, vk::AccessFlags::TRANSFER_WRITE, vk::AccessFlags::empty()),
        barrier(src.image, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, src.layout, vk::AccessFlags::TRANSFER_READ, vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE),
    ];
    let layers = vk::ImageSubresourceLayers::default().aspect_mask(vk::ImageAspectFlags::COLOR).layer_count(1);
    let [w, h] = src.size.map(|v| v.min(i32::MAX as u32) as i32);
    let (top, bottom) = if src.bottom_up { (h, 0) } else { (0, h) };
    let blit = vk::ImageBlit {
        src_subresource: layers,
        src_offsets: [vk::Offset3D { x: 0, y: top, z: 0 }, vk::Offset3D { x: w, y: bottom, z: 1 }],
        dst_subresource: layers,
        dst_offsets: [vk::Offset3D::default(), vk::Offset3D { x: extent.width as i32, y: extent.height as i32, z: 1 }],
    };
    // Safety: as documented.
    unsafe {
        device.cmd_pipeline_barrier(
            cmd,
            vk::PipelineStageFlags::ALL_COMMANDS,
            vk::PipelineStageFlags::TRANSFER,
            vk::DependencyFlags::empty(),
            &[],
            &[],
            &before,
        );
        device.cmd_blit_image(
            cmd,
            src.image,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            dst,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            &[blit],
            vk::Filter::NEAREST,
        );
        device.cmd_pipeline_barrier(
            cmd,
            vk::PipelineStageFlags::TRANSFER,
            vk::PipelineStageFlags::ALL_COMMANDS,
            vk::DependencyFlags::empty(),
            &[],
            &[],
            &after,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn present_mode_follows_the_swap_interval() {
        let all = [vk::PresentModeKHR::FIFO, vk::PresentModeKHR::MAILBOX, vk::PresentModeKHR::IMMEDIATE];
        assert_eq!(present_mode(0, &all), vk::PresentModeKHR::IMMEDIATE);
        assert_eq!(present_mode(0, &all[..2]), vk::PresentModeKHR::MAILBOX);
        assert_eq!(present_mode(0, &all[..1]), vk::PresentModeKHR::FIFO);
        assert_eq!(present_mode(1, &all), vk::PresentModeKHR::FIFO);
        assert_eq!(present_mode(3, &all), vk::PresentModeKHR::FIFO);
    }

    #[test]
    fn format_prefers_unorm_and_blittable() {
        let f = |format| vk::SurfaceFormatKHR { format, color_space: vk::ColorSpaceKHR::SRGB_NONLINEAR };
        let offered = [f(vk::Format::B8G8R8A8_SRGB), f(vk::Format::R8G8B8A8_UNORM), f(vk::Format::B8G8R8A8_UNORM)];
        assert_eq!(pick_format(&offered, |_| true).unwrap().format, vk::Format::B8G8R8A8_UNORM);
        let no_bgra = |x| x != vk::Format::B8G8R8A8_UNORM;
        assert_eq!(pick_format(&offered, no_bgra).unwrap().format, vk::Format::R8G8B8A8_UNORM);
        assert_eq!(pick_format(&offered[..1], |_| true).unwrap().format, vk::Format::B8G8R8A8_SRGB);
        assert_eq!(pick_format(&offered, |_| false), None);
        let names: Vec<vk::ExtensionProperties> = Vec::new();
        assert!(instance_extensions(&names).is_empty());
    }
}
