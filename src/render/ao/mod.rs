//! Screen-space ambient occlusion for raster mode (seed 000, issue 23): after the opaque 3D
//! draws of a frame, the occlusion of every pixel from the depth buffer, blurred, multiplies
//! the framebuffer's colour. [`settings`] reads `[ao]`; the passes are `shaders/ao/`.
//!
//! The passes, one frame ([`AmbientOcclusion::record`]):
//! 1. the depth buffer is copied into a storage buffer (resolved first when multisampled);
//! 2. `ssao.comp`: per pixel the eye-space position (depth and the camera draw's projection:
//!    the seed's G-buffer of view-space positions, which the depth buffer determines) and the
//!    normal (from the nearer neighbour on each axis, the seed's normal buffer taken from the
//!    same depth); a kernel of m samples in the tangent-space hemisphere (denser near the
//!    centre), rotated per pixel by a 4 × 4 tile of random vectors (Gram–Schmidt), scaled by
//!    the radius R; a sample counts as occluded where the depth buffer's surface lies in front
//!    of it by more than the bias δ, with a range check so that far surfaces do not darken
//!    edges; the result is the unoccluded fraction `1 − occlusion / m`. The depth a sample
//!    meets is its pixel's carried to the sample's own window point along the centre pixel's
//!    depth gradient (exact on a plane), not the pixel centre's: far away at a grazing angle
//!    one pixel spans more depth than δ, and that darkened open floors;
//! 3. `blur.comp`: the N × N box blur of the seed, which removes the noise tile's pattern;
//! 4. `apply.frag`: the colour multiplied by the blurred fraction (blending `ZERO, SRC_COLOR`).
//!
//! Alpha-tested draws discarded their transparent texels from the depth buffer already, as the
//! seed's alpha maps do.
//!
//! What it multiplies: the seed multiplies the ambient term of a deferred renderer. GL 1.x
//! games have no separate ambient term: their light is baked into lightmaps (a multiplying
//! pass or texture unit) and into per-vertex colours computed on the CPU, and both hold the
//! level's ambient and bounced light, which occlusion is about; fixed-function `glLight`
//! lighting is evaluated per vertex with its ambient, diffuse and specular summed before
//! rasterization. So the factor multiplies the lit colour of the opaque 3D surfaces after all
//! their passes (lightmap and detail layers included), and nothing drawn after them: glass,
//! effects, the HUD. For `glLight`-lit surfaces this also darkens the direct light in creases,
//! the usual compromise of forward renderers that apply SSAO after shading.
//!
//! On GPUs the four passes are timed ([`crate::render::pass_times`]: depth copy (with the
//! resolve of a multisampled depth buffer), kernel, blur, apply); [`AmbientOcclusion::destroy`] logs their average GPU time per frame at
//! `GLRT_LOG=info`.
//!
//! Where: after the last draw of an opaque 3D class (static, movable, dynamic, layer, light
//! passes; in a frame read back before its end, which is not classified yet, the unblended
//! perspective draws) in program order, once per frame (a frame read back past that place
//! before its end keeps what the read-back drew); the camera is the first such draw's projection,
//! viewport and depth range. Path-traced frames get none (their occlusion comes from the
//! traced rays).

pub mod settings;

use std::collections::HashMap;

use ash::vk;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::frame::class::{DrawClass, orthographic};
use crate::frame::{Draw, Frame};
use crate::render::pass_layout::PassLayout;
use crate::render::pass_times::PassTimes;
use crate::render::raster::commands::SetKey;
use crate::render::raster::device::{Buffer, Device, Result};
use crate::render::raster::pipelines::shader_module;
use crate::render::raster::renderer::Recorder;
use crate::render::raster::target::Plane;
use crate::render::trace::composite::full_screen_pipeline;
use crate::render::trace::pipelines::{completed, compute_pipeline};
use settings::AoSettings;

/// Kernel samples the block holds at most (`AO_MAX_SAMPLES` of `shaders/ao/params.glsl`).
pub const MAX_SAMPLES: usize = 256;

/// `AoParams` of `shaders/ao/params.glsl` (std430).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuAoParams {
    /// The camera draw's projection (eye → clip).
    pub projection: [[f32; 4]; 4],
    /// Its inverse (GL normalized device coordinates → eye).
    pub inverse_projection: [[f32; 4]; 4],
    /// The camera draw's viewport: x, y, width, height (GL window pixels).
    pub viewport: [f32; 4],
    /// `glDepthRange` near and far, radius R, bias δ.
    pub shape: [f32; 4],
    /// Framebuffer width and height, samples m, depth encoding (0: f32, 1: 24-bit unorm).
    pub sizes: [u32; 4],
    /// N of the N × N blur.
    pub blur: [u32; 4],
    /// The 4 × 4 noise tile (tangent-plane vectors, z = 0).
    pub noise: [[f32; 4]; 16],
    /// The hemisphere kernel (tangent space, z ≥ 0).
    pub kernel: [[f32; 4]; MAX_SAMPLES],
}

include!(concat!(env!("OUT_DIR"), "/layouts/ao_gpu_types.rs"));

/// Push constants of `apply.frag`: the framebuffer size.
const APPLY_PUSH_BYTES: u32 = 8;

/// The passes timed, in order.
const STEPS: [&str; 4] = ["depth copy", "kernel", "blur", "apply"];

/// A deterministic pseudo-random sequence in [0, 1) (the kernel and noise are the same in
/// every run, so images are reproducible).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The seed's kernel of `m` samples: random directions in the upper hemisphere (z ≥ 0) at
/// random lengths in [0, 1], scaled by `lerp(0.1, 1, (i / m)²)` so that more of them lie near
/// the centre.
pub fn kernel(m: usize) -> Vec<[f32; 4]> {
    let mut rng = Lcg(0xa0_5eed);
    (0..m)
        .map(|i| {
            let d = Vec3::new(rng.next() * 2.0 - 1.0, rng.next() * 2.0 - 1.0, rng.next()).normalize_or(Vec3::Z);
            let t = i as f32 / m as f32;
            let v = d * rng.next() * (0.1 + 0.9 * t * t);
            [v.x, v.y, v.z, 0.0]
        })
        .collect()
}

/// The 4 × 4 tile of random rotation vectors in the tangent plane.
fn noise() -> [[f32; 4]; 16] {
    let mut rng = Lcg(0x4015e);
    std::array::from_fn(|_| [rng.next() * 2.0 - 1.0, rng.next() * 2.0 - 1.0, 0.0, 0.0])
}

/// Whether `draw` is an opaque 3D surface, the kind occlusion applies to: of a traced class,
/// or in a frame read back before its end (not classified yet), unblended with a perspective
/// projection.
pub fn occluded(draw: &Draw) -> bool {
    match draw.class {
        DrawClass::Static | DrawClass::Movable | DrawClass::Dynamic | DrawClass::Layer | DrawClass::Light => true,
        DrawClass::Unclassified => draw.state.blend.is_none() && !orthographic(&draw.projection),
        _ => false,
    }
}

/// Where in `frame` the occlusion goes: after its last opaque 3D draw (a draw index, possibly
/// the end), and the camera (its first opaque 3D draw); `None` without such draws.
pub fn place(frame: &Frame) -> Option<(usize, &Draw)> {
    let last = frame.draws.iter().rposition(occluded)?;
    let camera = frame.draws.iter().find(|d| occluded(d))?;
    Some((last + 1, camera))
}

/// The per-pixel buffers of one framebuffer size.
struct Buffers {
    size: [u32; 2],
    depth: Buffer,
    raw: Buffer,
    blurred: Buffer,
}

/// The ambient occlusion stage: its settings, kernel, pipelines and buffers.
pub struct AmbientOcclusion {
    settings: AoSettings,
    kernel: Vec<[f32; 4]>,
    noise: [[f32; 4]; 16],
    /// Compute passes: binding 0 the parameters, 1 the input, 2 the output (dynamic storage
    /// buffers, so the frame's descriptor sets hold them).
    compute_layout: PassLayout,
    ssao: vk::Pipeline,
    blur: vk::Pipeline,
    /// The apply pass: binding 0 the blurred fraction.
    apply_layout: PassLayout,
    vertex: vk::ShaderModule,
    fragment: vk::ShaderModule,
    /// One apply pipeline per sample count of the framebuffer.
    apply: HashMap<u32, vk::Pipeline>,
    buffers: Option<Buffers>,
    /// The passes' GPU times (`None`: not timed).
    times: Option<PassTimes>,
}

impl AmbientOcclusion {
    /// Creates the stage's layouts and pipelines for `settings`.
    pub fn new(device: &Device, settings: AoSettings) -> Result<AmbientOcclusion> {
        let compute_layout = PassLayout::new(device, &PassLayout::dynamic_storage(3), vk::ShaderStageFlags::COMPUTE, 0)?;
        let apply_layout = match PassLayout::new(device, &PassLayout::dynamic_storage(1), vk::ShaderStageFlags::FRAGMENT, APPLY_PUSH_BYTES) {
            Ok(l) => l,
            Err(e) => {
                compute_layout.destroy(device);
                return Err(e);
            }
        };
        let stage = AmbientOcclusion {
            settings,
            kernel: kernel(settings.samples as usize),
            noise: noise(),
            compute_layout,
            ssao: vk::Pipeline::null(),
            blur: vk::Pipeline::null(),
            apply_layout,
            vertex: vk::ShaderModule::null(),
            fragment: vk::ShaderModule::null(),
            apply: HashMap::new(),
            buffers: None,
            times: None,
        };
        let make = |stage: &mut AmbientOcclusion| {
            stage.ssao = compute_pipeline(device, compute_layout.pipeline, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ao/ssao.comp.spv")))?;
            stage.blur = compute_pipeline(device, compute_layout.pipeline, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ao/blur.comp.spv")))?;
            stage.vertex = shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/trace_composite.vert.spv")))?;
            stage.fragment = shader_module(device, include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ao/apply.frag.spv")))?;
            stage.times = PassTimes::new(device, "ambient occlusion", &STEPS)?;
            Ok(())
        };
        completed(device, stage, make, AmbientOcclusion::destroy)
    }

    /// The parameters of a frame whose camera is `camera`, in a framebuffer of `size`.
    fn params(&self, device: &Device, camera: &Draw, size: [u32; 2]) -> GpuAoParams {
        let mut p = GpuAoParams::zeroed();
        p.projection = camera.projection.to_cols_array_2d();
        p.inverse_projection = camera.projection.inverse().to_cols_array_2d();
        p.viewport = camera.state.viewport.map(|v| v as f32);
        let [near, far] = camera.state.depth_range.map(|d| d as f32);
        p.shape = [near, far, self.settings.radius, self.settings.bias];
        let unorm24 = u32::from(device.depth_format == vk::Format::D24_UNORM_S8_UINT);
        p.sizes = [size[0], size[1], self.kernel.len() as u32, unorm24];
        p.blur = [self.settings.blur, 0, 0, 0];
        p.noise = self.noise;
        p.kernel[..self.kernel.len()].copy_from_slice(&self.kernel);
        p
    }

    /// The buffers for a framebuffer of `size` (made again when the size changed; the GPU
    /// must be done with the old ones, which a new size guarantees: the renderer waits for the
    /// device before it makes a target of a new size).
    fn buffers(&mut self, device: &Device, size: [u32; 2]) -> Result<&Buffers> {
        if self.buffers.as_ref().is_some_and(|b| b.size != size) {
            if let Some(old) = self.buffers.take() {
                for b in [old.depth, old.raw, old.blurred] {
                    device.destroy_buffer(b);
                }
            }
        }
        if self.buffers.is_none() {
            let bytes = size[0] as u64 * size[1] as u64 * 4;
            let [depth, raw, blurred] = device.create_storage_buffers([("glrt ao depth", bytes), ("glrt ao raw", bytes), ("glrt ao blurred", bytes)])?;
            self.buffers = Some(Buffers { size, depth, raw, blurred });
        }
        Ok(self.buffers.as_ref().expect("made above"))
    }

    /// Records the passes of the module doc into `rec`'s framebuffer, whose opaque 3D draws
    /// are recorded, with the projection of `camera`.
    pub fn record(&mut self, rec: &mut Recorder<'_>, camera: &Draw) -> Result<()> {
        let size = rec.target.size;
        let device = rec.device;
        let params = self.params(device, camera, size);
        let (depth, raw, blurred) = {
            let b = self.buffers(device, size)?;
            (b.depth.raw, b.raw.raw, b.blurred.raw)
        };
        let bytes = size[0] as u64 * size[1] as u64 * 4;
        let align = device.properties.limits.min_storage_buffer_offset_alignment.max(16);
        let params = rec.ring.push(device, bytemuck::bytes_of(&params), align)?;
        let params_bytes = size_of::<GpuAoParams>() as u64;
        let ssao_set = rec.descriptors.get(device, &SetKey { layout: self.compute_layout.set, buffers: &[(params.buffer, params_bytes), (depth, bytes), (raw, bytes)], images: &[] })?;
        let blur_set = rec.descriptors.get(device, &SetKey { layout: self.compute_layout.set, buffers: &[(params.buffer, params_bytes), (raw, bytes), (blurred, bytes)], images: &[] })?;
        let apply_set = rec.descriptors.get(device, &SetKey { layout: self.apply_layout.set, buffers: &[(blurred, bytes)], images: &[] })?;
        let pipeline = self.apply_pipeline(device, rec.target.samples)?;
        let (d, cmd) = (&device.raw, rec.cmd);
        let stamps = self.times.as_mut().and_then(|t| t.frame(device, rec.slot()));
        let stamp = |k: u32, stage: vk::PipelineStageFlags2| {
            if let Some(stamps) = stamps {
                stamps.write(device, cmd, k, stage);
            }
        };

        rec.end_rendering();
        stamp(0, vk::PipelineStageFlags2::ALL_COMMANDS);
        let image = rec.target.readable(device, cmd, Plane::DepthStencil);
        let layers = vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::DEPTH, mip_level: 0, base_array_layer: 0, layer_count: 1 };
        let copy = vk::BufferImageCopy { image_subresource: layers, image_extent: vk::Extent3D { width: size[0], height: size[1], depth: 1 }, ..Default::default() };
        let groups = [size[0].div_ceil(8), size[1].div_ceil(8)];
        let offsets = [params.offset as u32, 0, 0];
        let compute = vk::PipelineStageFlags2::COMPUTE_SHADER;
        // Safety: outside a rendering pass; the image is in TRANSFER_SRC_OPTIMAL and as large
        // as the buffers; every handle lives until the frame finishes.
        unsafe { d.cmd_copy_image_to_buffer(cmd, image, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, depth, &[copy]) };
        stamp(1, vk::PipelineStageFlags2::ALL_TRANSFER);
        barrier(device, cmd, vk::PipelineStageFlags2::ALL_TRANSFER, vk::AccessFlags2::TRANSFER_WRITE, compute);
        for (k, (pipeline, set)) in [(self.ssao, ssao_set), (self.blur, blur_set)].into_iter().enumerate() {
            // Safety: as above.
            unsafe {
                d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
                d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, self.compute_layout.pipeline, 0, &[set], &offsets);
                d.cmd_dispatch(cmd, groups[0], groups[1], 1);
            }
            stamp(k as u32 + 2, compute);
            barrier(device, cmd, compute, vk::AccessFlags2::SHADER_STORAGE_WRITE, if k == 0 { compute } else { vk::PipelineStageFlags2::FRAGMENT_SHADER });
        }
        rec.begin_rendering();
        let [w, h] = size;
        // Safety: inside the rendering pass on the framebuffer; the buffers were made readable
        // by fragment shaders above.
        unsafe {
            d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::GRAPHICS, pipeline);
            d.cmd_set_viewport(cmd, 0, &[vk::Viewport { x: 0.0, y: 0.0, width: w as f32, height: h as f32, min_depth: 0.0, max_depth: 1.0 }]);
            d.cmd_set_scissor(cmd, 0, &[vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width: w, height: h } }]);
            d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::GRAPHICS, self.apply_layout.pipeline, 0, &[apply_set], &[0]);
            d.cmd_push_constants(cmd, self.apply_layout.pipeline, vk::ShaderStageFlags::FRAGMENT, 0, bytemuck::cast_slice(&size));
            d.cmd_draw(cmd, 3, 1, 0, 0);
        }
        rec.forget_state();
        stamp(4, vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT);
        Ok(())
    }

    /// The apply pipeline for `samples` samples: colour multiplied by the source (blending
    /// `ZERO, SRC_COLOR`, rgb only), no depth test or write.
    fn apply_pipeline(&mut self, device: &Device, samples: u32) -> Result<vk::Pipeline> {
        if let Some(&p) = self.apply.get(&samples) {
            return Ok(p);
        }
        let depth = vk::PipelineDepthStencilStateCreateInfo::default();
        let attachment = vk::PipelineColorBlendAttachmentState::default()
            .blend_enable(true)
            .src_color_blend_factor(vk::BlendFactor::ZERO)
            .dst_color_blend_factor(vk::BlendFactor::SRC_COLOR)
            .color_blend_op(vk::BlendOp::ADD)
            .src_alpha_blend_factor(vk::BlendFactor::ZERO)
            .dst_alpha_blend_factor(vk::BlendFactor::ONE)
            .alpha_blend_op(vk::BlendOp::ADD)
            .color_write_mask(vk::ColorComponentFlags::R | vk::ColorComponentFlags::G | vk::ColorComponentFlags::B);
        let pipeline = full_screen_pipeline(device, self.apply_layout.pipeline, [self.vertex, self.fragment], samples, depth, attachment)?;
        self.apply.insert(samples, pipeline);
        Ok(pipeline)
    }

    /// Destroys everything (the GPU must be idle), after logging the passes' times.
    pub fn destroy(&mut self, device: &Device) {
        if let Some(times) = self.times.take() {
            times.destroy(device);
        }
        if let Some(b) = self.buffers.take() {
            for b in [b.depth, b.raw, b.blurred] {
                device.destroy_buffer(b);
            }
        }
        // Safety: the GPU is done with them; each is destroyed once (null handles are ignored).
        unsafe {
            for (_, p) in self.apply.drain() {
                device.raw.destroy_pipeline(p, None);
            }
            device.raw.destroy_pipeline(self.ssao, None);
            device.raw.destroy_pipeline(self.blur, None);
            device.raw.destroy_shader_module(self.vertex, None);
            device.raw.destroy_shader_module(self.fragment, None);
        }
        self.compute_layout.destroy(device);
        self.apply_layout.destroy(device);
    }
}

/// Records a memory barrier from the writes `access` of `src` to storage reads of `dst`.
fn barrier(device: &Device, cmd: vk::CommandBuffer, src: vk::PipelineStageFlags2, access: vk::AccessFlags2, dst: vk::PipelineStageFlags2) {
    let barrier = [vk::MemoryBarrier2::default().src_stage_mask(src).src_access_mask(access).dst_stage_mask(dst).dst_access_mask(vk::AccessFlags2::SHADER_STORAGE_READ)];
    // Safety: cmd is recording outside a rendering pass.
    unsafe { device.raw.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&barrier)) };
}

#[cfg(test)]
mod tests {
    use glam::Mat4;

    use super::*;

    #[test]
    fn the_kernel_fills_the_hemisphere_denser_near_the_centre() {
        let k = kernel(64);
        assert_eq!(k.len(), 64);
        assert!(k.iter().all(|v| v[2] >= 0.0 && Vec3::new(v[0], v[1], v[2]).length() <= 1.0));
        let length = |v: &[f32; 4]| Vec3::new(v[0], v[1], v[2]).length();
        let inner: f32 = k[..32].iter().map(length).sum::<f32>() / 32.0;
        let outer: f32 = k[32..].iter().map(length).sum::<f32>() / 32.0;
        assert!(inner < outer, "{inner} {outer}");
        assert!(noise().iter().all(|n| n[2] == 0.0 && n[0].abs() <= 1.0 && n[1].abs() <= 1.0));
    }

    #[test]
    fn occlusion_goes_after_the_last_opaque_draw() {
        let draw = |class| Draw { class, ..Draw::default() };
        let mut frame = Frame { draws: vec![draw(DrawClass::Sky), draw(DrawClass::Static), draw(DrawClass::Layer), draw(DrawClass::Translucent), draw(DrawClass::Overlay)], ..Frame::default() };
        assert_eq!(place(&frame).map(|(at, _)| at), Some(3));
        frame.draws.truncate(1);
        assert!(place(&frame).is_none());
        let perspective = Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0, -1.0, 0.0, 0.0, -0.2, 0.0]);
        frame.draws.push(Draw { projection: perspective, ..draw(DrawClass::Unclassified) });
        frame.draws.push(draw(DrawClass::Unclassified));
        assert_eq!(place(&frame).map(|(at, _)| at), Some(2), "a frame read before its end: perspective draws count");
    }
}
