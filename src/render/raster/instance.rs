//! The process's Vulkan instance: the loader (`libvulkan.so.1`, opened at run time) and one
//! `VkInstance`, created on first use and kept until the process ends; every renderer makes
//! its device from it ([`super::device::Device::new`]). It has the X11 surface extensions when
//! present, and the validation layer with a messenger when `GLRT_VALIDATE=1` and the layer is
//! installed.
//!
//! Why one, never destroyed: a program with GL contexts on several threads makes several
//! renderers at once. NVIDIA's driver races when instances are created on several threads
//! (crashes: gfx-rs/wgpu#5930, kvark/blade#336), and the loader unloads the driver at the last
//! `vkDestroyInstance`, so renderers made and dropped one after another (test threads, a
//! program opening and closing windows) loaded and unloaded the whole driver each time, while
//! other threads used it (issue 18: intermittent hangs with several renderers on NVIDIA). For
//! the same reason the creation of devices is serialised ([`lock_devices`]).
//!
//! Devices are not destroyed either while the process runs: a renderer that ends gives its idle
//! `VkDevice` back ([`give_back_device`]) and the next renderer on the same physical device takes
//! it ([`take_device`]). Measured on an NVIDIA H200 (driver of the GPU machine, issue 18):
//! `vkDestroyDevice` on one thread deadlocked inside the driver with `vkDestroyImage` and
//! `vkBindImageMemory` of other devices on other threads (all waiting on one driver lock,
//! stacks taken with `eu-stack`), in 3 of 5 runs of the raster tests with 4 test threads. The
//! pool holds at most as many devices as renderers ever lived at once. Nothing else is shared
//! between renderers (each has its own device while it lives, queue, allocator and caches).

use std::ffi::CStr;
use std::sync::OnceLock;

use ash::vk;
use parking_lot::{Mutex, MutexGuard};

use super::device::{Check, Error, Result};

/// The loader and the instance.
pub struct Instance {
    /// The loader.
    pub entry: ash::Entry,
    /// The instance.
    pub raw: ash::Instance,
    /// Whether [`SURFACE_EXTENSIONS`] are enabled: devices can present to X11 windows.
    pub surfaces: bool,
    /// The validation messenger (`GLRT_VALIDATE=1`), alive as long as the instance.
    _messenger: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
}

/// The process's instance, or why there is none (said to every caller).
static INSTANCE: OnceLock<Result<Instance>> = OnceLock::new();

/// Serialises `vkCreateDevice` and `vkDestroyDevice` across renderers.
static DEVICES: Mutex<()> = Mutex::new(());

/// The process's instance, made on the first call (opening the loader).
pub fn get() -> Result<&'static Instance> {
    INSTANCE.get_or_init(create).as_ref().map_err(Error::clone)
}

/// Held while a device is created or destroyed.
pub fn lock_devices() -> MutexGuard<'static, ()> {
    DEVICES.lock()
}

/// An idle logical device no renderer uses: every object made from it was destroyed and its
/// memory freed.
pub struct IdleDevice {
    /// The physical device it was made on.
    pub physical: vk::PhysicalDevice,
    /// The logical device.
    pub raw: ash::Device,
}

/// Devices given back by renderers that ended, for the next ones.
static IDLE_DEVICES: Mutex<Vec<IdleDevice>> = Mutex::new(Vec::new());

/// An idle device made on `physical`, if a renderer gave one back.
pub fn take_device(physical: vk::PhysicalDevice) -> Option<ash::Device> {
    let mut idle = IDLE_DEVICES.lock();
    let at = idle.iter().position(|d| d.physical == physical)?;
    Some(idle.swap_remove(at).raw)
}

/// Keeps an idle device for [`take_device`] instead of destroying it (see the module doc).
pub fn give_back_device(device: IdleDevice) {
    IDLE_DEVICES.lock().push(device);
}

/// Opens the loader and creates the instance.
fn create() -> Result<Instance> {
    // Safety: loading libvulkan runs its initialisers; it is the system's Vulkan loader.
    let entry = unsafe { ash::Entry::load() }.map_err(|e| Error::NoLoader(e.to_string()))?;
    let (raw, enabled) = create_instance(&entry)?;
    let messenger = enabled.validate.then(|| create_messenger(&entry, &raw)).flatten();
    Ok(Instance { entry, raw, surfaces: enabled.surfaces, _messenger: messenger })
}

/// The name of the validation layer.
const VALIDATION: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Creates the instance, with the X11 surface extensions when present, and the validation
/// layer and debug utils when `GLRT_VALIDATE=1` and the layer is installed.
fn create_instance(entry: &ash::Entry) -> Result<(ash::Instance, Enabled)> {
    let name = c"glrt";
    let app = vk::ApplicationInfo::default().application_name(name).engine_name(name).api_version(vk::API_VERSION_1_3);
    let mut layers: Vec<*const std::ffi::c_char> = Vec::new();
    // Safety: valid entry.
    let available = unsafe { entry.enumerate_instance_extension_properties(None) }.unwrap_or_default();
    let mut extensions: Vec<*const std::ffi::c_char> = SURFACE_EXTENSIONS
        .iter()
        .filter(|want| available.iter().any(|e| e.extension_name_as_c_str() == Ok(**want)))
        .map(|e| e.as_ptr())
        .collect();
    let surfaces = extensions.len() == SURFACE_EXTENSIONS.len();
    if !surfaces {
        extensions.clear();
    }
    if std::env::var("GLRT_VALIDATE").is_ok_and(|v| v == "1") {
        // Safety: valid entry.
        let available = unsafe { entry.enumerate_instance_layer_properties() }.unwrap_or_default();
        if available.iter().any(|l| l.layer_name_as_c_str() == Ok(VALIDATION)) {
            layers.push(VALIDATION.as_ptr());
            extensions.push(ash::ext::debug_utils::NAME.as_ptr());
        } else {
            eprintln!("glrt: GLRT_VALIDATE=1 but {VALIDATION:?} is not installed");
        }
    }
    let info = vk::InstanceCreateInfo::default().application_info(&app).enabled_layer_names(&layers).enabled_extension_names(&extensions);
    // Safety: valid create info.
    let instance = unsafe { entry.create_instance(&info, None) }.check("vkCreateInstance")?;
    Ok((instance, Enabled { validate: !layers.is_empty(), surfaces }))
}

/// What [`create_instance`] enabled.
#[derive(Clone, Copy)]
struct Enabled {
    /// The validation layer and debug utils.
    validate: bool,
    /// [`SURFACE_EXTENSIONS`].
    surfaces: bool,
}

/// Instance extensions for presenting to X11 windows, enabled together when all are present.
const SURFACE_EXTENSIONS: [&CStr; 2] = [ash::khr::surface::NAME, ash::khr::xlib_surface::NAME];

/// A messenger printing validation warnings and errors to stderr.
fn create_messenger(entry: &ash::Entry, instance: &ash::Instance) -> Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)> {
    let utils = ash::ext::debug_utils::Instance::new(entry, instance);
    let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR)
        .message_type(vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION)
        .pfn_user_callback(Some(validation_message));
    // Safety: debug utils is enabled on the instance.
    let messenger = unsafe { utils.create_debug_utils_messenger(&info, None) }.ok()?;
    Some((utils, messenger))
}

/// Prints a validation message. Called by the layer from C: catches panics.
unsafe extern "system" fn validation_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    _user: *mut std::ffi::c_void,
) -> vk::Bool32 {
    if std::thread::panicking() {
        return vk::FALSE;
    }
    let _ = std::panic::catch_unwind(|| {
        // Safety: the layer passes valid callback data for the duration of the call.
        let message = unsafe { data.as_ref().and_then(|d| d.message_as_c_str()) };
        let text = message.map(|m| m.to_string_lossy().into_owned()).unwrap_or_default();
        eprintln!("glrt: Vulkan validation ({severity:?}): {text}");
    });
    vk::FALSE
}
