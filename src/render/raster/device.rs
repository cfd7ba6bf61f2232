//! The Vulkan device of a renderer, made from the process's instance ([`super::instance`]):
//! the physical device chosen by `GLRT_DEVICE` (an index into the enumeration, or a substring
//! of the device name; otherwise a discrete GPU, then an integrated one, then anything, such as
//! Mesa lavapipe on the CPU), one graphics queue, and the memory allocator.
//!
//! Vulkan 1.3 is required (dynamic rendering, negative viewport heights); lavapipe 22.3 and the
//! NVIDIA driver both provide it. Optional features are probed and recorded in [`Features`]
//! so the pipelines use them only where present (logic ops, wide lines, non-solid fill).

use std::ffi::CString;
use std::mem::ManuallyDrop;

use ash::vk;
use gpu_allocator::MemoryLocation;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme, Allocator, AllocatorCreateDesc};
use parking_lot::Mutex;

/// What can go wrong in the back end. Everything degrades: the caller logs it once and drops
/// to the null renderer (no panic crosses the C ABI).
#[derive(Clone, Debug)]
pub enum Error {
    /// `libvulkan.so.1` could not be opened.
    NoLoader(String),
    /// No physical device fits (none, none with graphics, or `GLRT_DEVICE` matched nothing).
    NoDevice(String),
    /// A Vulkan call failed (out of memory, device lost, ...).
    Vulkan(&'static str, vk::Result),
    /// The allocator refused.
    Memory(String),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::NoLoader(e) => write!(f, "cannot load the Vulkan loader: {e}"),
            Error::NoDevice(e) => write!(f, "no usable Vulkan device: {e}"),
            Error::Vulkan(call, r) => write!(f, "{call} failed: {r}"),
            Error::Memory(e) => write!(f, "GPU memory allocation failed: {e}"),
        }
    }
}

/// Result of the back end's calls.
pub type Result<T> = std::result::Result<T, Error>;

/// Turns a `VkResult` into an [`Error`] naming the call.
pub(crate) trait Check<T> {
    /// Names the failed call.
    fn check(self, call: &'static str) -> Result<T>;
}

impl<T> Check<T> for std::result::Result<T, vk::Result> {
    fn check(self, call: &'static str) -> Result<T> {
        self.map_err(|r| Error::Vulkan(call, r))
    }
}

/// Optional device features the raster path uses when present.
#[derive(Clone, Debug, Default)]
pub struct Features {
    /// `logicOp`: `glLogicOp` on the colour buffer.
    pub logic_op: bool,
    /// `wideLines`: line widths other than 1.
    pub wide_lines: bool,
    /// Supported line widths.
    pub line_width_range: [f32; 2],
    /// `fillModeNonSolid`: polygon modes `GL_LINE`/`GL_POINT`.
    pub fill_mode_non_solid: bool,
    /// `largePoints`: point sizes other than 1.
    pub large_points: bool,
    /// `samplerAnisotropy`.
    pub sampler_anisotropy: bool,
    /// `occlusionQueryPrecise`: occlusion queries count samples exactly.
    pub occlusion_query_precise: bool,
    /// `alphaToOne`: `GL_SAMPLE_ALPHA_TO_ONE`.
    pub alpha_to_one: bool,
    /// `textureCompressionBC` is enabled: BC1–BC7 images can be sampled (the radiosity
    /// matrix).
    pub bc_textures: bool,
    /// Multisampled framebuffer sample counts ([`super::multisample::supported_counts`]).
    pub sample_counts: Vec<u32>,
}

/// The device and everything created once with it. Shared (`Arc`) by the renderer's parts.
pub struct Device {
    /// The loader (the process's, [`super::instance`]).
    pub entry: ash::Entry,
    /// The instance (the process's, never destroyed).
    pub instance: ash::Instance,
    /// The chosen physical device.
    pub physical: vk::PhysicalDevice,
    /// Its properties (limits, name).
    pub properties: vk::PhysicalDeviceProperties,
    /// The logical device.
    pub raw: ash::Device,
    /// Family of [`Device::queue`].
    pub queue_family: u32,
    /// The graphics (and transfer) queue.
    pub queue: vk::Queue,
    /// Optional features enabled.
    pub features: Features,
    /// The depth/stencil format of the framebuffer.
    pub depth_format: vk::Format,
    /// `VK_EXT_custom_border_color` (with `customBorderColorWithoutFormat`) is enabled.
    pub custom_border_color: bool,
    /// `VK_KHR_swapchain` is enabled, with the instance's `VK_KHR_surface` and
    /// `VK_KHR_xlib_surface`: the device can present to X11 windows (when a queue family
    /// supports the surface).
    pub swapchain: bool,
    /// `VK_KHR_acceleration_structure` and `VK_KHR_ray_tracing_pipeline` are enabled with
    /// their features and `bufferDeviceAddress`: the hardware tracer can run
    /// ([`crate::render::trace::hardware`]).
    pub ray_tracing: bool,
    /// Device memory.
    allocator: ManuallyDrop<Mutex<Allocator>>,
}

/// A buffer and its memory.
pub struct Buffer {
    /// The buffer.
    pub raw: vk::Buffer,
    /// Its size in bytes.
    pub size: u64,
    allocation: Allocation,
}

impl Buffer {
    /// The mapped bytes of a host-visible buffer.
    pub fn mapped(&mut self) -> &mut [u8] {
        self.allocation.mapped_slice_mut().unwrap_or(&mut [])
    }
}

/// An image, its memory and a view of all of it.
pub struct Image {
    /// The image.
    pub raw: vk::Image,
    /// The view of every level and layer.
    pub view: vk::ImageView,
    /// Its format.
    pub format: vk::Format,
    /// Width, height, depth.
    pub extent: vk::Extent3D,
    allocation: Allocation,
}

impl Device {
    /// Creates the device chosen by `GLRT_DEVICE` (see the module doc) on the process's
    /// instance ([`super::instance`]).
    pub fn new() -> Result<Device> {
        let shared = super::instance::get()?;
        let (entry, instance, surfaces) = (shared.entry.clone(), shared.raw.clone(), shared.surfaces);
        // Safety: valid instance.
        let physicals = unsafe { instance.enumerate_physical_devices() }.check("vkEnumeratePhysicalDevices")?;
        let choice = std::env::var("GLRT_DEVICE").ok();
        let physical = choose_physical(&instance, &physicals, choice.as_deref())?;
        // Safety: physical comes from this instance.
        let properties = unsafe { instance.get_physical_device_properties(physical) };
        let queue_family = graphics_queue_family(&instance, physical)?;
        // Safety: as above.
        let supported = unsafe { instance.get_physical_device_features(physical) };
        let features = Features {
            logic_op: supported.logic_op == vk::TRUE,
            wide_lines: supported.wide_lines == vk::TRUE,
            line_width_range: properties.limits.line_width_range,
            fill_mode_non_solid: supported.fill_mode_non_solid == vk::TRUE,
            large_points: supported.large_points == vk::TRUE,
            sampler_anisotropy: supported.sampler_anisotropy == vk::TRUE,
            occlusion_query_precise: supported.occlusion_query_precise == vk::TRUE,
            alpha_to_one: supported.alpha_to_one == vk::TRUE,
            bc_textures: supported.texture_compression_bc == vk::TRUE,
            sample_counts: super::multisample::supported_counts(&properties.limits),
        };
        let enabled = vk::PhysicalDeviceFeatures::default()
            .logic_op(features.logic_op)
            .wide_lines(features.wide_lines)
            .fill_mode_non_solid(features.fill_mode_non_solid)
            .large_points(features.large_points)
            .sampler_anisotropy(features.sampler_anisotropy)
            .occlusion_query_precise(features.occlusion_query_precise)
            .alpha_to_one(features.alpha_to_one)
            .texture_compression_bc(features.bc_textures)
            .shader_clip_distance(true);
        let mut extensions = device_extensions(&instance, physical);
        if !surfaces {
            extensions.retain(|e| e.as_c_str() != ash::khr::swapchain::NAME);
        }
        let ray_tracing = ray_tracing_supported(&instance, physical, &extensions);
        if !ray_tracing {
            extensions.retain(|e| !RAY_TRACING_EXTENSIONS.contains(&e.as_c_str()));
        }
        let mut v12 = vk::PhysicalDeviceVulkan12Features::default().host_query_reset(true).buffer_device_address(ray_tracing);
        let mut acceleration = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default().acceleration_structure(true);
        let mut pipeline = vk::PhysicalDeviceRayTracingPipelineFeaturesKHR::default().ray_tracing_pipeline(true);
        let mut v13 = vk::PhysicalDeviceVulkan13Features::default().dynamic_rendering(true).synchronization2(true);
        let priorities = [1.0];
        let queues = [vk::DeviceQueueCreateInfo::default().queue_family_index(queue_family).queue_priorities(&priorities)];
        let swapchain = extensions.iter().any(|e| e.as_c_str() == ash::khr::swapchain::NAME);
        let custom_border_color = extensions.iter().any(|e| e.as_c_str() == ash::ext::custom_border_color::NAME) && {
            let mut border = vk::PhysicalDeviceCustomBorderColorFeaturesEXT::default();
            let mut features2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut border);
            // Safety: the extension is supported by this physical device.
            unsafe { instance.get_physical_device_features2(physical, &mut features2) };
            border.custom_border_colors == vk::TRUE && border.custom_border_color_without_format == vk::TRUE
        };
        if !custom_border_color {
            extensions.retain(|e| e.as_c_str() != ash::ext::custom_border_color::NAME);
        }
        let mut border = vk::PhysicalDeviceCustomBorderColorFeaturesEXT::default()
            .custom_border_colors(true)
            .custom_border_color_without_format(true);
        let extension_ptrs: Vec<_> = extensions.iter().map(|e| e.as_ptr()).collect();
        let mut info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_features(&enabled)
            .enabled_extension_names(&extension_ptrs)
            .push_next(&mut v12)
            .push_next(&mut v13);
        if custom_border_color {
            info = info.push_next(&mut border);
        }
        if ray_tracing {
            info = info.push_next(&mut acceleration).push_next(&mut pipeline);
        }
        // Every device glrt makes on `physical` is made with this same `info` (it depends on
        // the physical device and the instance alone), so an idle one can be taken instead.
        let raw = match super::instance::take_device(physical) {
            Some(raw) => raw,
            None => {
                let _serialised = super::instance::lock_devices();
                // Safety: valid create info; the features were checked above.
                unsafe { instance.create_device(physical, &info, None) }.check("vkCreateDevice")?
            }
        };
        // Safety: family and index 0 were requested above.
        let queue = unsafe { raw.get_device_queue(queue_family, 0) };
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: raw.clone(),
            physical_device: physical,
            debug_settings: Default::default(),
            buffer_device_address: ray_tracing,
            allocation_sizes: Default::default(),
        })
        .map_err(|e| Error::Memory(e.to_string()));
        let allocator = match allocator {
            Ok(a) => a,
            Err(e) => {
                super::instance::give_back_device(super::instance::IdleDevice { physical, raw });
                return Err(e);
            }
        };
        let depth_format = depth_format(&instance, physical);
        log::info!("glrt: Vulkan device {}", device_name(&properties));
        Ok(Device {
            entry,
            instance,
            physical,
            properties,
            raw,
            queue_family,
            queue,
            features,
            depth_format,
            custom_border_color,
            swapchain,
            ray_tracing,
            allocator: ManuallyDrop::new(Mutex::new(allocator)),
        })
    }

    /// The device's name.
    pub fn name(&self) -> String {
        device_name(&self.properties)
    }

    /// Creates a buffer of `size` bytes in `location` (`CpuToGpu`/`GpuToCpu` ones are mapped).
    pub fn create_buffer(&self, name: &str, size: u64, usage: vk::BufferUsageFlags, location: MemoryLocation) -> Result<Buffer> {
        let info = vk::BufferCreateInfo::default().size(size.max(4)).usage(usage);
        // Safety: valid create info.
        let raw = unsafe { self.raw.create_buffer(&info, None) }.check("vkCreateBuffer")?;
        // Safety: raw is a buffer of this device.
        let requirements = unsafe { self.raw.get_buffer_memory_requirements(raw) };
        let allocation = self.allocate(name, requirements, location, true).and_then(|allocation| {
            // Safety: fresh allocation of the buffer's requirements.
            unsafe { self.raw.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) }
                .check("vkBindBufferMemory")
                .map(|()| allocation)
        });
        match allocation {
            Ok(allocation) => Ok(Buffer { raw, size, allocation }),
            Err(e) => {
                // Safety: the buffer is unused.
                unsafe { self.raw.destroy_buffer(raw, None) };
                Err(e)
            }
        }
    }

    /// Destroys a buffer the GPU no longer uses.
    pub fn destroy_buffer(&self, buffer: Buffer) {
        // Safety: the caller guarantees the GPU is done with it.
        unsafe { self.raw.destroy_buffer(buffer.raw, None) };
        self.free(buffer.allocation);
    }

    /// Creates the device-local storage buffers `specs` (name, bytes), which copies may also
    /// write; on failure those already made are freed.
    pub fn create_storage_buffers<const N: usize>(&self, specs: [(&str, u64); N]) -> Result<[Buffer; N]> {
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        let mut made = Vec::with_capacity(N);
        for (name, bytes) in specs {
            match self.create_buffer(name, bytes, usage, MemoryLocation::GpuOnly) {
                Ok(b) => made.push(b),
                Err(e) => {
                    made.into_iter().for_each(|b| self.destroy_buffer(b));
                    return Err(e);
                }
            }
        }
        Ok(made.try_into().unwrap_or_else(|_| unreachable!("one buffer per spec")))
    }

    /// Creates an optimal-tiling image in device memory with a view of all of it.
    pub fn create_image(&self, name: &str, info: &vk::ImageCreateInfo, view_type: vk::ImageViewType, aspect: vk::ImageAspectFlags) -> Result<Image> {
        self.create_image_swizzled(name, info, view_type, aspect, vk::ComponentMapping::default())
    }

    /// [`Device::create_image`] with a component swizzle on the view.
    pub fn create_image_swizzled(
        &self,
        name: &str,
        info: &vk::ImageCreateInfo,
        view_type: vk::ImageViewType,
        aspect: vk::ImageAspectFlags,
        swizzle: vk::ComponentMapping,
    ) -> Result<Image> {
        // Safety: valid create info.
        let raw = unsafe { self.raw.create_image(info, None) }.check("vkCreateImage")?;
        // Safety: raw is an image of this device.
        let requirements = unsafe { self.raw.get_image_memory_requirements(raw) };
        let bound = self.allocate(name, requirements, MemoryLocation::GpuOnly, false).and_then(|allocation| {
            // Safety: fresh allocation of the image's requirements.
            unsafe { self.raw.bind_image_memory(raw, allocation.memory(), allocation.offset()) }
                .check("vkBindImageMemory")
                .map(|()| allocation)
        });
        let allocation = match bound {
            Ok(a) => a,
            Err(e) => {
                // Safety: unused image.
                unsafe { self.raw.destroy_image(raw, None) };
                return Err(e);
            }
        };
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(view_type)
            .format(info.format)
            .components(swizzle)
            .subresource_range(vk::ImageSubresourceRange {
                aspect_mask: aspect,
                base_mip_level: 0,
                level_count: vk::REMAINING_MIP_LEVELS,
                base_array_layer: 0,
                layer_count: vk::REMAINING_ARRAY_LAYERS,
            });
        // Safety: the image is bound to memory; the view matches its format.
        match unsafe { self.raw.create_image_view(&view_info, None) }.check("vkCreateImageView") {
            Ok(view) => Ok(Image { raw, view, format: info.format, extent: info.extent, allocation }),
            Err(e) => {
                // Safety: unused image.
                unsafe { self.raw.destroy_image(raw, None) };
                self.free(allocation);
                Err(e)
            }
        }
    }

    /// Destroys an image the GPU no longer uses.
    pub fn destroy_image(&self, image: Image) {
        // Safety: the caller guarantees the GPU is done with it.
        unsafe {
            self.raw.destroy_image_view(image.view, None);
            self.raw.destroy_image(image.raw, None);
        }
        self.free(image.allocation);
    }

    /// Waits until the device is idle (resizes, shutdown).
    pub fn wait_idle(&self) -> Result<()> {
        // Safety: valid device; callers hold no queue submission in flight on other threads.
        unsafe { self.raw.device_wait_idle() }.check("vkDeviceWaitIdle")
    }

    fn allocate(&self, name: &str, requirements: vk::MemoryRequirements, location: MemoryLocation, linear: bool) -> Result<Allocation> {
        if crate::faults::fires(crate::faults::Fault::Allocation) {
            return Err(Error::Vulkan("vkAllocateMemory", vk::Result::ERROR_OUT_OF_DEVICE_MEMORY));
        }
        self.allocator
            .lock()
            .allocate(&AllocationCreateDesc { name, requirements, location, linear, allocation_scheme: AllocationScheme::GpuAllocatorManaged })
            .map_err(|e| Error::Memory(e.to_string()))
    }

    fn free(&self, allocation: Allocation) {
        if let Err(e) = self.allocator.lock().free(allocation) {
            log::warn!("glrt: freeing GPU memory: {e}");
        }
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // Safety: every object created from the device was destroyed by its owner (they hold
        // the `Arc<Device>`), so the allocator goes (freeing all memory), then the device is
        // idle and empty: kept for the next renderer (see `super::instance`), or destroyed when
        // it was lost. The instance is the process's and stays.
        unsafe {
            let idle = self.raw.device_wait_idle();
            ManuallyDrop::drop(&mut self.allocator);
            if idle.is_ok() {
                super::instance::give_back_device(super::instance::IdleDevice { physical: self.physical, raw: self.raw.clone() });
            } else {
                let _serialised = super::instance::lock_devices();
                self.raw.destroy_device(None);
            }
        }
    }
}

/// The properties of the physical device `GLRT_DEVICE` chooses, read without creating a
/// device (what the window-system layer needs before any context exists); `None` without a
/// Vulkan 1.3 device.
pub fn probe_properties() -> Option<vk::PhysicalDeviceProperties> {
    let instance = &super::instance::get().ok()?.raw;
    // Safety: valid instance; the physical device comes from it.
    unsafe {
        let physicals = instance.enumerate_physical_devices().unwrap_or_default();
        let choice = std::env::var("GLRT_DEVICE").ok();
        let chosen = choose_physical(instance, &physicals, choice.as_deref()).ok();
        let properties = chosen.map(|p| instance.get_physical_device_properties(p));
        properties.filter(|p| p.api_version >= vk::API_VERSION_1_3)
    }
}

/// The queue family glrt draws with on `physical`, or why the device cannot be used: it lacks
/// Vulkan 1.3, a graphics queue or `shaderClipDistance` (user clip planes).
pub(crate) fn graphics_queue_family(instance: &ash::Instance, physical: vk::PhysicalDevice) -> Result<u32> {
    // Safety: physical comes from this instance.
    let (properties, families, supported) = unsafe {
        (
            instance.get_physical_device_properties(physical),
            instance.get_physical_device_queue_family_properties(physical),
            instance.get_physical_device_features(physical),
        )
    };
    if properties.api_version < vk::API_VERSION_1_3 {
        return Err(Error::NoDevice(format!("{} lacks Vulkan 1.3", device_name(&properties))));
    }
    let family = families
        .iter()
        .position(|f| f.queue_flags.contains(vk::QueueFlags::GRAPHICS))
        .ok_or_else(|| Error::NoDevice("no graphics queue".into()))?;
    if supported.shader_clip_distance != vk::TRUE {
        return Err(Error::NoDevice("no shaderClipDistance (user clip planes)".into()));
    }
    Ok(family as u32)
}

/// Device extensions enabled when present.
fn device_extensions(instance: &ash::Instance, physical: vk::PhysicalDevice) -> Vec<CString> {
    // Safety: valid physical device.
    let available = unsafe { instance.enumerate_device_extension_properties(physical) }.unwrap_or_default();
    [ash::khr::swapchain::NAME, ash::ext::custom_border_color::NAME]
        .into_iter()
        .chain(RAY_TRACING_EXTENSIONS)
        .filter(|want| available.iter().any(|e| e.extension_name_as_c_str() == Ok(want)))
        .map(CString::from)
        .collect()
}

/// The extensions of the hardware tracer.
const RAY_TRACING_EXTENSIONS: [&std::ffi::CStr; 3] =
    [ash::khr::acceleration_structure::NAME, ash::khr::ray_tracing_pipeline::NAME, ash::khr::deferred_host_operations::NAME];

/// Whether `physical` has the hardware tracer's extensions (among `extensions`, the available
/// ones glrt enables) and features.
fn ray_tracing_supported(instance: &ash::Instance, physical: vk::PhysicalDevice, extensions: &[CString]) -> bool {
    if !RAY_TRACING_EXTENSIONS.iter().all(|want| extensions.iter().any(|e| e.as_c_str() == *want)) {
        return false;
    }
    let mut v12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut acceleration = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default();
    let mut pipeline = vk::PhysicalDeviceRayTracingPipelineFeaturesKHR::default();
    let mut features2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut v12).push_next(&mut acceleration).push_next(&mut pipeline);
    // Safety: the extensions are supported by this physical device.
    unsafe { instance.get_physical_device_features2(physical, &mut features2) };
    v12.buffer_device_address == vk::TRUE && acceleration.acceleration_structure == vk::TRUE && pipeline.ray_tracing_pipeline == vk::TRUE
}

/// The device name `properties` report.
pub(crate) fn device_name(properties: &vk::PhysicalDeviceProperties) -> String {
    properties.device_name_as_c_str().map(|c| c.to_string_lossy().into_owned()).unwrap_or_default()
}

/// Picks the physical device: `choice` is an index or a name substring (case-insensitive);
/// without it, the best type (discrete, integrated, virtual, CPU).
pub(crate) fn choose_physical(instance: &ash::Instance, physicals: &[vk::PhysicalDevice], choice: Option<&str>) -> Result<vk::PhysicalDevice> {
    // Safety: each handle comes from this instance.
    let props: Vec<_> = physicals.iter().map(|&p| unsafe { instance.get_physical_device_properties(p) }).collect();
    let names: Vec<String> = props.iter().map(device_name).collect();
    let types: Vec<_> = props.iter().map(|p| p.device_type).collect();
    pick(&names, &types, choice).map(|i| physicals[i]).ok_or_else(|| {
        let listed = names.join(", ");
        match choice {
            Some(c) => Error::NoDevice(format!("GLRT_DEVICE={c} matches none of [{listed}]")),
            None => Error::NoDevice("no physical device".into()),
        }
    })
}

/// Index of the device to use among `names`/`types` (see [`choose_physical`]).
fn pick(names: &[String], types: &[vk::PhysicalDeviceType], choice: Option<&str>) -> Option<usize> {
    if let Some(choice) = choice.map(str::trim).filter(|c| !c.is_empty()) {
        if let Ok(index) = choice.parse::<usize>() {
            return (index < names.len()).then_some(index);
        }
        let lower = choice.to_lowercase();
        return names.iter().position(|n| n.to_lowercase().contains(&lower));
    }
    let rank = |t: vk::PhysicalDeviceType| match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => 3,
        _ => 4,
    };
    (0..names.len()).min_by_key(|&i| rank(types[i]))
}

/// The first depth/stencil format usable as an attachment and a transfer source.
fn depth_format(instance: &ash::Instance, physical: vk::PhysicalDevice) -> vk::Format {
    let wanted = vk::FormatFeatureFlags::DEPTH_STENCIL_ATTACHMENT | vk::FormatFeatureFlags::TRANSFER_SRC;
    [vk::Format::D24_UNORM_S8_UINT, vk::Format::D32_SFLOAT_S8_UINT]
        .into_iter()
        .find(|&f| {
            // Safety: valid physical device.
            let p = unsafe { instance.get_physical_device_format_properties(physical, f) };
            p.optimal_tiling_features.contains(wanted)
        })
        .unwrap_or(vk::Format::D32_SFLOAT_S8_UINT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn prefers_a_gpu_over_the_cpu() {
        let types = [vk::PhysicalDeviceType::CPU, vk::PhysicalDeviceType::INTEGRATED_GPU, vk::PhysicalDeviceType::DISCRETE_GPU];
        assert_eq!(pick(&names(&["llvmpipe", "Intel", "NVIDIA H100"]), &types, None), Some(2));
        assert_eq!(pick(&names(&["llvmpipe", "Intel"]), &types[..2], None), Some(1));
    }

    #[test]
    fn glrt_device_selects_by_index_or_name() {
        let types = [vk::PhysicalDeviceType::DISCRETE_GPU, vk::PhysicalDeviceType::CPU];
        let list = names(&["NVIDIA H100", "llvmpipe (LLVM 15)"]);
        assert_eq!(pick(&list, &types, Some("1")), Some(1));
        assert_eq!(pick(&list, &types, Some("LLVMpipe")), Some(1));
        assert_eq!(pick(&list, &types, Some("7")), None);
        assert_eq!(pick(&list, &types, Some("radeon")), None);
    }
}
