//! The sink a context hands its frames to: the one seam between `translate`, which makes
//! [`Frame`]s, and `render`, which draws them (or a test, which keeps them). The Vulkan
//! renderer implements [`FrameSink`]; [`NullSink`] and [`RecordingSink`] are the two sinks
//! that draw nothing.

use std::sync::Arc;

use parking_lot::Mutex;

use super::Frame;
use super::pixels::PixelBuffer;
use super::storage::StoragePool;
use super::target::Target;

/// Inside `impl FrameSink for W`, where `W` wraps another sink in its field `inner`: forwards
/// `set_target`, the occlusion queries and `spent_storage` to it, so a wrapper (a tap, a
/// repeater, a frame filter) answers them as the sink it wraps; `present`, `read_pixels` and
/// `keeps_culled_triangles` stay the wrapper's own (a tap that inspects frames keeps culled
/// triangles whatever it wraps).
#[macro_export]
macro_rules! forward_to_inner_sink {
    () => {
        fn set_target(&mut self, target: $crate::frame::target::Target) {
            self.inner.set_target(target);
        }
        fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
            self.inner.occlusion_result(frame, query)
        }
        fn occlusion_counter_bits(&self) -> u32 {
            self.inner.occlusion_counter_bits()
        }
        fn spent_storage(&mut self) -> Option<&mut $crate::frame::storage::StoragePool> {
            self.inner.spent_storage()
        }
    };
}

/// Receives each finished frame.
pub trait FrameSink: Send {
    /// Takes the frame that `glXSwapBuffers` (or a read-back) ended.
    fn present(&mut self, frame: Frame);

    /// Where the next frames go: called when a context is made current on a drawable and when
    /// that drawable's size changes (only then: the target differs from the previous one).
    /// The default ignores it (sinks that keep frames in memory).
    fn set_target(&mut self, _target: Target) {}

    /// Samples that passed for occlusion query `query` of frame number `frame` (listed in
    /// that frame's [`Frame::occlusion_queries`]), once that frame was presented; `None` while
    /// unknown. A renderer whose [`FrameSink::occlusion_counter_bits`] is not 0 must answer
    /// every query of a presented frame eventually. The default counts nothing.
    fn occlusion_result(&mut self, _frame: u64, _query: u32) -> Option<u64> {
        None
    }

    /// Bits of the renderer's sample counter (`GL_QUERY_COUNTER_BITS`); 0 when it does not
    /// count samples (the default).
    fn occlusion_counter_bits(&self) -> u32 {
        0
    }

    /// Whether frames must keep the triangles that face culling removes (the default, for
    /// sinks that record or inspect frames). A rasterizer draws nothing of them and says no:
    /// the front end then drops batches it would cull entirely; a path tracer keeps them (a
    /// culled face still casts shadows and bounces light).
    fn keeps_culled_triangles(&self) -> bool {
        true
    }

    /// Whether anything reads what hash tracking (`translate::classify`) adds to frames: draw
    /// classes, instances and layers, the view, the static world, lights and statistics. The
    /// default says yes, for sinks that record or inspect frames; a rasterizer with nothing
    /// tracing and no HUD counting classes says no, and the front end then leaves frames
    /// unclassified (every draw [`crate::frame::class::DrawClass::Unclassified`], no static
    /// world, statistics at zero).
    fn reads_classes(&self) -> bool {
        true
    }

    /// The storage of the draws of frames this sink is done with, which the context takes
    /// after each [`FrameSink::present`] to fill again ([`StoragePool`]); `None` (the default)
    /// for sinks that keep their frames.
    fn spent_storage(&mut self) -> Option<&mut StoragePool> {
        None
    }

    /// Renders `frame` so far (it is not ended) and reads the rectangle `rect` (x, y, width,
    /// height, window coordinates) of `buffer`: RGBA for colour, the value in the first
    /// component for depth and stencil; rows bottom to top. `None` when the sink cannot
    /// render (the caller leaves the client's memory untouched).
    fn read_pixels(&mut self, _frame: &Frame, _buffer: PixelBuffer, _rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        None
    }
}

/// Drops frames, keeping only how many were presented and their draws' storage for the
/// context to reuse (used when no renderer is available).
#[derive(Default)]
pub struct NullSink {
    /// Frames presented so far.
    pub presented: u64,
    spent: StoragePool,
}

impl FrameSink for NullSink {
    fn present(&mut self, frame: Frame) {
        self.presented += 1;
        self.spent.keep_frame(frame);
    }

    fn spent_storage(&mut self) -> Option<&mut StoragePool> {
        Some(&mut self.spent)
    }

    /// Nothing is drawn, so nothing needs culled triangles.
    fn keeps_culled_triangles(&self) -> bool {
        false
    }

    /// Nothing reads the frames.
    fn reads_classes(&self) -> bool {
        false
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
