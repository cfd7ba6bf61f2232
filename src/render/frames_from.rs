//! Frames before the first one a replay writes (`glrt replay FILE --frames A..B --out DIR`):
//! they run for the state they build, and the renderer does not draw them, so that replaying
//! frame `A` costs one frame, not `A + 1`.
//!
//! Such a frame reaches the renderer empty (its number, size and end, and the framebuffer
//! attachments that died in it, so that the renderer's bookkeeping follows the program): no
//! clears, draws, pixel operations or queries. Read-backs still work: a frame before `A` that
//! reads pixels (`glReadPixels`, `glCopyTexImage`, a texture rendered through a framebuffer
//! object and read back into `translate`) is drawn as far as the read needs, and then whole,
//! since the renderer has begun it. The window's buffers therefore start frame `A` as the
//! renderer left them: a program that clears every frame (games do) gives frame `A` exactly;
//! one that draws over its earlier frames shows only what it drew from `A` on. The path
//! tracer's temporal history starts at `A` too: a traced frame `A` has the samples of its own
//! frame, not those of the frames before it.

use crate::frame::pixels::PixelBuffer;
use crate::frame::{Frame, FrameSink};

/// A sink that hands frames `first` and later to `inner` whole, and the earlier ones empty.
pub struct FramesFrom {
    first: u64,
    inner: Box<dyn FrameSink>,
    /// The frame before `first` that a read-back began drawing, if any.
    begun: Option<u64>,
    /// Frames before `first`, and those of them drawn for a read-back.
    skipped: u64,
    drawn_for_reads: u64,
}

impl FramesFrom {
    /// Draws frames `first` and later through `inner`.
    pub fn new(first: u64, inner: Box<dyn FrameSink>) -> FramesFrom {
        FramesFrom { first, inner, begun: None, skipped: 0, drawn_for_reads: 0 }
    }
}

impl FrameSink for FramesFrom {
    fn present(&mut self, frame: Frame) {
        if frame.number >= self.first {
            return self.inner.present(frame);
        }
        self.skipped += 1;
        if self.begun == Some(frame.number) {
            self.drawn_for_reads += 1;
            return self.inner.present(frame);
        }
        let Frame { number, size, released, end, .. } = frame;
        self.inner.present(Frame { number, size, released, end, ..Frame::default() });
    }

    crate::forward_to_inner_sink!();

    fn keeps_culled_triangles(&self) -> bool {
        self.inner.keeps_culled_triangles()
    }

    fn reads_classes(&self) -> bool {
        self.inner.reads_classes()
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        if frame.number < self.first {
            self.begun = Some(frame.number);
        }
        self.inner.read_pixels(frame, buffer, rect)
    }
}

impl Drop for FramesFrom {
    fn drop(&mut self) {
        log::info!(
            "replay: {} frames before frame {} ran for their state only ({} drawn for a read-back)",
            self.skipped,
            self.first,
            self.drawn_for_reads
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::{Clear, Draw, RecordingSink};

    fn frame(number: u64) -> Frame {
        Frame { number, size: [8, 8], draws: vec![Draw::default()], clears: vec![Clear::default()], ..Frame::default() }
    }

    #[test]
    fn frames_before_the_first_arrive_empty_unless_a_read_began_them() {
        let recording = RecordingSink::default();
        let mut sink = FramesFrom::new(2, Box::new(recording.clone()));
        sink.present(frame(0));
        let one = frame(1);
        let _ = sink.read_pixels(&one, PixelBuffer::default(), [0, 0, 1, 1]);
        sink.present(one);
        sink.present(frame(2));
        let frames = recording.frames.lock();
        let shape: Vec<(u64, usize, usize, [u32; 2])> = frames.iter().map(|f| (f.number, f.draws.len(), f.clears.len(), f.size)).collect();
        assert_eq!(shape, [(0, 0, 0, [8, 8]), (1, 1, 1, [8, 8]), (2, 1, 1, [8, 8])]);
        assert_eq!((sink.skipped, sink.drawn_for_reads), (2, 1));
    }
}
