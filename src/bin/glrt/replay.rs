//! `glrt replay FILE [--frames A..B] [--out DIR] [--size WxH | --scale N] [--repeat N] [--bench] [--stats]`: replays a
//! capture headless (frames before `A` are replayed too: they build the state; the replay stops
//! after `B - 1`). `--out` draws and writes frames `A` and later as `DIR/frame-NNNNN.png` (by
//! frame number) through the Vulkan renderer, which does not draw the frames before `A`
//! (`glrt::render::frames_from`); `--bench` prints the frame times of frames `A` and later (one
//! frame's end to the next's) and where their time went, in ms per frame: decoding records,
//! writing recorded memory, glrt's front end, hash tracking and the renderer; `--stats` prints
//! hash tracking's statistics of each frame as one JSON line (keys in docs/hash-tracking.md; frames are not
//! rendered unless `--out` is given). `--size` says on stderr what it changes when the capture
//! was made at another size; `--scale N` replays the capture N times larger
//! ([`glrt::replay::scale`]). With `--out`, a progress bar on stderr (when it is a
//! terminal) counts the frames written and the time left.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::progress::FrameProgress;
use glrt::frame::{FrameSink, NullSink};
use glrt::render::frames_repeated::FramesRepeated;
use glrt::replay::{self, reader::{Capture, Record}, scale::Scale};
use glrt::translate::capture::format::Event;
use glrt::translate::capture;
use glrt::translate::classify::report::{FrameTap, print_stats};

/// The arguments of `glrt replay`.
#[derive(clap::Args)]
pub struct Args {
    /// The capture file (written by a program run with GLRT_CAPTURE=FILE).
    file: PathBuf,
    /// Frames to draw, time or report: A..B, A.. or ..B (the frames before A are replayed for
    /// their state only; the replay stops after B - 1).
    #[arg(long, value_name = "A..B", value_parser = parse_frame_range)]
    frames: Option<(u64, u64)>,
    /// Draws frames A and later and writes them as DIR/frame-NNNNN.png.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// The window size the replay draws into (the capture's own glViewport calls stay as they
    /// were: a 320x240 capture drawn at 1280x720 fills its lower-left 320x240).
    #[arg(long, value_name = "WxH", value_parser = parse_size, conflicts_with = "scale")]
    size: Option<(i32, i32)>,
    /// Replays N times larger in each direction: window sizes, viewports, scissors, line widths
    /// and point sizes multiplied by N (a capture that draws or reads images in window pixels
    /// is refused, naming the call).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=i64::from(glrt::replay::scale::MAX_FACTOR)))]
    scale: Option<u32>,
    /// Draws each frame N times, its animation frozen (converged path-traced references).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    repeat: u32,
    /// Prints the frame times of the frames asked for and where their time went.
    #[arg(long)]
    bench: bool,
    /// Prints hash tracking's statistics of each frame as one JSON line.
    #[arg(long)]
    stats: bool,
}

/// `--bench`: the frame times (from one frame's end to the next's) as the demo prints them.
/// The frame times of frames `start` and later: `times[k]` is frame `k + 1`'s (from frame `k`'s
/// end to its own), so frame `start`'s is `times[start - 1]`. Frames before `start` only
/// rebuild state (a capture made with `GLRT_CAPTURE_FRAMES` draws nothing there).
fn times_from(times: &[std::time::Duration], start: u64) -> &[std::time::Duration] {
    let skip = usize::try_from(start.saturating_sub(1)).unwrap_or(usize::MAX).min(times.len());
    &times[skip..]
}

fn frame_time_summary(times: &[std::time::Duration]) -> String {
    let ms: Vec<f64> = times.iter().map(|t| t.as_secs_f64() * 1e3).collect();
    if ms.is_empty() {
        return "frame times: fewer than 2 frames".to_owned();
    }
    let avg = ms.iter().sum::<f64>() / ms.len() as f64;
    let (min, max) = ms.iter().fold((f64::MAX, 0f64), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    format!("frames: {}  frame time ms: avg {avg:.3}  min {min:.3}  max {max:.3}  frames/s {:.1}", ms.len(), 1e3 / avg)
}

/// `--bench`: where the time of the measured frames went, in ms per frame: decoding the
/// capture, writing recorded memory, glrt's front end, hash tracking, and the rest of the frame
/// ends (the renderer's recording and submission); wall clock, then the replaying thread's CPU
/// time split in the same proportions (steadier on a loaded machine).
fn split_summary(t: &replay::Timing, classify: std::time::Duration, frames: usize) -> String {
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3 / frames.max(1) as f64;
    let rest = t.swaps.saturating_sub(classify);
    let parts = [t.reader, t.memory, t.calls, classify, rest].map(ms);
    let line = |parts: [f64; 5]| {
        let [reader, memory, translate, classify, renderer] = parts;
        format!(
            "reader {reader:.3}  memory {memory:.3}  translate {translate:.3}  classify {classify:.3}  renderer {renderer:.3}  (glrt {:.3})",
            translate + classify + renderer
        )
    };
    let wall = format!("ms per frame: {}", line(parts));
    // The kernel counts a thread's CPU time at scheduler ticks: none over a few short frames.
    let Some(cpu) = t.cpu.filter(|cpu| !cpu.is_zero()) else { return wall };
    let scale = ms(cpu) / parts.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    format!("{wall}\ncpu ms per frame: {}", line(parts.map(|p| p * scale)))
}

/// `--bench`: how fast the reader decodes the records (all of them, their memory reads
/// included, nothing replayed), in MB of the decompressed body per second.
fn decode_summary(capture: &Capture) -> String {
    let start = std::time::Instant::now();
    let (mut records, mut read_bytes) = (0u64, 0usize);
    for record in capture.records() {
        let Ok((_, record)) = record else { break };
        if let replay::reader::Record::Call { reads, .. } = record {
            read_bytes += reads.iter().map(|(_, bytes)| bytes.len()).sum::<usize>();
        }
        records += 1;
    }
    let seconds = start.elapsed().as_secs_f64();
    let mb = capture.body_len() as f64 / 1e6;
    format!(
        "reader: {records} records ({mb:.1} MB, {:.1} MB of memory reads) decoded in {:.1} ms: {:.0} MB/s",
        read_bytes as f64 / 1e6,
        seconds * 1e3,
        mb / seconds
    )
}

/// `--frames`: `A..B` (either bound may be left out).
fn parse_frame_range(s: &str) -> Result<(u64, u64), String> {
    capture::parse_frames(s).ok_or_else(|| "expected A..B, A.. or ..B with A <= B".to_owned())
}

/// `--size`: `WxH`, two positive sizes.
fn parse_size(s: &str) -> Result<(i32, i32), String> {
    let size = s.split_once('x').and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)));
    size.filter(|&(w, h)| w > 0 && h > 0).ok_or_else(|| "expected WxH, two positive sizes such as 640x480".to_owned())
}

/// What `--size` changes, when the capture was made at another size: its drawables take the
/// new size, its `glViewport` calls stay as recorded.
fn size_note(capture: &Capture, (width, height): (i32, i32)) -> Option<String> {
    let made_at = capture.records().map_while(Result::ok).find_map(|(_, record)| match record {
        Record::Event(Event::MakeCurrent { id, width, height, .. }) if id != 0 => Some((width, height)),
        _ => None,
    })?;
    (made_at != (width, height)).then(|| {
        format!(
            "--size {width}x{height}: the capture was made at {}x{}; its glViewport calls are replayed as recorded, so its picture keeps that size at the lower left unless the program set its viewport again",
            made_at.0, made_at.1
        )
    })
}

/// Runs `glrt replay` with `args`.
pub fn run(args: &Args) -> Result<(), String> {
    let capture = Capture::open(&args.file)?;
    if let Some(note) = args.size.and_then(|size| size_note(&capture, size)) {
        eprintln!("glrt: {note}");
    }
    let scale = args.scale.map(|factor| Scale::new(&capture, factor)).transpose()?;
    let mut options = replay::Options { size: args.size, scale, out: args.out.clone(), ..Default::default() };
    let frames = args.frames.unwrap_or((0, u64::MAX));
    let (bench, stats) = (args.bench, args.stats);
    (options.start_frame, options.end_frame) = (frames.0, (frames.1 != u64::MAX).then_some(frames.1));
    options.timing = bench;
    let classify_ns = Arc::new(AtomicU64::new(0));
    let total = classify_ns.clone();
    let start = frames.0;
    // --out: frames `start` to the range's end or the capture's.
    let progress = args.out.as_ref().map(|_| FrameProgress::new("replay", start, || capture.frames().min(frames.1)));
    let tap_progress = progress.clone();
    let repeat = args.repeat;
    options.sink = (stats || bench || repeat > 1 || progress.is_some()).then(|| {
        replay::SinkWrapper(Arc::new(move |inner: Option<Box<dyn FrameSink>>| {
            // --stats alone renders nothing but with --out; --bench measures the renderer too.
            let mut sink: Box<dyn FrameSink> = match inner {
                Some(sink) => sink,
                None if stats => Box::new(NullSink::default()),
                None => glrt::render::default_sink(),
            };
            if repeat > 1 {
                sink = Box::new(FramesRepeated::new(repeat, sink));
            }
            if stats {
                sink = Box::new(FrameTap::new(sink, print_stats));
            }
            if bench {
                let total = total.clone();
                let add = move |frame: &glrt::frame::Frame| {
                    if frame.number >= start {
                        total.fetch_add(frame.stats.classify_ns, Ordering::Relaxed);
                    }
                };
                sink = Box::new(FrameTap::passing(sink, add));
            }
            if let Some(progress) = tap_progress.clone() {
                sink = Box::new(FrameTap::passing(sink, move |frame: &glrt::frame::Frame| progress.frame_done(frame.number)));
            }
            sink
        }))
    });
    let outcome = replay::run(&capture, &options);
    if let Some(progress) = &progress {
        progress.finish();
    }
    let outcome = outcome?;
    println!("replayed {} calls, {} frames", outcome.calls, outcome.frames);
    if bench {
        let times = times_from(&outcome.frame_times, frames.0);
        println!("{}", frame_time_summary(times));
        let classify = std::time::Duration::from_nanos(classify_ns.load(Ordering::Relaxed));
        println!("{}", split_summary(&outcome.timing, classify, times.len()));
        println!("{}", decode_summary(&capture));
    }
    if let Some(dir) = &options.out {
        // The renderers are gone (the replay destroyed its contexts): every PNG is complete.
        let missing: Vec<u64> = (frames.0..outcome.frames).filter(|n| !dir.join(format!("frame-{n:05}.png")).exists()).collect();
        if !missing.is_empty() {
            return Err(format!("--out {}: frames {missing:?} were not written (see the messages above)", dir.display()));
        }
        println!("wrote frames {}..{} to {}", frames.0, outcome.frames, dir.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{parse_size, times_from};
    use std::time::Duration;

    #[test]
    fn bench_times_start_at_the_first_frame_asked_for() {
        // The times of frames 1 to 5.
        let times: Vec<Duration> = (1..=5).map(Duration::from_millis).collect();
        assert_eq!(times_from(&times, 0), &times[..]);
        assert_eq!(times_from(&times, 1), &times[..]);
        assert_eq!(times_from(&times, 3), &times[2..]);
        assert_eq!(times_from(&times, 3)[0], Duration::from_millis(3));
        assert!(times_from(&times, 9).is_empty());
    }

    #[test]
    fn sizes_are_two_positive_numbers() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert!(parse_size("big").is_err());
        assert!(parse_size("0x480").is_err());
        assert!(parse_size("640x").is_err());
    }
}
