//! Rendering: consumes [`Frame`]s. The Vulkan back ends come here; for now the sinks that keep
//! frames for tests and for programs run without a renderer.

use std::sync::Arc;

use parking_lot::Mutex;

use crate::frame::Frame;
use crate::frame::pixels::PixelBuffer;

/// Receives each finished frame.
pub trait FrameSink: Send {
    /// Takes the frame that `glXSwapBuffers` (or a read-back) ended.
    fn present(&mut self, frame: Frame);

    /// Renders `frame` so far (it is not ended) and reads the rectangle `rect` (x, y, width,
    /// height, window coordinates) of `buffer`: RGBA for colour, the value in the first
    /// component for depth and stencil; rows bottom to top. `None` when the sink cannot
    /// render (the caller leaves the client's memory untouched).
    fn read_pixels(&mut self, _frame: &Frame, _buffer: PixelBuffer, _rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        None
    }
}

/// Drops frames, keeping only how many were presented (used when no renderer is available).
#[derive(Default)]
pub struct NullSink {
    /// Frames presented so far.
    pub presented: u64,
}

impl FrameSink for NullSink {
    fn present(&mut self, _frame: Frame) {
        self.presented += 1;
    }
}

/// Keeps every frame in a shared list, for tests.
#[derive(Clone, Default)]
pub struct RecordingSink {
    /// The frames presented so far.
    pub frames: Arc<Mutex<Vec<Frame>>>,
}

impl FrameSink for RecordingSink {
    fn present(&mut self, frame: Frame) {
        self.frames.lock().push(frame);
    }
}

/// The sink a new context presents to: the renderer chosen by the configuration. Until the
/// Vulkan back end exists this is the [`NullSink`].
pub fn default_sink() -> Box<dyn FrameSink> {
    Box::new(NullSink::default())
}
