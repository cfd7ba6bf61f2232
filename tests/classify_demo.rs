//! Hash tracking on the demo (`translate::classify`): 300 frames of `glrt-demo --headless`
//! are captured, replayed in this process and classified; each object of the scene
//! (demo/scene/) must get its class, every traced instance its id for good, and only the
//! first frames may upload static geometry while the camera turns. `glrt replay --stats`,
//! `glrt info` and the call log are checked on the 4-frame fixture.
//!
//! The demo's draws, in order (see tests/end_to_end/demo.rs for how batches merge): sky, floor,
//! ceiling and walls, pillars (display list), door, animated mesh (`glDrawElements`), glass, HUD bar.
//! Needs `cargo build` first (the demo runs through `target/<profile>/libglrt.so`).

mod programs;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, OnceLock};

use glam::Mat4;
use glrt::frame::FrameSink;
use glrt::frame::class::{DrawClass, FrameStats, Match, View};
use glrt::frame::{DrawSource, Frame};
use glrt::replay::{self, reader::Capture};
use parking_lot::Mutex;

/// Frames captured.
const FRAMES: usize = 300;

/// What the tests need of a draw.
#[derive(Clone, Debug)]
struct DrawSummary {
    class: DrawClass,
    source: DrawSource,
    id: Option<u64>,
    matched: Option<Match>,
    triangles: usize,
    modelview: Mat4,
}

/// What the tests need of a frame (frames themselves are dropped as they come).
#[derive(Clone, Debug)]
struct FrameSummary {
    draws: Vec<DrawSummary>,
    view: Option<View>,
    stats: FrameStats,
}

#[derive(Clone, Default)]
struct Summaries(Arc<Mutex<Vec<FrameSummary>>>);

impl FrameSink for Summaries {
    fn present(&mut self, frame: Frame) {
        let draws = frame
            .draws
            .iter()
            .map(|d| DrawSummary {
                class: d.class,
                source: d.source,
                id: d.instance.map(|i| i.id),
                matched: d.instance.map(|i| i.matched),
                triangles: d.indices.len() / 3,
                modelview: d.modelview,
            })
            .collect();
        self.0.lock().push(FrameSummary { draws, view: frame.view, stats: frame.stats });
    }
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(name)
}

/// The 300 frames, captured and replayed once for every test of this file.
fn frames() -> &'static [FrameSummary] {
    static FRAMES_SEEN: OnceLock<Vec<FrameSummary>> = OnceLock::new();
    FRAMES_SEEN.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("classify_demo");
        std::fs::create_dir_all(&dir).unwrap();
        let capture = dir.join("demo300.glrtcap");
        let out = Command::new(env!("CARGO_BIN_EXE_glrt-demo"))
            .args(["--headless", "--frames", &FRAMES.to_string(), "--size", "160x120"])
            .env("LD_LIBRARY_PATH", programs::lib_dir())
            .env("GLRT_CAPTURE", &capture)
            // Any mode but `raster` draws nothing: only the capture is wanted.
            .env("GLRT_MODE", "none")
            .output()
            .expect("run glrt-demo");
        assert!(out.status.success(), "glrt-demo: {}", String::from_utf8_lossy(&out.stderr));
        let capture = Capture::open(&capture).expect("capture");
        let sink = Summaries::default();
        let keep = sink.clone();
        let options = replay::Options {
            sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(keep.clone())))),
            ..Default::default()
        };
        let outcome = replay::run(&capture, &options).expect("replay");
        assert_eq!(outcome.frames, FRAMES as u64);
        let frames = sink.0.lock().clone();
        assert_eq!(frames.len(), FRAMES);
        frames
    })
}

/// The classes of the demo's 8 draws from frame 2 on (frame 0 has not seen anything move).
const CLASSES: [DrawClass; 8] = [
    DrawClass::Sky,         // sky box, drawn first without depth writes
    DrawClass::Static,      // floor
    DrawClass::Static,      // ceiling and walls
    DrawClass::Static,      // pillars (display list)
    DrawClass::Movable,     // door, swinging
    DrawClass::Dynamic,     // animated mesh, new vertices every frame
    DrawClass::Translucent, // glass, blended
    DrawClass::Overlay,     // HUD bar, orthographic
];

#[test]
fn each_object_of_the_demo_gets_its_class() {
    let frames = frames();
    for (n, f) in frames.iter().enumerate() {
        let classes: Vec<DrawClass> = f.draws.iter().map(|d| d.class).collect();
        let sources: Vec<DrawSource> = f.draws.iter().map(|d| d.source).collect();
        assert_eq!(sources[3], DrawSource::List(1), "frame {n}: the pillars are the 4th draw: {sources:?}");
        assert_eq!(sources[5], DrawSource::Arrays, "frame {n}: the mesh is the 6th draw");
        match n {
            0 => assert_eq!(classes[..4], CLASSES[..4], "frame 0"),
            1 => assert_eq!(classes[5], DrawClass::Dynamic, "frame 1: the mesh changed"),
            _ => assert_eq!(classes, CLASSES, "frame {n}"),
        }
        assert_eq!(f.stats.classes.get(DrawClass::Sky), 1);
        assert_eq!(f.stats.triangles.get(DrawClass::Dynamic), if n == 0 { 0 } else { f.draws[5].triangles as u64 });
    }
    // The door is matched exactly (same geometry) and its model changes: movable while it
    // swings, and it stays movable.
    assert!(frames[2..].iter().all(|f| f.draws[4].matched == Some(Match::Exact)));
    assert!(frames[2..].iter().all(|f| f.draws[5].matched == Some(Match::Slot)));
}

#[test]
fn traced_instances_keep_their_ids_for_300_frames() {
    let frames = frames();
    let ids = |f: &FrameSummary| f.draws.iter().map(|d| d.id).collect::<Vec<_>>();
    let first = ids(&frames[0]);
    assert_eq!(first.iter().filter(|i| i.is_some()).count(), 5, "room (2), pillars, door, mesh are traced: {first:?}");
    for (n, f) in frames.iter().enumerate() {
        assert_eq!(ids(f), first, "frame {n}: an id changed");
        let mut traced: Vec<u64> = f.draws.iter().filter_map(|d| d.id).collect();
        let count = traced.len();
        traced.sort();
        traced.dedup();
        assert_eq!(traced.len(), count, "frame {n}: two instances share an id");
        if n > 0 {
            assert_eq!((f.stats.matches_found, f.stats.matches_lost), (5, 0), "frame {n}");
        }
    }
}

#[test]
fn no_static_geometry_is_uploaded_while_only_the_camera_moves() {
    let frames = frames();
    let uploads: Vec<u64> = frames.iter().map(|f| f.stats.static_upload_bytes).collect();
    assert!(uploads[..2].iter().sum::<u64>() > 0, "the static world is built in the first frames: {:?}", &uploads[..3]);
    assert!(uploads[2..].iter().all(|&b| b == 0), "static uploads after frame 2: {:?}", &uploads[2..12]);
    // The camera does turn (the demo looks from side to side): the room's modelview changes.
    let turned = frames.windows(2).filter(|w| w[0].draws[1].modelview != w[1].draws[1].modelview).count();
    assert!(turned > FRAMES / 2, "the camera moved in {turned} frames");
    // The room, pillars and floor are held by the static world: 2012 triangles.
    let room: usize = frames[2].draws.iter().filter(|d| d.class == DrawClass::Static).map(|d| d.triangles).sum();
    assert_eq!(room, 2012);
    assert!(frames[2..].iter().all(|f| f.stats.static_world_triangles >= room && !f.stats.camera_cut));
}

#[test]
fn the_camera_is_recovered_from_the_room() {
    for (n, f) in frames().iter().enumerate() {
        let view = f.view.unwrap_or_else(|| panic!("frame {n}: no view"));
        // The world frame is the room's object space: the view is the room's modelview.
        assert!(view.view.abs_diff_eq(f.draws[2].modelview, 1e-5), "frame {n}: {:?}", view.view);
        assert!(view.perspective);
        assert!((view.fov_y.to_degrees() - 70.0).abs() < 0.01, "fov {}", view.fov_y.to_degrees());
        assert!((view.aspect - 160.0 / 120.0).abs() < 1e-4 && (view.near - 0.1).abs() < 1e-4, "{view:?}");
        assert!((view.far - 100.0).abs() < 0.1, "far {}", view.far);
    }
}

fn glrt(args: &[&str], env: &[(&str, &str)]) -> String {
    glrt_with_stderr(args, env).0
}

/// Standard output and standard error of a successful `glrt` run.
fn glrt_with_stderr(args: &[&str], env: &[(&str, &str)]) -> (String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_glrt")).args(args).envs(env.iter().copied()).output().expect("run glrt");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "glrt {args:?}: {err}");
    (String::from_utf8_lossy(&out.stdout).into_owned(), err)
}

/// The `classes` object of the last JSON line of `glrt replay --stats`.
fn last_classes(out: &str) -> String {
    let last = out.lines().rfind(|l| l.starts_with('{')).expect("a JSON line");
    let start = last.find("\"classes\":").unwrap();
    last[start..start + last[start..].find('}').unwrap() + 1].to_owned()
}

/// The value of `"key":` in a JSON line (numbers and booleans).
fn field<'a>(line: &'a str, key: &str) -> &'a str {
    let start = line.find(&format!("\"{key}\":")).unwrap_or_else(|| panic!("{key} missing in {line}")) + key.len() + 3;
    let end = line[start..].find([',', '}']).map_or(line.len(), |e| start + e);
    &line[start..end]
}

#[test]
fn replay_stats_prints_one_json_line_per_frame() {
    let out = glrt(&["replay", fixture("demo.glrtcap").to_str().unwrap(), "--stats"], &[]);
    let lines: Vec<&str> = out.lines().filter(|l| l.starts_with('{')).collect();
    assert_eq!(lines.len(), 4, "{out}");
    for (n, line) in lines.iter().enumerate() {
        assert_eq!(field(line, "frame"), n.to_string());
        for key in ["static_upload_bytes", "static_chunks_new", "static_chunks_reused", "static_world_triangles", "matches_found", "matches_lost", "camera_cut"] {
            field(line, key);
        }
    }
    let last = lines[3];
    let classes = &last[last.find("\"classes\":").unwrap()..];
    assert!(classes.starts_with("\"classes\":{\"static\":3,\"movable\":1,\"dynamic\":1,\"translucent\":1,\"overlay\":1,\"sky\":1,\"layer\":0,\"light\":0}"), "{last}");
    assert_eq!((field(last, "static_upload_bytes"), field(last, "camera_cut"), field(last, "matches_found")), ("0", "false", "5"));
}

/// `0x…` hashes after `marker` on each line of `text` that contains it.
fn hashes_after(text: &str, marker: &str) -> Vec<String> {
    let mut all: Vec<String> = text
        .lines()
        .filter_map(|l| l.split_once(marker))
        .flat_map(|(_, rest)| rest.split_whitespace().filter(|w| w.starts_with("0x")).map(str::to_owned).collect::<Vec<_>>())
        .collect();
    all.sort();
    all.dedup();
    all
}

#[test]
fn texture_hashes_are_printed_and_tag_textures() {
    let capture = fixture("demo.glrtcap");
    let info = glrt(&["info", capture.to_str().unwrap()], &[]);
    assert!(info.contains("textures drawn with (level-0 hash, the glrt.toml names): 5\n"), "{info}");
    let listed = hashes_after(&info, "  texture ");
    assert_eq!(listed.len(), 5, "5 distinct scene textures: {info}");
    // The call log prints the same hashes.
    let log = glrt(&["dump", capture.to_str().unwrap()], &[("GLRT_MODE", "none")]);
    assert_eq!(hashes_after(&log, " # texture "), listed, "call log and info agree");
    // Tagging the floor's texture `ui` (through GLRT_UI) makes the floor an overlay.
    let floor = info.lines().find(|l| l.starts_with("  texture ")).and_then(|l| l.split_whitespace().nth(2)).unwrap();
    let out = glrt(&["replay", capture.to_str().unwrap(), "--stats"], &[("GLRT_UI", floor)]);
    let last = out.lines().rfind(|l| l.starts_with('{')).unwrap();
    assert!(last.contains("\"overlay\":2"), "{floor}: {last}");
}

#[test]
fn glrt_toml_tags_textures_and_reports_problems_with_file_and_line() {
    let capture = fixture("demo.glrtcap");
    let info = glrt(&["info", capture.to_str().unwrap()], &[]);
    let floor = info.lines().find(|l| l.starts_with("  texture ")).and_then(|l| l.split_whitespace().nth(2)).unwrap();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("classify_demo");
    std::fs::create_dir_all(&dir).unwrap();
    let config = dir.join("glrt.toml");
    std::fs::write(&config, format!("# tags\nsky = [\"{floor}\"]\nshadows = true\n")).unwrap();
    let path = config.to_str().unwrap();
    let args = ["replay", capture.to_str().unwrap(), "--stats"];
    let (out, err) = glrt_with_stderr(&args, &[("GLRT_CONFIG", path)]);
    assert!(last_classes(&out).contains("\"sky\":2"), "the tagged texture's draw is sky: {}", last_classes(&out));
    assert_eq!(err.matches("unknown key 'shadows'").count(), 1, "reported once: {err}");
    assert!(err.contains(&format!("{path}:3: unknown key 'shadows'")), "{err}");
    // A bad file is named with its line and ignored: the classes are the heuristics'.
    std::fs::write(&config, "ui = [\"0x10\"]\ndynamic = [\"0xnothex\"]\n").unwrap();
    let (out, err) = glrt_with_stderr(&args, &[("GLRT_CONFIG", path)]);
    assert!(err.contains(&format!("{path}:2: dynamic: ")), "{err}");
    assert_eq!(last_classes(&out), "\"classes\":{\"static\":3,\"movable\":1,\"dynamic\":1,\"translucent\":1,\"overlay\":1,\"sky\":1,\"layer\":0,\"light\":0}");
}
