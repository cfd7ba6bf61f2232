//! The per-frame scene that `translate` hands to `render` at `glXSwapBuffers` (or at a
//! read-back that needs pixels): draws in object space with their state, clears, and what the
//! renderer needs to resolve textures. No GL enums here: `translate` converts them to these
//! types.

pub mod pixels;
pub mod state;
pub mod texture;

use std::sync::Arc;

pub use state::RasterState;
pub use texture::TextureRef;

/// One frame of the program's rendering.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Frame number, from 0.
    pub number: u64,
    /// Draws in program order.
    pub draws: Vec<Draw>,
    /// Clears, in program order, each placed before a draw index.
    pub clears: Vec<Clear>,
    /// Occlusion queries ended in this frame: query name and the draws (indices into
    /// [`Frame::draws`]) between its `glBeginQuery` and `glEndQuery`; the renderer counts their
    /// samples that pass and answers through [`crate::render::FrameSink::occlusion_result`].
    pub occlusion_queries: Vec<(u32, std::ops::Range<usize>)>,
    /// Bitmaps, pixel images and copies, in program order with the draws.
    pub pixels: Vec<pixels::PixelOp>,
}

/// One draw: primitives of one state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draw {
    /// Vertex count.
    pub vertex_count: usize,
    /// Raster state of the draw.
    pub state: Arc<RasterState>,
    /// Bound texture of each unit that texturing uses.
    pub textures: Vec<Option<TextureRef>>,
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
}
