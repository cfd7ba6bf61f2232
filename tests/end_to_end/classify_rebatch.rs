//! Hash tracking against a Quake-3-like program (issue 5): `glrt-demo --rebatch` re-batches its
//! world surfaces per texture into client arrays every frame, draws only those in the view
//! frustum, and turns the camera around in `TURN` frames. Captured through glrt's libGL and
//! replayed with `glrt replay FILE --stats`, the persistent static world must hold every
//! surface once after one turn (no duplicates), upload nothing afterwards, and keep the
//! surfaces the program no longer draws (behind the camera). Run `cargo build` first: the
//! demo runs through `target/<profile>/libglrt.so`. The demo itself is checked against the
//! system's libGL (Mesa, under Xvfb): the same frame, pixel for pixel within a tolerance.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use images::{Image, compare};
use programs::{lib_dir, run_for};

use crate::images;
use crate::programs;
use crate::x11::Xvfb;

/// Frames of one turn of the camera (`demo/rebatch.rs`, `TURN_FRAMES`).
const TURN: u64 = 120;
/// Frames captured: one turn and a quarter.
const FRAMES: u64 = 150;
/// The keys of the `classes` and `triangles` objects.
const CLASSES: [&str; 6] = ["static", "movable", "dynamic", "translucent", "overlay", "sky"];

fn scratch(name: &str) -> PathBuf {
    programs::scratch("classify_rebatch", name)
}

/// The number after `"key":` in a JSON object's text (the first at any depth).
fn number(json: &str, key: &str) -> Option<u64> {
    let at = json.find(&format!("\"{key}\":"))? + key.len() + 3;
    let digits: String = json[at..].trim_start().chars().take_while(char::is_ascii_digit).collect();
    digits.parse().ok()
}

/// The text of the object after `"key":`, braces included.
fn object<'a>(json: &'a str, key: &str) -> Option<&'a str> {
    let start = json.find(&format!("\"{key}\":"))? + key.len() + 3;
    let rest = json[start..].trim_start();
    let mut depth = 0;
    for (i, c) in rest.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(&rest[..=i]);
                }
            }
            _ if depth == 0 => return None,
            _ => {}
        }
    }
    None
}

/// What the demo printed: total triangles, and (triangles, draws) drawn per frame.
fn demo_counts(stdout: &str) -> (u64, Vec<(u64, u64)>) {
    let total = stdout
        .lines()
        .find_map(|l| l.strip_prefix("rebatch: "))
        .and_then(|l| l.split(", ").nth(1)?.strip_suffix(" triangles")?.parse().ok())
        .unwrap_or_else(|| panic!("no 'rebatch: S surfaces, T triangles' line:\n{stdout}"));
    let frames = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("rebatch frame "))
        .map(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            // "F: S surfaces, T triangles, D draws"
            (words[3].parse().expect("triangles"), words[5].parse().expect("draws"))
        })
        .collect();
    (total, frames)
}

#[test]
fn a_rebatched_world_is_kept_whole_once_and_uploaded_once() {
    let lib = lib_dir();
    let capture = scratch("rebatch.glrtcap");
    let out = Command::new(env!("CARGO_BIN_EXE_glrt-demo"))
        .args(["--rebatch", "--verbose", "--headless", "--size", "160x120", "--frames"])
        .arg(FRAMES.to_string())
        .env("LD_LIBRARY_PATH", &lib)
        .env("GLRT_CAPTURE", &capture)
        .output()
        .expect("run glrt-demo");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "glrt-demo: {}", String::from_utf8_lossy(&out.stderr));
    let (total, drawn) = demo_counts(&stdout);
    assert_eq!(drawn.len() as u64, FRAMES);

    let out = Command::new(env!("CARGO_BIN_EXE_glrt"))
        .arg("replay")
        .arg(&capture)
        .arg("--stats")
        .output()
        .expect("run glrt replay");
    assert!(out.status.success(), "glrt replay --stats: {}", String::from_utf8_lossy(&out.stderr));
    let stats = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = stats.lines().filter(|l| l.starts_with('{')).collect();
    assert_eq!(lines.len() as u64, FRAMES, "one JSON object per frame:\n{stats}");

    let mut uploaded = 0;
    for line in lines {
        let frame = number(line, "frame").unwrap_or_else(|| panic!("no frame: {line}"));
        let upload = number(line, "static_upload_bytes").unwrap_or_else(|| panic!("no static_upload_bytes: {line}"));
        let world = number(line, "static_world_triangles").unwrap_or_else(|| panic!("no static_world_triangles: {line}"));
        let triangles = object(line, "triangles").unwrap_or_else(|| panic!("no triangles object: {line}"));
        let classes = object(line, "classes").unwrap_or_else(|| panic!("no classes object: {line}"));
        let (drawn_triangles, draws) = drawn[frame as usize];
        uploaded += upload;
        assert!(world <= total, "frame {frame}: {world} static triangles, more than the {total} of the world");
        assert!(drawn_triangles < total, "frame {frame}: the program culls ({drawn_triangles} of {total} drawn)");
        if frame < TURN {
            continue;
        }
        // After one turn: every surface once, kept while the program draws only part of it.
        assert_eq!(world, total, "frame {frame}: the static world holds every surface once");
        assert_eq!(upload, 0, "frame {frame}: nothing new to upload while only the camera turns");
        let class = |object: &str, name: &str| number(object, name).unwrap_or_else(|| panic!("no {name} in {object}: {line}"));
        let per_class = |object: &str| CLASSES.iter().map(|c| class(object, c)).sum::<u64>();
        // glrt merges consecutive draw calls of one state into one draw.
        let instances = per_class(classes);
        assert!(instances >= 1 && instances <= draws, "frame {frame}: {instances} classified draws for {draws} draw calls: {line}");
        assert_eq!(per_class(triangles), drawn_triangles, "frame {frame}: every drawn triangle counted once: {line}");
    }
    // Positions (12 bytes per vertex) uploaded at least once; with texture coordinates
    // (8 bytes) and chunk merges, less than twice the whole world.
    let (positions, everything) = (total * 3 * 12, total * 3 * 20);
    assert!(uploaded >= positions && uploaded < 2 * everything, "{uploaded} bytes uploaded for {total} triangles");
}

/// Frame 40 of `glrt-demo --rebatch` (looking down at the checker floor, a pillar at the top)
/// through glrt headless and on Mesa under Xvfb: the same image.
#[test]
fn the_rebatch_demo_draws_the_same_frame_through_glrt_and_on_mesa() {
    let (glrt_shot, mesa_shot) = (scratch("rebatch-glrt.png"), scratch("rebatch-mesa.png"));
    let args = |shot: &Path| {
        let shot = shot.to_string_lossy().into_owned();
        ["--rebatch", "--first-frame", "40", "--frames", "1", "--size", "320x240", "--screenshot"].map(String::from).into_iter().chain([shot]).collect::<Vec<_>>()
    };
    let mut glrt = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    glrt.args(args(&glrt_shot)).arg("--headless").env("LD_LIBRARY_PATH", lib_dir());
    let (out, stopped) = run_for(glrt, Duration::from_secs(120));
    assert!(!stopped && out.status.success(), "through glrt: {}", String::from_utf8_lossy(&out.stderr));
    let x = Xvfb::with_screen("1024x768x24");
    let mut mesa = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    mesa.args(args(&mesa_shot)).env_remove("LD_LIBRARY_PATH").env("DISPLAY", &x.display);
    let (out, stopped) = run_for(mesa, Duration::from_secs(120));
    assert!(!stopped && out.status.success(), "on Mesa: {}", String::from_utf8_lossy(&out.stderr));
    let (a, b) = (Image::load_png(&glrt_shot), Image::load_png(&mesa_shot));
    let d = compare(&a, &b, 24);
    assert!(d.mismatched < 0.01 && d.mean_abs < 4.0, "glrt against Mesa: {d:?}");
    // Not a blank frame: light and dark checker squares each cover a fifth of it or more.
    let count = |f: &dyn Fn([u8; 3]) -> bool| a.rgb.chunks_exact(3).filter(|p| f([p[0], p[1], p[2]])).count();
    let light = count(&|[r, g, b]| r > 150 && g > 150 && b > 140);
    let dark = count(&|[r, g, b]| r < 90 && g < 90 && b < 100);
    assert!(light > 320 * 240 / 5 && dark > 320 * 240 / 5, "{light} light and {dark} dark pixels");
}

#[test]
fn the_json_helpers_read_nested_keys() {
    let line = r#"{"frame":7,"classes":{"static":3,"sky":1},"triangles":{"static":120,"sky":2},"static_upload_bytes":0}"#;
    assert_eq!(number(line, "frame"), Some(7));
    assert_eq!(number(line, "static_upload_bytes"), Some(0));
    assert_eq!(object(line, "triangles").and_then(|t| number(t, "static")), Some(120));
    assert_eq!(object(line, "classes").and_then(|t| number(t, "static")), Some(3));
    assert_eq!(object(line, "frame"), None);
    let (total, frames) = demo_counts("rebatch: 10 surfaces, 80 triangles\nrebatch frame 0: 3 surfaces, 24 triangles, 2 draws\n");
    assert_eq!((total, frames), (80, vec![(24, 2)]));
}
