//! `glrt replay --repeat N`: every frame drawn `N` times, the same [`Frame`] again each time
//! (its animation frozen), so that the path tracer's accumulation while nothing moves
//! converges on it: the converged references of the denoiser's quality test
//! (`tests/end_to_end/denoise.rs`, `bench/denoise.md`) are made so, one sample per pixel per
//! repetition, through the pixel centres like the frames they are compared with.

use crate::frame::pixels::PixelBuffer;
use crate::frame::{Frame, FrameSink};

/// A sink that presents each frame `times` times to `inner`.
pub struct FramesRepeated {
    times: u32,
    inner: Box<dyn FrameSink>,
}

impl FramesRepeated {
    /// Presents each frame `times` (at least once) to `inner`.
    pub fn new(times: u32, inner: Box<dyn FrameSink>) -> FramesRepeated {
        FramesRepeated { times: times.max(1), inner }
    }
}

impl FrameSink for FramesRepeated {
    fn present(&mut self, frame: Frame) {
        for _ in 1..self.times {
            self.inner.present(frame.clone());
        }
        self.inner.present(frame);
    }
    crate::forward_to_inner_sink!();
    fn keeps_culled_triangles(&self) -> bool {
        self.inner.keeps_culled_triangles()
    }
    fn reads_classes(&self) -> bool {
        self.inner.reads_classes()
    }
    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.inner.read_pixels(frame, buffer, rect)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::{Arc, Mutex};

    struct Count(Arc<Mutex<Vec<u64>>>);

    impl FrameSink for Count {
        fn present(&mut self, frame: Frame) {
            self.0.lock().unwrap().push(frame.number);
        }
    }

    #[test]
    fn each_frame_is_presented_the_given_number_of_times() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let mut sink = FramesRepeated::new(3, Box::new(Count(seen.clone())));
        for number in [4, 5] {
            sink.present(Frame { number, ..Frame::default() });
        }
        assert_eq!(*seen.lock().unwrap(), [4, 4, 4, 5, 5, 5]);
        let mut once = FramesRepeated::new(0, Box::new(Count(seen.clone())));
        once.present(Frame { number: 6, ..Frame::default() });
        assert_eq!(seen.lock().unwrap().len(), 7);
    }
}
