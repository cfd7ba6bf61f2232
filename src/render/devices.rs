//! The Vulkan devices of this machine as glrt sees them (`glrt info`, `glrt run`): for each
//! physical device its name, type and memory, the features glrt's choices depend on
//! (ray-tracing pipeline, acceleration structures, BC textures), whether glrt can draw on it,
//! which one `GLRT_DEVICE` chooses, and the mode and tracer it would get under this
//! process's `GLRT_MODE` (the choice [`super::default_sink`] makes).

use ash::vk;

use super::raster::{device, instance};

/// One physical device.
#[derive(Clone, Debug)]
pub struct DeviceReport {
    /// Its index in the enumeration (what `GLRT_DEVICE=N` names).
    pub index: usize,
    /// The driver's name for it.
    pub name: String,
    /// `discrete GPU`, `integrated GPU`, `virtual GPU`, `CPU` or `other`.
    pub kind: &'static str,
    /// The Vulkan version it supports, `major.minor.patch`.
    pub api_version: String,
    /// Bytes of its device-local memory heaps.
    pub device_memory: u64,
    /// `VK_KHR_ray_tracing_pipeline`.
    pub ray_tracing_pipeline: bool,
    /// `VK_KHR_acceleration_structure`.
    pub acceleration_structure: bool,
    /// `textureCompressionBC`: BC1-7 textures sampled as they are.
    pub bc_textures: bool,
    /// Whether `GLRT_DEVICE` (or, unset, the ranking by type) chooses it.
    pub chosen: bool,
    /// Why glrt cannot draw on it (`None`: it can).
    pub unusable: Option<String>,
    /// How frames would be rendered on it.
    pub rendering: Rendering,
}

/// How frames are rendered on a device, under this process's `GLRT_MODE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rendering {
    /// Everything rasterized; `by_default`: because the mode is unset and the device is a CPU.
    Raster {
        /// Chosen for a CPU device, `GLRT_MODE` being unset.
        by_default: bool,
    },
    /// The traced classes path traced by the named back end, the others rasterized.
    PathTrace {
        /// The ray-tracing back end and why ([`super::trace::backend_name`]).
        tracer: &'static str,
    },
    /// `GLRT_MODE` names no renderer: frames are not drawn.
    NotDrawn,
}

impl Rendering {
    /// The mode's name as `GLRT_MODE` spells it (`none` when frames are not drawn).
    pub fn mode(self) -> &'static str {
        match self {
            Rendering::Raster { .. } => "raster",
            Rendering::PathTrace { .. } => "pathtrace",
            Rendering::NotDrawn => "none",
        }
    }
}

impl std::fmt::Display for Rendering {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Rendering::Raster { by_default: true } => write!(f, "raster (a CPU device; GLRT_MODE=pathtrace traces at seconds per frame)"),
            Rendering::Raster { by_default: false } => write!(f, "raster"),
            Rendering::PathTrace { tracer } => write!(f, "pathtrace ({tracer})"),
            Rendering::NotDrawn => write!(f, "none (GLRT_MODE names no renderer: frames are not drawn)"),
        }
    }
}

/// Every physical device the Vulkan loader reports, in its order; the error says why there
/// is no list (no loader, no instance).
pub fn survey() -> Result<Vec<DeviceReport>, String> {
    let shared = instance::get().map_err(|e| e.to_string())?;
    let instance = &shared.raw;
    // Safety: valid instance.
    let physicals = unsafe { instance.enumerate_physical_devices() }.map_err(|e| format!("vkEnumeratePhysicalDevices failed: {e}"))?;
    let choice = std::env::var("GLRT_DEVICE").ok();
    let chosen = device::choose_physical(instance, &physicals, choice.as_deref()).ok();
    let reports = physicals.iter().enumerate().map(|(index, &physical)| {
        // Safety: each handle comes from this instance.
        let (properties, memory, features, extensions) = unsafe {
            (
                instance.get_physical_device_properties(physical),
                instance.get_physical_device_memory_properties(physical),
                instance.get_physical_device_features(physical),
                instance.enumerate_device_extension_properties(physical).unwrap_or_default(),
            )
        };
        let has = |name: &std::ffi::CStr| extensions.iter().any(|e| e.extension_name_as_c_str() == Ok(name));
        let heaps = &memory.memory_heaps[..memory.memory_heap_count as usize];
        let v = properties.api_version;
        DeviceReport {
            index,
            name: device::device_name(&properties),
            kind: kind_name(properties.device_type),
            api_version: format!("{}.{}.{}", vk::api_version_major(v), vk::api_version_minor(v), vk::api_version_patch(v)),
            device_memory: heaps.iter().filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL)).map(|h| h.size).sum(),
            ray_tracing_pipeline: has(ash::khr::ray_tracing_pipeline::NAME),
            acceleration_structure: has(ash::khr::acceleration_structure::NAME),
            bc_textures: features.texture_compression_bc == vk::TRUE,
            chosen: chosen == Some(physical),
            unusable: device::graphics_queue_family(instance, physical).err().map(|e| e.to_string()),
            rendering: super::rendering_on(properties.device_type, has(ash::khr::ray_tracing_pipeline::NAME) && has(ash::khr::acceleration_structure::NAME)),
        }
    });
    Ok(reports.collect())
}

fn kind_name(kind: vk::PhysicalDeviceType) -> &'static str {
    match kind {
        vk::PhysicalDeviceType::DISCRETE_GPU => "discrete GPU",
        vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated GPU",
        vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual GPU",
        vk::PhysicalDeviceType::CPU => "CPU",
        _ => "other",
    }
}
