//! Denoising of the traced image: A-SVGF's spatiotemporal variance-guided filter (Schied et
//! al., HPG 2017; seed 003 section 4.3.5; Quake II RTX's `asvgf_*` shaders are the open model),
//! the stage between the tracer's [`crate::render::trace::RayTracer::trace`] and the
//! composite, in place of the tracer's own temporal filter
//! ([`crate::render::trace::RayTracer::resolve`]).
//!
//! It reads the G-buffer every back end writes (`shaders/trace/samples.glsl`): depth, normal,
//! albedo, material key, motion vectors (from the instances' transforms of this and the last
//! frame, and for a dynamic mesh that deforms, the same point of its triangle in last frame's
//! shape: `Resident::previous`), and three lighting channels: direct light at the primary
//! hit and indirect light as its diffuse lobe reflects them, demodulated by albedo, and what
//! its specular lobe reflects of both, demodulated by the lobe's directional albedo
//! (`shaders/trace/channels.glsl`; with `[denoise] specular = false` the tracer does not split
//! it off, `FRAME_SPECULAR`, and specular light rides the diffuse channels).
//! Indirect diffuse light is one demodulated RGB value, not the seed's L1 spherical
//! harmonics: SH keep the direction light came from so that normal-mapped detail can be lit
//! after filtering, and GL 1.x surfaces have no normal maps (the filter's normal weights
//! already keep geometric edges), so RGB holds the same image in a quarter of the bytes (3 values for 12). Each
//! channel is filtered apart, in five compute passes per frame (`shaders/denoise/`); the specular
//! channel in the same passes (their pipelines specialised with it, [`pipelines`]: without
//! it they hold none of its code), with its own history length (shorter while the camera
//! moves and the lobe is glossy; its own gradients) and only in the first
//! `SPECULAR_ITERATIONS` à-trous iterations, with lobe-aware normal weights:
//!
//! 0. `gradient.comp` (with `[denoise] gradients`): temporal gradients (A-SVGF, Schied et al.
//!    2018): the tracer's gradient pass traces one pixel of every 3x3 stratum again with last
//!    frame's random numbers (`shaders/trace/gradient.glsl`, `FRAME_GRADIENTS`) of the pixel
//!    that saw its surface last frame (its source), into the stratum's G-buffer record after
//!    the pixels': where the surface moved, through the surface point the source's sample
//!    saw, forward projected (`shaders/trace/forward_projection.glsl`).
//!    The change of its luminance against the source's sample of last frame is the change
//!    of the lighting, free of noise;
//! 1. `temporal.comp`: reprojection with disocclusion tests (material, eye distance, normal),
//!    running means of light and running mean and variance of luminance, history length
//!    (whole frames), shortened by λ of itself, rounded to whole frames, where the gradients
//!    of the strata around say the lighting changed by λ;
//!    it also packs each pixel's surface (normal and eye distance) into the 8-byte guide the
//!    spatial passes read;
//! 2. `variance.comp`: the variance from the moments, estimated spatially where the history
//!    is young;
//! 3. `atrous.comp`, `[denoise] iterations` times (default 5): the edge-avoiding à-trous
//!    wavelet filter guided by depth, normals and the variance; while the camera moves the
//!    first iteration's output is the next frame's history (SVGF's feedback);
//! 4. `modulate.comp`: light times albedo plus the unfiltered emission, exposure and tone
//!    mapping into the [`TracedImage`] the composite draws.
//!
//! Accumulation while everything stands still stays: the tracer's history cap grows to
//! `[pathtrace] accumulate` frames, the history then keeps the unfiltered mean, and the
//! filter's luminance edge-stop narrows as the mean's variance falls, so a still frame
//! converges to the traced mean; a light switched on meanwhile drops the history where it
//! shines through the gradients (without them it would reach the image only as 1 / frames).
//!
//! The records are packed for the filter's memory traffic (`shaders/denoise/common.glsl`):
//! light and variance in half floats (the signal between the spatial passes: 16 bytes a
//! pixel for both channels, against 32 in single floats), surfaces in the 8-byte guide
//! (an à-trous tap reads 24 bytes from two tightly packed buffers instead of fields spread
//! over the 96-byte G-buffer sample and a 32-byte signal), and a frame's history in 36 bytes
//! a pixel in three buffers (against 64 in one), 52 with the specular channel's record (and
//! 8 bytes a pixel in each half of its signal). No binding exceeds a quarter of the
//! G-buffer's size.
//!
//! The passes are timed on GPUs ([`crate::render::pass_times`]; CPU devices have no
//! timestamps that bracket compute work): [`Denoiser::destroy`] logs their average times per
//! frame at `GLRT_LOG=info`.
//!
//! Modules: [`settings`] (`[denoise]`, `GLRT_DENOISE=0|1`), [`pipelines`] (layouts, push
//! constants, pipelines), [`shader_constants`] (bindings and flags shared with the shaders).

pub mod pipelines;
pub mod settings;
pub mod shader_constants;

use ash::vk;

use crate::render::raster::device::{Buffer, Check, Device, Result};
use crate::render::pass_times::PassTimes;
use crate::render::raster::renderer::Recorder;
use crate::render::trace::compute::{MOVING_HISTORY, barrier};
use crate::render::trace::gpu_types::{GSAMPLE_BYTES, GpuFrame, OUTPUT_SAMPLE_BYTES, gbuffer_records, gradient_strata};
use crate::render::trace::shader_constants::{FRAME_STILL, FRAME_TONEMAP_MASK, TRACE_GROUP};
use crate::render::trace::{Radiance, TracedImage};
use pipelines::{DenoisePass, DenoisePipelines, GRADIENT_BYTES, GUIDE_BYTES, HISTORY_LIGHT_BYTES, HISTORY_MOMENTS_BYTES, HISTORY_SPECULAR_BYTES, SIGNAL_BYTES, SPECULAR_SIGNAL_BYTES};
use settings::DenoiseSettings;
use shader_constants::{
    BINDING_COUNT, BINDING_GBUFFER, BINDING_GRADIENT, BINDING_GUIDE, BINDING_GUIDE_PREVIOUS, BINDING_LIGHT, BINDING_LIGHT_PREVIOUS, BINDING_MOMENTS, BINDING_MOMENTS_PREVIOUS, BINDING_OUTPUT,
    BINDING_SIGNAL, BINDING_SPECULAR, BINDING_SPECULAR_PREVIOUS, BINDING_SPECULAR_SIGNAL, FLAG_FEEDBACK, FLAG_GRADIENTS, SPECULAR_ITERATIONS, VIEW_SHIFT,
};

/// One frame's history: what the next frame reprojects (52 bytes a pixel in all).
struct FrameHistory {
    /// `HistoryLight` records: light and history length.
    light: Buffer,
    /// `HistoryMoments` records: luminance means and variances, the traced luminances.
    moments: Buffer,
    /// `Guide` records: the surfaces (normal and eye distance), also the spatial passes'.
    guide: Buffer,
    /// `HistorySpecular` records: the specular channel's light, moments and history length.
    specular: Buffer,
}

impl FrameHistory {
    /// The buffers of `n` pixels (none left behind on failure).
    fn new(device: &Device, n: u64) -> Result<FrameHistory> {
        let [light, moments, guide, specular] = device.create_storage_buffers([
            ("glrt denoiser history light", n * HISTORY_LIGHT_BYTES),
            ("glrt denoiser history moments", n * HISTORY_MOMENTS_BYTES),
            ("glrt denoiser guides", n * GUIDE_BYTES),
            ("glrt denoiser history specular", n * HISTORY_SPECULAR_BYTES),
        ])?;
        Ok(FrameHistory { light, moments, guide, specular })
    }

    fn buffers(&self) -> [&Buffer; 4] {
        [&self.light, &self.moments, &self.guide, &self.specular]
    }

    /// Frees the buffers (the GPU must be done with them).
    fn destroy(self, device: &Device) {
        for b in [self.light, self.moments, self.guide, self.specular] {
            device.destroy_buffer(b);
        }
    }
}

/// The denoiser's per-pixel buffers for one traced size and the descriptor sets over them and
/// the tracer's G-buffer and output. Each record kind has its own buffer, so the largest
/// binding is a quarter of the G-buffer's (at 1920x1080: 66 MB for the signal, 33 MB for a
/// frame's light, against lavapipe's 128 MiB storage-buffer range).
struct PixelBuffers {
    size: [u32; 2],
    /// The tracer's buffers the sets hold.
    gbuffer: vk::Buffer,
    output: vk::Buffer,
    /// Two frames of history: set `p` reads `history[p]` and writes `history[p ^ 1]`.
    history: [FrameHistory; 2],
    /// The spatial passes' two signals, one after the other.
    signal: Buffer,
    /// The two specular signals, one after the other.
    specular_signal: Buffer,
    /// The temporal gradients, one record per 3x3 stratum.
    gradient: Buffer,
    pool: vk::DescriptorPool,
    sets: [vk::DescriptorSet; 2],
}

/// The steps timed, in order.
const STEPS: [&str; 5] = ["gradient", "temporal", "variance", "a-trous", "modulate"];

/// The A-SVGF stage.
pub struct Denoiser {
    settings: DenoiseSettings,
    pipelines: DenoisePipelines,
    pixels: Option<PixelBuffers>,
    /// Which frame of the history this frame reads (the other is written): the set bound.
    parity: u32,
    /// The passes' GPU times (`None`: not timed).
    times: Option<PassTimes>,
}

impl Denoiser {
    /// Creates the pipelines; the buffers come with the first frame.
    pub fn new(device: &Device, settings: DenoiseSettings) -> Result<Denoiser> {
        let mut pipelines = DenoisePipelines::new(device, settings.specular)?;
        let times = match PassTimes::new(device, "denoiser", &STEPS) {
            Ok(t) => t,
            Err(e) => {
                pipelines.destroy(device);
                return Err(e);
            }
        };
        Ok(Denoiser { settings, pipelines, pixels: None, parity: 0, times })
    }

    /// (Re)creates the buffers and the sets for `radiance`'s size and buffers; a new history
    /// is zeroed (no pixel has one).
    fn ensure_pixels(&mut self, device: &Device, cmd: vk::CommandBuffer, radiance: &Radiance) -> Result<()> {
        if self.pixels.as_ref().is_some_and(|p| p.size == radiance.size && p.gbuffer == radiance.gbuffer && p.output == radiance.output) {
            return Ok(());
        }
        device.wait_idle()?;
        if let Some(old) = self.pixels.take() {
            destroy_pixels(device, old);
        }
        let n = radiance.size[0] as u64 * radiance.size[1] as u64;
        let first = FrameHistory::new(device, n)?;
        let second = match FrameHistory::new(device, n) {
            Ok(h) => h,
            Err(e) => {
                first.destroy(device);
                return Err(e);
            }
        };
        let history = [first, second];
        let [sx, sy] = gradient_strata(radiance.size);
        let strata = u64::from(sx) * u64::from(sy);
        let buffers = device.create_storage_buffers([
            ("glrt denoiser signal", 2 * n * SIGNAL_BYTES),
            ("glrt denoiser specular signal", 2 * n * SPECULAR_SIGNAL_BYTES),
            ("glrt denoiser gradients", strata * GRADIENT_BYTES),
        ]);
        let [signal, specular_signal, gradient] = match buffers {
            Ok(b) => b,
            Err(e) => {
                history.into_iter().for_each(|h| h.destroy(device));
                return Err(e);
            }
        };
        let mut pixels = PixelBuffers {
            size: radiance.size,
            gbuffer: radiance.gbuffer,
            output: radiance.output,
            history,
            signal,
            specular_signal,
            gradient,
            pool: vk::DescriptorPool::null(),
            sets: [vk::DescriptorSet::null(); 2],
        };
        if let Err(e) = self.write_sets(device, &mut pixels, n) {
            destroy_pixels(device, pixels);
            return Err(e);
        }
        // Safety: `cmd` records outside a rendering pass; the buffers live until destroyed
        // with the GPU idle.
        unsafe {
            for h in &pixels.history {
                for b in h.buffers() {
                    device.raw.cmd_fill_buffer(cmd, b.raw, 0, vk::WHOLE_SIZE, 0);
                }
            }
            barrier(&device.raw, cmd, vk::PipelineStageFlags2::TRANSFER, vk::PipelineStageFlags2::COMPUTE_SHADER);
        }
        self.pixels = Some(pixels);
        Ok(())
    }

    /// Makes the descriptor pool of `pixels` and its two sets, set `p` reading `history[p]`
    /// and writing `history[p ^ 1]`, over `n` pixels.
    fn write_sets(&self, device: &Device, pixels: &mut PixelBuffers, n: u64) -> Result<()> {
        let sizes = [vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: 2 * BINDING_COUNT }];
        // Safety (this block): valid create and allocate infos; the pool is destroyed with the
        // buffers; the sets' buffers live as long as they.
        unsafe {
            pixels.pool = device.raw.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(2).pool_sizes(&sizes), None).check("vkCreateDescriptorPool")?;
            let layouts = [self.pipelines.set_layout; 2];
            let allocated = device.raw.allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(pixels.pool).set_layouts(&layouts)).check("vkAllocateDescriptorSets")?;
            pixels.sets = [allocated[0], allocated[1]];
            for (parity, &set) in pixels.sets.iter().enumerate() {
                let (previous, current) = (&pixels.history[parity], &pixels.history[parity ^ 1]);
                let whole = |b: &Buffer| (b.raw, b.size);
                let mut table = [(vk::Buffer::null(), 0); BINDING_COUNT as usize];
                table[BINDING_GBUFFER as usize] = (pixels.gbuffer, gbuffer_records(pixels.size) * GSAMPLE_BYTES);
                table[BINDING_OUTPUT as usize] = (pixels.output, n * OUTPUT_SAMPLE_BYTES);
                table[BINDING_LIGHT_PREVIOUS as usize] = whole(&previous.light);
                table[BINDING_LIGHT as usize] = whole(&current.light);
                table[BINDING_MOMENTS_PREVIOUS as usize] = whole(&previous.moments);
                table[BINDING_MOMENTS as usize] = whole(&current.moments);
                table[BINDING_GUIDE_PREVIOUS as usize] = whole(&previous.guide);
                table[BINDING_GUIDE as usize] = whole(&current.guide);
                table[BINDING_SIGNAL as usize] = whole(&pixels.signal);
                table[BINDING_GRADIENT as usize] = whole(&pixels.gradient);
                table[BINDING_SPECULAR_PREVIOUS as usize] = whole(&previous.specular);
                table[BINDING_SPECULAR as usize] = whole(&current.specular);
                table[BINDING_SPECULAR_SIGNAL as usize] = whole(&pixels.specular_signal);
                let infos = table.map(|(buffer, range)| [vk::DescriptorBufferInfo { buffer, offset: 0, range }]);
                let writes: Vec<vk::WriteDescriptorSet> = infos
                    .iter()
                    .enumerate()
                    .map(|(b, info)| vk::WriteDescriptorSet::default().dst_set(set).dst_binding(b as u32).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info))
                    .collect();
                device.raw.update_descriptor_sets(&writes, &[]);
            }
        }
        Ok(())
    }

    /// Records the passes of the module doc over `radiance`, traced with `frame`'s camera and
    /// settings (exposure, history cap, tone mapping), into the image the composite draws.
    pub fn record(&mut self, rec: &mut Recorder<'_>, frame: &GpuFrame, radiance: &Radiance) -> Result<TracedImage> {
        let (device, cmd) = (rec.device, rec.cmd);
        let slot = rec.slot();
        self.ensure_pixels(device, cmd, radiance)?;
        let Some(pixels) = &self.pixels else { return Ok(TracedImage { size: radiance.size, output: radiance.output }) };
        let [w, h] = radiance.size;
        let n = w * h;
        let set = pixels.sets[self.parity as usize];
        self.parity ^= 1;
        let still = frame.flags[0] & FRAME_STILL != 0;
        let flags = (frame.flags[0] & FRAME_TONEMAP_MASK)
            | if still { 0 } else { FLAG_FEEDBACK }
            | self.settings.view.code() << VIEW_SHIFT
            | if self.settings.gradients { FLAG_GRADIENTS } else { 0 };
        let params = [frame.params[0], frame.params[1], frame.params[2], MOVING_HISTORY];
        let pixel_groups = [w.div_ceil(TRACE_GROUP), h.div_ceil(TRACE_GROUP)];
        let stratum_groups = gradient_strata(radiance.size).map(|s| s.div_ceil(TRACE_GROUP));
        let d = &device.raw;
        let layout = self.pipelines.layout;
        // A pass: its pipeline, work groups, flags, à-trous step, and offsets into the signal
        // and the specular signal (read, written).
        let dispatch = |pipeline: vk::Pipeline, groups: [u32; 2], flags: u32, step: u32, signal: [u32; 2], specular: [u32; 2]| {
            let pass = DenoisePass { params, size: [w, h, flags, step], signal, specular };
            // Safety: `cmd` records outside a rendering pass (the tracer ended it); the sets'
            // buffers live until the frame finishes.
            unsafe {
                d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
                d.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::COMPUTE, 0, bytemuck::bytes_of(&pass));
                d.cmd_dispatch(cmd, groups[0], groups[1], 1);
                barrier(d, cmd, vk::PipelineStageFlags2::COMPUTE_SHADER, vk::PipelineStageFlags2::COMPUTE_SHADER);
            }
        };
        let stamps = self.times.as_mut().and_then(|t| t.frame(device, slot));
        // Timestamp `k` of this frame (after step k, 0 before the first).
        let stamp = |k: u32| {
            if let Some(stamps) = stamps {
                stamps.write(device, cmd, k, vk::PipelineStageFlags2::COMPUTE_SHADER);
            }
        };
        let run = |pipeline: vk::Pipeline, flags: u32, step: u32, signal: [u32; 2], specular: [u32; 2]| dispatch(pipeline, pixel_groups, flags, step, signal, specular);
        // Safety: as above.
        unsafe { d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, layout, 0, &[set], &[]) };
        stamp(0);
        if self.settings.gradients {
            dispatch(self.pipelines.gradient, stratum_groups, flags, 1, [0, 0], [0, 0]);
        }
        stamp(1);
        // The signals ping-pong between their halves, starting at 0 and n; the variance pass
        // estimates the specular signal in place.
        run(self.pipelines.temporal, flags, 1, [0, 0], [0, 0]);
        stamp(2);
        run(self.pipelines.variance, flags, 1, [0, n], [0, 0]);
        stamp(3);
        let (mut current, mut current_specular) = (n, 0);
        for iteration in 0..self.settings.iterations {
            let other = n - current;
            if iteration < SPECULAR_ITERATIONS && self.settings.specular {
                let other_specular = n - current_specular;
                run(self.pipelines.atrous_specular, flags, 1 << iteration, [current, other], [current_specular, other_specular]);
                current_specular = other_specular;
            } else {
                run(self.pipelines.atrous, flags, 1 << iteration, [current, other], [0, 0]);
            }
            current = other;
        }
        stamp(4);
        run(self.pipelines.modulate, flags, 1, [current, 0], [current_specular, 0]);
        stamp(5);
        // Safety: as above.
        unsafe { barrier(d, cmd, vk::PipelineStageFlags2::COMPUTE_SHADER, vk::PipelineStageFlags2::FRAGMENT_SHADER | vk::PipelineStageFlags2::HOST) };
        Ok(TracedImage { size: radiance.size, output: radiance.output })
    }

    /// Whether the tracer should trace gradient samples (`FRAME_GRADIENTS`) for this stage.
    pub fn wants_gradient_samples(&self) -> bool {
        self.settings.gradients
    }

    /// Whether the tracer should split specular light into its own channel (`FRAME_SPECULAR`)
    /// for this stage.
    pub fn wants_specular_channel(&self) -> bool {
        self.settings.specular
    }

    /// Frees the GPU objects (the GPU must be idle), after logging the passes' times.
    pub fn destroy(&mut self, device: &Device) {
        if let Some(times) = self.times.take() {
            times.destroy(device);
        }
        if let Some(p) = self.pixels.take() {
            destroy_pixels(device, p);
        }
        self.pipelines.destroy(device);
    }
}

fn destroy_pixels(device: &Device, p: PixelBuffers) {
    // Safety: the GPU is idle; the sets go with their pool (a null pool is ignored).
    unsafe { device.raw.destroy_descriptor_pool(p.pool, None) };
    p.history.into_iter().for_each(|h| h.destroy(device));
    device.destroy_buffer(p.signal);
    device.destroy_buffer(p.specular_signal);
    device.destroy_buffer(p.gradient);
}
