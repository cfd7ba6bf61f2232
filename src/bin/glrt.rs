//! The `glrt` command:
//! - `glrt info`: the build and how many functions it exports;
//! - `glrt info FILE`: what a capture holds (frames, calls per function, bytes, textures, and
//!   the hash of each texture draws used, by which `glrt.toml` tags textures);
//! - `glrt replay FILE [--frames A..B] [--out DIR] [--size WxH]`: replays a capture headless
//!   (frames before `A` are replayed too: they build the state; the replay stops after `B - 1`);
//!   `--out` draws and writes frames `A` and later as `DIR/frame-NNNNN.png` (by frame number)
//!   through the Vulkan raster renderer, which does not draw the frames before `A`
//!   (`glrt::render::frames_from`); `--bench` prints the frame times of frames `A` and later (one
//!   frame's end to the next's) and where their time went, in ms per frame: decoding records,
//!   writing recorded memory, glrt's front end, hash tracking and the renderer;
//!   `--stats` prints hash tracking's statistics of each frame as one JSON line (keys in
//!   README.md; frames are not rendered unless `--out` is given);
//! - `glrt dump FILE`: the call log of a capture (the `GLRT_TRACE` format, with the captured
//!   program's addresses: the same text on every run) on standard output.

use std::process::ExitCode;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use glrt::replay::{self, reader::Capture, summary::Summary};
use glrt::translate::capture;
use glrt::frame::{FrameSink, NullSink};
use glrt::render::frames_repeated::FramesRepeated;
use glrt::translate::classify::report::{FrameTap, TextureCatalog, print_stats};

const USAGE: &str = "usage: glrt info [FILE] | glrt replay FILE [--frames A..B] [--out DIR] [--size WxH] [--repeat N] [--bench] [--stats] | glrt dump FILE";

fn main() -> ExitCode {
    default_sigpipe();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("info") | None if args.len() <= 1 => {
            println!("glrt {}", env!("CARGO_PKG_VERSION"));
            println!("exports: {} functions", glrt::gl_entry::exports::PROCS.len());
            Ok(())
        }
        Some("info") => info(&args[1..]),
        Some("replay") => replay_command(&args[1..]),
        Some("dump") => dump(&args[1..]),
        Some(other) => Err(format!("unknown command '{other}'\n{USAGE}")),
        None => Err(USAGE.to_owned()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("glrt: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The one positional argument `FILE` of `args`, and the options after it.
fn file_and_options(args: &[String]) -> Result<(Capture, &[String]), String> {
    let (file, rest) = args.split_first().ok_or(USAGE)?;
    Ok((Capture::open(std::path::Path::new(file))?, rest))
}

fn info(args: &[String]) -> Result<(), String> {
    let (capture, rest) = file_and_options(args)?;
    if !rest.is_empty() {
        return Err(format!("info: unexpected arguments {rest:?}"));
    }
    print!("{}", Summary::of(&capture)?.report(&capture));
    let catalog = TextureCatalog::default();
    let sink = catalog.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(sink.clone())))), ..Default::default() };
    // What draws used needs a replay; a capture that cannot be replayed still gets its summary.
    match replay::run(&capture, &options) {
        Ok(_) => print!("{}", catalog.report()),
        Err(e) => println!("textures drawn with: unknown (the replay failed: {e})"),
    }
    Ok(())
}

fn dump(args: &[String]) -> Result<(), String> {
    let (capture, rest) = file_and_options(args)?;
    if !rest.is_empty() {
        return Err(format!("dump: unexpected arguments {rest:?}"));
    }
    // The call log is read from the environment at the first GL call, which the replay makes.
    // Safety: single-threaded so far; nothing else reads the environment concurrently.
    unsafe { std::env::set_var("GLRT_TRACE", "/dev/stdout") };
    replay::run(&capture, &replay::Options::default())?;
    glrt::gl_entry::call_log::flush();
    Ok(())
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

/// Restores the default action of `SIGPIPE`, so that `glrt dump FILE | head` ends quietly as
/// Unix tools do (Rust programs ignore it, which turns a closed pipe into a panic of `println!`).
#[cfg(target_os = "linux")]
fn default_sigpipe() {
    const SIGPIPE: i32 = 13;
    const SIG_DFL: usize = 0;
    unsafe extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    // Safety: libc's `signal` with a valid signal number and the default disposition.
    unsafe { signal(SIGPIPE, SIG_DFL) };
}

#[cfg(not(target_os = "linux"))]
fn default_sigpipe() {}

/// `WxH` as two positive sizes.
fn parse_size(s: &str) -> Option<(i32, i32)> {
    let (w, h) = s.split_once('x')?;
    let (w, h) = (w.parse().ok()?, h.parse().ok()?);
    (w > 0 && h > 0).then_some((w, h))
}

fn replay_command(args: &[String]) -> Result<(), String> {
    let (capture, mut rest) = file_and_options(args)?;
    let mut options = replay::Options::default();
    let mut frames = (0, u64::MAX);
    let (mut bench, mut stats) = (false, false);
    // Each frame drawn this many times (animation frozen: converged path-traced references).
    let mut repeat = 1u32;
    while let [flag, tail @ ..] = rest {
        if flag == "--bench" {
            (bench, rest) = (true, tail);
            continue;
        }
        if flag == "--stats" {
            (stats, rest) = (true, tail);
            continue;
        }
        let [value, tail @ ..] = tail else { return Err(format!("replay: option {flag} needs a value\n{USAGE}")) };
        match flag.as_str() {
            "--frames" => frames = capture::parse_frames(value).ok_or(format!("--frames {value}: expected A..B"))?,
            "--size" => options.size = Some(parse_size(value).ok_or(format!("--size {value}: expected WxH"))?),
            "--out" => options.out = Some(value.into()),
            "--repeat" => repeat = value.parse().ok().filter(|&n| n > 0).ok_or(format!("--repeat {value}: expected a positive count"))?,
            _ => return Err(format!("replay: unknown option {flag}\n{USAGE}")),
        }
        rest = tail;
    }
    (options.start_frame, options.end_frame) = (frames.0, (frames.1 != u64::MAX).then_some(frames.1));
    options.timing = bench;
    let classify_ns = Arc::new(AtomicU64::new(0));
    let total = classify_ns.clone();
    let start = frames.0;
    options.sink = (stats || bench || repeat > 1).then(|| {
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
                sink = Box::new(FrameTap::new(sink, add));
            }
            sink
        }))
    });
    let outcome = replay::run(&capture, &options)?;
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
    use super::times_from;
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
}
