//! The compute back end ([`ComputeTracer`], a [`RayTracer`]): BVHs built on the CPU
//! ([`super::bvh`], [`super::resident`]) and traversed in compute shaders, so it runs on every
//! Vulkan 1.2 device, lavapipe included. Its stages: [`RayTracer::build`] gathers the instances
//! of a [`Frame`] (traced draws and the static world's chunks, [`super::instances`]), builds or
//! refits their bottom-level BVHs, uploads geometry and texels and builds the top-level BVH;
//! [`RayTracer::trace`] runs `pathtrace.comp`, one dispatch per sample (then, with temporal
//! gradients, its gradient pass, one invocation per stratum); [`RayTracer::resolve`]
//! runs the temporal pass and tone mapping (`trace_resolve.comp`) into the image that
//! [`super::composite`] draws.
//!
//! With `hardware` ([`super::hardware`]) the same tracer builds the driver's acceleration
//! structures over the same geometry instead of the top-level BVH and traces with the
//! ray-tracing pipeline (`pathtrace.rgen`) instead of `pathtrace.comp`; everything else is
//! shared.

use std::ops::Range;

use ash::vk;
use glam::{Affine3A, Mat4};
use gpu_allocator::MemoryLocation;
use xxhash_rust::xxh3::Xxh3;

use super::bvh::Tlas;
use super::emitters::{self, EmitterList, Estimate};
use super::hardware::accel::{Accelerations, TopInstance};
use super::gpu_types::{self, GpuFrame, GpuInstance, GpuLight};
use super::instances::{self, Source};
use super::lights::{self, LightSettings};
use super::material::{self, MaterialDefaults};
use super::pipelines::TracePipelines;
use super::radiosity::TracedRadiosity;
use super::regions::{self, MergedRun, Member, Placed};
use super::resident::{NewGeometry, Resident};
use super::scene;
use super::settings::{KNEE, Settings, Tonemap};
use super::shader_constants::{
    FRAME_GRADIENTS, FRAME_PERSPECTIVE, FRAME_SKY, FRAME_SKY_SAMPLED, FRAME_STILL, INSTANCE_ALPHA_TESTED, MATERIAL_LAYERS, NO_PREVIOUS_TRIANGLES, TONEMAP_ACES, TONEMAP_CLAMP, TONEMAP_KNEE, TONEMAP_REINHARD,
    TRACE_GROUP,
};
use super::surfaces::Surfaces;
use super::sky::Sky;
use super::sky_selection::SkySelection;
use super::stats::{PassSeconds, RayCounts, SceneCounts, Statistics};
use super::texels::TexelPool;
use super::tracks::Tracks;
use super::vertex_light;
use super::{GpuScene, Radiance, RayTracer, TracedImage, bindings};
use crate::frame::class::SurfaceLighting;
use crate::frame::{Draw, Frame};
use crate::render::pass_times::{self, SlotStamps};
use crate::render::radiosity::stage::FrameIndirect;
use crate::render::raster::device::{Buffer, Check, Device, Result};
use crate::render::raster::renderer::Recorder;

/// Frames a moving camera's history keeps (the temporal filter's weight is 1 / (n + 1); the
/// denoiser's temporal pass keeps as many).
pub const MOVING_HISTORY: f32 = 8.0;

/// Timestamps per frame in flight: builds start and end, tracing pass start, the end of its
/// main pass (the start of its gradient pass) and its end (in the order they are recorded:
/// the first resets the frame's queries).
const TIMESTAMPS: u32 = 5;

/// Per-pixel buffers of one traced size.
struct PixelBuffers {
    size: [u32; 2],
    gbuffer: Buffer,
    /// Accumulation, ping-ponged: one is written this frame, the other read as history.
    accumulation: [Buffer; 2],
    output: Buffer,
}

/// What the last frame looked like, for the temporal pass.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Previous {
    signature: u64,
    projection: Mat4,
    /// The recovered view (world to eye), when there was one.
    view: Option<Mat4>,
}

/// The compute path tracer.
pub struct ComputeTracer {
    settings: Settings,
    pipelines: TracePipelines,
    resident: Resident,
    tracks: Tracks,
    texels: TexelPool,
    /// The texel pool on the GPU and its capacity in words.
    texel_buffer: Option<(Buffer, usize)>,
    /// The environment cube map of the sky draws.
    sky: Option<Sky>,
    pixels: Option<PixelBuffers>,
    /// Ray counters per frame in flight (host-readable).
    counters: Vec<Buffer>,
    /// Descriptor pools per frame in flight.
    pools: Vec<vk::DescriptorPool>,
    /// Per frame in flight, [`TIMESTAMPS`] timestamps: around the geometry uploads and
    /// acceleration-structure builds, then around the tracing pass (`None`: the device has no
    /// timestamps on compute queues, or is a CPU).
    timestamps: Option<SlotStamps>,
    /// Per frame in flight: whether it traced a frame whose counters were not read yet.
    unread: Vec<bool>,
    frame_index: u32,
    parity: usize,
    previous: Option<Previous>,
    /// The top-level BVH of the frame being traced ([`RayTracer::build`] makes it; empty for
    /// the hardware tracer).
    tlas: Tlas,
    /// The hardware tracer's acceleration structures (`None`: the compute tracer).
    accelerations: Option<Accelerations>,
    /// The top-level acceleration structure of the frame being traced (hardware tracer).
    top_level: vk::AccelerationStructureKHR,
    /// Radiosity's values on the static world's geometries.
    radiosity: TracedRadiosity,
    statistics: Statistics,
    /// How often path vertices sample the sky, from the counters read last.
    sky_selection: SkySelection,
    /// How last frame's path vertices sampled the sky, which its gradient samples replay.
    last_sky: SkySampled,
    /// How long the static world's runs of chunks have stayed the same (merged BVHs).
    settling: regions::Settling,
}

/// The sky distribution's cells a frame sampled (empty: it did not sample the sky) and the
/// probability with which its path vertices did.
#[derive(Default)]
struct SkySampled {
    cells: Vec<[f32; 2]>,
    probability: f32,
}

impl ComputeTracer {
    /// Creates the tracer's pipelines and buffers for `slots` frames in flight; with
    /// `hardware` (the device has [`Device::ray_tracing`]) the hardware tracer.
    pub fn new(device: &Device, settings: Settings, slots: usize, hardware: bool) -> Result<ComputeTracer> {
        let pipelines = TracePipelines::new(device, hardware, settings.bvh)?;
        let mut counters = Vec::new();
        let mut pools = Vec::new();
        for _ in 0..slots {
            let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
            counters.push(device.create_buffer("glrt ray counters", gpu_types::COUNTER_BYTES, usage, MemoryLocation::GpuToCpu)?);
            let sizes = [
                vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: bindings::COUNT },
                vk::DescriptorPoolSize { ty: vk::DescriptorType::COMBINED_IMAGE_SAMPLER, descriptor_count: 1 },
                vk::DescriptorPoolSize { ty: vk::DescriptorType::ACCELERATION_STRUCTURE_KHR, descriptor_count: 1 },
            ];
            let info = vk::DescriptorPoolCreateInfo::default().max_sets(1).pool_sizes(&sizes[..if hardware { 3 } else { 2 }]);
            // Safety: valid create info; destroyed in `destroy`.
            pools.push(unsafe { device.raw.create_descriptor_pool(&info, None) }.check("vkCreateDescriptorPool")?);
        }
        let timestamps = SlotStamps::new(device, TIMESTAMPS, slots)?;
        Ok(ComputeTracer {
            settings,
            pipelines,
            resident: Resident::new((!hardware).then_some(settings.bvh)),
            tracks: Tracks::default(),
            texels: TexelPool::new(super::texels::MAX_WORDS, slots),
            texel_buffer: None,
            sky: Some(Sky::new(device, settings.sky_size, if settings.sky_sampling { slots } else { 0 })?),
            pixels: None,
            counters,
            pools,
            timestamps,
            unread: vec![false; slots],
            frame_index: 0,
            parity: 0,
            previous: None,
            tlas: Tlas::build(&[], settings.bvh),
            accelerations: hardware.then(|| Accelerations::new(device, slots)),
            top_level: vk::AccelerationStructureKHR::null(),
            radiosity: TracedRadiosity::default(),
            statistics: Statistics::default(),
            sky_selection: SkySelection::default(),
            last_sky: SkySampled::default(),
            settling: regions::Settling::default(),
        })
    }

    /// Reads the ray counters and the pass time of the frame slot `slot` last traced (its
    /// fence has signalled) into the statistics' `rays` and `totals`, once per traced frame.
    fn read_counters(&mut self, device: &Device, slot: usize) {
        if !self.unread.get_mut(slot).is_some_and(std::mem::take) {
            return;
        }
        let Some(rays) = self.counters.get_mut(slot).and_then(|b| RayCounts::from_counters(b.mapped())) else { return };
        let seconds = self.timestamps.as_ref().and_then(|stamps| {
            let ticks = stamps.read(device, slot)?;
            Some(PassSeconds {
                trace: pass_times::seconds(device, ticks[2], ticks[4]),
                gradient: pass_times::seconds(device, ticks[3], ticks[4]),
                build: pass_times::seconds(device, ticks[0], ticks[1]),
            })
        });
        self.sky_selection.observe(rays.sky, rays.sky_unoccluded);
        self.statistics.rays = rays;
        self.statistics.totals.add(rays, seconds);
    }

    /// Copies the texel pool's new words to the GPU (all of them into a larger buffer when it
    /// grew past the buffer).
    fn upload_texels(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut crate::render::raster::upload::Ring) -> Result<()> {
        let ranges = self.texels.take_uploads();
        let words = self.texels.words();
        let needed = words.len().max(1);
        let ranges = if self.texel_buffer.as_ref().is_none_or(|(_, capacity)| *capacity < needed) {
            device.wait_idle()?;
            if let Some((old, _)) = self.texel_buffer.take() {
                device.destroy_buffer(old);
            }
            let capacity = needed.next_power_of_two();
            let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
            self.texel_buffer = Some((device.create_buffer("glrt texel pool", capacity as u64 * 4, usage, MemoryLocation::GpuOnly)?, capacity));
            std::iter::once(0..words.len()).collect()
        } else {
            ranges
        };
        let Some((buffer, _)) = &self.texel_buffer else { return Ok(()) };
        ranges.into_iter().try_for_each(|range| super::resident::upload(device, cmd, ring, buffer.raw, range.start as u64 * 4, bytemuck::cast_slice(&words[range])))
    }

    /// (Re)creates the per-pixel buffers for a traced image of `size`.
    fn ensure_pixels(&mut self, device: &Device, size: [u32; 2]) -> Result<()> {
        if self.pixels.as_ref().is_some_and(|p| p.size == size) {
            return Ok(());
        }
        device.wait_idle()?;
        if let Some(old) = self.pixels.take() {
            destroy_pixels(device, old);
        }
        let n = size[0] as u64 * size[1] as u64;
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        let make = |name, bytes: u64| device.create_buffer(name, n * bytes, usage, MemoryLocation::GpuOnly);
        self.pixels = Some(PixelBuffers {
            size,
            gbuffer: device.create_buffer("glrt G-buffer", gpu_types::gbuffer_records(size) * gpu_types::GSAMPLE_BYTES, usage, MemoryLocation::GpuOnly)?,
            accumulation: [make("glrt accumulation", gpu_types::ACCUM_SAMPLE_BYTES)?, make("glrt accumulation", gpu_types::ACCUM_SAMPLE_BYTES)?],
            output: make("glrt traced output", gpu_types::OUTPUT_SAMPLE_BYTES)?,
        });
        Ok(())
    }

    /// Uploads the frame's small buffers, writes the descriptor set and dispatches the tracing
    /// pass ([`RayTracer::trace`]); `None` when no geometry is on the GPU yet.
    fn dispatch(&mut self, rec: &mut Recorder<'_>, scene: &GpuScene) -> Result<Option<Radiance>> {
        let device = rec.device;
        let cmd = rec.cmd;
        let slot = rec.slot();
        let gpu_frame = &scene.frame;
        let Some(pixels) = &self.pixels else { return Ok(None) };
        let Some([nodes, triangles, attributes, layer_corners]) = self.resident.buffers() else { return Ok(None) };
        let align = device.properties.limits.min_storage_buffer_offset_alignment.max(16);
        // A binding's range must not be empty: empty arrays get one zeroed element.
        let mut push = |bytes: &[u8]| -> Result<(vk::Buffer, u64, u64)> {
            let padded;
            let bytes = if bytes.is_empty() {
                padded = [0u8; 64];
                &padded[..]
            } else {
                bytes
            };
            let s = rec.ring.push(device, bytes, align)?;
            Ok((s.buffer, s.offset, bytes.len() as u64))
        };
        let frame_slice = push(bytemuck::bytes_of(gpu_frame))?;
        let instance_slice = push(bytemuck::cast_slice(&scene.instances))?;
        let material_slice = push(bytemuck::cast_slice(&scene.materials))?;
        let light_slice = push(bytemuck::cast_slice(&scene.lights))?;
        let emitter_slice = push(bytemuck::cast_slice(&scene.emitters))?;
        let sky_cells_slice = push(bytemuck::cast_slice(&scene.sky_cells))?;
        let radiosity_slice = push(bytemuck::cast_slice(&scene.radiosity))?;
        let previous_slice = push(bytemuck::cast_slice(&scene.previous_triangles))?;
        let tlas_slice = push(self.tlas.node_bytes())?;
        let textures_slice = push(bytemuck::cast_slice(self.texels.textures()))?;
        let Some((texel_buffer, _)) = &self.texel_buffer else { return Ok(None) };
        let Some(sky) = &self.sky else { return Ok(None) };
        let whole = |b: &Buffer| (b.raw, 0, vk::WHOLE_SIZE);
        let counters = &self.counters[slot];
        let mut table = vec![(vk::Buffer::null(), 0, 0); bindings::COUNT as usize];
        table[bindings::FRAME as usize] = frame_slice;
        table[bindings::BLAS_NODES as usize] = (nodes.0, 0, nodes.1);
        table[bindings::TLAS_NODES as usize] = tlas_slice;
        table[bindings::TRIANGLES as usize] = (triangles.0, 0, triangles.1);
        table[bindings::INSTANCES as usize] = instance_slice;
        table[bindings::ATTRIBUTES as usize] = (attributes.0, 0, attributes.1);
        table[bindings::MATERIALS as usize] = material_slice;
        table[bindings::LIGHTS as usize] = light_slice;
        table[bindings::TEXELS as usize] = whole(texel_buffer);
        table[bindings::TEXTURES as usize] = textures_slice;
        table[bindings::ACCUMULATION as usize] = whole(&pixels.accumulation[self.parity]);
        table[bindings::GBUFFER as usize] = whole(&pixels.gbuffer);
        table[bindings::OUTPUT as usize] = whole(&pixels.output);
        table[bindings::COUNTERS as usize] = whole(counters);
        table[bindings::HISTORY as usize] = whole(&pixels.accumulation[self.parity ^ 1]);
        table[bindings::LAYER_CORNERS as usize] = (layer_corners.0, 0, layer_corners.1);
        table[bindings::EMITTERS as usize] = emitter_slice;
        table[bindings::SKY_DISTRIBUTION as usize] = sky_cells_slice;
        table[bindings::RADIOSITY as usize] = radiosity_slice;
        table[bindings::PREVIOUS_TRIANGLES as usize] = previous_slice;

        let pool = self.pools[slot];
        // Safety (this block): the pool's sets of this slot's previous frame are finished (the
        // slot's fence signalled before its recording began); every buffer in `table` lives
        // until this frame finishes.
        let set = unsafe {
            device.raw.reset_descriptor_pool(pool, vk::DescriptorPoolResetFlags::empty()).check("vkResetDescriptorPool")?;
            let layouts = [self.pipelines.set_layout];
            let set = device.raw.allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&layouts)).check("vkAllocateDescriptorSets")?[0];
            let infos: Vec<[vk::DescriptorBufferInfo; 1]> = table.iter().map(|&(buffer, offset, range)| [vk::DescriptorBufferInfo { buffer, offset, range }]).collect();
            let sky_info = [sky.descriptor()];
            let mut writes: Vec<vk::WriteDescriptorSet> = infos
                .iter()
                .enumerate()
                .map(|(b, info)| vk::WriteDescriptorSet::default().dst_set(set).dst_binding(b as u32).descriptor_type(vk::DescriptorType::STORAGE_BUFFER).buffer_info(info))
                .collect();
            writes.push(vk::WriteDescriptorSet::default().dst_set(set).dst_binding(bindings::SKY).descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER).image_info(&sky_info));
            let structures = [self.top_level];
            let mut structure_info = vk::WriteDescriptorSetAccelerationStructureKHR::default().acceleration_structures(&structures);
            if self.accelerations.is_some() {
                let mut write = vk::WriteDescriptorSet::default()
                    .dst_set(set)
                    .dst_binding(bindings::ACCELERATION)
                    .descriptor_type(vk::DescriptorType::ACCELERATION_STRUCTURE_KHR)
                    .push_next(&mut structure_info);
                write.descriptor_count = 1;
                writes.push(write);
            }
            device.raw.update_descriptor_sets(&writes, &[]);

            let d = &device.raw;
            let (stage, push_stages) = match &self.pipelines.table {
                Some(_) => (vk::PipelineStageFlags2::RAY_TRACING_SHADER_KHR, vk::ShaderStageFlags::COMPUTE | vk::ShaderStageFlags::RAYGEN_KHR),
                None => (vk::PipelineStageFlags2::COMPUTE_SHADER, vk::ShaderStageFlags::COMPUTE),
            };
            d.cmd_fill_buffer(cmd, counters.raw, 0, vk::WHOLE_SIZE, 0);
            barrier(d, cmd, vk::PipelineStageFlags2::TRANSFER, stage);
            let bind_point = self.pipelines.trace_bind_point();
            d.cmd_bind_descriptor_sets(cmd, bind_point, self.pipelines.layout, 0, &[set], &[]);
            d.cmd_bind_pipeline(cmd, bind_point, self.pipelines.pathtrace);
            if let Some(stamps) = &self.timestamps {
                stamps.frame(slot).write(device, cmd, 2, stage);
            }
            // One dispatch per sample, each adding its share to the G-buffer's radiance. Lavapipe
            // (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS) stops every loop of a shader after the
            // loops of one call of it (a SIMD batch of invocations) have run 65535 iterations
            // in all; one invocation tracing every sample of its pixel (a traversal loop per
            // ray) silently lost the light of the later samples: beyond about 48 samples of 3
            // bounces in tests/pathtrace/cornell.rs's Cornell box.
            // The hardware tracer launches per sample too (the same shader body).
            // Then, with temporal gradients, the gradient pass (`trace_invocation` of
            // trace/path.glsl), once per sample: one invocation per gradient stratum, so that
            // the gradient samples' extra work keeps no lane of the main pass waiting.
            let size = [gpu_frame.size[0], gpu_frame.size[1]];
            // Pass `pass` (0: main, 1: gradients) over `extent` invocations, once per sample.
            let trace_pass = |pass: u32, extent: [u32; 2]| {
                for sample in 0..gpu_frame.counts[1] {
                    d.cmd_push_constants(cmd, self.pipelines.layout, push_stages, 0, bytemuck::bytes_of(&[sample, pass]));
                    match &self.pipelines.table {
                        Some(table) => table.trace(cmd, extent[0], extent[1]),
                        None => d.cmd_dispatch(cmd, extent[0].div_ceil(TRACE_GROUP), extent[1].div_ceil(TRACE_GROUP), 1),
                    }
                    barrier(d, cmd, stage, stage | vk::PipelineStageFlags2::COMPUTE_SHADER);
                }
            };
            trace_pass(0, size);
            if let Some(stamps) = &self.timestamps {
                stamps.frame(slot).write(device, cmd, 3, stage);
            }
            if gpu_frame.flags[0] & FRAME_GRADIENTS != 0 {
                trace_pass(1, gpu_types::gradient_strata(size));
            }
            if let Some(stamps) = &self.timestamps {
                stamps.frame(slot).write(device, cmd, 4, stage);
            }
            self.unread[slot] = true;
            set
        };
        Ok(Some(Radiance { size: [gpu_frame.size[0], gpu_frame.size[1]], set, gbuffer: pixels.gbuffer.raw, output: pixels.output.raw }))
    }
}

impl RayTracer for ComputeTracer {
    /// Gathers the instances, builds the BVHs of new geometry (or refits the last BVH of a
    /// moved dynamic draw) on the CPU and uploads them with the texels, draws the sky cube
    /// when it changed, builds the top-level BVH over the instances on the CPU and lists the
    /// emissive triangles and, with radiosity, its values on the static world's triangles.
    fn build(&mut self, rec: &mut Recorder<'_>, frame: &Frame, surfaces: &Surfaces, camera: &Draw, indirect: Option<&FrameIndirect>) -> Result<GpuScene> {
        let slot = rec.slot();
        let device = rec.device;
        self.read_counters(device, slot);
        rec.end_rendering();
        let cmd = rec.cmd;
        let traced = surfaces.surfaces(frame);
        let draws: Vec<&Draw> = traced.iter().map(|s| s.base).collect();

        let previous_view = self.previous.and_then(|p| p.view).filter(|_| !frame.stats.camera_cut);
        let (mut items, covered_draws) = instances::gather(frame, traced, previous_view);
        // The chunks of a region are merged ([`regions`]): they go together, after the rest.
        let region_size = self.settings.chunk_regions;
        let region_of = |item: &instances::Item| match &item.source {
            Source::Chunk(c) => regions::region(c.cell, region_size),
            Source::Surface(_) => None,
        };
        items.sort_by_key(region_of);
        // The compute tracer's merged BVHs: runs of two chunks or more, built once settled
        // (the hardware tracer finds its runs over its instance records).
        let merged_runs: Vec<(Range<usize>, u64)> = match self.accelerations {
            Some(_) => Vec::new(),
            None => {
                let placed: Vec<Placed> = items.iter().enumerate().map(|(i, item)| Placed { region: region_of(item), index: i as u32, rows: gpu_types::rows(&item.object_to_eye) }).collect();
                let runs: Vec<Range<usize>> = regions::runs(&placed).into_iter().filter(|run| run.len() > 1).collect();
                let keys: Vec<u64> = runs.iter().map(|run| regions::members_key(&items[run.clone()].iter().map(|item| Member { key: item.key, opaque: true }).collect::<Vec<_>>())).collect();
                let settled = self.settling.settled(&keys, frame.number);
                let resident = &mut self.resident;
                runs.into_iter().zip(keys).zip(settled).filter(|((_, key), settled)| *settled || resident.lookup(*key, frame.number).is_some()).map(|(run, _)| run).collect()
            }
        };

        let build_started = std::time::Instant::now();
        if let Some(stamps) = &self.timestamps {
            // `cmd` is recording outside a rendering pass; the slot's last frame, which wrote
            // these queries, has finished and was read.
            stamps.frame(slot).write(device, cmd, 0, vk::PipelineStageFlags2::ALL_COMMANDS);
        }
        let mut build_micros = 0u64;
        // Geometry: build (or refit) and upload what is new.
        let mut new: Vec<NewGeometry> = Vec::new();
        for item in &items {
            if self.resident.lookup(item.key, frame.number).is_none() && !new.iter().any(|n| n.key == item.key) {
                let refit_from = match &item.source {
                    Source::Surface(surface) => self.tracks.refit_source(surface.base),
                    Source::Chunk(_) => None,
                };
                new.push(NewGeometry { key: item.key, geometry: item.geometry(), refit_from, members: Vec::new() });
            }
        }
        for (run, key) in &merged_runs {
            if self.resident.lookup(*key, frame.number).is_none() && !new.iter().any(|n| n.key == *key) {
                let members = &items[run.clone()];
                let triangles = members.iter().flat_map(|item| item.geometry().triangles).collect();
                let geometry = scene::Geometry { triangles, ..scene::Geometry::default() };
                new.push(NewGeometry { key: *key, geometry, refit_from: None, members: members.iter().map(|item| item.key).collect() });
            }
        }
        let replaced: Vec<(u64, u64)> = new.iter().filter_map(|n| Some((n.key, n.refit_from?))).collect();
        self.resident.insert_all(device, cmd, rec.ring, new, frame.number)?;
        if let Some(accelerations) = &mut self.accelerations {
            accelerations.begin_frame(device);
            let keys: Vec<u64> = items.iter().filter(|item| region_of(item).is_none()).map(|item| item.key).collect();
            accelerations.build_bottom(device, cmd, &self.resident, &keys, &|key| replaced.iter().find(|r| r.0 == key).map(|r| r.1))?;
        }
        build_micros += build_started.elapsed().as_micros() as u64;
        for item in &items {
            if let Source::Surface(surface) = &item.source {
                self.tracks.record(surface.base, item.key, frame.number);
            }
        }
        self.tracks.prune(frame.number);

        // Textures: the traced units' and the passes'.
        let textured: Vec<[Option<&crate::frame::TextureRef>; MATERIAL_LAYERS]> = items.iter().map(|item| item.textures()).collect();
        let refs: Vec<&crate::frame::TextureRef> = textured.iter().flatten().flatten().copied().collect();
        let mut indices = self.texels.prepare(&refs).into_iter();
        let texture_of: Vec<[Option<u32>; MATERIAL_LAYERS]> = textured.iter().map(|units| units.map(|t| t.and_then(|_| indices.next()))).collect();
        self.upload_texels(device, cmd, rec.ring)?;

        // Instances, materials, emitters, lights.
        let defaults = MaterialDefaults::default();
        let mut instances = Vec::with_capacity(items.len());
        let mut materials = Vec::with_capacity(items.len());
        let mut bounds = Vec::with_capacity(items.len());
        let mut top_instances = Vec::new();
        let mut emitter_list = EmitterList::default();
        let mut recovered: Vec<GpuLight> = Vec::new();
        let mut radiosity = Vec::new();
        let mut previous_triangles = Vec::new();
        self.radiosity.begin_frame(indirect.map(|i| &i.light));
        let mut signature = Xxh3::new();
        // New texture contents (an updated lightmap, an animated texture) restart accumulation.
        for t in &refs {
            signature.update(&u64::from(t.id).to_le_bytes());
            signature.update(&t.version.to_le_bytes());
        }
        let mut counts = SceneCounts { covered_draws, built: self.resident.built, refitted: self.resident.refitted, ..SceneCounts::default() };
        // Each item's record, when it has one.
        let mut record_of: Vec<Option<u32>> = vec![None; items.len()];
        for (i, item) in items.iter().enumerate() {
            let Some(placement) = self.resident.lookup(item.key, frame.number) else { continue };
            record_of[i] = Some(instances.len() as u32);
            let mut material = item.material(texture_of[i], &defaults, self.settings.lightmaps);
            material.layer_corners = placement.first_layer_corners;
            if self.settings.sample_emitters
                && emitters::is_emissive(&material)
                && let Some((triangles, attributes, corners)) = self.resident.contents(item.key)
            {
                let textures = self.texels.textures();
                let average = |t: u32| textures.get(t as usize).map_or(u32::MAX, |t| t.average);
                let weights = Estimate { material: &material, average: &average }.weights(triangles, attributes, corners, &item.object_to_eye);
                if let Some(first) = emitter_list.add(instances.len() as u32, placement.first_triangle, &weights) {
                    material.emitters = first;
                }
            }
            material.key = material::key(&material);
            // Radiosity's indirect light on the static world's triangles.
            if let Some(indirect) = indirect
                && let Some(front) = item.static_world_front()
                && let Some((triangles, _, _)) = self.resident.contents(item.key)
                && let Some(values) = self.radiosity.values(item.key, triangles, &(indirect.eye_to_world * item.object_to_eye), front)
            {
                material.radiosity = radiosity.len() as u32;
                radiosity.extend_from_slice(values);
            }
            // The light a vertex-lit model's colours hold, for that model alone.
            if let Source::Surface(surface) = &item.source
                && surface.base.instance.is_some_and(|i| i.lighting == SurfaceLighting::VertexLit)
                && let Some(light) = vertex_light::recover(surface.base, &item.object_to_eye, instances.len() as u32)
            {
                recovered.push(light.directed);
                material.ambient = light.ambient;
            }
            // A deforming mesh's last shape (its motion vectors).
            let previous = match self.resident.previous(item.key) {
                Some(triangles) => {
                    previous_triangles.extend_from_slice(triangles);
                    (previous_triangles.len() - triangles.len()) as u32
                }
                None => NO_PREVIOUS_TRIANGLES,
            };
            let flags = if material.alpha_func != 7 { INSTANCE_ALPHA_TESTED } else { 0 };
            if self.accelerations.is_some() {
                let (rows, index, opaque) = (gpu_types::rows(&item.object_to_eye), instances.len() as u32, flags == 0);
                top_instances.push(TopInstance { key: item.key, rows, index, opaque, region: region_of(item) });
            }
            instances.push(GpuInstance {
                object_to_eye: gpu_types::rows(&item.object_to_eye),
                eye_to_object: gpu_types::rows(&item.object_to_eye.inverse()),
                previous_object_to_eye: gpu_types::rows(&item.previous_object_to_eye),
                blas_root: placement.blas_root,
                first_triangle: placement.first_triangle,
                flags,
                material: materials.len() as u32,
                previous_triangles: previous,
                first_member: 0,
                pad1: 0,
                pad2: 0,
            });
            materials.push(material);
            bounds.push(placement.bounds.transformed(&Affine3A::from_mat4(item.object_to_eye)));
            signature.update(&item.key.to_le_bytes());
            signature.update(bytemuck::cast_slice(&item.object_to_eye.to_cols_array()));
            // A new texture environment, pass or material changes the image as much as new
            // geometry does (and the temporal pass drops the history of its pixels).
            signature.update(&material.key.to_le_bytes());
            match &item.source {
                Source::Surface(surface) => {
                    counts.draw_instances += 1;
                    counts.passes += surface.passes.len() as u32;
                }
                Source::Chunk(_) => counts.chunk_instances += 1,
            }
            counts.triangles += item.triangles() as u64;
        }
        counts.emitters = emitter_list.len() as u32;
        let top_started = std::time::Instant::now();
        match &mut self.accelerations {
            Some(accelerations) => (self.top_level, counts.top_instances) = accelerations.build_top(device, cmd, slot, &top_instances, &self.resident)?,
            None => {
                // A run's chunks leave the top level for its merged BVH (whose records follow).
                let placed: Vec<MergedRun> = merged_runs
                    .iter()
                    .filter_map(|(run, key)| {
                        let (first, last) = (record_of[run.start]?, record_of[run.end - 1]?);
                        let merged = self.resident.lookup(*key, frame.number)?;
                        let bounds = merged.bounds.transformed(&Affine3A::from_mat4(items[run.start].object_to_eye));
                        (last - first + 1 == run.len() as u32).then_some(MergedRun { records: first..last + 1, blas_root: merged.blas_root, first_triangle: merged.first_triangle, bounds })
                    })
                    .collect();
                counts.top_instances = regions::merge_records(&mut instances, &mut bounds, &placed);
                self.tlas = Tlas::build(&bounds, self.settings.bvh);
            }
        }
        if let Some(stamps) = &self.timestamps {
            stamps.frame(slot).write(device, cmd, 1, vk::PipelineStageFlags2::ALL_COMMANDS);
        }
        counts.build_micros = build_micros + top_started.elapsed().as_micros() as u64;
        self.statistics.scene = counts;
        self.statistics.totals.add_scene(&counts);
        let light_settings = LightSettings::of(&self.settings);
        let mut lights: Vec<GpuLight> = lights::of_frame(frame, draws.iter().copied(), &light_settings);
        lights.extend(recovered);
        signature.update(bytemuck::cast_slice(&lights));
        signature.update(bytemuck::cast_slice(&radiosity));

        // Camera and sizes.
        let state = &camera.state;
        let window = rec.target.size;
        let scale = self.settings.resolution_scale.clamp(0.25, 1.0);
        let traced = window.map(|w| ((w as f32 * scale).ceil() as u32).max(1));
        let environment = environment(frame);
        let sky = match &mut self.sky {
            Some(sky) => sky.update(rec, frame)?,
            None => None,
        };
        let mut sky_cells = match (&self.sky, sky) {
            (Some(s), Some(_)) if self.settings.sky_sampling => s.distribution().map(|d| d.cells()).unwrap_or_default(),
            _ => Vec::new(),
        };
        // Gradient samples replay last frame's sky sampling (its cells follow this frame's)
        // where both frames sampled the sky.
        let sampled = SkySampled { cells: sky_cells.clone(), probability: self.sky_selection.probability() };
        let last_sky = std::mem::replace(&mut self.last_sky, sampled);
        let replayed_sky = if !sky_cells.is_empty() && last_sky.cells.len() == sky_cells.len() {
            sky_cells.extend_from_slice(&last_sky.cells);
            last_sky.probability
        } else {
            0.0
        };
        signature.update(bytemuck::cast_slice(&camera.projection.to_cols_array()));
        signature.update(bytemuck::cast_slice(&environment));
        signature.update(&sky.unwrap_or(0).to_le_bytes());
        signature.update(bytemuck::cast_slice(&traced));
        let signature = signature.digest();
        let still = self.previous.is_some_and(|p| p.signature == signature);
        let history = if self.pixels.as_ref().is_none_or(|p| p.size != traced) {
            0.0
        } else if still {
            self.settings.accumulate as f32
        } else if self.settings.temporal && self.previous.is_some() {
            MOVING_HISTORY
        } else {
            0.0
        };
        self.ensure_pixels(device, traced)?;
        let [vx, vy, vw, vh] = state.viewport;
        let projection = camera.projection;
        let perspective = projection.w_axis.w == 0.0;
        let fov = 2.0 * (1.0 / projection.y_axis.y.abs().max(1e-6)).atan();
        let spread = if perspective { fov / traced[1].max(1) as f32 } else { 0.0 };
        let tonemap = match self.settings.tonemap {
            Tonemap::Clamp => TONEMAP_CLAMP,
            Tonemap::Reinhard => TONEMAP_REINHARD,
            Tonemap::Aces => TONEMAP_ACES,
            Tonemap::Knee => TONEMAP_KNEE,
        };
        let emitters = emitter_list.finish();
        let gpu_frame = GpuFrame {
            projection: projection.to_cols_array_2d(),
            inverse_projection: projection.inverse().to_cols_array_2d(),
            previous_projection: self.previous.map_or(projection, |p| p.projection).to_cols_array_2d(),
            environment,
            viewport: [vx as f32, vy as f32, vw as f32, vh as f32],
            depth_range: [state.depth_range[0] as f32, state.depth_range[1] as f32, 0.0, 0.0],
            params: [2f32.powf(self.settings.exposure), history, KNEE, spread],
            size: [traced[0], traced[1], window[0], window[1]],
            counts: [self.frame_index, self.settings.spp.max(1), self.settings.bounces, lights.len() as u32],
            flags: [
                tonemap | if perspective { FRAME_PERSPECTIVE } else { 0 } | if sky.is_some() { FRAME_SKY } else { 0 }
                    | if sky_cells.is_empty() { 0 } else { FRAME_SKY_SAMPLED }
                    | if still { FRAME_STILL } else { 0 },
                instances.len() as u32,
                emitters.len() as u32,
                0,
            ],
            sampling: [self.sky_selection.probability(), replayed_sky, 0.0, 0.0],
        };
        self.previous = Some(Previous { signature, projection, view: frame.view.map(|v| v.view) });
        self.frame_index = self.frame_index.wrapping_add(1);
        self.statistics.frames += 1;
        Ok(GpuScene { frame: gpu_frame, instances, materials, lights, emitters, sky_cells, radiosity, previous_triangles })
    }

    /// Dispatches `pathtrace.comp` once per sample into the G-buffer and the accumulation
    /// buffer of this frame's parity (the other one is the temporal pass's history).
    fn trace(&mut self, rec: &mut Recorder<'_>, scene: &GpuScene) -> Result<Option<Radiance>> {
        let radiance = self.dispatch(rec, scene);
        self.parity ^= 1;
        radiance
    }

    /// Dispatches `trace_resolve.comp`: the temporal filter over the history and tone mapping
    /// into the output buffer, made readable by the composite and the host.
    fn resolve(&mut self, rec: &mut Recorder<'_>, radiance: Radiance) -> Result<TracedImage> {
        let (d, cmd) = (&rec.device.raw, rec.cmd);
        let groups = radiance.size.map(|s| s.div_ceil(TRACE_GROUP));
        // Safety: `cmd` is recording outside a rendering pass (`trace` ended it); the set's
        // buffers live until this frame finishes.
        unsafe {
            d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, self.pipelines.layout, 0, &[radiance.set], &[]);
            d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, self.pipelines.resolve);
            d.cmd_dispatch(cmd, groups[0], groups[1], 1);
            barrier(d, cmd, vk::PipelineStageFlags2::COMPUTE_SHADER, vk::PipelineStageFlags2::FRAGMENT_SHADER | vk::PipelineStageFlags2::HOST);
        }
        Ok(TracedImage { size: radiance.size, output: radiance.output })
    }

    fn statistics(&self) -> &Statistics {
        &self.statistics
    }

    fn name(&self) -> &'static str {
        if self.accelerations.is_some() { "hardware" } else { "compute" }
    }

    /// Reads the counters of the frames in flight first (the GPU must be idle).
    fn destroy(&mut self, device: &Device) {
        for slot in 0..self.unread.len() {
            self.read_counters(device, slot);
        }
        if let Some(stamps) = self.timestamps.take() {
            stamps.destroy(device);
        }
        self.resident.destroy(device);
        if let Some(mut accelerations) = self.accelerations.take() {
            accelerations.destroy(device);
        }
        if let Some((b, _)) = self.texel_buffer.take() {
            device.destroy_buffer(b);
        }
        if let Some(sky) = self.sky.take() {
            sky.destroy(device);
        }
        if let Some(p) = self.pixels.take() {
            destroy_pixels(device, p);
        }
        for b in self.counters.drain(..) {
            device.destroy_buffer(b);
        }
        for pool in self.pools.drain(..) {
            // Safety: the GPU is idle.
            unsafe { device.raw.destroy_descriptor_pool(pool, None) };
        }
        self.pipelines.destroy(device);
    }
}

fn destroy_pixels(device: &Device, p: PixelBuffers) {
    let [a, b] = p.accumulation;
    for buffer in [p.gbuffer, a, b, p.output] {
        device.destroy_buffer(buffer);
    }
}

/// A full memory barrier from `src` to `dst` stages.
///
/// # Safety
/// `cmd` is recording outside a rendering pass.
pub(crate) unsafe fn barrier(d: &ash::Device, cmd: vk::CommandBuffer, src: vk::PipelineStageFlags2, dst: vk::PipelineStageFlags2) {
    let barrier = [vk::MemoryBarrier2::default()
        .src_stage_mask(src)
        .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
        .dst_stage_mask(dst)
        .dst_access_mask(vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE)];
    // Safety: per the function's contract.
    unsafe { d.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().memory_barriers(&barrier)) };
}

/// The radiance of missed rays when the frame has no sky draws: the frame's first colour
/// clear of the window, linear.
fn environment(frame: &Frame) -> [f32; 4] {
    let [r, g, b, _] = scene::clear_color(frame).unwrap_or([0.0; 4]);
    [scene::srgb_to_linear(r), scene::srgb_to_linear(g), scene::srgb_to_linear(b), 0.0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_environment_is_the_linear_clear_colour() {
        let frame = Frame { clears: vec![crate::frame::Clear { color: Some([1.0, 0.5, 0.0, 1.0]), ..Default::default() }], ..Frame::default() };
        let env = environment(&frame);
        assert_eq!(env[0], 1.0);
        assert!((env[1] - 0.214_041).abs() < 1e-5);
        assert_eq!(environment(&Frame::default()), [0.0; 4]);
    }
}
