//! The context: every piece of OpenGL state, grouped by the module that owns it, plus the
//! objects shared with other contexts of the same share group.

use std::sync::Arc;

use parking_lot::Mutex;

use super::error::ErrorState;
use super::lists::{ListState, ListTable};
use crate::frame::{Frame, FrameEnd};
use crate::frame::{FrameSink, RecordingSink};

/// Objects shared by the contexts of one share group (`glXCreateContext`'s `shareList`):
/// display lists, texture objects, buffer objects, renderbuffer and framebuffer objects.
#[derive(Default)]
pub struct SharedObjects {
    /// Display lists by name.
    pub lists: ListTable,
    /// Texture objects by name.
    pub textures: super::texture::TextureTable,
    /// Buffer objects by name.
    pub buffers: super::buffer_objects::BufferTable,
    /// Renderbuffer and framebuffer objects by name.
    pub fbos: super::framebuffers::FramebufferTables,
    /// Shader and program objects by name.
    pub programs: super::programs::ProgramTable,
}

/// How a context is created.
pub struct ContextConfig {
    /// Objects to share with (another context's [`Context::shared`]), or a new share group.
    pub share: Option<Arc<Mutex<SharedObjects>>>,
    /// Where finished frames go.
    pub sink: Box<dyn FrameSink>,
}

/// An OpenGL 1.5 rendering context.
pub struct Context {
    pub(crate) errors: ErrorState,
    /// Display-list compilation state.
    pub lists: ListState,
    /// Objects shared with the share group.
    pub shared: Arc<Mutex<SharedObjects>>,
    /// Capabilities (`glEnable`).
    pub enables: super::enable::EnableState,
    /// Active texture units.
    pub texunit: super::texunit::TexUnitState,
    /// Matrix stacks.
    pub transform: super::transform::TransformState,
    /// Viewport, depth range and scissor box.
    pub viewport: super::viewport::ViewportState,
    /// Fixed-function state: lighting, fog, per-fragment operations, rasterization, clip
    /// planes, hints, clear values, buffers, attribute stack.
    pub fixed: super::fixed::FixedState,
    /// Evaluator maps and grids.
    pub eval: super::eval::EvalState,
    /// Render mode, selection and feedback.
    pub render_mode: super::render_mode::RenderModeState,
    /// Occlusion query objects.
    pub queries: super::queries::QueryState,
    /// Framebuffer-object bindings.
    pub framebuffers: super::framebuffers::FramebufferState,
    /// Texture units: bindings, environments, coordinate generation.
    pub texture: super::texture::TextureState,
    /// Pixel storage, transfer, zoom and the raster position.
    pub pixels: super::pixels::PixelState,
    /// Immediate-mode assembly (`glBegin`/`glEnd`).
    pub(crate) immediate: super::immediate::ImmediateState,
    /// Client vertex arrays and buffer bindings.
    pub(crate) arrays: super::arrays::ArrayState,
    /// `EXT_vertex_array` element counts.
    pub(crate) arrays_ext: super::arrays_ext::ArrayCounts,
    /// Storage the draws from arrays reuse.
    pub(crate) fetch: super::array_fetch::FetchStorage,
    /// `glPushClientAttrib` stack.
    pub(crate) client_attrib: super::client_attrib::ClientAttribStack,
    /// The program in use.
    pub(crate) programs: super::programs::ProgramState,
    /// The frame being assembled since the last swap.
    pub(crate) frame: Frame,
    /// What the frame holds against its budget.
    pub(crate) frame_memory: super::frame_memory::FrameMemory,
    /// Storage of spent frames' draws that new draws fill again (a frame budget at most).
    pub(crate) storage: crate::frame::storage::StoragePool,
    pub(crate) sink: Box<dyn FrameSink>,
    /// Whether the drawables are single-buffered (see [`Context::set_double_buffered`]).
    pub(crate) single_buffered: bool,
    /// Size of the drawable last made current, `(width, height)`.
    pub(crate) drawable_size: Option<(i32, i32)>,
    /// Where the renderer was last told frames go (`translate::target`).
    pub(crate) target: Option<crate::frame::Target>,
    /// Hash tracking: classes, instances, view and static world of each frame.
    pub(crate) classify: super::classify::Classifier,
}

impl Context {
    /// Creates a context with the initial state of the specification.
    pub fn new(config: ContextConfig) -> Context {
        Context {
            errors: ErrorState::default(),
            lists: ListState::default(),
            shared: config.share.unwrap_or_default(),
            enables: Default::default(),
            texunit: Default::default(),
            transform: Default::default(),
            viewport: super::viewport::ViewportState::new(),
            fixed: Default::default(),
            eval: Default::default(),
            render_mode: Default::default(),
            queries: Default::default(),
            framebuffers: Default::default(),
            texture: Default::default(),
            pixels: Default::default(),
            immediate: Default::default(),
            arrays: Default::default(),
            arrays_ext: Default::default(),
            fetch: Default::default(),
            client_attrib: Default::default(),
            programs: Default::default(),
            frame: Frame::default(),
            frame_memory: super::frame_memory::FrameMemory::new(super::frame_memory::configured_budget()),
            storage: crate::frame::storage::StoragePool::for_budget(usize::try_from(super::frame_memory::configured_budget()).unwrap_or(usize::MAX)),
            sink: config.sink,
            single_buffered: false,
            drawable_size: None,
            target: None,
            classify: Default::default(),
        }
    }

    /// A context whose frames go to a [`RecordingSink`] (returned), for tests.
    pub fn with_recording() -> (Context, RecordingSink) {
        let sink = RecordingSink::default();
        (Context::new(ContextConfig { share: None, sink: Box::new(sink.clone()) }), sink)
    }

    /// Whether a `glBegin` is open (the `glBegin`/`glEnd` rule of section 2.6.3).
    pub fn inside_begin_end(&self) -> bool {
        self.immediate.primitive.is_some()
    }

    /// Called when the context is made current on a drawable of `width` × `height` pixels.
    /// The first time, the viewport and scissor box take the drawable's size (GLX 1.4, 3.3.7).
    pub fn bind_drawable(&mut self, width: i32, height: i32) {
        self.drawable_size = Some((width, height));
        self.frame.size = [width.max(0) as u32, height.max(0) as u32];
        self.init_viewport(width, height);
    }

    /// Declares whether the drawables of this context are double-buffered (from its GLX
    /// configuration). Single-buffered contexts draw to `GL_FRONT` by default (section 4.2.1)
    /// and end a frame at `glFlush`/`glFinish` instead of at swaps.
    pub fn set_double_buffered(&mut self, double: bool) {
        if self.single_buffered == double {
            self.single_buffered = !double;
            let initial = if double { super::gl::GL_BACK } else { super::gl::GL_FRONT };
            self.fixed.buffers.draw = initial;
            self.fixed.buffers.read = initial;
        }
    }

    /// `glFlush`/`glFinish`: when the program draws to the front buffer (a single-buffered
    /// context, or `glDrawBuffer(GL_FRONT)`), what it drew so far is a frame to show.
    pub(crate) fn flush_front(&mut self) {
        let front = self.draw_buffers().front;
        let drew = !self.frame.draws.is_empty() || !self.frame.clears.is_empty();
        if (self.single_buffered || front) && drew {
            self.end_frame_as(FrameEnd::Flush);
        }
    }

    /// Whether frames are classified: the sink reads classes
    /// ([`crate::frame::FrameSink::reads_classes`]) or the call log announces the texture
    /// hashes classification computes ([`super::classify::texture_hash::announced`]).
    pub(crate) fn reads_classes(&self) -> bool {
        self.sink.reads_classes() || super::classify::texture_hash::announced()
    }

    /// Ends the frame (`glXSwapBuffers`): hands the assembled [`Frame`] to the renderer. The
    /// next frame's draw list starts with the capacity this one needed, its draws with the
    /// storage the sink gives back ([`crate::frame::FrameSink::spent_storage`]).
    pub fn end_frame(&mut self) {
        self.end_frame_as(self.swap_end());
    }

    /// Ends the frame as `end` says. A part ([`FrameEnd::Part`], see
    /// [`super::frame_memory`]) is routed as a read-back routes the frame so far; hash
    /// tracking sees the whole frame's last part at its end. Frames are classified only when
    /// something reads classes ([`Context::reads_classes`]).
    pub(crate) fn end_frame_as(&mut self, end: FrameEnd) {
        let number = self.frame.number + 1;
        let draws = Vec::with_capacity(self.frame.draws.len());
        let size = self.frame.size;
        let next = Frame { number, draws, size, ..Frame::default() };
        let mut frame = Frame { end, ..std::mem::replace(&mut self.frame, next) };
        self.frame_memory.reset();
        if self.reads_classes() {
            if end == FrameEnd::Part {
                self.classify.route_partial(&mut frame);
            } else {
                let versions = super::classify::keys::list_versions(&frame, &self.shared.lock().lists);
                self.classify.classify(&mut frame, |list| versions.iter().find(|v| v.0 == list).and_then(|v| v.1));
            }
        }
        self.sink.present(frame);
        if let Some(spent) = self.sink.spent_storage() {
            self.storage.refill(spent);
        }
    }
}
