//! Bounded frames: what the frame being assembled holds (its draws with their vertices and
//! indices, clears, pixel operations, and the texture images its draws reference, each image
//! counted once) is estimated as it grows, and a frame past its budget is handed to the
//! renderer as a part ([`FrameEnd::Part`]) and dropped: the frame goes on empty. The renderer
//! draws the parts in program order on the same framebuffers, so the image is the one a single
//! submission gives; texture versions that only the dropped draws referenced are freed with
//! them (here, and in the renderer once the part is drawn).
//!
//! A frame read back (`glReadPixels` and the like) is drawn up to that point anyway, so past
//! an eighth of the budget it becomes a part right after the read-back ([`READ_BACK_SHARE`]):
//! a program that draws and reads back for a long time without swapping (piglit's
//! `gl-1.0-blend-func`: 27,500 blend states, each drawn and read back) holds little.
//!
//! The budget is `frame_budget_mb` of the `[memory]` table of `glrt.toml`, or
//! `GLRT_FRAME_BUDGET_MB` ([`MemorySettings`], 256 MB by default). A frame is not split while
//! an occlusion query is active: its count would span two parts.

use std::mem::{size_of, size_of_val};
use std::sync::{Arc, OnceLock};

use rustc_hash::FxHashSet;

use super::Context;
use crate::config::{Config, Key, Table, integer_in};
use crate::frame::pixels::{PixelData, PixelKind, PixelOp};
use crate::frame::texture::{TexImage, TextureRef};
use crate::frame::{Clear, Draw, Frame, FrameEnd, RasterState, Vertices};

/// After a read-back, a frame holding more than the budget divided by this becomes a part.
pub const READ_BACK_SHARE: u64 = 8;

/// The `[memory]` settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemorySettings {
    /// Bytes a frame may hold before it is submitted in parts (`frame_budget_mb`, in MB).
    pub frame_budget: u64,
}

impl Default for MemorySettings {
    fn default() -> MemorySettings {
        MemorySettings { frame_budget: 256 << 20 }
    }
}

impl Table for MemorySettings {
    const NAME: &'static str = "memory";
    const KEYS: &'static [Key<MemorySettings>] =
        &[Key { name: "frame_budget_mb", set: |m, v| integer_in(v, 1..=1 << 20).map(|mb| m.frame_budget = (mb as u64) << 20) }];
}

/// The frame budget of this process, read from the configuration once (problems reported
/// once).
pub fn configured_budget() -> u64 {
    static BUDGET: OnceLock<u64> = OnceLock::new();
    *BUDGET.get_or_init(|| {
        let (settings, problems) = Config::of_process().table::<MemorySettings>();
        crate::config::warn(&problems);
        settings.frame_budget
    })
}

/// What the frame being assembled holds, counted as it grows.
#[derive(Debug)]
pub struct FrameMemory {
    /// The budget in bytes.
    budget: u64,
    /// Bytes counted.
    bytes: u64,
    /// Draws counted (the last of them may still grow by merging).
    draws: usize,
    /// Bytes counted for the last counted draw.
    last_draw: u64,
    /// Clears counted.
    clears: usize,
    /// Pixel operations counted.
    pixels: usize,
    /// Addresses of the texture contents counted (alive while the frame holds them): a
    /// content's images are looked at once per frame, not once per draw.
    contents: FxHashSet<usize>,
    /// Addresses of the texture images counted (alive while the frame holds them; contents
    /// of other versions may share images).
    images: FxHashSet<usize>,
}

impl FrameMemory {
    /// Nothing counted yet, against a budget of `budget` bytes.
    pub fn new(budget: u64) -> FrameMemory {
        FrameMemory { budget, bytes: 0, draws: 0, last_draw: 0, clears: 0, pixels: 0, contents: FxHashSet::default(), images: FxHashSet::default() }
    }

    /// The budget in bytes.
    pub fn budget(&self) -> u64 {
        self.budget
    }

    /// Bytes the frame holds, as counted by the last [`FrameMemory::count`].
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Counts what `frame` gained since the last call: the growth of the last draw counted,
    /// new draws with the texture images not counted yet, new clears and pixel operations.
    pub fn count(&mut self, frame: &Frame) {
        if let Some(last) = self.draws.checked_sub(1).and_then(|i| frame.draws.get(i)) {
            let now = draw_bytes(last);
            self.bytes += now.saturating_sub(self.last_draw);
            self.last_draw = now;
        }
        for draw in frame.draws.get(self.draws..).unwrap_or_default() {
            self.last_draw = draw_bytes(draw);
            self.bytes += self.last_draw;
            let program_textures = draw.program.as_ref().map_or(&[][..], |p| &p.textures[..]);
            for t in draw.textures.iter().chain(program_textures).flatten() {
                self.bytes += self.new_images(t);
            }
        }
        self.draws = frame.draws.len();
        self.bytes += (frame.clears.len().saturating_sub(self.clears) * size_of::<Clear>()) as u64;
        self.clears = frame.clears.len();
        self.bytes += frame.pixels.get(self.pixels..).unwrap_or_default().iter().map(pixel_op_bytes).sum::<u64>();
        self.pixels = frame.pixels.len();
    }

    /// Bytes of the images of `t` not counted yet (and now counted).
    fn new_images(&mut self, t: &TextureRef) -> u64 {
        if !self.contents.insert(Arc::as_ptr(&t.content) as usize) {
            return 0;
        }
        let mut bytes = 0;
        for image in t.content.faces.iter().flatten().flatten() {
            if self.images.insert(Arc::as_ptr(image) as usize) {
                bytes += image_bytes(image);
            }
        }
        bytes
    }

    /// Whether the frame holds more than the budget.
    pub fn over(&self) -> bool {
        self.bytes > self.budget
    }

    /// Whether a frame just read back holds more than its share of the budget
    /// ([`READ_BACK_SHARE`]).
    pub fn over_after_read_back(&self) -> bool {
        self.bytes > self.budget / READ_BACK_SHARE
    }

    /// Forgets what was counted: the frame was handed to the renderer. The sets keep their
    /// storage for the next frame.
    pub fn reset(&mut self) {
        let (mut contents, mut images) = (std::mem::take(&mut self.contents), std::mem::take(&mut self.images));
        contents.clear();
        images.clear();
        *self = FrameMemory { contents, images, ..FrameMemory::new(self.budget) };
    }
}

/// Bytes of a draw besides its texture images: the draw, its vertices, indices and edge masks,
/// its per-unit lists and a raster state.
fn draw_bytes(draw: &Draw) -> u64 {
    let per_unit = size_of_val(&draw.texture_matrices[..]) + size_of_val(&draw.textures[..]) + size_of_val(&draw.texture_units[..]);
    let total = size_of::<Draw>()
        + size_of::<RasterState>()
        + vertex_bytes(&draw.vertices)
        + size_of_val(&draw.indices[..])
        + size_of_val(&draw.edge_masks[..])
        + per_unit;
    total as u64
}

/// Bytes of the attribute values of `v`.
fn vertex_bytes(v: &Vertices) -> usize {
    let units = v.texcoords.iter().chain(&v.generic).map(|a| size_of_val(&a.values[..])).sum::<usize>();
    size_of_val(&v.position[..])
        + size_of_val(&v.normal.values[..])
        + size_of_val(&v.color.values[..])
        + size_of_val(&v.secondary_color.values[..])
        + size_of_val(&v.fog_coord.values[..])
        + size_of_val(&v.color_index.values[..])
        + units
}

/// Bytes of the texels of a texture image, at every precision it keeps.
fn image_bytes(image: &TexImage) -> u64 {
    let bytes = size_of::<TexImage>()
        + size_of_val(&image.texels[..])
        + size_of_val(&image.values[..])
        + size_of_val(&image.integers[..])
        + size_of_val(&image.depth_values[..]);
    bytes as u64
}

/// Bytes of a pixel operation with its pixels or bitmap.
fn pixel_op_bytes(op: &PixelOp) -> u64 {
    let data = match &op.kind {
        PixelKind::Bitmap { mask, .. } => size_of_val(&mask[..]),
        PixelKind::Image { data, .. } => match data {
            PixelData::Rgba8(d) => size_of_val(&d[..]),
            PixelData::Depth(d) => size_of_val(&d[..]),
            PixelData::Stencil(s) => size_of_val(&s[..]),
            PixelData::DepthStencil(d, s) => size_of_val(&d[..]) + size_of_val(&s[..]),
        },
        _ => 0,
    };
    (size_of::<PixelOp>() + size_of::<RasterState>() + data) as u64
}

impl Context {
    /// Called after something entered the frame: past the budget, submits the frame so far as
    /// a part (see the module doc).
    pub(crate) fn keep_frame_in_budget(&mut self) {
        self.frame_memory.count(&self.frame);
        if self.frame_memory.over() && !self.queries.is_active() {
            self.end_frame_as(FrameEnd::Part);
        }
    }

    /// Called after the frame so far was read back: past [`READ_BACK_SHARE`] of the budget,
    /// submits it as a part (it is drawn already).
    pub(crate) fn part_after_read_back(&mut self) {
        self.frame_memory.count(&self.frame);
        if self.frame_memory.over_after_read_back() && !self.queries.is_active() {
            self.end_frame_as(FrameEnd::Part);
        }
    }

    /// Sets the frame budget to `bytes` (the configuration's otherwise; tests lower it).
    pub fn set_frame_budget(&mut self, bytes: u64) {
        self.frame_memory = FrameMemory::new(bytes);
        self.frame_memory.count(&self.frame);
    }

    /// Bytes the frame being assembled holds, as last counted.
    pub fn frame_bytes(&self) -> u64 {
        self.frame_memory.bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::translate::{dispatch, gl};

    /// A unit quad at `x` (consecutive quads merge into one draw).
    fn quad(ctx: &mut Context, x: f32) {
        unsafe {
            dispatch::glBegin(ctx, gl::GL_QUADS);
            for (dx, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                dispatch::glVertex2f(ctx, x + dx, y);
            }
            dispatch::glEnd(ctx);
        }
    }

    #[test]
    fn parts_keep_program_order_and_stay_within_the_budget() {
        let (mut ctx, sink) = Context::with_recording();
        ctx.set_frame_budget(16 * 1024);
        for i in 0..2000 {
            if i % 100 == 0 {
                ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
            }
            quad(&mut ctx, i as f32);
        }
        ctx.end_frame();
        let frames = sink.frames.lock();
        let ends: Vec<FrameEnd> = frames.iter().map(|f| f.end).collect();
        assert!(frames.len() > 5, "{} frames", frames.len());
        assert!(ends[..ends.len() - 1].iter().all(|&e| e == FrameEnd::Part), "{ends:?}");
        assert_eq!(ends.last(), Some(&FrameEnd::Swap));
        let numbers: Vec<u64> = frames.iter().map(|f| f.number).collect();
        assert_eq!(numbers, (0..frames.len() as u64).collect::<Vec<_>>());
        // Every quad once, in program order, across the parts.
        let xs: Vec<f32> = frames.iter().flat_map(|f| &f.draws).flat_map(|d| d.vertices.position.iter().step_by(4).map(|p| p[0])).collect();
        assert_eq!(xs, (0..2000).map(|i| i as f32).collect::<Vec<_>>());
        assert_eq!(frames.iter().map(|f| f.clears.len()).sum::<usize>(), 20);
        for f in frames.iter() {
            let mut memory = FrameMemory::new(u64::MAX);
            memory.count(f);
            // At most the budget and the draw (with its state) that passed it.
            assert!(memory.bytes() <= 16 * 1024 + 4096, "frame {} holds {} bytes", f.number, memory.bytes());
        }
    }

    #[test]
    fn no_part_while_an_occlusion_query_is_active() {
        let (mut ctx, sink) = Context::with_recording();
        ctx.set_frame_budget(4 * 1024);
        ctx.glBeginQuery(gl::GL_SAMPLES_PASSED, 1);
        for i in 0..500 {
            quad(&mut ctx, i as f32);
        }
        assert!(sink.frames.lock().is_empty(), "the query's draws stay in one frame");
        assert!(ctx.frame_bytes() > 4 * 1024);
        ctx.glEndQuery(gl::GL_SAMPLES_PASSED);
        quad(&mut ctx, 500.0);
        let frames = sink.frames.lock();
        assert_eq!(frames.len(), 1, "the next draw after the query submits a part");
        assert_eq!(frames[0].occlusion_queries, vec![(1, 0..1)]);
    }

    #[test]
    fn a_frame_read_back_past_an_eighth_of_the_budget_becomes_a_part() {
        let (mut ctx, sink) = Context::with_recording();
        ctx.set_frame_budget(8 * 4096);
        let mut pixel = [0u8; 4];
        let read = |ctx: &mut Context, pixel: &mut [u8; 4]| unsafe {
            dispatch::glReadPixels(ctx, 0, 0, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, pixel.as_mut_ptr().cast());
        };
        quad(&mut ctx, 0.0);
        read(&mut ctx, &mut pixel);
        assert!(sink.frames.lock().is_empty(), "a small frame stays whole: {} bytes", ctx.frame_bytes());
        for i in 1..200 {
            quad(&mut ctx, i as f32);
        }
        assert!(ctx.frame_bytes() > 4096 && ctx.frame_bytes() < 8 * 4096);
        read(&mut ctx, &mut pixel);
        let frames = sink.frames.lock();
        assert_eq!(frames.iter().map(|f| f.end).collect::<Vec<_>>(), [FrameEnd::Part]);
        assert_eq!(frames[0].draws[0].vertex_count, 800);
        assert_eq!(ctx.frame_bytes(), 0);
    }

    #[test]
    fn texture_images_count_once_per_frame() {
        let (mut ctx, _) = Context::with_recording();
        let texels = vec![255u8; 64 * 64 * 4];
        unsafe {
            dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR as i32);
            dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 64, 64, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        }
        ctx.glEnable(gl::GL_TEXTURE_2D);
        quad(&mut ctx, 0.0);
        let one = ctx.frame_bytes();
        assert!(one > 16 * 1024, "the 16 KB texture counts: {one}");
        ctx.glTranslatef(1.0, 0.0, 0.0);
        quad(&mut ctx, 0.0);
        assert!(ctx.frame_bytes() - one < 4 * 1024, "a second draw with the same texture adds only itself");
    }

    #[test]
    fn the_budget_is_a_setting() {
        let (config, _) = Config::parse("[memory]\nframe_budget_mb = 64\n", "m.toml").unwrap();
        assert_eq!(config.table::<MemorySettings>(), (MemorySettings { frame_budget: 64 << 20 }, vec![]));
        let (mut config, _) = Config::parse("[memory]\nframe_budget_mb = 0\n", "m.toml").unwrap();
        let (settings, problems) = config.table::<MemorySettings>();
        assert_eq!(settings, MemorySettings::default());
        assert_eq!(problems, ["m.toml:2: memory.frame_budget_mb: expected an integer in 1..=1048576, found 0; the default is used"]);
        config.apply_env([("GLRT_FRAME_BUDGET_MB".to_owned(), "8".to_owned())]).unwrap();
        assert_eq!(config.table::<MemorySettings>().0.frame_budget, 8 << 20);
    }
}
