//! The raster stage ([`Raster`]): the frame's command recording and the raster part of every
//! frame, one stage provider of [`crate::render::frame::Renderer`].
//!
//! [`Raster::record`] records a frame into the command buffer of the current frame-in-flight
//! [`Slot`] in program order: at each draw index, the clears placed before it, then the pixel
//! operations placed before it, then the draw, if it is one the caller rasterizes; it can stop
//! before a given draw, where the caller records another stage (the traced image) and then
//! marks that draw done ([`Raster::skip_draw`]). It remembers in [`Progress`] how far it got,
//! so a frame read back several times is drawn once: [`Raster::read`] submits, waits and
//! copies a rectangle back; [`Raster::present`] finishes the frame and submits it without
//! waiting (two frames in flight: the program's next frame is assembled while the GPU draws
//! this one). It also owns the framebuffers (the window's, framebuffer objects'), occlusion
//! queries and the accumulation buffer.
//!
//! Memory stays bounded however long a frame is: past [`SUBMISSION_UPLOADS`] bytes uploaded,
//! what is recorded is submitted and waited for and recording goes on in the same slot (as a
//! read-back does); a frame that `translate` submits in parts ([`FrameEnd::Part`]) is
//! presented part by part, and after each part the texture versions no frame references any
//! more are freed ([`Raster::release_unreferenced_textures`]).
//!
//! Extension points for the other stages, the pixel path and presentation: [`Recorder`]
//! gives the device, the current command buffer, the [`Target`] images, the upload ring and
//! the frame's descriptor sets, and starts or ends the dynamic-rendering pass on demand
//! ([`super::pixel_ops::record`] receives one per pixel operation, the tracer one per traced
//! frame); [`FrameOutput`]s added with [`Raster::add_output`] record their copies at the end
//! of each presented frame, give the submission semaphores, and hear when the GPU finished it
//! (the `GLRT_DUMP` writer and the window are two).

use std::collections::HashMap;
use std::sync::Arc;

use ash::vk;

use super::commands::{SetKey, Slot};
use super::occlusion::Occlusion;
use super::output::{FrameOutput, SubmitSync};
use super::device::{Device, Result};
use super::dynamic::{DynamicValues, Tracked};
use super::ff;
use super::pipelines::{FixedState, PipelineKey, Pipelines};
use super::target::{Plane, Target};
use super::textures::Textures;
use super::upload::Slice;
use super::{conv, multisample, pixel_ops, readback};
use crate::frame::pixels::{PixelBuffer, PixelOp};
use crate::render::fog::FrameFog;
use crate::render::fog::settings::FogSettings;
use crate::render::hud::canvas::Canvas;
use crate::render::radiosity::stage::FrameIndirect;
use crate::frame::state::{Stencil, StencilFaces};
use crate::frame::framebuffer::FramebufferKey;
use crate::frame::{Clear, ColorBuffer, Draw, DrawBuffers, Frame, FrameEnd, Framebuffer, RasterState};

/// Frames in flight.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Bytes of vertices, indices, uniforms and texels one submission uploads at most before
/// [`Raster::record`] submits what it recorded and goes on in a new one (the upload memory of
/// a frame in flight stays about this size, however long the frame).
pub const SUBMISSION_UPLOADS: u64 = 64 << 20;

/// How much of which frame is already recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Progress {
    /// The frame number.
    pub frame: u64,
    /// Draws recorded.
    pub draws: usize,
    /// Clears recorded.
    pub clears: usize,
    /// Pixel operations recorded.
    pub pixels: usize,
    /// Indices of the last recorded draw that were recorded (translate may append to that
    /// draw after a read-back: the rest is recorded next time).
    pub last_indices: usize,
}

/// The raster stage and the frame's command recording.
pub struct Raster {
    parts: Parts,
    slots: Vec<Slot>,
    current: usize,
    /// Whether the current slot's command buffer is recording.
    recording: bool,
    progress: Option<Progress>,
    /// Frame dumps (`GLRT_DUMP`), presentation.
    outputs: Vec<Box<dyn FrameOutput>>,
    /// The accumulation buffer.
    accum: pixel_ops::accum::Accum,
}

/// The renderer's state other than the slots (borrowed apart from them by [`Recorder`]).
struct Parts {
    device: Device,
    occlusion: Occlusion,
    pipelines: Pipelines,
    textures: Textures,
    /// The window's framebuffer.
    target: Option<Target>,
    /// The images of framebuffer objects, by their description
    /// ([`crate::frame::framebuffer`]).
    offscreen: HashMap<FramebufferKey, Target>,
    /// The framebuffer recorded into: a framebuffer object's key, or `None` for the window.
    active: Option<FramebufferKey>,
    rendering: bool,
    /// The colour image the rendering pass draws into.
    color: Plane,
    /// Samples per pixel of the target ([`Raster::set_target`]).
    samples: u32,
    /// Whether the target has destination alpha ([`Raster::set_target`]).
    alpha: bool,
    /// The height fog's settings ([`Raster::set_fog`]).
    fog: FogSettings,
    /// The height fog of the frame being recorded (`None`: off).
    frame_fog: Option<FrameFog>,
    /// Radiosity's indirect light for the static draws of the frame being recorded
    /// ([`Raster::set_indirect`]).
    frame_indirect: Option<FrameIndirect>,
}

/// Access to the frame being recorded, for the parts that record into it (draws, clears,
/// pixel operations, presentation).
pub struct Recorder<'a> {
    /// The device.
    pub device: &'a Device,
    /// The command buffer being recorded.
    pub cmd: vk::CommandBuffer,
    /// The framebuffer.
    pub target: &'a mut Target,
    /// The frame's upload memory.
    pub ring: &'a mut super::upload::Ring,
    /// The frame's descriptor sets.
    pub descriptors: &'a mut super::commands::Descriptors,
    /// Pipelines.
    pub pipelines: &'a mut Pipelines,
    /// Textures.
    pub textures: &'a mut Textures,
    rendering: &'a mut bool,
    color: &'a mut Plane,
    occlusion: &'a mut Occlusion,
    /// The frame-in-flight slot recorded into.
    slot: usize,
    /// The frame number and the GL occlusion query counting the next draws, if any.
    query: (u64, Option<u32>),
    /// The framebuffer recorded into (`None`: the window's).
    framebuffer: Option<FramebufferKey>,
    /// The frame's height fog, for draws into the window's framebuffer (`None`: off).
    pub fog: Option<FrameFog>,
    /// Radiosity's indirect light, for the static world's draws into the window's
    /// framebuffer (`None`: off).
    pub indirect: Option<FrameIndirect>,
    /// The pipeline and dynamic state set in the rendering pass.
    tracked: Tracked,
    /// The last draw's uniform block and where it was uploaded: a draw with the same block
    /// (consecutive draws of one transform and state) reads that copy.
    uniform: Option<(ff::uniforms::FfBlock, Slice)>,
}

impl Recorder<'_> {
    /// The frame-in-flight slot recorded into.
    pub fn slot(&self) -> usize {
        self.slot
    }

    /// Begins the dynamic-rendering pass on the target (no-op if begun).
    pub fn begin_rendering(&mut self) {
        if *self.rendering {
            return;
        }
        self.target.transition(self.device, self.cmd, *self.color, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL);
        self.target.transition(self.device, self.cmd, Plane::DepthStencil, vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
        let color = [vk::RenderingAttachmentInfo::default()
            .image_view(self.target.image(*self.color).view)
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE)];
        let depth = vk::RenderingAttachmentInfo::default()
            .image_view(self.target.depth.view)
            .image_layout(vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE);
        let [w, h] = self.target.size;
        let info = vk::RenderingInfo::default()
            .render_area(vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width: w, height: h } })
            .layer_count(1)
            .color_attachments(&color)
            .depth_attachment(&depth)
            .stencil_attachment(&depth);
        // Safety: the attachments are in the layouts named; cmd is recording outside a pass.
        unsafe { self.device.raw.cmd_begin_rendering(self.cmd, &info) };
        *self.rendering = true;
        self.tracked.forget();
    }

    /// Forgets the pipeline and dynamic state the recorder's draws set: for parts that bind
    /// their own graphics pipeline or set dynamic state in the pass (the next draw sets all).
    pub fn forget_state(&mut self) {
        self.tracked.forget();
    }

    /// Ends the rendering pass (no-op outside one), before transfers or barriers.
    pub fn end_rendering(&mut self) {
        if *self.rendering {
            self.occlusion.end_span(self.device, self.cmd, self.slot);
            // Safety: a pass is open on cmd.
            unsafe { self.device.raw.cmd_end_rendering(self.cmd) };
            *self.rendering = false;
        }
    }

    /// Runs `record` with a recorder drawing into the back colour image of `target` instead
    /// of the framebuffer (an image the renderer does not own: the tracer's environment faces,
    /// [`crate::render::trace::sky`]), its draws counted in no occlusion query; the pass on
    /// the framebuffer is ended before, and the one on `target` after.
    pub fn with_target<T>(&mut self, target: &mut Target, record: impl FnOnce(&mut Recorder<'_>) -> Result<T>) -> Result<T> {
        self.end_rendering();
        let mut color = Plane::Color;
        let mut rec = Recorder {
            device: self.device,
            cmd: self.cmd,
            target,
            ring: self.ring,
            descriptors: self.descriptors,
            pipelines: self.pipelines,
            textures: self.textures,
            rendering: self.rendering,
            color: &mut color,
            occlusion: self.occlusion,
            slot: self.slot,
            query: (self.query.0, None),
            framebuffer: self.framebuffer,
            fog: None,
            indirect: None,
            tracked: Tracked::default(),
            uniform: None,
        };
        let result = record(&mut rec);
        rec.end_rendering();
        result
    }

    /// Makes the rendering pass draw into the colour image of `buffer` (ending the pass when
    /// it drew into the other).
    pub fn set_color_buffer(&mut self, buffer: ColorBuffer) {
        let plane = Plane::of(buffer);
        if *self.color != plane {
            self.end_rendering();
            *self.color = plane;
        }
    }

    /// Runs `write` once per colour buffer that `buffers` selects (section 4.2.1), front
    /// first, with the state to use: for `GL_FRONT_AND_BACK` the front pass leaves depth,
    /// stencil and occlusion counts alone (so the back pass sees the framebuffer as it was and
    /// updates them once); with no colour buffer (`GL_NONE`, whose colour mask translate
    /// clears) it runs once on the back image for depth and stencil.
    pub fn for_each_buffer(&mut self, buffers: DrawBuffers, state: &Arc<RasterState>, mut write: impl FnMut(&mut Self, &Arc<RasterState>) -> Result<()>) -> Result<()> {
        let mut buffers = buffers.buffers();
        let Some(mut last) = buffers.next() else {
            self.set_color_buffer(ColorBuffer::Back);
            return write(self, state);
        };
        let mut color_only = None;
        for next in buffers {
            let color_only = color_only.get_or_insert_with(|| {
                Arc::new(RasterState {
                    depth_write: false,
                    stencil: state.stencil.map(|s| StencilFaces {
                        front: Stencil { write_mask: 0, ..s.front },
                        back: Stencil { write_mask: 0, ..s.back },
                    }),
                    ..(**state).clone()
                })
            });
            let query = self.query;
            self.query.1 = None;
            self.set_color_buffer(last);
            let written = write(self, color_only);
            self.query = query;
            written?;
            last = next;
        }
        self.set_color_buffer(last);
        write(self, state)
    }

    /// Records a `glClear`: cleared buffers, masks and scissor box as the frame says
    /// (section 4.2.3). Unmasked clears use `vkCmdClearAttachments`.
    pub fn clear(&mut self, clear: &Clear) {
        let [w, h] = self.target.size;
        let rect = match clear.scissor {
            Some(s) => self.target.vk_rect(s),
            None => Some(vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width: w, height: h } }),
        };
        let Some(rect) = rect else { return };
        let mut attachments = Vec::new();
        if let Some(c) = clear.color.filter(|_| clear.color_mask.iter().any(|&m| m)) {
            if clear.color_mask != [true; 4] {
                log_once("colour clears with a partial colour mask are drawn unmasked");
            }
            attachments.push(vk::ClearAttachment {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                color_attachment: 0,
                clear_value: vk::ClearValue { color: vk::ClearColorValue { float32: self.target.stored_color(c.map(|v| v.clamp(0.0, 1.0))) } },
            });
        }
        let mut aspects = vk::ImageAspectFlags::empty();
        let depth = clear.depth.filter(|_| clear.depth_mask);
        if depth.is_some() {
            aspects |= vk::ImageAspectFlags::DEPTH;
        }
        let stencil = clear.stencil.filter(|_| clear.stencil_mask & 0xff != 0);
        if stencil.is_some() {
            if clear.stencil_mask & 0xff != 0xff {
                log_once("stencil clears with a partial stencil mask write every bit");
            }
            aspects |= vk::ImageAspectFlags::STENCIL;
        }
        if !aspects.is_empty() {
            attachments.push(vk::ClearAttachment {
                aspect_mask: aspects,
                color_attachment: 0,
                clear_value: vk::ClearValue {
                    depth_stencil: vk::ClearDepthStencilValue {
                        depth: depth.unwrap_or(1.0).clamp(0.0, 1.0) as f32,
                        stencil: stencil.unwrap_or(0) as u32 & 0xff,
                    },
                },
            });
        }
        if attachments.is_empty() {
            return;
        }
        self.begin_rendering();
        let rects = [vk::ClearRect { rect, base_array_layer: 0, layer_count: 1 }];
        // Safety: inside the pass; the rectangle lies in the render area.
        unsafe { self.device.raw.cmd_clear_attachments(self.cmd, &attachments, &rects) };
    }

    /// Records the batches of `draw`, each once per pass of [`multisample::passes`] (one,
    /// except with `GL_MULTISAMPLE` off on a multisampled target).
    pub fn draw(&mut self, draw: &Draw) -> Result<()> {
        let state = &draw.state;
        let [vx, vy, vw, vh] = state.viewport;
        if vw <= 0 || vh <= 0 {
            return Ok(());
        }
        let [w, h] = self.target.size;
        let full = vk::Rect2D { offset: vk::Offset2D::default(), extent: vk::Extent2D { width: w, height: h } };
        let scissor = match state.scissor {
            Some(s) => match self.target.vk_rect(s) {
                Some(r) => r,
                None => return Ok(()),
            },
            None => full,
        };
        let indirect = self.indirect.as_ref().filter(|_| self.framebuffer.is_none()).and_then(|i| i.light.of_draw(draw, &i.eye_to_world));
        let batches = ff::prepare(draw, indirect.as_deref());
        if batches.is_empty() {
            return Ok(());
        }
        let slot_textures = draw.program.as_ref().map_or(&[][..], |p| &p.textures[..]);
        if self.textures.needs_upload(draw.textures.iter().chain(slot_textures)) {
            self.end_rendering();
            self.textures.upload(self.device, self.cmd, self.ring, draw.textures.iter().chain(slot_textures))?;
        }
        let lod_bias = std::array::from_fn(|u| draw.texture_units.get(u).copied().flatten().map_or(0.0, |t| t.env.lod_bias));
        let images = self.textures.bindings(self.device, &draw.textures, lod_bias)?;
        let program = match &draw.program {
            Some(p) => Some((p.program.id, super::programs::bind_set(self, p)?)),
            None => None,
        };
        self.begin_rendering();
        let (frame, query) = self.query;
        self.occlusion.before_draw(self.device, self.cmd, self.slot, frame, query)?;
        let d = &self.device.raw;
        let limits = &self.device.properties.limits;
        // The per-draw block is a storage buffer (shaders/ff_uniforms.glsl says why).
        let block_align = limits.min_storage_buffer_offset_alignment.max(16);
        let passes = multisample::passes(self.target.samples, &state.multisample, self.device.features.alpha_to_one);
        let viewport = [
            vx as f32,
            (h as i64 - vy as i64) as f32,
            vw as f32,
            -(vh as f32),
            state.depth_range[0].clamp(0.0, 1.0) as f32,
            state.depth_range[1].clamp(0.0, 1.0) as f32,
        ];
        let features = &self.device.features;
        // Lines a program's vertex stage places (the only ones Vulkan draws as lines): aliased
        // widths round to whole pixels (section 3.4.2).
        let width = if state.line.smooth { state.line.width } else { state.line.width.round().max(1.0) };
        let line_width = if features.wide_lines {
            width.clamp(features.line_width_range[0], features.line_width_range[1])
        } else {
            1.0
        };
        note_missing_features(features, &batches, draw);
        // The draw's uniform block, the same for all its batches, written once where the GPU
        // reads it (or not at all when the previous draw's is the same, byte for byte), and
        // the descriptor set that holds it.
        let mut block = ff::uniforms::block(draw);
        ff::uniforms::set_framebuffer_height(bytemuck::bytes_of_mut(&mut block), h);
        if let Some(fog) = self.fog.as_ref().filter(|_| self.framebuffer.is_none()) {
            ff::uniforms::set_height_fog(bytemuck::bytes_of_mut(&mut block), &fog.for_draw(draw, h));
        }
        let uniform = match &self.uniform {
            Some((last, slice)) if bytemuck::bytes_of(last) == bytemuck::bytes_of(&block) => *slice,
            _ => {
                let slice = self.ring.push_slice(self.device, bytemuck::bytes_of(&block), block_align)?;
                self.uniform = Some((block, slice));
                slice
            }
        };
        let set_key = SetKey { layout: self.pipelines.set_layout, buffers: &[(uniform.buffer, ff::UNIFORM_SIZE as u64)], images: &images };
        let set = self.descriptors.get(self.device, &set_key)?;
        // The draw's own vertices, packed into upload memory once for the batches that use them:
        // in a compact format but for a program's draws and those radiosity lights. The batches
        // that use them differ only in their keys' primitive and facing, which no attribute's
        // reading depends on: the first one's key chooses the format.
        let own_format = match batches.iter().find(|b| b.vertices == ff::BatchVertices::Draw) {
            Some(batch) if program.is_none() && indirect.is_none() => ff::VertexFormat::of(&draw.vertices, &batch.shader),
            _ => ff::VertexFormat::FULL,
        };
        let mut own_vertices = None;
        for batch in &batches {
            let index_count = batch.indices.len(draw);
            if index_count == 0 {
                continue;
            }
            let stencil = batch.stencil(state.stencil);
            let mut fixed = FixedState::new(state, batch.cull, batch.polygon_offset, stencil, features.logic_op);
            fixed.color_mask = self.target.color_write_mask(fixed.color_mask);
            if state.logic_op.is_some() && !features.logic_op {
                log_once("the device has no logicOp feature: glLogicOp is ignored");
            }
            let (vertex_format, (vertices, shared)) = match (&batch.vertices, own_vertices) {
                (ff::BatchVertices::Draw, Some(packed)) => (own_format, packed),
                (ff::BatchVertices::Draw, None) => (own_format, *own_vertices.insert(self.pack_own(draw, own_format, indirect.as_deref())?)),
                (ff::BatchVertices::Expanded(expanded), _) => (ff::VertexFormat::FULL, (self.ring.push_slice(self.device, expanded, 16)?, None)),
            };
            let generic = if batch.generic.is_empty() { None } else { Some(self.ring.push_slice(self.device, &batch.generic, 16)?) };
            let indices = self.ring.push_with(self.device, index_count, 4, |out: &mut [u32]| batch.indices.write(draw, out))?;
            let polygon_mode = if features.fill_mode_non_solid { conv::polygon_mode(batch.polygon_mode) } else { vk::PolygonMode::FILL };
            let stencil = stencil.unwrap_or(StencilFaces::both(Stencil::default()));
            let face = |s: Stencil| [s.reference.clamp(0, 255) as u32, s.value_mask, s.write_mask];
            let dynamic = DynamicValues {
                viewport,
                scissor,
                line_width,
                depth_bias: [state.polygon_offset.units, state.polygon_offset.factor],
                blend_constants: state.blend.map_or([0.0; 4], |b| b.color),
                stencil: [face(stencil.front), face(stencil.back)],
            };
            for &(samples, [dx, dy]) in passes.iter() {
                let key = PipelineKey {
                    shader: batch.shader,
                    topology: conv::topology(batch.topology),
                    polygon_mode,
                    program: program.map(|(id, _)| id),
                    fixed: FixedState { samples, ..fixed },
                    vertex_format,
                };
                let Some(pipeline) = self.pipelines.get(self.device, &key)? else { continue };
                let [x, y, width, height, near, far] = viewport;
                let dynamic = DynamicValues { viewport: [x + dx, y + dy, width, height, near, far], ..dynamic };
                // Safety: inside the pass (begun above, so `tracked` is of it); every handle is
                // alive for the frame; the dynamic offset is aligned and within the ring chunk.
                unsafe {
                    self.tracked.set(self.device, self.cmd, pipeline, &dynamic);
                    d.cmd_bind_descriptor_sets(self.cmd, vk::PipelineBindPoint::GRAPHICS, self.pipelines.layout, 0, &[set], &[uniform.offset as u32]);
                    if let Some((_, (program_set, offsets))) = program {
                        d.cmd_bind_descriptor_sets(self.cmd, vk::PipelineBindPoint::GRAPHICS, self.pipelines.layout, 1, &[program_set], &offsets);
                    }
                    d.cmd_bind_vertex_buffers(self.cmd, 0, &[vertices.buffer], &[vertices.offset]);
                    if let Some(shared) = shared {
                        d.cmd_bind_vertex_buffers(self.cmd, ff::compact::SHARED_BINDING, &[shared.buffer], &[shared.offset]);
                    }
                    if let Some(generic) = generic {
                        d.cmd_bind_vertex_buffers(self.cmd, 1, &[generic.buffer], &[generic.offset]);
                    }
                    d.cmd_bind_index_buffer(self.cmd, indices.buffer, indices.offset, vk::IndexType::UINT32);
                    d.cmd_draw_indexed(self.cmd, index_count as u32, 1, 0, 0, 0);
                }
            }
        }
        Ok(())
    }

    /// Packs the draw's own vertices into upload memory in `format`, with radiosity's
    /// `indirect` light in the full layout: the vertices, and for a compact format the shared
    /// vertex ([`ff::compact::shared`]).
    fn pack_own(&mut self, draw: &Draw, format: ff::VertexFormat, indirect: Option<&[[f32; 3]]>) -> Result<(Slice, Option<Slice>)> {
        if format.is_full() {
            let floats = draw.vertices.len() * ff::VERTEX_FLOATS;
            let packed = self.ring.push_with(self.device, floats, 16, |out: &mut [f32]| {
                ff::vertex::pack_into(draw, out);
                if let Some(indirect) = indirect {
                    ff::vertex::set_indirect(out, indirect);
                }
            })?;
            return Ok((packed, None));
        }
        let words = draw.vertices.len() * format.stride() as usize / 4;
        let packed = self.ring.push_with(self.device, words, 16, |out: &mut [u32]| ff::compact::pack_into(draw, format, out))?;
        let shared = self.ring.push_slice(self.device, &ff::compact::shared(draw), 16)?;
        Ok((packed, Some(shared)))
    }
}

impl Raster {
    /// Creates the stage on the device chosen by `GLRT_DEVICE` (see [`Device::new`]), with no
    /// [`FrameOutput`]: frames stay in the framebuffer until outputs are added.
    pub fn new() -> Result<Raster> {
        let device = Device::new()?;
        let pipelines = Pipelines::new(&device)?;
        let textures = Textures::new(&device);
        let slots = (0..FRAMES_IN_FLIGHT).map(|_| Slot::new(&device)).collect::<Result<Vec<_>>>()?;
        let occlusion = Occlusion::new(FRAMES_IN_FLIGHT, device.features.occlusion_query_precise);
        Ok(Raster {
            parts: Parts {
                device,
                occlusion,
                pipelines,
                textures,
                target: None,
                offscreen: HashMap::new(),
                active: None,
                rendering: false,
                color: Plane::Color,
                samples: 1,
                alpha: true,
                fog: FogSettings::default(),
                frame_fog: None,
                frame_indirect: None,
            },
            slots,
            current: 0,
            recording: false,
            progress: None,
            outputs: Vec::new(),
            accum: pixel_ops::accum::Accum::default(),
        })
    }

    /// The device.
    pub fn device(&self) -> &Device {
        &self.parts.device
    }

    /// Fogs the next frames' 3D draws with the height fog of `settings` ([`crate::render::fog`]).
    pub fn set_fog(&mut self, settings: FogSettings) {
        self.parts.fog = settings;
    }

    /// Lights the static world's lit draws of the frame being recorded with radiosity's
    /// `indirect` light in place of GL's ambient term (`None`: GL's).
    pub fn set_indirect(&mut self, indirect: Option<FrameIndirect>) {
        self.parts.frame_indirect = indirect;
    }

    /// Adds a consumer of presented frames (presentation, dumps), called in the order added.
    pub fn add_output(&mut self, output: Box<dyn FrameOutput>) {
        self.outputs.push(output);
    }

    /// Takes the consumers of presented frames away, their objects of this stage's device
    /// freed ([`FrameOutput::release`]): for a stage on a new device, after this one's was
    /// lost.
    pub fn take_outputs(&mut self) -> Vec<Box<dyn FrameOutput>> {
        // A device that is not really gone (an injected loss) may still be running frames
        // that write into the outputs' buffers.
        let _ = self.parts.device.wait_idle();
        let mut outputs = std::mem::take(&mut self.outputs);
        for output in &mut outputs {
            output.release(&self.parts.device);
        }
        outputs
    }

    /// Pipelines created so far (tests, statistics).
    pub fn pipeline_count(&self) -> usize {
        self.parts.pipelines.len()
    }

    /// Programs whose shader modules are on the GPU (tests, statistics).
    pub fn program_count(&self) -> usize {
        self.parts.pipelines.program_count()
    }

    /// Texture versions on the GPU (tests, statistics).
    pub fn texture_count(&self) -> usize {
        self.parts.textures.len()
    }

    /// A [`Recorder`] on the current slot for a frame of `size`, starting the command buffer
    /// and (re)creating the target when needed (new size, sample count or alpha). It records into
    /// the active framebuffer ([`Raster::switch_to`]): the window's, or a framebuffer
    /// object's images (created on first use, single-sampled).
    pub fn recorder(&mut self, size: [u32; 2]) -> Result<Recorder<'_>> {
        let max = self.parts.device.properties.limits.max_image_dimension2_d;
        let size = size.map(|s| s.clamp(1, max));
        let (samples, alpha) = (self.parts.samples, self.parts.alpha);
        if self.parts.target.as_ref().is_some_and(|t| t.size != size || t.samples != samples || t.alpha != alpha) {
            self.flush()?;
            self.parts.device.wait_idle()?;
            if let Some(t) = self.parts.target.take() {
                t.destroy(&self.parts.device);
            }
        }
        if !self.recording {
            self.wait_slot(self.current)?;
            let slot = &mut self.slots[self.current];
            slot.begin(&self.parts.device)?;
            self.parts.occlusion.begin_slot(&self.parts.device, slot.cmd, self.current);
            self.recording = true;
        }
        let slot = &mut self.slots[self.current];
        let parts = &mut self.parts;
        let target = match parts.active {
            None => {
                if parts.target.is_none() {
                    let mut target = Target::new(&parts.device, size, samples, alpha)?;
                    target.clear_initial(&parts.device, slot.cmd);
                    parts.target = Some(target);
                }
                parts.target.as_mut()
            }
            Some(key) => {
                if !parts.offscreen.contains_key(&key) {
                    let mut target = Target::new(&parts.device, key.size.map(|s| s.clamp(1, max)), 1, key.alpha)?;
                    target.clear_initial(&parts.device, slot.cmd);
                    parts.offscreen.insert(key, target);
                }
                parts.offscreen.get_mut(&key)
            }
        };
        let Some(target) = target else { unreachable!("created above") };
        Ok(Recorder {
            device: &parts.device,
            cmd: slot.cmd,
            target,
            ring: &mut slot.ring,
            descriptors: &mut slot.descriptors,
            pipelines: &mut parts.pipelines,
            textures: &mut parts.textures,
            rendering: &mut parts.rendering,
            color: &mut parts.color,
            occlusion: &mut parts.occlusion,
            slot: self.current,
            query: (0, None),
            framebuffer: parts.active,
            fog: parts.frame_fog,
            indirect: parts.frame_indirect.clone(),
            tracked: Tracked::default(),
            uniform: None,
        })
    }

    /// A [`Recorder`] into `framebuffer` (`None`: the window's) for a frame of `size`, the
    /// rendering pass on another framebuffer ended first.
    pub fn recorder_into(&mut self, framebuffer: Option<FramebufferKey>, size: [u32; 2]) -> Result<Recorder<'_>> {
        if self.parts.active != framebuffer {
            self.end_pass();
            self.switch_to(framebuffer);
        }
        self.recorder(size)
    }

    /// Records what of `frame` is not recorded yet, in program order, up to the draw `until`
    /// (exclusive: the clears and pixel operations placed before it are recorded) or to the
    /// end; of the draws, those whose index `rasterized` accepts (the others are another
    /// stage's).
    pub fn record(&mut self, frame: &Frame, until: Option<usize>, rasterized: &dyn Fn(usize) -> bool) -> Result<()> {
        self.parts.frame_fog = FrameFog::of(frame, &self.parts.fog);
        let mut accum = std::mem::take(&mut self.accum);
        let result = self.record_with(frame, until, rasterized, &mut accum);
        self.accum = accum;
        result
    }

    /// Draws of `frame` recorded so far (or marked done by [`Raster::skip_draw`]).
    pub fn recorded_draws(&self, frame: &Frame) -> usize {
        self.progress.filter(|p| p.frame == frame.number).map_or(0, |p| p.draws)
    }

    /// Marks draw `index` of `frame` as recorded without rasterizing it (another stage drew
    /// in its place); the draws before it were recorded.
    pub fn skip_draw(&mut self, frame: &Frame, index: usize) {
        if let Some(draw) = frame.draws.get(index) {
            let progress = self.progress.filter(|p| p.frame == frame.number).unwrap_or_default();
            self.progress = Some(Progress { frame: frame.number, draws: index + 1, last_indices: draw.indices.len(), ..progress });
        }
    }

    /// [`Raster::record`] with the accumulation buffer taken out of `self` (pixel operations
    /// that read the framebuffer submit and wait in the middle of the frame).
    fn record_with(&mut self, frame: &Frame, until: Option<usize>, rasterized: &dyn Fn(usize) -> bool, accum: &mut pixel_ops::accum::Accum) -> Result<()> {
        let mut progress = match self.progress {
            Some(p) if p.frame == frame.number => p,
            _ => Progress { frame: frame.number, ..Progress::default() },
        };
        let mut rec = self.recorder(frame.size)?;
        // Makes `rec` record into `$framebuffer` (ending the pass on another one).
        macro_rules! record_into {
            ($framebuffer:expr) => {
                if key_of(&$framebuffer) != rec.framebuffer {
                    rec.end_rendering();
                    self.switch_to(key_of(&$framebuffer));
                    rec = self.recorder(frame.size)?;
                }
            };
        }
        let query_of = |index: usize| frame.occlusion_queries.iter().find(|(_, range)| range.contains(&index)).map(|(q, _)| *q);
        if let Some(last) = progress.draws.checked_sub(1).and_then(|i| frame.draws.get(i))
            && last.indices.len() > progress.last_indices
            && rasterized(progress.draws - 1)
        {
            record_into!(last.state.framebuffer);
            rec.query = (frame.number, query_of(progress.draws - 1));
            draw_in_buffers(&mut rec, &tail(last, progress.last_indices))?;
            progress.last_indices = last.indices.len();
        }
        for index in progress.draws..=until.unwrap_or(frame.draws.len()) {
            // Clears and pixel operations before this draw, in program order (their rectangles
            // count in no occlusion query).
            loop {
                rec.query = (frame.number, None);
                let clear = frame.clears.get(progress.clears).filter(|c| c.before_draw <= index);
                let op = frame.pixels.get(progress.pixels).filter(|p| p.before_draw <= index);
                match (clear, op) {
                    (Some(clear), op) if op.is_none_or(|op| op.after_clears > progress.clears) => {
                        record_into!(clear.framebuffer);
                        let mut buffers = clear.draw_buffers.buffers().peekable();
                        if buffers.peek().is_none() {
                            pixel_ops::clear::record(&mut rec, clear)?;
                        }
                        for buffer in buffers {
                            rec.set_color_buffer(buffer);
                            pixel_ops::clear::record(&mut rec, clear)?;
                        }
                        if let Some(value) = clear.accum {
                            accum.clear(rec.target.size, clear.scissor, value);
                        }
                        progress.clears += 1;
                    }
                    (_, Some(op)) => {
                        record_into!(op.state.framebuffer);
                        let read = match pixel_ops::source(op, rec.target.size) {
                            Some((buffer, rect)) => {
                                let read = self.read_target(buffer, op.state.read_buffer, rect)?;
                                rec = self.recorder(frame.size)?;
                                read
                            }
                            None => None,
                        };
                        if pixel_ops::writes_color(op) {
                            rec.for_each_buffer(op.state.draw_buffers, &op.state, |rec, state| {
                                let op = PixelOp { state: state.clone(), ..op.clone() };
                                pixel_ops::record(rec, accum, &op, read.as_deref())
                            })?;
                        } else {
                            pixel_ops::record(&mut rec, accum, op, read.as_deref())?;
                        }
                        progress.pixels += 1;
                    }
                    (_, None) => break,
                }
            }
            if let Some(draw) = frame.draws.get(index).filter(|_| until != Some(index)) {
                if rasterized(index) {
                    record_into!(draw.state.framebuffer);
                    rec.query = (frame.number, query_of(index));
                    draw_in_buffers(&mut rec, draw)?;
                }
                progress.draws = index + 1;
                progress.last_indices = draw.indices.len();
                if rec.ring.bytes_used() > SUBMISSION_UPLOADS {
                    self.flush()?;
                    rec = self.recorder(frame.size)?;
                }
            }
        }
        self.progress = Some(progress);
        Ok(())
    }

    /// Submits the current slot's commands and waits for them (the slot starts again on the
    /// next [`Raster::recorder`]); occlusion counts recorded so far are read.
    fn flush(&mut self) -> Result<()> {
        if self.recording {
            self.end_pass();
            self.slots[self.current].submit(&self.parts.device, &SubmitSync::default())?;
            self.parts.pipelines.end_submission(&self.parts.device);
            self.recording = false;
            self.wait_slot(self.current)?;
        }
        Ok(())
    }

    fn end_pass(&mut self) {
        if self.parts.rendering {
            let cmd = self.slots[self.current].cmd;
            self.parts.occlusion.end_span(&self.parts.device, cmd, self.current);
            // Safety: a pass is open on the slot's command buffer.
            unsafe { self.parts.device.raw.cmd_end_rendering(cmd) };
            self.parts.rendering = false;
        }
    }

    /// Submits what is recorded of `frame` and copies `rect` of `buffer` back, colour from the
    /// frame's read buffer (see [`crate::frame::FrameSink::read_pixels`]).
    pub fn read(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Result<Option<Vec<[f32; 4]>>> {
        self.end_pass();
        self.switch_to(key_of(&frame.read_framebuffer));
        self.recorder(frame.size)?;
        self.read_target(buffer, frame.read_buffer, rect)
    }

    /// Submits what is recorded, waits, and copies `rect` of `buffer` (colour from `color`)
    /// back.
    fn read_target(&mut self, buffer: PixelBuffer, color: ColorBuffer, rect: [i32; 4]) -> Result<Option<Vec<[f32; 4]>>> {
        self.end_pass();
        let slot = &mut self.slots[self.current];
        let target = match self.parts.active {
            None => self.parts.target.as_mut(),
            Some(key) => self.parts.offscreen.get_mut(&key),
        };
        let Some(target) = target else { return Ok(None) };
        let Some(copy) = readback::Readback::record(&self.parts.device, slot.cmd, target, buffer, color, rect)? else {
            return Ok(None);
        };
        self.flush()?;
        Ok(Some(copy.finish(&self.parts.device)))
    }

    /// Finishes the recorded `frame` (the back buffer copied to the front at a swap, with
    /// `overlay` over its top-left corner, then the outputs' copies) and submits it without
    /// waiting; the next frame starts on the next slot. A part of a frame ([`FrameEnd::Part`])
    /// is only submitted: the outputs do not see it.
    pub fn present(&mut self, frame: &Frame, overlay: Option<&Canvas>) -> Result<()> {
        self.end_pass();
        self.switch_to(None);
        let slot = self.current;
        let mut sync = SubmitSync::default();
        let mut outputs = std::mem::take(&mut self.outputs);
        let shown = frame.end != FrameEnd::Part;
        let recorded = (|| {
            let mut rec = self.recorder(frame.size)?;
            rec.end_rendering();
            if frame.end == FrameEnd::Swap {
                rec.target.copy_back_to_front(rec.device, rec.cmd);
                if let Some(canvas) = overlay {
                    let slice = rec.ring.push(rec.device, &canvas.rgba, 16)?;
                    rec.target.copy_to_front(rec.device, rec.cmd, slice.buffer, slice.offset, canvas.size);
                }
            }
            for output in outputs.iter_mut().filter(|_| shown) {
                sync.extend(output.record(&mut rec, slot, frame.number)?);
            }
            let queries = frame.occlusion_queries.iter().map(|(q, _)| *q).collect();
            self.parts.occlusion.finish_frame(slot, frame.number, queries);
            self.slots[slot].submit(&self.parts.device, &sync)?;
            self.parts.pipelines.end_submission(&self.parts.device);
            outputs.iter_mut().filter(|_| shown).try_for_each(|o| o.submitted(&self.parts.device, slot))
        })();
        self.outputs = outputs;
        recorded?;
        self.parts.textures.end_frame(&self.parts.device);
        self.parts.pipelines.end_frame(&self.parts.device);
        self.recording = false;
        self.progress = None;
        self.current = (self.current + 1) % self.slots.len();
        self.release_offscreen(&frame.released)
    }

    /// Makes `framebuffer` (`None`: the window's) the one recorded into; the caller ended the
    /// rendering pass.
    fn switch_to(&mut self, framebuffer: Option<FramebufferKey>) {
        debug_assert!(!self.parts.rendering, "switching framebuffers inside a rendering pass");
        self.parts.active = framebuffer;
    }

    /// Frees the framebuffer-object images made of `released` attachments, once the GPU is
    /// done with every frame in flight.
    fn release_offscreen(&mut self, released: &[crate::frame::framebuffer::Attachment]) -> Result<()> {
        let dead: Vec<FramebufferKey> = self.parts.offscreen.keys().filter(|k| released.iter().any(|r| k.uses(r))).copied().collect();
        if dead.is_empty() {
            return Ok(());
        }
        self.wait_all()?;
        for key in dead {
            if let Some(target) = self.parts.offscreen.remove(&key) {
                target.destroy(&self.parts.device);
            }
        }
        Ok(())
    }

    /// Waits for every frame in flight and frees the texture versions no frame references
    /// any more (called after a part of a frame, whose texture versions may all be dead).
    pub fn release_unreferenced_textures(&mut self) -> Result<()> {
        if self.parts.textures.has_unreferenced() {
            self.wait_all()?;
            self.parts.textures.release_unreferenced(&self.parts.device);
        }
        Ok(())
    }

    /// Waits for every frame in flight (and writes their dumps).
    pub fn wait_all(&mut self) -> Result<()> {
        self.flush()?;
        (0..self.slots.len()).try_for_each(|i| self.wait_slot(i))
    }

    /// Waits for slot `i`'s submission and tells the outputs.
    fn wait_slot(&mut self, i: usize) -> Result<()> {
        if self.slots[i].wait(&self.parts.device)? {
            self.parts.occlusion.completed(&self.parts.device, i);
            for output in &mut self.outputs {
                output.completed(&self.parts.device, i);
            }
        }
        Ok(())
    }

    /// Where the next frames go (see [`crate::frame::FrameSink::set_target`]): the
    /// framebuffer is recreated with the drawable's sample count and destination alpha at the
    /// next frame (a count the device cannot render gives a single-sampled one, logged).
    pub fn set_target(&mut self, target: crate::frame::Target) {
        let counts = &self.parts.device.features.sample_counts;
        self.parts.samples = if target.samples <= 1 || counts.contains(&target.samples) {
            target.samples.max(1)
        } else {
            log_once("a drawable asks for a sample count the device cannot render: it is single-sampled");
            1
        };
        self.parts.alpha = target.alpha;
        for output in &mut self.outputs {
            output.set_target(&self.parts.device, target);
        }
    }

    /// Bits of the occlusion sample counter (see
    /// [`crate::frame::FrameSink::occlusion_counter_bits`]).
    pub fn occlusion_counter_bits(&self) -> u32 {
        self.parts.occlusion.counter_bits()
    }

    /// Samples that passed for occlusion query `query` of frame number `frame`, waiting for
    /// the frame in flight that ended it when the result is not known yet (see
    /// [`crate::frame::FrameSink::occlusion_result`]).
    pub fn occlusion_result(&mut self, frame: u64, query: u32) -> Result<Option<u64>> {
        if let Some(count) = self.parts.occlusion.result(frame, query) {
            return Ok(Some(count));
        }
        let Some(slot) = (0..self.slots.len()).find(|&i| self.parts.occlusion.holds(i, frame)) else { return Ok(None) };
        self.wait_slot(slot)?;
        Ok(self.parts.occlusion.result(frame, query))
    }
}

impl Drop for Raster {
    fn drop(&mut self) {
        if let Err(e) = self.wait_all() {
            log::warn!("glrt: waiting for the GPU at shutdown: {e}");
        }
        let device = &self.parts.device;
        let _ = device.wait_idle();
        for output in &mut self.outputs {
            output.destroy(device);
        }
        for slot in &mut self.slots {
            slot.destroy(device);
        }
        if let Some(target) = self.parts.target.take() {
            target.destroy(device);
        }
        for (_, target) in self.parts.offscreen.drain() {
            target.destroy(device);
        }
        self.parts.pipelines.destroy(device);
        self.parts.occlusion.destroy(device);
        self.parts.textures.destroy(device);
    }
}

/// Logs once what the device cannot draw of `batches` as asked: wide lines, large points and
/// polygon modes drawn natively (a program's vertex stage) need `wideLines`, `largePoints` and
/// `fillModeNonSolid` (lavapipe and NVIDIA have them); without them lines are 1 pixel wide,
/// points 1 pixel, and polygons filled.
fn note_missing_features(features: &super::device::Features, batches: &[ff::Batch], draw: &Draw) {
    use crate::frame::{Topology, state::PolygonMode};
    for b in batches {
        let lines = b.topology == Topology::Lines || b.polygon_mode == PolygonMode::Line;
        if lines && !features.wide_lines && draw.state.line.width != 1.0 {
            log_once("the device has no wideLines feature: lines a vertex shader places are 1 pixel wide");
        }
        let points = b.topology == Topology::Points || b.polygon_mode == PolygonMode::Point;
        if points && !features.large_points {
            log_once("the device has no largePoints feature: points a vertex shader places are 1 pixel wide");
        }
        if b.polygon_mode != PolygonMode::Fill && !features.fill_mode_non_solid {
            log_once("the device has no fillModeNonSolid feature: polygons a vertex shader places are filled in GL_LINE and GL_POINT modes");
        }
    }
}

/// The renderer's key of `framebuffer` (`None` for the window's).
fn key_of(framebuffer: &Framebuffer) -> Option<FramebufferKey> {
    framebuffer.object().map(|fbo| fbo.key())
}

/// Records `draw` into the colour buffers its state selects.
fn draw_in_buffers(rec: &mut Recorder<'_>, draw: &Draw) -> Result<()> {
    rec.for_each_buffer(draw.state.draw_buffers, &draw.state, |rec, state| {
        if Arc::ptr_eq(state, &draw.state) { rec.draw(draw) } else { rec.draw(&Draw { state: state.clone(), ..draw.clone() }) }
    })
}

/// The primitives of `draw` from index `from` on (whole primitives: `from` is a multiple of
/// the primitive size, as the draw only ever grows by whole primitives), with only the
/// vertices from the first one they use on (the draw grew by appending vertices: what was
/// recorded before is not copied again).
fn tail(draw: &Draw, from: usize) -> Draw {
    let indices = draw.indices.get(from..).unwrap_or_default();
    let first = indices.iter().copied().min().unwrap_or(0);
    let edges_from = if draw.edge_masks.is_empty() { 0 } else { from / 3 };
    Draw {
        vertex_count: draw.vertex_count.saturating_sub(first as usize),
        topology: draw.topology,
        vertices: draw.vertices.tail(first as usize),
        indices: indices.iter().map(|&i| i - first).collect(),
        edge_masks: draw.edge_masks.get(edges_from..).unwrap_or_default().to_vec(),
        modelview: draw.modelview,
        projection: draw.projection,
        texture_matrices: draw.texture_matrices.clone(),
        source: draw.source,
        state: draw.state.clone(),
        textures: draw.textures.clone(),
        texture_units: draw.texture_units.clone(),
        program: draw.program.clone(),
        class: draw.class,
        instance: draw.instance,
        layer: draw.layer.clone(),
    }
}

/// Logs `what` once per process.
pub(crate) fn log_once(what: &'static str) {
    use std::collections::HashSet;
    use std::sync::Mutex;
    static SEEN: Mutex<Option<HashSet<&'static str>>> = Mutex::new(None);
    if let Ok(mut seen) = SEEN.lock()
        && seen.get_or_insert_with(HashSet::new).insert(what)
    {
        log::warn!("glrt: {what}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tail_draws_the_same_vertices_without_those_recorded_before() {
        // Two triangles, then two more merged in with three vertices of their own.
        let mut draw = Draw::default();
        draw.vertices.position = (0..6).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect();
        draw.vertices.color.values = (0..6).map(|i| [i as f32 / 8.0, 0.5, 0.5, 1.0]).collect();
        draw.vertices.texcoords = vec![crate::frame::Attrib { values: vec![[0.25, 0.5, 0.0, 1.0]] }];
        draw.vertex_count = 6;
        draw.indices = vec![0, 1, 2, 2, 1, 0, 3, 4, 5, 5, 4, 3];
        draw.edge_masks = vec![1, 2, 3, 4];
        let t = tail(&draw, 6);
        assert_eq!(t.indices, vec![0, 1, 2, 2, 1, 0]);
        assert_eq!((t.vertices.len(), t.vertex_count), (3, 3), "only the vertices the tail uses");
        assert_eq!(t.edge_masks, vec![3, 4]);
        assert!(Arc::ptr_eq(&t.state, &draw.state));
        let (whole, part) = (ff::vertex::pack(&draw), ff::vertex::pack(&t));
        for (j, &i) in t.indices.iter().enumerate() {
            assert_eq!(ff::vertex::get(&part, i), ff::vertex::get(&whole, draw.indices[6 + j]), "index {j}");
        }
        assert!(tail(&draw, 12).indices.is_empty());
    }
}
