//! The measured `auto` choice of ray-tracing back end (`tracer = "auto"`, issue 21 item 2):
//! on a device with `VK_KHR_ray_tracing_pipeline` neither back end is faster everywhere (the
//! H200 traces the demo faster with compute shaders, the Quake-3-like demo faster with the
//! ray-tracing pipeline), so the first frames of a program measure both.
//!
//! - **Trial.** [`Trial`] traces [`WARMUP_FRAMES`] + [`MEASURED_FRAMES`] frames with the
//!   hardware tracer, then as many with the compute tracer; each one's time is the mean GPU
//!   time of its tracing pass (timestamps, [`super::stats::Totals`]) over the frames read after
//!   its warm-up (uploads, first builds). The faster one traces from then on; the other is
//!   destroyed (one wait for the GPU). The choice and both times are logged.
//! - **Memory.** The choice is remembered per device (vendor, device, driver version, name),
//!   glrt version and program ([`choice_key`]) in `<cache>/glrt/tracers` ([`Choices`]): later
//!   runs make the remembered back end at once, without a trial. Deleting the file (or its
//!   line) measures again.
//! - **Unmeasured.** A device without timestamps gives no times: the hardware tracer is kept
//!   (the extensions' rule) and nothing is remembered.
//!
//! Devices without the extensions get the compute tracer and no trial.

use std::path::{Path, PathBuf};

use ash::vk;

use super::stats::Statistics;
use super::{GpuScene, Radiance, RayTracer, TracedImage};
use crate::frame::{Draw, Frame};
use crate::render::radiosity::stage::FrameIndirect;
use crate::render::raster::device::{Device, Result};
use crate::render::raster::renderer::Recorder;

/// Frames each back end traces before its times count.
pub const WARMUP_FRAMES: u64 = 30;
/// Frames whose tracing pass times each back end is measured by.
pub const MEASURED_FRAMES: u64 = 60;

/// What a trial found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decision {
    /// Whether the hardware tracer traces on.
    pub hardware: bool,
    /// Mean tracing-pass milliseconds of the hardware tracer (`None`: not measured).
    pub hardware_ms: Option<f64>,
    /// The same of the compute tracer.
    pub compute_ms: Option<f64>,
}

impl Decision {
    /// The decision for these times: the faster back end; the hardware one when either is
    /// unmeasured.
    pub fn of(hardware_ms: Option<f64>, compute_ms: Option<f64>) -> Decision {
        let hardware = match (hardware_ms, compute_ms) {
            (Some(h), Some(c)) => h <= c,
            _ => true,
        };
        Decision { hardware, hardware_ms, compute_ms }
    }

    /// Whether both were measured (only then is the choice remembered).
    pub fn measured(&self) -> bool {
        self.hardware_ms.is_some() && self.compute_ms.is_some()
    }

    /// The log line.
    pub fn describe(&self) -> String {
        let ms = |t: Option<f64>| t.map_or("unmeasured".to_owned(), |t| format!("{t:.3} ms"));
        let name = if self.hardware { "hardware" } else { "compute" };
        let why = if self.measured() { "the faster tracing pass" } else { "no timestamps: the device's extensions decide" };
        format!("glrt: tracer = \"auto\" chose the {name} tracer ({why}: hardware {}, compute {})", ms(self.hardware_ms), ms(self.compute_ms))
    }
}

/// The key a choice is remembered under: the device of `properties`, this glrt's version and
/// the program `program` (one line, no tabs).
pub fn choice_key(properties: &vk::PhysicalDeviceProperties, program: &str) -> String {
    let name = crate::render::raster::device::device_name(properties);
    let key = format!("{:04x}:{:04x}:{:x} {name} glrt {} {program}", properties.vendor_id, properties.device_id, properties.driver_version, env!("CARGO_PKG_VERSION"));
    key.replace(['\t', '\n'], " ")
}

/// The program this process runs (its executable's file name).
pub fn program() -> String {
    std::env::current_exe().ok().and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned())).unwrap_or_default()
}

/// The remembered choices: a text file of lines `key <tab> hardware|compute <tab> hardware ms
/// <tab> compute ms`.
pub struct Choices {
    path: PathBuf,
}

impl Choices {
    /// The choices in `<cache>/glrt/tracers` ([`crate::config::cache_dir`]).
    pub fn of_user() -> Choices {
        Choices::at(crate::config::cache_dir().join("glrt").join("tracers"))
    }

    /// The choices in the file `path`.
    pub fn at(path: PathBuf) -> Choices {
        Choices { path }
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The choice remembered for `key`: `Some(true)` the hardware tracer.
    pub fn get(&self, key: &str) -> Option<bool> {
        let text = std::fs::read_to_string(&self.path).ok()?;
        text.lines().find_map(|line| {
            let mut fields = line.split('\t');
            (fields.next() == Some(key)).then_some(())?;
            match fields.next() {
                Some("hardware") => Some(true),
                Some("compute") => Some(false),
                _ => None,
            }
        })
    }

    /// Remembers `decision` for `key` (replacing its line), when both were measured.
    pub fn put(&self, key: &str, decision: &Decision) -> std::io::Result<()> {
        if !decision.measured() {
            return Ok(());
        }
        let old = std::fs::read_to_string(&self.path).unwrap_or_default();
        let mut text: String = old.lines().filter(|l| l.split('\t').next() != Some(key)).map(|l| format!("{l}\n")).collect();
        let ms = |t: Option<f64>| t.map_or(String::new(), |t| format!("{t:.3}"));
        let name = if decision.hardware { "hardware" } else { "compute" };
        text += &format!("{key}\t{name}\t{}\t{}\n", ms(decision.hardware_ms), ms(decision.compute_ms));
        if let Some(dir) = self.path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(&self.path, text)
    }
}

/// One back end's measurement: its totals after the warm-up, then its mean.
#[derive(Clone, Copy, Debug, Default)]
struct Measure {
    /// Tracing-pass seconds and timed frames read when the warm-up ended.
    start: Option<(f64, u64)>,
    /// Mean milliseconds over the frames read since `start` (set when its turn ended).
    ms: Option<f64>,
}

/// The mean tracing-pass milliseconds of the frames `statistics` read since `start`.
fn mean_ms(statistics: &Statistics, start: (f64, u64)) -> Option<f64> {
    let t = &statistics.totals;
    let frames = t.timed_frames.checked_sub(start.1).filter(|&n| n > 0)?;
    Some((t.trace_seconds - start.0) * 1e3 / frames as f64)
}

/// The trial: both back ends, the hardware one first, until [`Decision`]; then the winner.
pub struct Trial {
    /// The hardware tracer, then the compute tracer.
    tracers: [Box<dyn RayTracer>; 2],
    /// Which of them were destroyed (the loser, once decided).
    destroyed: [bool; 2],
    measures: [Measure; 2],
    /// The back end tracing now (index into `tracers`).
    active: usize,
    /// Frames the active back end built in its turn.
    turn_frames: u64,
    decided: bool,
    /// Where the choice is remembered, and under which key.
    choices: Choices,
    key: String,
}

impl Trial {
    /// A trial of `hardware` against `compute`, remembered in `choices` under `key`.
    pub fn new(hardware: Box<dyn RayTracer>, compute: Box<dyn RayTracer>, choices: Choices, key: String) -> Trial {
        Trial { tracers: [hardware, compute], destroyed: [false; 2], measures: [Measure::default(); 2], active: 0, turn_frames: 0, decided: false, choices, key }
    }

    /// Counts a frame of the active back end; ends its warm-up or its turn; after both turns
    /// keeps the faster (waiting for the GPU to destroy the other).
    fn step(&mut self, device: &Device) {
        if self.decided {
            return;
        }
        let statistics = self.tracers[self.active].statistics();
        let measure = &mut self.measures[self.active];
        if self.turn_frames == WARMUP_FRAMES {
            measure.start = Some((statistics.totals.trace_seconds, statistics.totals.timed_frames));
        }
        if self.turn_frames < WARMUP_FRAMES + MEASURED_FRAMES {
            self.turn_frames += 1;
            return;
        }
        measure.ms = measure.start.and_then(|start| mean_ms(statistics, start));
        if self.active == 0 {
            (self.active, self.turn_frames) = (1, 0);
            return;
        }
        let decision = Decision::of(self.measures[0].ms, self.measures[1].ms);
        log::info!("{}", decision.describe());
        if let Err(e) = self.choices.put(&self.key, &decision) {
            log::warn!("glrt: the tracer choice could not be remembered in {}: {e}", self.choices.path().display());
        }
        self.decided = true;
        self.active = if decision.hardware { 0 } else { 1 };
        let loser = 1 - self.active;
        // Safety: waits for every submitted frame, the loser's last ones included; the frame
        // being recorded has not used it. When the wait fails it is destroyed with the trial.
        if unsafe { device.raw.device_wait_idle() }.is_ok() {
            self.tracers[loser].destroy(device);
            self.destroyed[loser] = true;
        }
    }
}

impl RayTracer for Trial {
    fn build(&mut self, rec: &mut Recorder<'_>, frame: &Frame, surfaces: &super::surfaces::Surfaces, camera: &Draw, indirect: Option<&FrameIndirect>) -> Result<GpuScene> {
        self.step(rec.device);
        self.tracers[self.active].build(rec, frame, surfaces, camera, indirect)
    }

    fn trace(&mut self, rec: &mut Recorder<'_>, scene: &GpuScene) -> Result<Option<Radiance>> {
        self.tracers[self.active].trace(rec, scene)
    }

    fn resolve(&mut self, rec: &mut Recorder<'_>, radiance: Radiance) -> Result<TracedImage> {
        self.tracers[self.active].resolve(rec, radiance)
    }

    fn statistics(&self) -> &Statistics {
        self.tracers[self.active].statistics()
    }

    fn name(&self) -> &'static str {
        self.tracers[self.active].name()
    }

    fn destroy(&mut self, device: &Device) {
        for (tracer, destroyed) in self.tracers.iter_mut().zip(&mut self.destroyed) {
            if !*destroyed {
                tracer.destroy(device);
                *destroyed = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_faster_tracing_pass_wins_and_unmeasured_keeps_the_hardware_tracer() {
        // The H200's numbers of session 21 (bench/pathtrace.md): demo and q3.
        let demo = Decision::of(Some(24.3), Some(17.25));
        assert!(!demo.hardware && demo.measured());
        assert!(demo.describe().contains("chose the compute tracer (the faster tracing pass: hardware 24.300 ms, compute 17.250 ms)"), "{}", demo.describe());
        assert!(Decision::of(Some(1.38), Some(1.92)).hardware);
        let unmeasured = Decision::of(None, Some(1.0));
        assert!(unmeasured.hardware && !unmeasured.measured());
        assert!(Decision::of(Some(2.0), None).hardware);
    }

    #[test]
    fn choices_are_remembered_per_key_and_replaced() {
        let dir = std::env::temp_dir().join(format!("glrt-auto-test-{}", std::process::id()));
        let choices = Choices::at(dir.join("glrt").join("tracers"));
        assert_eq!(choices.get("gpu demo"), None, "nothing remembered yet");
        choices.put("gpu demo", &Decision::of(Some(24.3), Some(17.25))).unwrap();
        choices.put("gpu q3", &Decision::of(Some(1.38), Some(1.92))).unwrap();
        assert_eq!((choices.get("gpu demo"), choices.get("gpu q3"), choices.get("gpu")), (Some(false), Some(true), None));
        choices.put("gpu demo", &Decision::of(Some(10.0), Some(17.25))).unwrap();
        choices.put("gpu other", &Decision::of(None, Some(1.0))).unwrap();
        assert_eq!((choices.get("gpu demo"), choices.get("gpu other")), (Some(true), None), "replaced; an unmeasured trial is not remembered");
        let text = std::fs::read_to_string(choices.path()).unwrap();
        assert_eq!(text, "gpu q3\thardware\t1.380\t1.920\ngpu demo\thardware\t10.000\t17.250\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_mean_counts_the_frames_read_after_the_warm_up() {
        let mut s = Statistics::default();
        s.totals.trace_seconds = 0.5;
        s.totals.timed_frames = 40;
        assert_eq!(mean_ms(&s, (0.5, 40)), None, "no frame read since");
        s.totals.trace_seconds = 0.5 + 0.06;
        s.totals.timed_frames = 100;
        assert!((mean_ms(&s, (0.5, 40)).unwrap() - 1.0).abs() < 1e-9);
    }
}
