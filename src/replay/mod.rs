//! Reading and replaying captures (`glrt replay|dump|info FILE`): a client of the exported C
//! API, apart from the recorder (`translate::capture`) as apitrace keeps its retracer apart
//! from its tracer. It depends on everything below it: the capture file format and command
//! table (`translate::capture`), the generated C exports and headless contexts
//! ([`crate::gl_entry`]), and the renderer for `--out` ([`crate::render::dumping_sink`]);
//! nothing below names it.
//!
//! - [`reader`]: reads a capture file, never trusting it;
//! - [`summary`]: what a capture holds (`glrt info FILE`);
//! - [`shadow`]: the replay's copy of the captured program's address space;
//! - [`scale`]: a replay N times larger (`glrt replay --scale N`);
//! - [`calls`]: the generated thunks that call a command's export with recorded arguments;
//! - [`run`] (here): replays a capture on this thread.
//!
//! **Replay** creates headless contexts of the captured sizes and calls the same generated C
//! exports a program calls ([`calls::call`]), so the call log and capture hooks work during a
//! replay too. Client memory lives in a *shadow* of the captured address space: each 4 GiB
//! window of addresses the capture uses maps to a slot of one reserved region, pointer
//! arguments in those windows are translated into it, and each call's recorded bytes are
//! written there before the call. Values below 4 GiB (buffer offsets, null) pass unchanged;
//! memory below 4 GiB that the capture read (the data of a program that is not position
//! independent) is mapped at its own address. The shadow is installed as the recorder's
//! address map while the replay runs, so that a capture made during a replay maps addresses
//! back through it and writes a byte-identical file.
//!
//! Replay checks every length in the file, but runs the recorded GL calls as they are: a
//! hand-made capture whose arguments make a call read far past its recorded memory can crash
//! the replay, as it would the program (the compressed body's checksums and the trailer's
//! hash refuse accidental damage first).

pub mod reader;
pub mod scale;
pub mod shadow;
pub mod summary;

use std::collections::{BTreeSet, HashMap};
use std::ffi::c_void;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use reader::{Capture, Record};
use shadow::Shadow;

use crate::frame::FrameSink;
use crate::gl_entry::{current, headless};
use crate::translate::capture::format::{Event, SwapKind};
use crate::translate::capture::table::COMMANDS;
use crate::translate::capture::{self, AddressMap};

/// The generated replay thunks: command id and raw arguments → the command's C export.
pub mod calls {
    include!(concat!(env!("OUT_DIR"), "/replay_calls.rs"));
}

/// How to replay.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Stop after the frame before this one (frames count from 0); `None`: every frame.
    pub end_frame: Option<u64>,
    /// Drawable size to use instead of the captured sizes (at make-current and at each
    /// `glXSwapBuffers`, which refreshes the size).
    pub size: Option<(i32, i32)>,
    /// Replay N times larger: drawable sizes and the window-pixel arguments of commands
    /// multiplied ([`scale::Scale`], made for the capture replayed).
    pub scale: Option<scale::Scale>,
    /// Where to write frames `start_frame` and later as PNG (`frame-NNNNN.png`, by frame
    /// number), through the Vulkan raster renderer ([`crate::render::dumping_sink`]); `None`:
    /// frames go to the default sink.
    pub out: Option<PathBuf>,
    /// The first frame written to `out`.
    pub start_frame: u64,
    /// Wraps the sink of each context the replay creates (the `out` sink, or `None` for a
    /// replay that does not render), for `--stats` and `glrt info`.
    pub sink: Option<SinkWrapper>,
    /// Measure where the time of frames `start_frame` and later goes ([`Outcome::timing`]).
    pub timing: bool,
}

/// Makes the sink of a replayed context from the sink it would have had (`None`: no renderer
/// is needed).
#[derive(Clone)]
pub struct SinkWrapper(pub Arc<WrapSink>);

/// What a [`SinkWrapper`] calls.
pub type WrapSink = dyn Fn(Option<Box<dyn FrameSink>>) -> Box<dyn FrameSink> + Send + Sync;

impl std::fmt::Debug for SinkWrapper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SinkWrapper")
    }
}

/// What a replay did.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    /// Frames ended.
    pub frames: u64,
    /// GL calls made.
    pub calls: u64,
    /// Time from each frame's end to the next one's (frames 1 and later): the frame times
    /// of `glrt replay --bench`.
    pub frame_times: Vec<std::time::Duration>,
    /// Where the time of frames `start_frame` and later went, when [`Options::timing`] asked.
    pub timing: Timing,
}

/// The wall-clock time of a replay's frames split by what ran (`glrt replay --bench`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Timing {
    /// Decoding records ([`reader`]).
    pub reader: Duration,
    /// Writing the memory calls read into the shadow ([`shadow`]).
    pub memory: Duration,
    /// The GL calls: glrt's front end (`translate`).
    pub calls: Duration,
    /// Frame ends (classification and the renderer's work on the frame) and the other
    /// window-system events.
    pub swaps: Duration,
    /// CPU time of the replaying thread over the same frames (`None` where
    /// `/proc/thread-self/schedstat` cannot be read): unlike the parts above, it excludes the
    /// time the thread waited for a CPU on a loaded machine.
    pub cpu: Option<Duration>,
}

/// CPU time this thread has run (Linux: the first field of `/proc/thread-self/schedstat`, in
/// nanoseconds).
fn thread_cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(Duration::from_nanos(stat.split_whitespace().next()?.parse().ok()?))
}

/// Adds the time since its last lap to one part of a [`Timing`], while on.
struct Stopwatch {
    last: Option<Instant>,
}

impl Stopwatch {
    /// Ends a lap: its time goes to `part`.
    #[inline]
    fn lap(&mut self, part: &mut Duration) {
        if let Some(last) = &mut self.last {
            let now = Instant::now();
            *part += now - *last;
            *last = now;
        }
    }
}

/// The address space a capture uses: the 4 GiB windows its reads touch and its pointer
/// arguments point into, the pages below 4 GiB it read, and those pointer arguments below
/// 4 GiB point into (buffer offsets, or a non-PIE program's data).
fn layout(capture: &Capture) -> Result<Shadow, String> {
    let (mut windows, mut read, mut pointed) = (BTreeSet::new(), BTreeSet::new(), BTreeSet::new());
    for record in capture.records() {
        let (_, record) = record.map_err(|e| e.to_string())?;
        let Record::Call { id, args, reads } = record else { continue };
        for (address, bytes) in reads {
            windows.extend(Shadow::windows_of(address, bytes.len() as u64));
            read.extend(Shadow::low_pages_of(address, bytes.len() as u64));
        }
        for (&a, kind) in args.iter().zip(COMMANDS[id].1.bytes()) {
            if kind == b'p' {
                windows.insert(a >> 32);
                pointed.extend(Shadow::low_pages_of(a, 1));
            }
        }
        if windows.len() > shadow::MAX_WINDOWS {
            break;
        }
    }
    pointed.remove(&0);
    Shadow::new(&windows, &read, &pointed)
}

/// Clears the replay's address mapping of capture when the replay ends, however it ends.
struct Mapping;

impl Drop for Mapping {
    fn drop(&mut self) {
        capture::map_addresses(None);
    }
}

/// Replays `capture` on this thread; the contexts it creates are released and destroyed at
/// the end.
pub fn run(capture: &Capture, options: &Options) -> Result<Outcome, String> {
    // Before any sink is made: renderers log the device they chose.
    crate::logging::init();
    let shadow = Arc::new(layout(capture)?);
    capture::map_addresses(Some(shadow.clone()));
    let _mapping = Mapping;
    let mut contexts: HashMap<u32, *mut c_void> = HashMap::new();
    let result = replay_records(capture, options, &shadow, &mut contexts);
    // Released without a make-current event: the capture of a replay ends as the original.
    current::make_current(0, None);
    for (_, handle) in contexts {
        headless::glrtDestroyContext(handle);
    }
    result
}

fn replay_records(
    capture: &Capture,
    options: &Options,
    shadow: &Shadow,
    contexts: &mut HashMap<u32, *mut c_void>,
) -> Result<Outcome, String> {
    let mut outcome = Outcome::default();
    let mut last_swap = None;
    let translate = |a: u64| shadow.translate(a);
    let timed = |frames: u64| options.timing && frames >= options.start_frame;
    let mut clock = Stopwatch { last: timed(0).then(Instant::now) };
    let mut cpu_start = timed(0).then(thread_cpu_time).flatten();
    let mut records = capture.records();
    loop {
        let Some(record) = records.next() else { break };
        clock.lap(&mut outcome.timing.reader);
        let (at, record) = record.map_err(|e| e.to_string())?;
        let fail = |cause: String| format!("record at byte {at} of the decompressed body: {cause}");
        match record {
            Record::Call { id, mut args, reads } => {
                if let Some(scale) = &options.scale {
                    scale.rewrite(id, &mut args);
                }
                for (address, bytes) in reads {
                    shadow.write(address, bytes).map_err(fail)?;
                }
                clock.lap(&mut outcome.timing.memory);
                // Safety: every pointer argument is translated into the shadow, which holds
                // the bytes the call read and is writable wherever the program's memory was.
                if !unsafe { calls::call(id, &args, &translate) } {
                    return Err(fail(format!("{} cannot be replayed", COMMANDS[id].0)));
                }
                clock.lap(&mut outcome.timing.calls);
                outcome.calls += 1;
            }
            Record::Event(Event::Context { id, share }) => {
                let share = if share == 0 {
                    std::ptr::null_mut()
                } else {
                    *contexts.get(&share).ok_or_else(|| fail(format!("context {id} shares with unknown context {share}")))?
                };
                let sink = match &options.out {
                    Some(dir) => Some(crate::render::dumping_sink(dir, options.start_frame).map_err(|e| format!("--out: {e}"))?),
                    None => None,
                };
                let sink = match &options.sink {
                    Some(wrap) => Some((wrap.0)(sink)),
                    None => sink,
                };
                let handle = headless::create_context(share, sink);
                if handle.is_null() {
                    return Err(fail(format!("cannot create context {id}")));
                }
                if let Some(old) = contexts.insert(id, handle) {
                    headless::glrtDestroyContext(old);
                }
                clock.lap(&mut outcome.timing.swaps);
            }
            Record::Event(Event::MakeCurrent { id, width, height, double }) => {
                let handle = if id == 0 {
                    std::ptr::null_mut()
                } else {
                    *contexts.get(&id).ok_or_else(|| fail(format!("unknown context {id} made current")))?
                };
                let (width, height) = options.size.unwrap_or((width, height));
                let (width, height) = options.scale.as_ref().map_or((width, height), |s| s.size((width, height)));
                headless::make_current(handle, width, height, double);
                clock.lap(&mut outcome.timing.swaps);
            }
            Record::Event(Event::Swap(kind)) => {
                headless::swap(match (kind, options.size, &options.scale) {
                    (SwapKind::Glx { .. }, Some((width, height)), _) => SwapKind::Glx { width, height },
                    (SwapKind::Glx { width, height }, None, Some(scale)) => {
                        let (width, height) = scale.size((width, height));
                        SwapKind::Glx { width, height }
                    }
                    _ => kind,
                });
                outcome.frames += 1;
                let now = Instant::now();
                outcome.frame_times.extend(last_swap.replace(now).map(|t| now - t));
                clock.lap(&mut outcome.timing.swaps);
                if clock.last.is_none() && timed(outcome.frames) {
                    clock.last = Some(now);
                    cpu_start = thread_cpu_time();
                }
                if options.end_frame.is_some_and(|end| outcome.frames >= end) {
                    break;
                }
            }
        }
    }
    outcome.timing.cpu = cpu_start.zip(thread_cpu_time()).map(|(start, end)| end.saturating_sub(start));
    Ok(outcome)
}
