//! The frame log: with `GLRT_FRAME_LOG=path`, every presented frame appends one JSON line
//! `{"frame":N,"draws":D,"vertices":V,"clears":C,"hash":"H"}` to `path` before going on to the
//! renderer, where `H` is an xxh3 hash (16 hex digits) of everything the frame holds (draws with
//! their vertices, state, matrices and textures, clears, pixel operations, queries, size): two
//! frames with the same hash are equal draw for draw. Tests use it to check the per-frame draw
//! counts of real programs and that replays produce the live frames.
//!
//! The file is opened in append mode and each line is written with one `write` call, so the
//! contexts of a program (each with its own sink) can share it.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::Path;

use crate::frame::Frame;
use crate::frame::FrameSink;

/// The environment variable naming the log file.
pub const VARIABLE: &str = "GLRT_FRAME_LOG";

/// A sink that logs each frame, then hands it to `inner`.
pub struct FrameLog {
    inner: Box<dyn FrameSink>,
    file: File,
}

impl FrameLog {
    /// Logs to `path` (created if needed, appended to) in front of `inner`.
    pub fn open(path: &Path, inner: Box<dyn FrameSink>) -> std::io::Result<FrameLog> {
        Ok(FrameLog { inner, file: append(path)? })
    }
}

fn append(path: &Path) -> std::io::Result<File> {
    OpenOptions::new().create(true).append(true).open(path)
}

/// The log line of a frame (with its newline).
pub fn line(frame: &Frame) -> String {
    let vertices: usize = frame.draws.iter().map(|d| d.vertex_count).sum();
    format!(
        "{{\"frame\":{},\"draws\":{},\"vertices\":{},\"clears\":{},\"hash\":\"{:016x}\"}}\n",
        frame.number,
        frame.draws.len(),
        vertices,
        frame.clears.len(),
        content_hash(frame)
    )
}

/// xxh3 of the `Debug` form of what the program drew: every field of every draw, clear and
/// pixel operation (texture contents included), so equal hashes mean equal frames. Hash
/// tracking's results (draw classes and instances, view, static world, statistics) are left
/// out: they depend on the frames before, which a replay of a frame range does not draw.
pub fn content_hash(frame: &Frame) -> u64 {
    use std::fmt::Write as _;
    /// Feeds formatted text to the hasher without building the whole string.
    struct Hashing(xxhash_rust::xxh3::Xxh3);
    impl std::fmt::Write for Hashing {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            self.0.update(s.as_bytes());
            Ok(())
        }
    }
    let mut h = Hashing(xxhash_rust::xxh3::Xxh3::new());
    // Destructured without `..`: a new field must be placed on one side or the other here.
    let Frame { number, draws, clears, occlusion_queries, pixels, size, read_buffer, read_framebuffer, released, end, view: _, static_world: _, lights: _, stats: _ } =
        frame;
    let _ = write!(h, "{number:?}{clears:?}{occlusion_queries:?}{pixels:?}{size:?}{read_buffer:?}{read_framebuffer:?}{released:?}{end:?}");
    for draw in draws {
        let crate::frame::Draw {
            vertex_count,
            topology,
            vertices,
            indices,
            edge_masks,
            modelview,
            projection,
            texture_matrices,
            source,
            state,
            textures,
            texture_units,
            program,
            class: _,
            instance: _,
            layer: _,
        } = draw;
        let _ = write!(
            h,
            "{vertex_count:?}{topology:?}{vertices:?}{indices:?}{edge_masks:?}{modelview:?}{projection:?}{texture_matrices:?}{source:?}{state:?}{textures:?}{texture_units:?}{program:?}"
        );
    }
    h.0.digest()
}

impl FrameSink for FrameLog {
    fn present(&mut self, frame: Frame) {
        if let Err(e) = self.file.write_all(line(&frame).as_bytes()) {
            log::warn!("{VARIABLE}: {e}");
        }
        self.inner.present(frame);
    }

    fn set_target(&mut self, target: crate::frame::Target) {
        self.inner.set_target(target);
    }

    fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
        self.inner.occlusion_result(frame, query)
    }

    fn occlusion_counter_bits(&self) -> u32 {
        self.inner.occlusion_counter_bits()
    }

    fn spent_storage(&mut self) -> Option<&mut crate::frame::storage::StoragePool> {
        self.inner.spent_storage()
    }

    /// The log leaves hash tracking's results out ([`content_hash`]).
    fn reads_classes(&self) -> bool {
        self.inner.reads_classes()
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: crate::frame::pixels::PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.inner.read_pixels(frame, buffer, rect)
    }
}

/// `inner` wrapped in a [`FrameLog`] when `GLRT_FRAME_LOG` names a file that can be opened
/// (a failure is logged), else `inner` itself.
pub fn wrap_from_env(inner: Box<dyn FrameSink>) -> Box<dyn FrameSink> {
    let Some(path) = std::env::var_os(VARIABLE).filter(|p| !p.is_empty()) else { return inner };
    match append(Path::new(&path)) {
        Ok(file) => Box::new(FrameLog { inner, file }),
        Err(e) => {
            log::warn!("{VARIABLE}={}: {e}", Path::new(&path).display());
            inner
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::RecordingSink;
    use crate::frame::{Clear, Draw};

    #[test]
    fn one_line_per_frame_and_frames_go_on_to_the_inner_sink() {
        let dir = std::env::temp_dir().join(format!("glrt-frame-log-{}", std::process::id()));
        let _ = std::fs::remove_file(&dir);
        let recording = RecordingSink::default();
        let mut log = FrameLog::open(&dir, Box::new(recording.clone())).unwrap();
        let draw = |n| Draw { vertex_count: n, ..Draw::default() };
        log.present(Frame { number: 0, draws: vec![draw(3), draw(6)], clears: vec![Clear::default()], ..Frame::default() });
        log.present(Frame { number: 1, ..Frame::default() });
        let text = std::fs::read_to_string(&dir).unwrap();
        let _ = std::fs::remove_file(&dir);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2);
        assert!(lines[0].starts_with("{\"frame\":0,\"draws\":2,\"vertices\":9,\"clears\":1,\"hash\":\""), "{text}");
        assert!(lines[1].starts_with("{\"frame\":1,\"draws\":0,\"vertices\":0,\"clears\":0,\"hash\":\""), "{text}");
        assert_ne!(lines[0][lines[0].len() - 18..], lines[1][lines[1].len() - 18..], "different frames hash differently");
        assert_eq!(recording.frames.lock().len(), 2);
    }

    /// A renderer answering read-backs and queries with fixed values.
    struct Answers;

    impl FrameSink for Answers {
        fn present(&mut self, _frame: Frame) {}
        fn occlusion_result(&mut self, frame: u64, query: u32) -> Option<u64> {
            Some(frame * 100 + query as u64)
        }
        fn occlusion_counter_bits(&self) -> u32 {
            64
        }
        fn read_pixels(&mut self, _frame: &Frame, _buffer: crate::frame::pixels::PixelBuffer, [x, y, _, _]: [i32; 4]) -> Option<Vec<[f32; 4]>> {
            Some(vec![[x as f32, y as f32, 0.0, 1.0]])
        }
    }

    #[test]
    fn read_backs_and_queries_reach_the_inner_sink() {
        let path = std::env::temp_dir().join(format!("glrt-frame-log-fwd-{}", std::process::id()));
        let mut log = FrameLog::open(&path, Box::new(Answers)).unwrap();
        let _ = std::fs::remove_file(&path);
        assert_eq!(log.occlusion_counter_bits(), 64);
        assert_eq!(log.occlusion_result(2, 5), Some(205));
        let read = log.read_pixels(&Frame::default(), crate::frame::pixels::PixelBuffer::Color, [3, 4, 1, 1]);
        assert_eq!(read, Some(vec![[3.0, 4.0, 0.0, 1.0]]));
    }
}
