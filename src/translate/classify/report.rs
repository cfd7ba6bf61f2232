//! Sinks that report what hash tracking found, for the `glrt` command: per-frame statistics
//! as JSON lines (`glrt replay --stats`) or classification times (`--bench`), and the hashes of the textures draws used
//! (`glrt info FILE`, the names `glrt.toml` tags textures by).

use std::collections::BTreeMap;
use std::io::Write as _;
use std::sync::Arc;

use parking_lot::Mutex;

use crate::frame::Frame;
use crate::frame::pixels::PixelBuffer;
use crate::frame::FrameSink;

/// Calls a function on each frame, then hands the frame to `inner`: `glrt replay --stats`
/// prints its statistics ([`print_stats`]), `--bench` adds up its classification time.
pub struct FrameTap {
    inner: Box<dyn FrameSink>,
    tap: Box<dyn FnMut(&Frame) + Send>,
    /// Whether the tap reads hash tracking's results (else frames are classified only when
    /// `inner` reads them).
    reads_classes: bool,
}

impl FrameTap {
    /// Calls `tap`, which reads hash tracking's results (frames are classified), then
    /// presents to `inner`.
    pub fn new(inner: Box<dyn FrameSink>, tap: impl FnMut(&Frame) + Send + 'static) -> FrameTap {
        FrameTap { inner, tap: Box::new(tap), reads_classes: true }
    }

    /// Calls `tap`, which reads no class (frames are classified only when `inner` reads
    /// them: a classification time it adds up is then what the renderer's frames cost), then
    /// presents to `inner`.
    pub fn passing(inner: Box<dyn FrameSink>, tap: impl FnMut(&Frame) + Send + 'static) -> FrameTap {
        FrameTap { inner, tap: Box::new(tap), reads_classes: false }
    }
}

/// Prints a frame's [`crate::frame::class::FrameStats`] as one JSON line on standard output.
pub fn print_stats(frame: &Frame) {
    let _ = writeln!(std::io::stdout().lock(), "{}", frame.stats.json_line(frame.number));
}

impl FrameSink for FrameTap {
    fn present(&mut self, frame: Frame) {
        (self.tap)(&frame);
        self.inner.present(frame);
    }
    crate::forward_to_inner_sink!();
    fn reads_classes(&self) -> bool {
        self.reads_classes || self.inner.reads_classes()
    }
    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.inner.read_pixels(frame, buffer, rect)
    }
}

/// Texture name → (content version, hash) pairs, one per version used.
pub type Versions = BTreeMap<u32, Vec<(u64, u64)>>;

/// The texture hashes of every texture content that draws used: texture name → hashes, in
/// the order first seen.
#[derive(Clone, Default)]
pub struct TextureCatalog {
    /// What draws used, shared by the sinks of every context.
    pub textures: Arc<Mutex<Versions>>,
}

impl FrameSink for TextureCatalog {
    fn present(&mut self, frame: Frame) {
        let mut textures = self.textures.lock();
        for t in frame.draws.iter().flat_map(|d| d.textures.iter().flatten()) {
            let versions = textures.entry(t.id).or_default();
            if !versions.iter().any(|&(v, _)| v == t.version) {
                versions.push((t.version, super::texture_hash::content_hash(&t.content)));
            }
        }
    }
}

impl TextureCatalog {
    /// The report `glrt info FILE` prints: one line per texture name with its distinct hashes.
    pub fn report(&self) -> String {
        let textures = self.textures.lock();
        let mut out = format!("textures drawn with (level-0 hash, the glrt.toml names): {}\n", textures.len());
        for (id, versions) in textures.iter() {
            let mut hashes: Vec<u64> = versions.iter().map(|&(_, h)| h).collect();
            hashes.dedup();
            let list: Vec<String> = hashes.iter().map(|h| format!("{h:#018x}")).collect();
            out += &format!("  texture {id}: {}\n", list.join(" "));
        }
        out
    }
}
