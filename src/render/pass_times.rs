//! GPU time of a stage's passes from timestamps: [`SlotStamps`], a query pool of timestamps
//! per frame slot (the path tracer's pass and build times); [`PassTimes`], a stage's steps
//! summed over the frames and logged when the stage is destroyed (`GLRT_LOG=info`): the
//! denoiser's and the ambient occlusion's passes.
//!
//! Each frame-in-flight slot (the first [`TIMED_SLOTS`]) has its own queries: timestamp 0
//! before the first step and timestamp `k` after step `k`. A slot's queries are read when the
//! slot is recorded again (its fence has signalled by then) and, for the last frames, at
//! [`PassTimes::destroy`]. Only devices whose timestamps time compute and graphics work are
//! timed (GPUs; CPU devices such as lavapipe have none that bracket the work: [`supported`]).

use ash::vk;

use crate::render::raster::device::{Check, Device, Result};

/// Frame slots whose passes are timed (frames in flight are fewer).
pub const TIMED_SLOTS: usize = 4;

/// Whether `device`'s timestamps time compute and graphics work (not on CPU devices).
pub fn supported(device: &Device) -> bool {
    device.properties.limits.timestamp_compute_and_graphics == vk::TRUE && device.properties.device_type != vk::PhysicalDeviceType::CPU
}

/// `per_slot` timestamps for each frame slot, in one query pool.
pub struct SlotStamps {
    pool: vk::QueryPool,
    per_slot: u32,
}

impl SlotStamps {
    /// `per_slot` timestamps for each of `slots` frame slots on devices that time their work
    /// ([`supported`]); `None` elsewhere.
    pub fn new(device: &Device, per_slot: u32, slots: usize) -> Result<Option<SlotStamps>> {
        if !supported(device) {
            return Ok(None);
        }
        let info = vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(per_slot * slots as u32);
        // Safety: valid create info; destroyed in `destroy`.
        let pool = unsafe { device.raw.create_query_pool(&info, None) }.check("vkCreateQueryPool")?;
        Ok(Some(SlotStamps { pool, per_slot }))
    }

    /// The timestamps of the frame slot `slot`, to record.
    pub fn frame(&self, slot: usize) -> FrameStamps {
        FrameStamps { pool: self.pool, first: self.per_slot * slot as u32, count: self.per_slot }
    }

    /// The ticks of the frame slot `slot`'s timestamps, written by its frame, which has
    /// finished; `None` where they cannot be read.
    pub fn read(&self, device: &Device, slot: usize) -> Option<Vec<u64>> {
        let mut ticks = vec![0u64; self.per_slot as usize];
        // Safety: the queries were written by the slot's finished frame.
        unsafe { device.raw.get_query_pool_results(self.pool, self.per_slot * slot as u32, &mut ticks, vk::QueryResultFlags::TYPE_64) }.ok()?;
        Some(ticks)
    }

    /// Destroys the queries (the GPU must be idle).
    pub fn destroy(self, device: &Device) {
        // Safety: the GPU is idle.
        unsafe { device.raw.destroy_query_pool(self.pool, None) };
    }
}

/// Seconds from timestamp ticks `start` to `end` on `device`.
pub fn seconds(device: &Device, start: u64, end: u64) -> f64 {
    end.wrapping_sub(start) as f64 * f64::from(device.properties.limits.timestamp_period) * 1e-9
}

/// The GPU times of one stage's steps, summed over the frames read.
pub struct PassTimes {
    /// The stage's name in the summary.
    stage: &'static str,
    /// The steps, in order.
    steps: &'static [&'static str],
    stamps: SlotStamps,
    /// Per slot: whether it recorded a frame whose timestamps were not read yet.
    unread: [bool; TIMED_SLOTS],
    /// Seconds per step, summed.
    seconds: Vec<f64>,
    frames: u64,
}

/// The timestamps of one frame's slot, while it is recorded.
#[derive(Clone, Copy, Debug)]
pub struct FrameStamps {
    pool: vk::QueryPool,
    first: u32,
    count: u32,
}

impl PassTimes {
    /// Timestamps for the `steps` of `stage` on GPUs that time their work; `None` elsewhere.
    pub fn new(device: &Device, stage: &'static str, steps: &'static [&'static str]) -> Result<Option<PassTimes>> {
        let Some(stamps) = SlotStamps::new(device, Self::stamps(steps), TIMED_SLOTS)? else { return Ok(None) };
        Ok(Some(PassTimes { stage, steps, stamps, unread: [false; TIMED_SLOTS], seconds: vec![0.0; steps.len()], frames: 0 }))
    }

    /// Timestamps per frame: one before the first step and one after each.
    fn stamps(steps: &[&str]) -> u32 {
        steps.len() as u32 + 1
    }

    /// Starts timing the frame recorded into the frame-in-flight slot `slot` (after adding
    /// what the slot's last frame measured); `None` for slots beyond [`TIMED_SLOTS`].
    pub fn frame(&mut self, device: &Device, slot: usize) -> Option<FrameStamps> {
        if slot >= TIMED_SLOTS {
            return None;
        }
        self.read(device, slot);
        self.unread[slot] = true;
        Some(self.stamps.frame(slot))
    }

    /// Adds the times of the frame slot `slot` recorded last, once its fence has signalled.
    fn read(&mut self, device: &Device, slot: usize) {
        if !self.unread.get_mut(slot).is_some_and(std::mem::take) {
            return;
        }
        let Some(ticks) = self.stamps.read(device, slot) else { return };
        for (step, total) in self.seconds.iter_mut().enumerate() {
            *total += seconds(device, ticks[step], ticks[step + 1]);
        }
        self.frames += 1;
    }

    /// One line: the average GPU time per frame of each step and of all.
    fn summary(&self) -> String {
        let n = self.frames.max(1) as f64;
        let steps: Vec<String> = self.steps.iter().zip(&self.seconds).map(|(name, s)| format!("{name} {:.3}", s * 1e3 / n)).collect();
        format!("{}: {} frames timed; GPU ms per frame: {}, all {:.3}", self.stage, self.frames, steps.join(", "), self.seconds.iter().sum::<f64>() * 1e3 / n)
    }

    /// Reads the slots not read yet, logs the summary (`info`) when a frame was timed and
    /// destroys the queries (the GPU must be idle).
    pub fn destroy(mut self, device: &Device) {
        for slot in 0..TIMED_SLOTS {
            self.read(device, slot);
        }
        if self.frames > 0 {
            log::info!("{}", self.summary());
        }
        self.stamps.destroy(device);
    }
}

impl FrameStamps {
    /// Records timestamp `k` (0 before the first step, `k` after step `k`) once the work
    /// before it has passed `stage`. Timestamp 0 also resets the frame's queries, so it is
    /// recorded outside a rendering pass; the others may be recorded inside one.
    pub fn write(self, device: &Device, cmd: vk::CommandBuffer, k: u32, stage: vk::PipelineStageFlags2) {
        debug_assert!(k < self.count, "timestamp {k} of {}", self.count);
        // Safety: `cmd` is recording; the slot's queries were read (or never written).
        unsafe {
            if k == 0 {
                device.raw.cmd_reset_query_pool(cmd, self.pool, self.first, self.count);
            }
            device.raw.cmd_write_timestamp2(cmd, stage, self.pool, self.first + k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_averages_each_step_over_the_frames() {
        let times = PassTimes {
            stage: "denoiser",
            steps: &["gradient", "temporal", "variance", "a-trous", "modulate"],
            stamps: SlotStamps { pool: vk::QueryPool::null(), per_slot: 6 },
            unread: [false; TIMED_SLOTS],
            seconds: vec![0.0002, 0.002, 0.001, 0.004, 0.001],
            frames: 2,
        };
        assert_eq!(
            times.summary(),
            "denoiser: 2 frames timed; GPU ms per frame: gradient 0.100, temporal 1.000, variance 0.500, a-trous 2.000, modulate 0.500, all 4.100"
        );
    }
}
