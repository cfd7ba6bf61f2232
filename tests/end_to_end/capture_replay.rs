//! Captures (`GLRT_CAPTURE`) of real programs replayed headless (`glrt replay`): the replay
//! draws the same frames as the live run, replaying with `GLRT_CAPTURE` set writes the same
//! file byte for byte, and damaged files are refused with the offset and cause.
//!
//! Fixtures in `tests/fixtures/`: `demo.glrtcap` (4 frames of `glrt-demo --headless`),
//! `q3.glrtcap` (4 frames of `glrt-demo --q3 --headless`) and `glxgears.glrtcap` (frames of
//! Mesa's glxgears under Xvfb, through glrt's libGL.so.1);
//! `tests/fixtures/*.frames` are the frame logs of the live runs that made them
//! (`tests/fixtures/make.sh` remakes both). The range test runs `glrt-demo` through
//! `target/<profile>/libglrt.so`: run `cargo build` first.

use std::path::{Path, PathBuf};
use std::process::Command;

use glrt::replay::reader::{Capture, Record};
use images::Image;

use crate::images;
use crate::programs;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name)
}

fn scratch(name: &str) -> PathBuf {
    programs::scratch("capture_replay", name)
}

/// The first record where two captures differ, described.
fn first_difference(a: &Capture, b: &Capture) -> Option<String> {
    let (mut ra, mut rb) = (a.records(), b.records());
    for index in 0.. {
        match (ra.next(), rb.next()) {
            (None, None) => return None,
            (x, y) => {
                let (x, y) = (x.map(|r| r.map(|(_, r)| format!("{r:?}"))), y.map(|r| r.map(|(_, r)| format!("{r:?}"))));
                if x != y {
                    return Some(format!("record {index}:\n  first:  {x:?}\n  second: {y:?}"));
                }
            }
        }
    }
    unreachable!()
}

/// Replays `capture` with `glrt replay` (another process: the environment configures the
/// library), recording a frame log and a new capture; returns (frame log, new capture path).
fn replay_with_capture(capture: &Path, tag: &str) -> (String, PathBuf) {
    let log = scratch(&format!("{tag}.replay.frames"));
    let again = scratch(&format!("{tag}.again.glrtcap"));
    let out = Command::new(env!("CARGO_BIN_EXE_glrt"))
        .arg("replay")
        .arg(capture)
        .env("GLRT_FRAME_LOG", &log)
        .env("GLRT_CAPTURE", &again)
        .output()
        .expect("run glrt replay");
    assert!(out.status.success(), "glrt replay failed: {}", String::from_utf8_lossy(&out.stderr));
    (std::fs::read_to_string(&log).expect("replay frame log"), again)
}

fn round_trip(name: &str) {
    let original = fixture(&format!("{name}.glrtcap"));
    let live = std::fs::read_to_string(fixture(&format!("{name}.frames"))).expect("live frame log");
    let (replayed, again) = replay_with_capture(&original, name);
    assert!(live.lines().count() >= 3, "the fixture holds at least 3 frames");
    assert_eq!(replayed, live, "replayed frames differ from the live run's");
    let (a, b) = (std::fs::read(&original).unwrap(), std::fs::read(&again).unwrap());
    if a != b {
        let (ca, cb) = (Capture::parse(&a).unwrap(), Capture::parse(&b).unwrap());
        panic!("the capture of the replay differs: {}", first_difference(&ca, &cb).unwrap_or("in compression only".into()));
    }
}

#[test]
fn demo_replays_to_the_same_frames_and_the_same_file() {
    round_trip("demo");
}

#[test]
fn glxgears_replays_to_the_same_frames_and_the_same_file() {
    round_trip("glxgears");
}

#[test]
fn q3_replays_to_the_same_frames_and_the_same_file() {
    round_trip("q3");
}

/// A deterministic xorshift generator for the mutation tests.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// The error message of a capture that must be refused, checked to name a byte offset
/// within `limit` and a cause.
fn refused(bytes: &[u8], limit: u64, what: &str) -> String {
    let e = match Capture::parse(bytes) {
        Err(e) => e,
        Ok(c) => match c.records().find_map(Result::err) {
            Some(e) => e,
            None => panic!("{what}: accepted"),
        },
    };
    assert!(e.offset <= limit, "{what}: offset {} past {limit}", e.offset);
    let message = e.to_string();
    assert!(message.contains(&format!("at byte {} of the ", e.offset)), "{what}: {message}");
    assert!(!e.cause.is_empty(), "{what}: no cause");
    message
}

/// The decompressed body of a capture file.
fn body_of(file: &[u8]) -> Vec<u8> {
    let mut body = Vec::new();
    let compressed = &file[12..file.len() - 24];
    std::io::Read::read_to_end(&mut lz4_flex::frame::FrameDecoder::new(compressed), &mut body).unwrap();
    body
}

/// A capture file with the header of `file`, `body` compressed, and a matching trailer.
fn with_body(file: &[u8], body: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut out = file[..12].to_vec();
    let mut encoder = lz4_flex::frame::FrameEncoder::new(&mut out);
    encoder.write_all(body).unwrap();
    encoder.finish().unwrap();
    out.extend_from_slice(b"GLRTEND\0");
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(&xxhash_rust::xxh3::xxh3_64(body).to_le_bytes());
    out
}

#[test]
fn truncated_captures_are_refused_with_offset_and_cause() {
    let bytes = std::fs::read(fixture("glxgears.glrtcap")).unwrap();
    let len = bytes.len();
    let cuts: Vec<usize> = (0..64).chain((64..len).step_by(97)).chain(len - 64..len).collect();
    for cut in cuts {
        let message = refused(&bytes[..cut], len as u64 + (1 << 20), &format!("cut at {cut}"));
        if cut < 12 {
            assert!(message.contains("truncated") || message.contains("magic"), "{message}");
        }
    }
}

#[test]
fn corrupted_captures_are_refused_with_offset_and_cause() {
    let bytes = std::fs::read(fixture("glxgears.glrtcap")).unwrap();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for round in 0..400 {
        let mut damaged = bytes.clone();
        for _ in 0..1 + rng.below(3) {
            let at = rng.below(damaged.len());
            damaged[at] ^= 1 << rng.below(8);
        }
        refused(&damaged, bytes.len() as u64 + (1 << 20), &format!("flip round {round}"));
    }
}

#[test]
fn wrong_versions_and_other_builds_are_named() {
    let bytes = std::fs::read(fixture("glxgears.glrtcap")).unwrap();
    let mut v2 = bytes.clone();
    v2[8..12].copy_from_slice(&2u32.to_le_bytes());
    let message = refused(&v2, 8, "version 2");
    assert!(message.contains("at byte 8 of the file: format version 2, this glrt reads version 1 only"), "{message}");

    // A build that knows a command this one does not: the description names it.
    let body = body_of(&bytes);
    let len = u32::from_le_bytes(body[..4].try_into().unwrap()) as usize;
    let description = std::str::from_utf8(&body[4..4 + len]).unwrap().replacen("glAccum vv", "glAccuX vv", 1);
    let mut other = (description.len() as u32).to_le_bytes().to_vec();
    other.extend_from_slice(description.as_bytes());
    other.extend_from_slice(&xxhash_rust::xxh3::xxh3_64(description.as_bytes()).to_le_bytes());
    other.extend_from_slice(&body[4 + len + 8..]);
    let message = refused(&with_body(&bytes, &other), body.len() as u64, "other build");
    assert!(message.contains("\"glAccuX\" is unknown to this build: written by another glrt build (glrt "), "{message}");
}

/// Property: damaged records in a body whose checksums pass (`Capture::from_body`, what the
/// reader does after decompressing) never panic the reader; each damaged capture is read to its end or refused at an offset
/// inside the body. Deterministic: 3000 mutations (flips, cuts, inserted and deleted bytes).
#[test]
fn damaged_records_never_panic_the_reader() {
    let bytes = std::fs::read(fixture("glxgears.glrtcap")).unwrap();
    let body = body_of(&bytes);
    let records_at = 4 + u32::from_le_bytes(body[..4].try_into().unwrap()) as usize + 8;
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut refusals = 0;
    for _ in 0..3000 {
        let mut b = body.clone();
        match rng.below(4) {
            0 => {
                for _ in 0..1 + rng.below(8) {
                    let at = records_at + rng.below(b.len() - records_at);
                    b[at] = rng.next() as u8;
                }
            }
            1 => b.truncate(records_at + rng.below(b.len() - records_at)),
            2 => {
                let at = records_at + rng.below(b.len() - records_at);
                let junk: Vec<u8> = (0..1 + rng.below(16)).map(|_| rng.next() as u8).collect();
                b.splice(at..at, junk);
            }
            _ => {
                let at = records_at + rng.below(b.len() - records_at);
                let end = (at + 1 + rng.below(32)).min(b.len());
                b.drain(at..end);
            }
        }
        let capture = Capture::from_body(b.clone(), b.len()).expect("the description is intact");
        for record in capture.records() {
            match record {
                Ok((_, Record::Call { reads, .. })) => assert!(reads.iter().all(|(_, r)| r.len() <= b.len())),
                Ok(_) => {}
                Err(e) => {
                    assert!(e.in_body && e.offset <= b.len() as u64, "{e}");
                    refusals += 1;
                }
            }
        }
    }
    assert!(refusals > 100, "only {refusals} of 3000 mutations were refused");
}

/// `GLRT_CAPTURE_FRAMES=2..4`: frames 0 and 1 keep their state commands (and display list
/// calls) but not their drawing, frames 2 and 3 are complete and replay as they were drawn live, and the file
/// closes after frame 3.
#[test]
fn a_frame_range_drops_drawing_before_it_and_stops_after_it() {
    let (capture, live) = (scratch("range.glrtcap"), scratch("range.live.frames"));
    let lib = Path::new(env!("CARGO_BIN_EXE_glrt")).parent().unwrap().to_path_buf();
    let so = lib.join("libGL.so.1");
    if !so.exists() {
        std::os::unix::fs::symlink("libglrt.so", &so).unwrap();
    }
    let out = Command::new(env!("CARGO_BIN_EXE_glrt-demo"))
        .args(["--headless", "--frames", "6", "--size", "320x240"])
        .env("LD_LIBRARY_PATH", &lib)
        .env("GLRT_CAPTURE", &capture)
        .env("GLRT_CAPTURE_FRAMES", "2..4")
        .env("GLRT_FRAME_LOG", &live)
        .output()
        .expect("run glrt-demo");
    assert!(out.status.success(), "glrt-demo: {}", String::from_utf8_lossy(&out.stderr));
    let live = std::fs::read_to_string(&live).unwrap();
    let live: Vec<&str> = live.lines().collect();
    assert_eq!(live.len(), 6);
    let (replayed, _) = replay_with_capture(&capture, "range");
    let replayed: Vec<&str> = replayed.lines().collect();
    assert_eq!(replayed.len(), 4, "the capture ends after frame 3: {replayed:?}");
    // Before the range only display lists still draw (glCallList is kept: a list may set state).
    for (i, line) in replayed[..2].iter().enumerate() {
        let pillars = format!("{{\"frame\":{i},\"draws\":1,\"vertices\":96,\"clears\":0,\"hash\":");
        assert!(line.starts_with(&pillars), "frame {i}: no clear, no immediate-mode or array drawing: {line}");
    }
    assert_eq!(replayed[2..], live[2..4], "frames 2 and 3 replay as drawn live");
    let full = std::fs::metadata(fixture("demo.glrtcap")).unwrap().len();
    let ranged = std::fs::metadata(&capture).unwrap().len();
    assert!(ranged < full * 3 / 4, "2 complete frames ({ranged} bytes) against 4 ({full} bytes)");
}

fn glrt(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_glrt")).args(args).output().expect("run glrt");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn info_summarises_a_capture() {
    let (ok, out, err) = glrt(&["info", fixture("demo.glrtcap").to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(out.contains("\nframes: 4 ("), "{out}");
    assert!(out.contains("\ncontexts: 1\n"), "{out}");
    // The demo uploads 5 textures (the font and 4 scene textures) once, in frame 0.
    assert!(out.contains("\ntexture uploads: 5\n"), "{out}");
    assert_eq!(out.matches("  frame 0 glTexImage2D ").count(), 5, "{out}");
    assert!(out.lines().any(|l| l.trim_start().starts_with("4 glClear")), "one clear per frame: {out}");
    let (ok, out, _) = glrt(&["info"]);
    assert!(ok && out.contains("exports: "), "info without a file describes the build: {out}");
}

#[test]
fn dump_prints_the_call_log_of_a_capture() {
    let (ok, out, err) = glrt(&["dump", fixture("glxgears.glrtcap").to_str().unwrap()]);
    assert!(ok, "{err}");
    let frames: Vec<&str> = out.lines().filter(|l| l.contains("== end of frame")).collect();
    assert_eq!(frames.len(), 4, "{frames:?}");
    assert_eq!(frames[3], "3 == end of frame (glXSwapBuffers)");
    let capture = Capture::open(&fixture("glxgears.glrtcap")).unwrap();
    let calls = capture.records().filter(|r| matches!(r, Ok((_, Record::Call { .. })))).count();
    assert_eq!(out.lines().count(), calls + 4, "one line per call and per frame");
    assert!(out.contains("0 glEnable(cap=GL_LIGHTING)\n"), "{}", &out[..out.len().min(2000)]);
    assert!(out.lines().any(|l| l.starts_with("0 glBegin(mode=GL_QUAD_STRIP)")), "gears are compiled into lists");
    assert_eq!(out.lines().filter(|l| l.starts_with("2 glCallList(")).count(), 3, "and called each frame");
}

/// Two dumps of one capture print the same text: pointers as the captured program's
/// addresses (each a read the capture holds), `glGetString`'s results as their text.
#[test]
fn dump_prints_captured_addresses_and_the_same_text_every_time() {
    for name in ["demo", "q3"] {
        let file = fixture(&format!("{name}.glrtcap"));
        let (ok, first, err) = glrt(&["dump", file.to_str().unwrap()]);
        assert!(ok, "{err}");
        let (_, second, _) = glrt(&["dump", file.to_str().unwrap()]);
        assert!(first == second, "{name}: two dumps differ");
        let capture = Capture::open(&file).unwrap();
        let mut read_at = std::collections::BTreeSet::new();
        for record in capture.records() {
            if let Ok((_, Record::Call { reads, .. })) = record {
                read_at.extend(reads.iter().map(|(address, _)| address));
            }
        }
        // `params=0x7ffd5c0e1a3c(16 bytes, ...`: the address of bytes the call read.
        let printed: Vec<u64> = first
            .split("=0x")
            .skip(1)
            .filter_map(|rest| rest.split_once("(").filter(|(_, tail)| tail.contains(" bytes, xxh3 ")).map(|(hex, _)| hex))
            .map(|hex| u64::from_str_radix(hex, 16).unwrap())
            .collect();
        assert!(printed.len() > 10, "{name}: {} pointers with their bytes", printed.len());
        let foreign: Vec<String> = printed.iter().filter(|a| !read_at.contains(a)).map(|a| format!("{a:#x}")).collect();
        assert!(foreign.is_empty(), "{name}: addresses the capture never read: {foreign:?}");
        assert!(first.lines().any(|l| l.starts_with("0 glGetString(name=GL_VENDOR) = \"")), "{name}: glGetString's text");
    }
}

#[test]
fn replay_takes_a_frame_range_and_refuses_bad_files_and_options() {
    let file = fixture("glxgears.glrtcap");
    let (ok, out, err) = glrt(&["replay", file.to_str().unwrap(), "--frames", "0..2", "--size", "100x80"]);
    assert!(ok, "{err}");
    assert!(out.contains(", 2 frames"), "{out}");
    let not_a_dir = scratch("not-a-dir");
    std::fs::write(&not_a_dir, b"").unwrap();
    let (ok, _, err) = glrt(&["replay", file.to_str().unwrap(), "--out", not_a_dir.to_str().unwrap()]);
    assert!(!ok && err.contains(&format!("--out: {}: ", not_a_dir.display())), "{err}");
    let out = Command::new(env!("CARGO_BIN_EXE_glrt")).args(["replay", file.to_str().unwrap(), "--size", "big"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "a usage error: {err}");
    assert!(err.contains("invalid value 'big' for '--size <WxH>': expected WxH"), "{err}");
    let cut = scratch("cut.glrtcap");
    let bytes = std::fs::read(&file).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let (ok, _, err) = glrt(&["replay", cut.to_str().unwrap()]);
    assert!(!ok && err.contains("bad capture at byte "), "{err}");
}

/// `glrt replay FILE --out DIR ARGS`: the frames written to a fresh `DIR`, by file name.
fn replay_out(name: &str, args: &[&str]) -> Vec<(String, Image)> {
    let dir = scratch(&format!("{name}.out"));
    let _ = std::fs::remove_dir_all(&dir);
    let file = fixture(&format!("{name}.glrtcap"));
    let (ok, out, err) = glrt(&[&["replay", file.to_str().unwrap(), "--out", dir.to_str().unwrap()], args].concat());
    assert!(ok, "{err}");
    assert!(out.contains("wrote frames "), "{out}");
    let mut names: Vec<String> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    names.into_iter().map(|n| (n.clone(), Image::load_png(&dir.join(n)))).collect()
}

/// Pixels of `image` in the rectangle `[x0, y0, x1, y1)` that `f` accepts.
fn count(image: &Image, [x0, y0, x1, y1]: [usize; 4], f: impl Fn([u8; 3]) -> bool) -> usize {
    (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).filter(|&(x, y)| f(image.pixel(x, y))).count()
}

/// The demo's 4 frames as PNG through the Vulkan renderer (lavapipe here), at the captured
/// 320 × 240: the HUD's yellow first line, the sky blue seen through the window at the back of
/// the room, and the brick red walls are where the scene puts them.
#[test]
fn replay_out_writes_the_demo_frames_as_png() {
    let frames = replay_out("demo", &[]);
    let names: Vec<&str> = frames.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["frame-00000.png", "frame-00001.png", "frame-00002.png", "frame-00003.png"]);
    for (name, image) in &frames {
        assert_eq!((image.width, image.height), (320, 240), "{name}");
        let yellow = count(image, [0, 0, 320, 24], |[r, g, b]| r > 220 && g > 190 && b < 130);
        let sky = count(image, [120, 60, 210, 110], |[r, g, b]| b > 215 && g > 180 && r > 140 && r < b - 15);
        let brick = count(image, [0, 40, 320, 240], |[r, g, b]| r > 110 && r / 2 > g && r / 2 > b);
        eprintln!("{name}: HUD yellow {yellow}, window sky {sky}, brick {brick}");
        assert!(yellow > 800, "{name}: HUD text: {yellow} yellow pixels");
        assert!(sky > 600, "{name}: the window: {sky} sky blue pixels");
        assert!(brick > 1200, "{name}: walls: {brick} brick red pixels");
    }
}

/// `--frames 3..4 --out`: the frames before 3 run for their state only (the renderer draws
/// none of them), and frame 3 is the image of a replay that draws every frame, pixel for pixel.
#[test]
fn replay_out_draws_only_the_frames_asked_for() {
    let file = fixture("demo.glrtcap");
    let run = |tag: &str, frames: &str| {
        let dir = scratch(tag);
        let _ = std::fs::remove_dir_all(&dir);
        let out = Command::new(env!("CARGO_BIN_EXE_glrt"))
            .args(["replay", file.to_str().unwrap(), "--frames", frames, "--out", dir.to_str().unwrap()])
            .env("GLRT_LOG", "info")
            .output()
            .expect("run glrt");
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "{err}");
        (Image::load_png(&dir.join("frame-00003.png")), err)
    };
    let (every, err) = run("every-frame.out", "0..4");
    assert!(err.contains("replay: 0 frames before frame 0 ran for their state only"), "{err}");
    let (last, err) = run("frame-3.out", "3..4");
    assert!(err.contains("replay: 3 frames before frame 3 ran for their state only (0 drawn for a read-back)"), "{err}");
    assert!(last == every, "frame 3 alone differs from frame 3 of the whole replay");
    assert!(!std::fs::exists(scratch("frame-3.out").join("frame-00002.png")).unwrap());
}

/// glxgears' frames 1 and 2 (`--frames 1..3`: frame 0 is replayed, not written): the red,
/// green and blue gears where glxgears draws them on black; `--size` sets the image size.
#[test]
fn replay_out_writes_the_glxgears_frames_as_png() {
    let frames = replay_out("glxgears", &["--frames", "1..3"]);
    let names: Vec<&str> = frames.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["frame-00001.png", "frame-00002.png"]);
    for (name, image) in &frames {
        assert_eq!((image.width, image.height), (300, 300), "{name}: the captured window size");
        let red = count(image, [0, 100, 190, 290], |[r, g, b]| r > 100 && g < 60 && b < 60);
        let green = count(image, [150, 120, 260, 230], |[r, g, b]| g > 100 && r < 60 && b < 60);
        let blue = count(image, [40, 20, 150, 140], |[r, g, b]| b > 100 && r < 60 && g < 60);
        let black = count(image, [0, 0, 300, 300], |p| p.iter().all(|&c| c < 8));
        eprintln!("{name}: red {red}, green {green}, blue {blue}, black {black}");
        assert!(red > 12000 && green > 3000 && blue > 2500, "{name}: gears red {red}, green {green}, blue {blue}");
        assert!(black > 50000, "{name}: background: {black} black pixels");
    }
    let small = replay_out("glxgears", &["--frames", "0..1", "--size", "200x150"]);
    assert_eq!(small.len(), 1);
    assert_eq!((small[0].1.width, small[0].1.height), (200, 150), "--size");
}

/// The demo replayed on another device (`scripts/device_replay.sh` on the GPU machine; the
/// directory it wrote in `GLRT_DEVICE_FRAMES`) matches the replay here on lavapipe, frame by
/// frame, with the metric and tolerance of `tests/end_to_end/raster_vs_mesa.rs` (per channel
/// within 24, one-pixel edge shifts forgiven, at most 1% of the pixels unmatched). Run by hand:
/// `GLRT_DEVICE_FRAMES=DIR cargo test --test end_to_end -- --ignored device_frames`.
#[test]
#[ignore = "needs the frames of a replay on another device in GLRT_DEVICE_FRAMES"]
fn device_frames_match_lavapipe() {
    let dir = PathBuf::from(std::env::var_os("GLRT_DEVICE_FRAMES").expect("GLRT_DEVICE_FRAMES: the directory of the device's frames"));
    let here = replay_out("demo", &[]);
    assert_eq!(here.len(), 4);
    for (name, lavapipe) in &here {
        let device = Image::load_png(&dir.join(name));
        let d = images::compare(&device, lavapipe, 24);
        eprintln!("{name}: {:.3}% mismatched, {:.3}% identical, mean |difference| {:.4}", d.mismatched * 100.0, d.identical * 100.0, d.mean_abs);
        assert!(d.mismatched <= 0.01, "{name}: {:.2}% of the pixels differ by more than 24", d.mismatched * 100.0);
    }
}
