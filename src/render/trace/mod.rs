//! Path tracing (`GLRT_MODE=pathtrace`): traces the traced classes of a [`Frame`] (static,
//! movable, dynamic draws, with the `Layer` draws over them) and hands the traced image and depth to the raster composite, which
//! draws the sky, translucent and overlay draws around it in program order (thesis 4.3.6).
//! [`crate::render::frame`] runs the stages: [`RayTracer::build`], [`RayTracer::trace`],
//! [`RayTracer::resolve`], then [`composite`].
//!
//! A ray-tracing back end implements [`RayTracer`]; [`backend`] chooses it for a device (one
//! place; with `tracer = "auto"` on a device that runs both, [`auto`] measures them). The
//! compute one, [`compute`], BVH traversal in compute shaders, runs on every Vulkan 1.2
//! device, lavapipe included (DESIGN.md, "Ray tracing back ends"); the hardware one
//! ([`hardware`], `VK_KHR_ray_tracing_pipeline`) goes beside it, reading the same [`GpuScene`]
//! and writing the same G-buffer, radiance and output layouts (`shaders/trace/gbuffer.glsl`).
//!
//! Space: rays are traced in the **eye space of the current frame** (camera at the origin,
//! looking down −z, as OpenGL's modelview leaves it). Each traced draw is an instance whose
//! object-to-eye transform is its modelview; geometry stays in object space in its bottom-level
//! acceleration structure, reused across frames by geometry key; the top level over the
//! instances is rebuilt every frame. GL lights are stored in eye space already.
//!
//! Environment: a ray that leaves the scene sees the frame's `Sky` draws, rendered by the
//! raster pipelines into an eye-space cube map around the eye ([`sky`]); without sky draws,
//! the linear clear colour. The cube lights and is reflected in the traced surfaces; the sky
//! visible where primary rays miss stays the rasterized one (the composite leaves those
//! pixels to the framebuffer).
//!
//! The persistent static world of hash tracking is traced too ([`chunks`]): each chunk is an
//! instance of world-space triangles placed by the recovered view, built once, and traced
//! whether the program drew it this frame or not; the draws the chunks hold are left out.
//! A dynamic draw whose vertices moved refits its last BVH instead of building a new one
//! ([`tracks`], [`resident`]).
//!
//! Surfaces: a traced draw and the draws of class `Layer` over it (lightmap, detail, glow and
//! decal passes) are one traced surface ([`surfaces`]), evaluated as the rasterizer would draw
//! it and split into albedo, baked light and emission ([`material`]); layer draws are then not
//! rasterized. Emissive surfaces (additive passes, emissive materials) are also light sources
//! that next-event estimation samples ([`emitters`]). With radiosity on, a path's first
//! diffuse bounce on the static world reads radiosity's indirect light there and ends
//! ([`radiosity`]).
//!
//! Parts shared by the back ends:
//! - [`surfaces`]: which draws are traced, grouped into surfaces; [`scene`]: traced surfaces
//!   as geometries; [`material`]: their materials; [`chunks`]: the static world's chunks as
//!   geometries; [`instances`]: a frame's instances, surfaces and chunks; [`emitters`]: the
//!   emissive triangles and their alias table; [`lights`]: GL lights as physical lights;
//!   [`vertex_light`]: the direct light a vertex-lit model's colours hold, a light of its own;
//!   [`radiosity`]: radiosity's indirect light per corner of the static world's triangles;
//!   [`regions`]: the static world's chunks of a region traced as one bottom level (both
//!   back ends); [`sky`]: the sky draws as the environment cube map; [`sky_distribution`]: a
//!   distribution of directions by the sky's luminance, which next-event estimation samples
//!   (`shaders/trace/sky_sampling.glsl`); [`gpu_types`]: the structures the
//!   shaders read, checked against the compiled SPIR-V;
//!   [`shader_constants`]: flags and special values shared with the shaders as generated headers
//!   ([`crate::render::shader_abi`]).
//! - [`texels`]: every texture level the tracer samples, packed into one storage buffer (no
//!   descriptor indexing on lavapipe); `shaders/trace/texels.glsl` samples it.
//! - [`tracks`]: dynamic instances across frames (what their next shape refits).
//! - [`settings`]: `glrt.toml` `[pathtrace]` and `GLRT_*` settings.
//! - [`stats`]: rays traced by kind, traversal work and the tracing pass's GPU time.
//! - [`composite`]: the traced image drawn into the raster framebuffer with its depth.
//!
//! The compute back end:
//! - [`compute`]: the [`RayTracer`] implementation, one traced frame.
//! - [`bvh`]: bottom-level BVHs of triangle sets and the per-frame top-level BVH (CPU build,
//!   GPU layout, CPU traversal for tests); `shaders/trace/bvh.glsl` traverses them.
//! - [`resident`]: geometries and their BVHs on the GPU; [`pipelines`]: the compute pipelines;
//!   [`bindings`]: their descriptor bindings, shared with `shaders/trace/bindings.glsl`.

pub mod auto;
pub mod bindings;
pub mod bvh;
pub mod chunks;
pub mod composite;
pub mod compute;
pub mod emitters;
pub mod gpu_types;
pub mod hardware;
pub mod instances;
pub mod lights;
pub mod material;
pub mod pipelines;
pub mod radiosity;
pub mod regions;
pub mod resident;
pub mod scene;
pub mod settings;
pub mod shader_constants;
pub mod sky;
pub mod sky_distribution;
pub mod sky_selection;
pub mod stats;
pub mod surfaces;
pub mod texels;
pub mod tracks;
pub mod vertex_light;

use ash::vk;

use crate::frame::{Draw, Frame};
use crate::render::raster::device::{Device, Result};
use crate::render::raster::renderer::Recorder;
use crate::render::radiosity::stage::FrameIndirect;
use gpu_types::{GpuEmitter, GpuFrame, GpuInstance, GpuLight, GpuMaterial, GpuRadiosityTriangle};
use settings::Settings;
use surfaces::Surfaces;
use stats::Statistics;

/// A ray-tracing back end: turns the traced surfaces of a frame into a traced image,
/// recording into the frame's command buffer at the place of its first traced draw
/// ([`surfaces::Surfaces::first`]). The renderer calls [`RayTracer::build`], [`RayTracer::trace`]
/// and [`RayTracer::resolve`] in that order, once per frame; the denoiser
/// ([`crate::render::denoise`]) takes the place of `resolve`.
pub trait RayTracer: Send {
    /// Upload and acceleration structures: gathers the frame's traced surfaces, `surfaces`
    /// (`camera`, the first base, gives the projection and viewport), and the static world's
    /// chunks as instances, uploads new geometry and textures, builds or refits the
    /// bottom-level acceleration structures of new or moved geometry and the top level over
    /// the instances, and lists the emissive triangles; with radiosity's `indirect` light, the
    /// static world's triangles get its values ([`radiosity`]). Returns the records the
    /// tracing shaders read.
    fn build(&mut self, rec: &mut Recorder<'_>, frame: &Frame, surfaces: &Surfaces, camera: &Draw, indirect: Option<&FrameIndirect>) -> Result<GpuScene>;

    /// Traces `scene` into the G-buffer (primary hits) and the radiance accumulated for this
    /// frame; `None` when nothing could be traced (no geometry on the GPU yet).
    fn trace(&mut self, rec: &mut Recorder<'_>, scene: &GpuScene) -> Result<Option<Radiance>>;

    /// Resolves `radiance` into the image to composite: the temporal filter over the frames
    /// before, exposure and tone mapping, and each pixel's depth.
    fn resolve(&mut self, rec: &mut Recorder<'_>, radiance: Radiance) -> Result<TracedImage>;

    /// Rays, traversal work, scenes and frames traced so far.
    fn statistics(&self) -> &Statistics;

    /// The back end's name: `hardware` or `compute`.
    fn name(&self) -> &'static str;

    /// Frees the back end's GPU objects (the GPU must be idle); its statistics are final then.
    fn destroy(&mut self, device: &Device);
}

/// A frame's scene as the tracing shaders of every back end read it ([`gpu_types`]): camera,
/// sizes and settings, then instances, materials and lights. The acceleration structures over
/// the instances are the back end's own.
pub struct GpuScene {
    /// Camera, sizes and settings.
    pub frame: GpuFrame,
    /// One per traced draw or static-world chunk.
    pub instances: Vec<GpuInstance>,
    /// One per instance.
    pub materials: Vec<GpuMaterial>,
    /// The frame's GL lights as physical lights.
    pub lights: Vec<GpuLight>,
    /// The emissive triangles that next-event estimation samples ([`emitters`]).
    pub emitters: Vec<GpuEmitter>,
    /// The sky's distribution of directions, per cell its probability and cumulative
    /// probability ([`sky_distribution::SkyDistribution::cells`]; empty: the sky is not
    /// sampled), followed by last frame's cells where the frame's `sampling[1]` is above 0.
    pub sky_cells: Vec<[f32; 2]>,
    /// Radiosity's indirect light at the corners of the static world's triangles
    /// ([`radiosity`]; empty without radiosity).
    pub radiosity: Vec<GpuRadiosityTriangle>,
    /// Deforming meshes' last-frame triangles ([`resident::Resident::previous`]), each mesh's
    /// from its instance's `previous_triangles` on.
    pub previous_triangles: Vec<bvh::GpuTriangle>,
}

/// A traced frame's G-buffer and radiance, in the back end's per-pixel buffers until
/// [`RayTracer::resolve`] turns them into a [`TracedImage`].
pub struct Radiance {
    /// The traced size (the window's, times the resolution scale).
    pub size: [u32; 2],
    /// The back end's descriptor set of the frame (its buffers and the frame's records).
    set: vk::DescriptorSet,
    /// The G-buffer and lighting channels (`GSample` of `shaders/trace/samples.glsl`), one
    /// per traced pixel, for the denoiser.
    pub gbuffer: vk::Buffer,
    /// The buffer the resolve (or the denoiser) writes the image into (`OutputSample`).
    pub output: vk::Buffer,
}

/// The image a back end traced and resolved: per pixel of `size` (row 0 the bottom, as GL
/// has it) the tone-mapped colour and the window depth of the primary hit, 1 where the ray
/// missed (`OutputSample` of `shaders/trace/gbuffer.glsl`). [`composite`] draws it.
pub struct TracedImage {
    /// The traced size.
    pub size: [u32; 2],
    /// The per-pixel samples, readable by fragment shaders and the host.
    pub output: vk::Buffer,
}

/// Whether [`backend`] makes the hardware tracer for a device with (`true`) or without
/// [`Device::ray_tracing`] under `tracer` (with `auto`, at least for its trial).
pub fn uses_hardware(ray_tracing: bool, tracer: settings::Tracer) -> bool {
    ray_tracing && tracer != settings::Tracer::Compute
}

/// The back end [`backend`] makes for a device with or without [`Device::ray_tracing`] (`glrt
/// info`, the HUD), and why; `remembered`: the choice [`auto`] remembered for the device and
/// program (`Some(true)`: hardware).
pub fn backend_name(ray_tracing: bool, tracer: settings::Tracer, remembered: Option<bool>) -> &'static str {
    match (uses_hardware(ray_tracing, tracer), tracer, remembered) {
        (true, settings::Tracer::Auto, Some(true)) => "hardware tracer: measured faster than the compute tracer on this device for this program (remembered)",
        (true, settings::Tracer::Auto, Some(false)) => "compute tracer: measured faster than the hardware tracer on this device for this program (remembered)",
        (true, settings::Tracer::Auto, None) => {
            "auto: the device has VK_KHR_ray_tracing_pipeline; a program's first frames trace with both tracers and keep the one whose tracing pass is faster (remembered per device and program in ~/.cache/glrt/tracers)"
        }
        (true, _, _) => "hardware tracer: tracer = \"hardware\"",
        (false, settings::Tracer::Compute, _) => "compute tracer: tracer = \"compute\"",
        (false, _, _) => "compute tracer: the device has no VK_KHR_ray_tracing_pipeline",
    }
}

/// The ray-tracing back end for `device`, with `settings`, for `frames_in_flight` frames in
/// flight: the compute tracer ([`compute`]) on a device without [`Device::ray_tracing`] or
/// with `tracer = "compute"`; the hardware tracer ([`hardware`]) with `tracer = "hardware"`;
/// with `auto`, the back end [`auto`] remembered for the device and this program, else a
/// [`auto::Trial`] of both. A hardware tracer that cannot be made (a driver refusing the
/// pipeline) falls back to the compute one with a message.
pub fn backend(device: &Device, settings: Settings, frames_in_flight: usize) -> Result<Box<dyn RayTracer>> {
    let hardware = uses_hardware(device.ray_tracing, settings.tracer);
    if settings.tracer == settings::Tracer::Hardware && !hardware {
        crate::render::raster::renderer::log_once("tracer = \"hardware\": the device has no VK_KHR_ray_tracing_pipeline; tracing with compute shaders");
    }
    let compute = || -> Result<Box<dyn RayTracer>> { Ok(Box::new(compute::ComputeTracer::new(device, settings, frames_in_flight, false)?)) };
    if !hardware {
        return compute();
    }
    let (choices, key) = (auto::Choices::of_user(), auto::choice_key(&device.properties, &auto::program()));
    let remembered = (settings.tracer == settings::Tracer::Auto).then(|| choices.get(&key)).flatten();
    if remembered == Some(false) {
        log::info!("glrt: {}", backend_name(true, settings.tracer, remembered));
        return compute();
    }
    let tracer = match compute::ComputeTracer::new(device, settings, frames_in_flight, true) {
        Ok(tracer) => tracer,
        Err(e) => {
            log::warn!("glrt: the hardware ray tracer could not be made ({e}); tracing with compute shaders");
            return compute();
        }
    };
    if settings.tracer == settings::Tracer::Hardware || remembered == Some(true) {
        if remembered.is_some() {
            log::info!("glrt: {}", backend_name(true, settings.tracer, remembered));
        }
        return Ok(Box::new(tracer));
    }
    match compute() {
        Ok(other) => Ok(Box::new(auto::Trial::new(Box::new(tracer), other, choices, key))),
        Err(e) => {
            let mut tracer = tracer;
            tracer.destroy(device);
            Err(e)
        }
    }
}
