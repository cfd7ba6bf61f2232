//! Occlusion queries (OpenGL 1.5 section 4.1.7) as Vulkan occlusion queries.
//!
//! A GL query covers a range of a frame's draws ([`crate::frame::Frame::occlusion_queries`]).
//! Vulkan queries must begin and end inside one rendering pass, and the recorder ends passes
//! for uploads and copies, so one GL query becomes one or more Vulkan queries (a *span* each)
//! whose counts are summed. Spans are recorded per frame-in-flight slot; once the slot's
//! fence signalled their counts are read, and when the slot carried the end of the frame the
//! GL results are final. Counts are exact when the device has `occlusionQueryPrecise`
//! (lavapipe and NVIDIA do); otherwise any non-zero count may read as 1, which section 4.1.7
//! does not allow, so [`Occlusion::counter_bits`] is then 0 and translate answers 0.
//!
//! Draws already rendered by a read-back before their query ended are not counted (the query's
//! range is only known at `glEndQuery`).

use std::collections::HashMap;

use ash::vk;

use super::device::{Check, Device, Result};

/// Queries per pool.
const POOL_SIZE: u32 = 256;

/// Results kept for this many frames when the program does not ask for them.
const KEEP_FRAMES: u64 = 1000;

/// Query pools and spans of one slot.
#[derive(Default)]
struct SlotQueries {
    pools: Vec<vk::QueryPool>,
    /// Queries used in the slot's current submission.
    used: u32,
    /// (frame, GL query, Vulkan query index) of each span.
    spans: Vec<(u64, u32, u32)>,
    /// The frame whose end this slot's submission carries, and its GL queries.
    finished: Option<(u64, Vec<u32>)>,
}

/// The occlusion queries of a renderer.
pub struct Occlusion {
    slots: Vec<SlotQueries>,
    /// Counts summed so far, per (frame, GL query).
    partial: HashMap<(u64, u32), u64>,
    /// Final counts.
    results: HashMap<(u64, u32), u64>,
    /// The span being recorded: GL query and Vulkan query index.
    active: Option<(u64, u32, u32)>,
    precise: bool,
}

impl Occlusion {
    /// Queries for `slots` frames in flight; `precise` says whether counts are exact.
    pub fn new(slots: usize, precise: bool) -> Occlusion {
        Occlusion {
            slots: (0..slots).map(|_| SlotQueries::default()).collect(),
            partial: HashMap::new(),
            results: HashMap::new(),
            active: None,
            precise,
        }
    }

    /// `GL_QUERY_COUNTER_BITS`: 64 with exact counts, else 0 (see the module doc).
    pub fn counter_bits(&self) -> u32 {
        if self.precise { 64 } else { 0 }
    }

    /// Records the reset of `slot`'s pools at the start of its command buffer (outside a
    /// rendering pass).
    pub fn begin_slot(&mut self, device: &Device, cmd: vk::CommandBuffer, slot: usize) {
        let Some(s) = self.slots.get_mut(slot) else { return };
        s.used = 0;
        for &pool in &s.pools {
            // Safety: outside a pass; the pool's previous results were read.
            unsafe { device.raw.cmd_reset_query_pool(cmd, pool, 0, POOL_SIZE) };
        }
    }

    /// Inside a rendering pass, before a draw of frame `frame` covered by GL query `query`
    /// (or none): ends the span of another query and begins one for `query`.
    pub fn before_draw(&mut self, device: &Device, cmd: vk::CommandBuffer, slot: usize, frame: u64, query: Option<u32>) -> Result<()> {
        if self.active.is_some_and(|(f, q, _)| Some(q) == query && f == frame) {
            return Ok(());
        }
        self.end_span(device, cmd, slot);
        let Some(query) = query else { return Ok(()) };
        let Some(s) = self.slots.get_mut(slot) else { return Ok(()) };
        let index = s.used;
        if index / POOL_SIZE >= s.pools.len() as u32 {
            // A new pool needs a reset before use, and a reset cannot be recorded inside a
            // pass: a pool created now is reset from the host (Vulkan 1.2 core).
            let info = vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::OCCLUSION).query_count(POOL_SIZE);
            // Safety: valid create info.
            let pool = unsafe { device.raw.create_query_pool(&info, None) }.check("vkCreateQueryPool")?;
            // Safety: the pool is new and unused; hostQueryReset is enabled (device.rs).
            unsafe { device.raw.reset_query_pool(pool, 0, POOL_SIZE) };
            s.pools.push(pool);
        }
        let pool = s.pools[(index / POOL_SIZE) as usize];
        let flags = if self.precise { vk::QueryControlFlags::PRECISE } else { vk::QueryControlFlags::empty() };
        // Safety: inside a pass; the query was reset and is not active.
        unsafe { device.raw.cmd_begin_query(cmd, pool, index % POOL_SIZE, flags) };
        s.used += 1;
        s.spans.push((frame, query, index));
        self.active = Some((frame, query, index));
        Ok(())
    }

    /// Ends the current span (before a rendering pass ends).
    pub fn end_span(&mut self, device: &Device, cmd: vk::CommandBuffer, slot: usize) {
        let Some((_, _, index)) = self.active.take() else { return };
        if let Some(&pool) = self.slots.get(slot).and_then(|s| s.pools.get((index / POOL_SIZE) as usize)) {
            // Safety: the query is active in the current pass.
            unsafe { device.raw.cmd_end_query(cmd, pool, index % POOL_SIZE) };
        }
    }

    /// Notes that `slot`'s submission ends frame `frame` with GL queries `queries`.
    pub fn finish_frame(&mut self, slot: usize, frame: u64, queries: Vec<u32>) {
        if let Some(s) = self.slots.get_mut(slot) {
            s.finished = Some((frame, queries));
        }
    }

    /// Whether `slot`'s pending submission ends frame `frame`.
    pub fn holds(&self, slot: usize, frame: u64) -> bool {
        self.slots.get(slot).is_some_and(|s| s.finished.as_ref().is_some_and(|(f, _)| *f == frame))
    }

    /// Reads the counts of `slot` once its fence signalled; final results for the frame it
    /// ended.
    pub fn completed(&mut self, device: &Device, slot: usize) {
        let Some(s) = self.slots.get_mut(slot) else { return };
        for (frame, query, index) in s.spans.drain(..) {
            let mut count = [0u64; 1];
            let Some(&pool) = s.pools.get((index / POOL_SIZE) as usize) else { continue };
            // Safety: the submission that wrote the query finished.
            let read = unsafe { device.raw.get_query_pool_results(pool, index % POOL_SIZE, &mut count, vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT) };
            if read.is_ok() {
                *self.partial.entry((frame, query)).or_default() += count[0];
            }
        }
        if let Some((frame, queries)) = s.finished.take() {
            for query in queries {
                let count = self.partial.remove(&(frame, query)).unwrap_or(0);
                self.results.insert((frame, query), count);
            }
            self.results.retain(|(f, _), _| f + KEEP_FRAMES >= frame);
            self.partial.retain(|(f, _), _| *f >= frame);
        }
    }

    /// The final count of `query` in `frame`, once known (given out once).
    pub fn result(&mut self, frame: u64, query: u32) -> Option<u64> {
        self.results.remove(&(frame, query))
    }

    /// Frees the pools (the GPU is idle).
    pub fn destroy(&mut self, device: &Device) {
        for s in &mut self.slots {
            for pool in s.pools.drain(..) {
                // Safety: the GPU is idle.
                unsafe { device.raw.destroy_query_pool(pool, None) };
            }
        }
    }
}
