//! The per-frame scene that `translate` hands to `render` at `glXSwapBuffers` (or at a
//! read-back that needs pixels): draws in object space with their state, clears, and what the
//! renderer needs to resolve textures. No GL enums here: `translate` converts them to these
//! types.
//!
//! This is the interface layer between the two sides, and names neither: where frames go
//! ([`sink::FrameSink`], to a [`target::Target`]) and how their vertex storage comes back
//! ([`storage`]), and the few definitions both sides must
//! share (the mipmap box filter in [`mipmap`], [`class::orthographic`], the shader interface
//! constants of [`program`]).

pub mod class;
pub mod framebuffer;
pub mod mipmap;
pub mod pixels;
pub mod program;
pub mod sink;
pub mod state;
pub mod storage;
pub mod target;
pub mod texture;
pub mod vertex;
pub mod world;

use std::sync::Arc;

use glam::Mat4;

pub use framebuffer::Framebuffer;
pub use sink::{FrameSink, NullSink, RecordingSink};
pub use state::{ColorBuffer, DrawBuffers, RasterState};
pub use target::{Surface, Target, XDrawable};
pub use texture::TextureRef;
pub use vertex::{Attrib, Vertices};

/// One frame of the program's rendering.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Frame number, from 0 (each part of a frame submitted in parts counts as a frame).
    pub number: u64,
    /// Draws in program order.
    pub draws: Vec<Draw>,
    /// Clears, in program order, each placed before a draw index.
    pub clears: Vec<Clear>,
    /// Occlusion queries ended in this frame: query name and the draws (indices into
    /// [`Frame::draws`]) between its `glBeginQuery` and `glEndQuery`; the renderer counts their
    /// samples that pass and answers through [`crate::frame::FrameSink::occlusion_result`].
    pub occlusion_queries: Vec<(u32, std::ops::Range<usize>)>,
    /// Bitmaps, pixel images and copies, in program order with the draws.
    pub pixels: Vec<pixels::PixelOp>,
    /// Width and height of the drawable, in pixels (`[0, 0]` when no drawable was bound).
    pub size: [u32; 2],
    /// The colour buffer [`crate::frame::FrameSink::read_pixels`] reads (`glReadBuffer` at
    /// the time of the read).
    pub read_buffer: ColorBuffer,
    /// The framebuffer [`crate::frame::FrameSink::read_pixels`] reads (the read framebuffer
    /// binding at the time of the read).
    pub read_framebuffer: Framebuffer,
    /// Framebuffer-object attachments that no longer exist (renderbuffers deleted or given new
    /// storage, textures deleted): the renderer frees the images it keeps for them. A texture
    /// stands for every image of that texture ([`framebuffer::Attachment::same_object`]).
    pub released: Vec<framebuffer::Attachment>,
    /// How the frame ends.
    pub end: FrameEnd,
    /// The camera recovered by hash tracking (`translate::classify`), when there is one.
    pub view: Option<class::View>,
    /// The persistent static world: world-space chunks that change rarely (kept by `Arc`, so
    /// a renderer recognises a chunk it already uploaded).
    pub static_world: Arc<[Arc<world::StaticChunk>]>,
    /// Point lights recovered from the frame's dynamic-light passes (draws of class
    /// [`class::DrawClass::Light`]), one per light however many passes drew it.
    pub lights: Vec<class::DynamicLight>,
    /// Statistics of hash tracking.
    pub stats: class::FrameStats,
}

/// How a frame ends: what the window shows afterwards.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FrameEnd {
    /// `glXSwapBuffers` on a double-buffered drawable: the back buffer becomes the front
    /// buffer. The renderer copies it, so the back buffer keeps its contents (GLX leaves them
    /// undefined after a swap).
    #[default]
    Swap,
    /// `glFlush`/`glFinish` after drawing to the front buffer, or a swap of a single-buffered
    /// drawable: the front buffer is shown as it is.
    Flush,
    /// Not an end: the frame grew past its memory budget (`translate::frame_memory`), so what
    /// it holds so far is drawn now and dropped, and the frame goes on in the next one, drawn
    /// over what this one left in the framebuffers. Nothing is shown.
    Part,
}

/// One draw: indexed primitives of one topology, one state, one set of matrices. Consecutive
/// batches that share all of these are merged into one draw (`translate::frame_builder`).
///
/// Index order: every primitive keeps the winding of the program's vertices, and its
/// **provoking vertex** (the one whose colour flat shading uses, section 2.14.7) is always its
/// **last** index, as with `VK_PROVOKING_VERTEX_MODE_LAST_VERTEX_EXT`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draw {
    /// Vertex count: `vertices.len()` (kept as a field for the consumers that only count).
    pub vertex_count: usize,
    /// Triangles, lines or points.
    pub topology: Topology,
    /// Object-space vertices and their attributes.
    pub vertices: Vertices,
    /// Three indices per triangle, two per line, one per point, into `vertices`.
    pub indices: Vec<u32>,
    /// For triangles, one mask per triangle: bit `k` set when the edge from its index `k` to
    /// index `(k + 1) % 3` is a boundary edge of the program's polygon (drawn in polygon mode
    /// `GL_LINE`, section 3.5.4); diagonals added by decomposing quads and polygons, and edges
    /// whose edge flag was false, are clear. Empty for lines and points.
    pub edge_masks: Vec<u8>,
    /// Modelview matrix.
    pub modelview: Mat4,
    /// Projection matrix.
    pub projection: Mat4,
    /// Texture matrix of each texture unit that has a texture target enabled (`None` for the
    /// others).
    pub texture_matrices: Vec<Option<Mat4>>,
    /// Where the geometry came from.
    pub source: DrawSource,
    /// Raster state of the draw.
    pub state: Arc<RasterState>,
    /// Bound texture of each unit that texturing uses.
    pub textures: Vec<Option<TextureRef>>,
    /// Texture environment and coordinate generation of each texture unit that has a texture
    /// target enabled (`None` for the others), indexed like [`Draw::texture_matrices`].
    pub texture_units: Vec<Option<TextureUnit>>,
    /// The OpenGL 2.0 program the draw runs (`None`: the fixed-function pipeline).
    pub program: Option<Arc<program::ProgramDraw>>,
    /// How the renderer treats it (set when the frame ends).
    pub class: class::DrawClass,
    /// Its identity across frames, for traced draws.
    pub instance: Option<class::Instance>,
    /// For a draw of class [`class::DrawClass::Layer`]: the traced draw it is a pass over.
    pub layer: Option<class::Layer>,
}

/// How one texture unit combines and generates coordinates in a draw (sections 2.10.4 and
/// 3.8.13).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TextureUnit {
    /// `glTexEnv` state.
    pub env: texture::TextureEnv,
    /// Generation of s, t, r, q (`None`: the coordinate is taken as issued).
    pub texgen: [Option<texture::TexGenMode>; 4],
}

/// The primitives of a draw.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Topology {
    /// Separate triangles.
    #[default]
    Triangles,
    /// Separate line segments.
    Lines,
    /// Points.
    Points,
}

/// Which commands produced a draw.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DrawSource {
    /// `glBegin`/`glEnd` (and `glRect`, `glArrayElement`).
    #[default]
    Immediate,
    /// `glDrawArrays`, `glDrawElements` and their variants.
    Arrays,
    /// Executing the display list of this name (the innermost when lists nest).
    List(u32),
}

/// A `glClear`: which buffers, with which values, before which draw.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Clear {
    /// Index in [`Frame::draws`] of the first draw after the clear.
    pub before_draw: usize,
    /// Colour buffers are cleared to this value.
    pub color: Option<[f32; 4]>,
    /// The depth buffer is cleared to this value.
    pub depth: Option<f64>,
    /// The stencil buffer is cleared to this value.
    pub stencil: Option<i32>,
    /// The accumulation buffer is cleared to this value.
    pub accum: Option<[f32; 4]>,
    /// Only this window rectangle (x, y, width, height) is cleared: the scissor box, when the
    /// scissor test is on (OpenGL 1.5 section 4.2.3).
    pub scissor: Option<[i32; 4]>,
    /// Colour channels written (`glColorMask`).
    pub color_mask: [bool; 4],
    /// Depth writes enabled (`glDepthMask`).
    pub depth_mask: bool,
    /// Stencil bits written (`glStencilMask`).
    pub stencil_mask: u32,
    /// Colour buffers cleared (`glDrawBuffer`).
    pub draw_buffers: DrawBuffers,
    /// The framebuffer cleared.
    pub framebuffer: Framebuffer,
}
