//! End-to-end runs through glrt's `libGL.so.1` (`target/<profile>/libGL.so.1`, a symlink to
//! `libglrt.so` made here when missing), checked with glrt's per-frame log
//! (`GLRT_FRAME_LOG=<file>`, one JSON object per presented frame:
//! `{"frame":N,"draws":D,"vertices":V,"clears":C,"hash":"H"}`):
//! - `glrt-demo --headless` (glrt's headless context API);
//! - `glrt-demo` in an X11 window with GLX, under Xvfb;
//! - Mesa's `glxgears` under Xvfb.
//!
//! Two more check the demo itself against the system's (Mesa's) libGL: it runs under Xvfb,
//! and `--headless` refuses a libGL without glrt's headless API.
//!
//! The glrt runs need the whole library (the frame log and GLX come from other modules); they pass
//! once every branch is merged. The Xvfb tests fail with a clear message when Xvfb (or
//! glxgears) is missing: `bash scripts/setup.sh` installs them.

use crate::images;
use crate::programs;
use crate::x11::Xvfb;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use images::Image;
use programs::{lib_dir, run_for};

/// Frames the demo runs in each test.
const DEMO_FRAMES: usize = 300;

/// Frames glxgears runs (rendered on lavapipe in a debug build: about 2 per second on a loaded
/// 2-core machine).
const GEARS_FRAMES: usize = 30;

/// Draws per frame of glrt-demo, from its scene (demo/scene/): sky 1, room 3 (floor,
/// ceiling, walls), pillars 4 (one `glBegin`/`glEnd` per pillar in the display list), door 1,
/// animated mesh 1 (`glDrawElements`), glass 1 (both panes in one `glBegin`), HUD bar 1 = 12
/// batches. glrt merges consecutive batches whose state, matrices, textures and source are
/// equal: the ceiling with the walls (same brick texture) and the four pillars, giving 8.
/// The HUD's `glBitmap` text is a pixel operation, not a draw.
pub(crate) const DEMO_DRAWS: (u64, u64) = (8, 12);

/// Vertices per frame of glrt-demo. Quads submitted: room 982 (floor 16×20, ceiling 16×20,
/// back wall 16×5 less an 18-cell window and doorway, front 16×5, sides 20×5 each), sky 10,
/// pillars 4×6, door 6, glass 2, HUD bar 1 = 1025 quads; the mesh has 425 vertices and 2304
/// indices. Fewest: quads kept as 4 vertices and the mesh counted by its vertices
/// (1025×4 + 425 = 4525, what glrt reports). Most: quads as two separate triangles and the
/// mesh by its indices (1025×6 + 2304 = 8454).
const DEMO_VERTICES: (u64, u64) = (4525, 8454);

/// glxgears draws three gears from display lists; each list has 6 `glBegin`/`glEnd` blocks
/// (front face, front teeth, back face, back teeth, outer faces, inner cylinder), 18 in all.
/// glrt merges consecutive blocks of one state (the five flat-shaded blocks of a gear, then
/// its smooth-shaded cylinder: 6 draws), never across gears (each has its own modelview and
/// material): 3 ..= 18.
pub(crate) const GEARS_DRAWS: (u64, u64) = (3, 18);

/// glxgears' vertices per frame: a gear of t teeth submits 26t + 8 vertices (quad strips of
/// 4t+2, 4t+2, 8t+2, 2t+2 and quads of 4t, 4t), and the gears have 20, 10 and 10 teeth: 1064.
/// As triangles the same gear is 66t vertices: 2640.
const GEARS_VERTICES: (u64, u64) = (1064, 2640);

/// One line of the frame log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FrameRecord {
    pub(crate) frame: u64,
    pub(crate) draws: u64,
    pub(crate) vertices: u64,
    pub(crate) clears: u64,
}

/// The unsigned integer value of `"key":` in a flat JSON object.
fn json_u64(line: &str, key: &str) -> Option<u64> {
    let pattern = format!("\"{key}\"");
    let rest = &line[line.find(&pattern)? + pattern.len()..];
    let rest = rest.trim_start().strip_prefix(':')?.trim_start();
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    digits.parse().ok()
}

pub(crate) fn read_frame_log(path: &Path) -> Vec<FrameRecord> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("frame log {} not written: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let get =
                |k| json_u64(l, k).unwrap_or_else(|| panic!("no \"{k}\" in frame log line {l}"));
            FrameRecord {
                frame: get("frame"),
                draws: get("draws"),
                vertices: get("vertices"),
                clears: get("clears"),
            }
        })
        .collect()
}

fn temp_log(name: &str) -> PathBuf {
    let path = std::env::temp_dir().join(format!("glrt-{name}-{}.jsonl", std::process::id()));
    let _ = std::fs::remove_file(&path);
    path
}

/// A command that loads glrt's libGL.so.1 and writes the frame log to `log`.
fn through_glrt(program: &str, log: &Path) -> Command {
    let mut cmd = Command::new(program);
    cmd.env("LD_LIBRARY_PATH", lib_dir()).env("GLRT_FRAME_LOG", log);
    cmd
}

fn assert_within(what: &str, value: u64, (lo, hi): (u64, u64), frame: u64) {
    assert!((lo..=hi).contains(&value), "frame {frame}: {what} = {value}, expected {lo}..={hi}");
}

/// Checks the demo's frame log: one line per frame, numbered from 0, one clear each, and
/// the same draw and vertex counts every frame (the scene's calls do not depend on time)
/// within the bounds derived from the scene.
fn check_demo_log(frames: &[FrameRecord]) {
    assert_eq!(frames.len(), DEMO_FRAMES, "one log line per presented frame");
    for (i, f) in frames.iter().enumerate() {
        assert_eq!(f.frame, i as u64, "frames are numbered from 0 in order");
        assert_eq!(f.clears, 1, "frame {i}: the demo clears colour and depth once");
        assert_within("draws", f.draws, DEMO_DRAWS, f.frame);
        assert_within("vertices", f.vertices, DEMO_VERTICES, f.frame);
        assert_eq!(
            (f.draws, f.vertices),
            (frames[0].draws, frames[0].vertices),
            "frame {i} differs from frame 0"
        );
    }
}

fn demo_command(log: &Path, extra: &[&str]) -> Command {
    let mut cmd = through_glrt(env!("CARGO_BIN_EXE_glrt-demo"), log);
    cmd.args(["--frames", &DEMO_FRAMES.to_string(), "--size", "320x240"]).args(extra);
    cmd
}

fn assert_demo_ran(out: &Output, stopped: bool) {
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stopped, "glrt-demo did not finish in time\n{stdout}\n{stderr}");
    assert!(out.status.success(), "glrt-demo failed: {:?}\n{stdout}\n{stderr}", out.status);
    assert!(stdout.contains(&format!("frames: {DEMO_FRAMES} ")), "summary line missing:\n{stdout}");
}

#[test]
fn json_fields_are_read() {
    let line = r#"{"frame":12, "draws": 7,"vertices":4525,"clears":1}"#;
    assert_eq!(json_u64(line, "frame"), Some(12));
    assert_eq!(json_u64(line, "draws"), Some(7));
    assert_eq!(json_u64(line, "vertices"), Some(4525));
    assert_eq!(json_u64(line, "missing"), None);
}

#[test]
fn headless_demo_draws_the_scene_every_frame() {
    let log = temp_log("demo-headless");
    let (out, stopped) = run_for(demo_command(&log, &["--headless"]), Duration::from_secs(300));
    assert_demo_ran(&out, stopped);
    check_demo_log(&read_frame_log(&log));
}

#[test]
fn x11_demo_draws_the_scene_every_frame() {
    let x = Xvfb::with_screen("1024x768x24");
    let log = temp_log("demo-x11");
    let mut cmd = demo_command(&log, &[]);
    cmd.env("DISPLAY", &x.display);
    let (out, stopped) = run_for(cmd, Duration::from_secs(300));
    assert_demo_ran(&out, stopped);
    check_demo_log(&read_frame_log(&log));
}

#[test]
fn glxgears_draws_three_gears_every_frame() {
    assert!(
        Path::new("/usr/bin/glxgears").exists(),
        "glxgears missing: run `bash scripts/setup.sh` (mesa-utils)"
    );
    let x = Xvfb::with_screen("1024x768x24");
    let log = temp_log("glxgears");
    let mut child = through_glrt("/usr/bin/glxgears", &log)
        .env("DISPLAY", &x.display)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn glxgears");
    // glxgears has no frame-count flag: wait for GEARS_FRAMES frames, then press Escape, on which it
    // quits with status 0.
    let start = Instant::now();
    let logged = || std::fs::read_to_string(&log).map_or(0, |t| t.lines().count());
    while logged() < GEARS_FRAMES && start.elapsed() < Duration::from_secs(240) && child.try_wait().unwrap().is_none() {
        std::thread::sleep(Duration::from_millis(50));
    }
    let pressed = press_escape(&x.display, "glxgears");
    let quit = Instant::now();
    while child.try_wait().unwrap().is_none() && quit.elapsed() < Duration::from_secs(10) {
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let out = child.wait_with_output().expect("glxgears output");
    assert!(pressed, "no glxgears window found");
    assert!(out.status.success(), "glxgears: {:?}\n{}", out.status, String::from_utf8_lossy(&out.stderr));
    let frames = read_frame_log(&log);
    assert!(frames.len() >= GEARS_FRAMES, "only {} frames", frames.len());
    for f in &frames {
        assert_eq!(f.clears, 1, "frame {}: glxgears clears once", f.frame);
        assert_within("draws", f.draws, GEARS_DRAWS, f.frame);
        assert_within("vertices", f.vertices, GEARS_VERTICES, f.frame);
        assert_eq!(
            (f.draws, f.vertices),
            (frames[0].draws, frames[0].vertices),
            "frame {} differs",
            f.frame
        );
    }
}

/// Sends an Escape key press to the top-level windows called `name` on `display`; false when
/// there is none.
fn press_escape(display: &str, name: &str) -> bool {
    use std::ffi::{CStr, CString};
    use x11_dl::{keysym, xlib};
    let x = xlib::Xlib::open().expect("libX11");
    let display = CString::new(display).unwrap();
    // Safety: plain Xlib calls on a display this function opens and closes; every pointer
    // Xlib returns is checked and freed with XFree.
    unsafe {
        let dpy = (x.XOpenDisplay)(display.as_ptr());
        assert!(!dpy.is_null(), "cannot open the Xvfb display");
        let root = (x.XDefaultRootWindow)(dpy);
        let (mut root_ret, mut parent, mut children, mut count) = (0, 0, std::ptr::null_mut(), 0u32);
        (x.XQueryTree)(dpy, root, &mut root_ret, &mut parent, &mut children, &mut count);
        let keycode = (x.XKeysymToKeycode)(dpy, u64::from(keysym::XK_Escape));
        let mut sent = false;
        for i in 0..count as usize {
            let window = *children.add(i);
            let mut title = std::ptr::null_mut();
            if (x.XFetchName)(dpy, window, &mut title) == 0 || title.is_null() {
                continue;
            }
            if CStr::from_ptr(title).to_bytes() == name.as_bytes() {
                let mut event: xlib::XEvent = std::mem::zeroed();
                event.key = xlib::XKeyEvent {
                    type_: xlib::KeyPress,
                    display: dpy,
                    window,
                    root,
                    same_screen: xlib::True,
                    keycode: u32::from(keycode),
                    ..std::mem::zeroed()
                };
                (x.XSendEvent)(dpy, window, xlib::True, xlib::KeyPressMask, &mut event);
                sent = true;
            }
            (x.XFree)(title.cast());
        }
        if !children.is_null() {
            (x.XFree)(children.cast());
        }
        (x.XFlush)(dpy);
        (x.XCloseDisplay)(dpy);
        sent
    }
}

/// The system libGL (Mesa through glvnd), whatever `LD_LIBRARY_PATH` cargo set up.
fn with_system_libgl(extra: &[&str]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    cmd.env_remove("LD_LIBRARY_PATH").args(extra);
    cmd
}

/// Runs the demo on the system's libGL (Mesa) in a window under Xvfb, 30 frames from frame
/// 206 (the door is then open), and checks the last frame read back with `--screenshot`:
/// the scene's colours are all there.
#[test]
fn demo_runs_on_the_system_libgl_under_xvfb() {
    let x = Xvfb::with_screen("1024x768x24");
    let shot = std::env::temp_dir().join(format!("glrt-demo-mesa-{}.png", std::process::id()));
    let shot_arg = shot.to_string_lossy().into_owned();
    let args =
        ["--frames", "30", "--first-frame", "206", "--size", "320x240", "--screenshot", &shot_arg];
    let mut cmd = with_system_libgl(&args);
    cmd.env("DISPLAY", &x.display);
    let (out, stopped) = run_for(cmd, Duration::from_secs(120));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        !stopped && out.status.success(),
        "{:?}\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("frames: 30 "), "summary line missing:\n{stdout}");

    let Image { width: w, height: h, rgb } = Image::load_png(&shot);
    assert_eq!((w, h), (320, 240));
    let pixels: Vec<[i32; 3]> =
        rgb.chunks_exact(3).map(|p| [p[0] as i32, p[1] as i32, p[2] as i32]).collect();
    let count = |rows: std::ops::Range<usize>, f: &dyn Fn([i32; 3]) -> bool| {
        rows.flat_map(|y| (0..w).map(move |x| y * w + x)).filter(|&i| f(pixels[i])).count()
    };
    // HUD text (yellow, 1.0 0.9 0.3) in the bar over the top 52 pixels.
    let yellow = count(0..52, &|[r, g, b]| r > 180 && g > 160 && b < 120);
    assert!(yellow > 50, "HUD text: {yellow} yellow pixels in the top bar");
    // Brick walls: clearly red.
    let brick = count(52..h, &|[r, g, b]| r > g + 50 && r > b + 50);
    assert!(brick > w * h / 20, "brick walls: {brick} red pixels");
    // Sky through the window (behind blue glass) and the doorway: light blue.
    let sky = count(52..h, &|[r, g, b]| b > 170 && b > r + 15 && g > 120);
    assert!(sky > 100, "sky: {sky} light blue pixels");
    // The green glass pane over the room.
    let green = count(52..h, &|[r, g, b]| g > r + 30 && g > b + 20);
    assert!(green > 100, "green glass: {green} green pixels");
    let _ = std::fs::remove_file(&shot);
}

#[test]
fn headless_needs_glrt() {
    let (out, stopped) =
        run_for(with_system_libgl(&["--headless", "--frames", "1"]), Duration::from_secs(60));
    assert!(!stopped);
    assert_eq!(out.status.code(), Some(2), "exit status for a libGL without glrtCreateContext");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no headless context API"), "message: {stderr}");
}
