//! The texel pool: every texture level the path tracer samples, packed into one storage buffer
//! of `u32` texels (RGBA8, red in the low byte: what GLSL's `unpackUnorm4x8` reads) plus a
//! table of [`GpuTexture`] records into it, because lavapipe has no descriptor indexing and
//! allows at most 128 MiB per storage buffer (DESIGN.md). `shaders/trace/texels.glsl` samples
//! it; [`sample`] is its CPU mirror (same math), used by the tests.
//!
//! What is packed, per content version `(id, version)` of a [`TextureRef`]:
//! - 2D and rectangle textures as they are; 1D textures as 2D images one texel high; cube maps
//!   and 3D textures flat, face 0 (+X) or slice 0 only (logged once);
//! - the levels from the base level (`GL_TEXTURE_BASE_LEVEL`) as the raster back end takes them
//!   (`render::raster::textures::level_chain`: each halves the one above), stored
//!   consecutively; borders are dropped, the inner image is sampled (logged once), so
//!   `GL_CLAMP` and `GL_CLAMP_TO_BORDER` are approximated by clamp-to-edge (no border colour);
//! - levels the texture does not have are generated on the CPU with the 2×2 box filter of
//!   `GL_GENERATE_MIPMAP` ([`downsample`]) so that ray-cone LOD always has a chain down to 1×1:
//!   for a mipmapped texture up to its max level; for a texture whose minification filter
//!   uses no mipmaps the whole chain, sampled with a mipmap filter matching its texel filter
//!   (`GL_LINEAR` → trilinear, `GL_NEAREST` → nearest level). This departs from OpenGL, which
//!   would read the base level only, because wide ray footprints (distant and secondary hits)
//!   would otherwise alias into noise;
//! - sRGB levels keep their encoded texels and are decoded per texel when sampled; float,
//!   depth and other formats are sampled through their canonical 8-bit texels (clamped to
//!   [0, 1]).
//!
//! Memory: the pool is one growing array of at most a budget of words ([`MAX_WORDS`] for the
//! tracer, 128 MiB). Space is found first-fit in a list of free ranges, else at the end.
//! [`TexelPool::prepare`] is called once per frame; versions unused for [`KEEP_FRAMES`] frames
//! are freed, and so is every other version of a texture the frame uses (an animated texture
//! or lightmap updated each frame keeps one version packed, plus the versions frames in flight
//! still read). When the budget is exceeded, versions this frame does not use are evicted,
//! least recently used first; a texture that still does not fit is sampled as its average
//! colour (logged once) and packed in a later frame when space allows. Nothing fails.
//!
//! Frames in flight: the GPU may still run the last `frames_in_flight − 1` frames while the
//! next one is prepared, and those read the words of the versions they used. Freed words are
//! therefore *retired*, not free: a range freed while frame N is prepared joins the free list
//! when frame N + `frames_in_flight` is prepared, when every frame that could read it (N − 1
//! at the latest, since a version is freed only in a frame that does not use it) has finished
//! — the renderer waits for a slot's fence before it records into it again. Space evicted
//! under pressure is thus used `frames_in_flight` frames later, not in the frame that evicts
//! (with one frame in flight or none, in the same frame), the way the geometry cache keys its
//! frees on frame numbers (`resident.rs`).
//!
//! Uploads: the caller copies [`TexelPool::take_uploads`]' word ranges of
//! [`TexelPool::words`] (and the whole, small table, [`TexelPool::textures`]) into its
//! buffers in the frame it prepared; no word a frame in flight reads is among them. The GPU
//! buffer must hold [`TexelPool::words`]' length; when it is reallocated (after waiting for
//! the GPU), all of it is uploaded.

pub mod sample;
#[cfg(test)]
mod tests;

use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use super::shader_constants::{
    NO_TEXTURE, TEXEL_MAG_LINEAR, TEXEL_MAG_TO_HALF, TEXEL_MIN_LINEAR, TEXEL_MIP_LINEAR, TEXEL_MIPMAP, TEXEL_RECT, TEXEL_SRGB, TEXEL_WRAP_CLAMP,
    TEXEL_WRAP_MIRROR, TEXEL_WRAP_REPEAT, TEXEL_WRAP_T_SHIFT,
};
use crate::frame::mipmap::downsample;
use crate::frame::texture::{Filter, Precision, TexImage, TextureContent, TextureKind, TextureRef, Wrap};
use crate::render::raster::renderer::log_once;
use crate::render::raster::textures::{Upload, interior, level_chain, texel_bytes};

pub use sample::{sample, texel_size};

/// The default budget: 32 Mi texels, 128 MiB, the largest storage buffer lavapipe allows.
pub const MAX_WORDS: usize = 32 << 20;
/// Frames a version stays packed without being used.
pub const KEEP_FRAMES: u64 = 60;
/// Most levels a texture keeps (a side of 2³¹ texels has 32).
const MAX_LEVELS: u32 = 32;
/// The widest and highest texture packed (texel coordinates stay exact in `f32` up to it).
const MAX_SIDE: u32 = 1 << 24;

/// One texture of the table, as `GpuTexture` in `shaders/trace/texels.glsl` (std430, checked
/// by the build against the compiled `pathtrace.comp`). Level `l` is `max(width >> l, 1)` × `max(height >> l, 1)` texels, rows bottom to
/// top, and starts right after level `l − 1`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTexture {
    /// Word offset of level 0 in the pool.
    pub offset: u32,
    /// Base level width in texels (at least 1).
    pub width: u32,
    /// Base level height in texels (at least 1).
    pub height: u32,
    /// Levels stored; 0 when the texture did not fit the budget and samples as `average`.
    pub levels: u32,
    /// Wrap modes (bits 0–1: s, bits 2–3: t; `TEXEL_WRAP_*`) and the other `TEXEL_*` flags of
    /// [`super::shader_constants`].
    pub flags: u32,
    /// Average colour of the base level, packed RGBA8 like the texels (sRGB-encoded when
    /// they are).
    pub average: u32,
    /// `GL_TEXTURE_MIN_LOD`.
    pub lod_min: f32,
    /// `GL_TEXTURE_MAX_LOD`.
    pub lod_max: f32,
}

include!(concat!(env!("OUT_DIR"), "/layouts/trace_texels.rs"));

impl GpuTexture {
    /// The wrap mode of s (`axis` 0) or t (1).
    pub fn wrap(&self, axis: u32) -> u32 {
        (self.flags >> (axis * TEXEL_WRAP_T_SHIFT)) & 3
    }

    /// Whether `flag` is set.
    pub fn has(&self, flag: u32) -> bool {
        self.flags & flag != 0
    }

    /// Word count of the levels stored.
    pub fn words(&self) -> usize {
        (0..self.levels).map(|l| level_size(self.width, self.height, l)).map(|[w, h]| w as usize * h as usize).sum()
    }
}

/// Width and height of level `level` of a `width` × `height` base.
pub fn level_size(width: u32, height: u32, level: u32) -> [u32; 2] {
    [width, height].map(|s| s.checked_shr(level).unwrap_or(0).max(1))
}

/// A packed (or average-coloured) content version.
struct Entry {
    /// Its index in the table.
    slot: u32,
    /// Its words in the pool (empty when it samples as its average colour).
    range: Range<usize>,
    /// Frame of its last use.
    used: u64,
}

/// The texel pool (see the module doc).
pub struct TexelPool {
    /// The pool.
    words: Vec<u32>,
    /// Most words the pool may hold.
    budget: usize,
    /// Free ranges of `words`, sorted, disjoint and not adjacent.
    free: Vec<Range<usize>>,
    /// Ranges freed while frames in flight may still read them, with the frame that freed
    /// them; they join `free` `frames_in_flight` frames later.
    retired: Vec<(u64, Range<usize>)>,
    /// Frames the GPU may be running when a frame is prepared, that one included.
    frames_in_flight: u64,
    entries: HashMap<(u32, u64), Entry>,
    table: Vec<GpuTexture>,
    /// Table slots of freed entries.
    free_slots: Vec<u32>,
    /// Word ranges written since the last [`TexelPool::take_uploads`].
    dirty: Vec<Range<usize>>,
    /// Frames prepared so far.
    frame: u64,
}

impl TexelPool {
    /// An empty pool of at most `budget` words, for a renderer with `frames_in_flight` frame
    /// slots (see the module doc).
    pub fn new(budget: usize, frames_in_flight: usize) -> TexelPool {
        TexelPool {
            words: Vec::new(),
            budget,
            free: Vec::new(),
            retired: Vec::new(),
            frames_in_flight: frames_in_flight as u64,
            entries: HashMap::new(),
            table: Vec::new(),
            free_slots: Vec::new(),
            dirty: Vec::new(),
            frame: 0,
        }
    }

    /// Starts a frame that samples `textures`: frees what the frame no longer needs, packs
    /// the versions not packed yet, and returns the table index of each texture, in order
    /// ([`NO_TEXTURE`], sampled as white, for a texture without a base level or wider or higher
    /// than 2²⁴ texels). Call once per frame.
    pub fn prepare(&mut self, textures: &[&TextureRef]) -> Vec<u32> {
        self.frame += 1;
        let frame = self.frame;
        for t in textures {
            if let Some(e) = self.entries.get_mut(&(t.id, t.version)) {
                e.used = frame;
            }
        }
        let ids: HashSet<u32> = textures.iter().map(|t| t.id).collect();
        let stale: Vec<_> = self.entries.iter().filter(|(k, e)| e.used < frame && (e.used + KEEP_FRAMES < frame || ids.contains(&k.0))).map(|(k, _)| *k).collect();
        for key in stale {
            self.release(key);
        }
        self.reclaim();
        textures.iter().map(|t| self.index_of(t)).collect()
    }

    /// The pool's words; its length is what the GPU buffer must hold.
    pub fn words(&self) -> &[u32] {
        &self.words
    }

    /// The texture table (slots of freed versions included; nothing indexes them).
    pub fn textures(&self) -> &[GpuTexture] {
        &self.table
    }

    /// The word ranges of [`TexelPool::words`] written since the last call, sorted and merged.
    pub fn take_uploads(&mut self) -> Vec<Range<usize>> {
        let mut ranges = std::mem::take(&mut self.dirty);
        ranges.retain(|r| r.start < self.words.len());
        for r in &mut ranges {
            r.end = r.end.min(self.words.len());
        }
        ranges.sort_by_key(|r| r.start);
        let mut merged: Vec<Range<usize>> = Vec::with_capacity(ranges.len());
        for r in ranges {
            match merged.last_mut() {
                Some(last) if r.start <= last.end => last.end = last.end.max(r.end),
                _ => merged.push(r),
            }
        }
        merged
    }

    /// The CPU mirror of `texel_sample` on this pool ([`sample`]).
    pub fn sample(&self, texture: u32, uv: [f32; 2], lod: f32) -> [f32; 4] {
        sample(&self.words, &self.table, texture, uv, lod)
    }

    /// The table index of `t`, packed (or retried, if it samples as its average colour and
    /// space may have been freed) when needed.
    fn index_of(&mut self, t: &TextureRef) -> u32 {
        let key = (t.id, t.version);
        let packed = self.entries.get(&key).map(|e| (e.slot, e.range.is_empty()));
        if let Some((slot, false)) = packed {
            return slot;
        }
        let Some(plan) = Plan::new(&t.content) else { return NO_TEXTURE };
        let range = self.place(plan.record.words());
        let (slot, average) = match packed {
            Some((slot, _)) if range.is_none() => return slot,
            Some((slot, _)) => (slot, self.table[slot as usize].average),
            None => {
                let slot = self.free_slots.pop().unwrap_or_else(|| {
                    self.table.push(GpuTexture::default());
                    self.table.len() as u32 - 1
                });
                (slot, plan.average())
            }
        };
        let mut record = GpuTexture { average, ..plan.record };
        match &range {
            Some(range) => {
                record.offset = range.start as u32;
                plan.write(&mut self.words[range.clone()]);
                self.dirty.push(range.clone());
            }
            None => {
                log_once("the texel pool is full: some textures are traced as their average colour");
                record.levels = 0;
            }
        }
        self.table[slot as usize] = record;
        self.entries.insert(key, Entry { slot, range: range.unwrap_or_default(), used: self.frame });
        slot
    }

    /// Finds `n` words: first fit, else at the end. Else evicts the versions this frame does
    /// not use, least recently used first, until `n` words will be free once the retired
    /// ranges are reclaimed, and returns `None`: a later frame finds them (this one, when
    /// nothing is in flight). `None` without evicting when they can never be found.
    fn place(&mut self, n: usize) -> Option<Range<usize>> {
        let evictable: usize = self.entries.values().filter(|e| e.used < self.frame).map(|e| e.range.len()).sum();
        let retired: usize = self.retired.iter().map(|(_, r)| r.len()).sum();
        let available = self.budget.saturating_sub(self.words.len()) + self.free.iter().map(Range::len).sum::<usize>() + retired + evictable;
        if n > available {
            return None;
        }
        loop {
            self.reclaim();
            if let Some(range) = self.allocate(n) {
                return Some(range);
            }
            if self.fits_later(n) {
                return None;
            }
            let lru = self.entries.iter().filter(|(_, e)| e.used < self.frame && !e.range.is_empty()).min_by_key(|(_, e)| e.used).map(|(k, _)| *k)?;
            // The evicted version keeps its slot, sampled as its average colour, until
            // `prepare` releases it.
            if let Some(e) = self.entries.get_mut(&lru) {
                let range = std::mem::take(&mut e.range);
                self.table[e.slot as usize].levels = 0;
                self.retire(range);
            }
        }
    }

    /// Whether `n` contiguous words will be free, at the end of the pool within the budget
    /// or in the free and retired ranges merged.
    fn fits_later(&self, n: usize) -> bool {
        let mut ranges: Vec<Range<usize>> = self.free.iter().cloned().chain(self.retired.iter().map(|(_, r)| r.clone())).collect();
        ranges.sort_by_key(|r| r.start);
        let room = self.budget.saturating_sub(self.words.len());
        let mut run = self.words.len()..self.words.len();
        for r in ranges.into_iter().rev() {
            if r.end == run.start {
                run.start = r.start;
            } else {
                run = r;
            }
            let tail = if run.end == self.words.len() { room } else { 0 };
            if run.len() + tail >= n {
                return true;
            }
        }
        room >= n
    }

    /// `n` words from the free list or the end of the pool, within the budget.
    fn allocate(&mut self, n: usize) -> Option<Range<usize>> {
        if let Some(i) = self.free.iter().position(|r| r.len() >= n) {
            let start = self.free[i].start;
            self.free[i].start += n;
            if self.free[i].is_empty() {
                self.free.remove(i);
            }
            return Some(start..start + n);
        }
        let start = self.words.len();
        if start + n > self.budget {
            return None;
        }
        self.words.resize(start + n, 0);
        Some(start..start + n)
    }

    /// Frees `range` once the frames in flight are done with it ([`TexelPool::reclaim`]).
    fn retire(&mut self, range: Range<usize>) {
        if !range.is_empty() {
            self.retired.push((self.frame, range));
        }
    }

    /// Frees the retired ranges no frame in flight can read any more.
    fn reclaim(&mut self) {
        let (frame, in_flight) = (self.frame, self.frames_in_flight);
        let (ready, waiting): (Vec<_>, Vec<_>) = std::mem::take(&mut self.retired).into_iter().partition(|(freed, _)| freed + in_flight <= frame);
        self.retired = waiting;
        for (_, range) in ready {
            self.free_range(range);
        }
    }

    /// Returns `range` to the free list, merging neighbours; free space at the end shrinks
    /// the pool.
    fn free_range(&mut self, range: Range<usize>) {
        if range.is_empty() {
            return;
        }
        let i = self.free.partition_point(|r| r.start < range.start);
        self.free.insert(i, range);
        if i + 1 < self.free.len() && self.free[i].end == self.free[i + 1].start {
            self.free[i].end = self.free.remove(i + 1).end;
        }
        if i > 0 && self.free[i - 1].end == self.free[i].start {
            self.free[i - 1].end = self.free.remove(i).end;
        }
        if self.free.last().is_some_and(|r| r.end == self.words.len()) {
            let tail = self.free.pop().unwrap_or_default();
            self.words.truncate(tail.start);
        }
    }

    /// Frees a version: its table slot now (the table is copied whole each frame), its words
    /// once the frames in flight are done.
    fn release(&mut self, key: (u32, u64)) {
        if let Some(e) = self.entries.remove(&key) {
            self.retire(e.range);
            self.table[e.slot as usize] = GpuTexture::default();
            self.free_slots.push(e.slot);
        }
    }
}

/// What a content version becomes: its table record (offset and average still unset) and
/// the levels it has.
struct Plan {
    record: GpuTexture,
    /// The levels the texture has, from the base level, face 0.
    chain: Vec<Arc<TexImage>>,
}

impl Plan {
    /// The plan of `content`; `None` without a base level.
    fn new(content: &TextureContent) -> Option<Plan> {
        let s = &content.sampler;
        let base = s.levels[0] as usize;
        let mipmapped = s.min_filter.mipmap.is_some();
        let max = if mipmapped { s.levels[1] as usize } else { base + MAX_LEVELS as usize };
        let chain = level_chain(&content.faces, base, max.min(base + MAX_LEVELS as usize), content.kind);
        let top = chain.first()?;
        if top.border != 0 {
            log_once("textures with a border are traced without it (the inner image is sampled)");
        }
        if matches!(content.kind, TextureKind::Cube | TextureKind::D3) {
            log_once("cube maps and 3D textures are traced flat: face 0 or slice 0");
        }
        let [width, height, _] = interior(top);
        if width.max(height) > MAX_SIDE {
            log_once("textures wider or higher than 2^24 texels are not traced");
            return None;
        }
        let full = 32 - width.max(height).leading_zeros();
        let allowed = if mipmapped { (s.levels[1].saturating_sub(s.levels[0])).saturating_add(1) } else { MAX_LEVELS };
        let levels = full.min(allowed);
        let wrap = |w: Wrap| match w {
            Wrap::Repeat => TEXEL_WRAP_REPEAT,
            Wrap::Clamp | Wrap::ClampToEdge | Wrap::ClampToBorder => TEXEL_WRAP_CLAMP,
            Wrap::MirroredRepeat => TEXEL_WRAP_MIRROR,
        };
        let bit = |on: bool, flag: u32| if on { flag } else { 0 };
        let min_linear = s.min_filter.texel == Filter::Linear;
        let mag_linear = s.mag_filter == Filter::Linear;
        let mip_linear = s.min_filter.mipmap.map_or(min_linear, |m| m == Filter::Linear);
        let flags = wrap(s.wrap[0])
            | wrap(s.wrap[1]) << TEXEL_WRAP_T_SHIFT
            | bit(mag_linear, TEXEL_MAG_LINEAR)
            | bit(min_linear, TEXEL_MIN_LINEAR)
            | bit(levels > 1, TEXEL_MIPMAP)
            | bit(levels > 1 && mip_linear, TEXEL_MIP_LINEAR)
            | bit(content.kind == TextureKind::Rect, TEXEL_RECT)
            | bit(top.precision == Precision::Srgb8, TEXEL_SRGB)
            | bit(mipmapped && mag_linear && !min_linear, TEXEL_MAG_TO_HALF);
        let record = GpuTexture { offset: 0, width, height, levels, flags, average: 0, lod_min: s.lod[0], lod_max: s.lod[1] };
        Some(Plan { record, chain })
    }

    /// The average colour of the base level.
    fn average(&self) -> u32 {
        self.chain.first().map_or(u32::MAX, |top| average(&base_texels(top, self.record.width, self.record.height)))
    }

    /// Writes the levels into `out` (the record's word count): those the texture has, then
    /// those generated from the last of them.
    fn write(&self, out: &mut [u32]) {
        let (width, height) = (self.record.width, self.record.height);
        let mut at = 0;
        let mut last: Option<(Vec<u8>, [usize; 3])> = None;
        for level in 0..self.record.levels {
            let [w, h] = level_size(width, height, level);
            let texels = match (self.chain.get(level as usize), last.take()) {
                (Some(img), _) => base_texels(img, w, h),
                (None, Some((above, size))) => downsample(&above, size).0,
                (None, None) => Vec::new(),
            };
            let n = w as usize * h as usize;
            for (word, px) in out.iter_mut().skip(at).take(n).zip(texels.chunks_exact(4)) {
                *word = u32::from_le_bytes([px[0], px[1], px[2], px[3]]);
            }
            at += n;
            last = Some((texels, [w as usize, h as usize, 1]));
        }
    }
}

/// The average colour of `content`'s base level as the tracer samples it (face 0 or slice 0),
/// packed like a texel (sRGB-encoded when its texels are); `None` without a base level. The
/// radiosity patches take their albedo from it.
pub fn average_color(content: &TextureContent) -> Option<u32> {
    Plan::new(content).map(|plan| plan.average())
}

/// The RGBA8 texels of the first slice of `img`'s interior (`width` × `height`).
fn base_texels(img: &TexImage, width: u32, height: u32) -> Vec<u8> {
    let mut bytes = texel_bytes(img, Upload::Rgba8);
    bytes.resize(width as usize * height as usize * 4, 0);
    bytes
}

/// The average of RGBA8 texels, rounded, packed like a texel (opaque white when empty).
fn average(texels: &[u8]) -> u32 {
    let n = (texels.len() / 4) as u64;
    if n == 0 {
        return u32::MAX;
    }
    let mut sum = [0u64; 4];
    for px in texels.chunks_exact(4) {
        for (s, &c) in sum.iter_mut().zip(px) {
            *s += u64::from(c);
        }
    }
    u32::from_le_bytes(sum.map(|s| ((s + n / 2) / n) as u8))
}
