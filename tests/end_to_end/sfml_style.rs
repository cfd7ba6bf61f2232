//! A program making the GLX and GL calls of an SFML 2 game (`tests/programs/sfml_style.c`,
//! compiled here with `cc`) runs through glrt under Xvfb for 300 frames: a hidden 1x1 window
//! with a context of its own, the game window with a second context sharing its objects, both
//! configurations found as SFML finds them (the first of `glXChooseFBConfig(NULL)`'s list with
//! the window's visual), a framebuffer-object blit, 1,500 `glDrawArrays` and a `glGetError`
//! after every call per frame. Every frame must reach the renderer (the frame log), and the
//! window, read back with `XGetImage` by the program every 10 frames, must keep changing and
//! show each frame's colour where the blitted texture is drawn.
//!
//! Before glrt dealt its configurations out over the server's visuals, that configuration was
//! single-buffered (the list puts single-buffered ones first, and every configuration of a
//! visual shared it): swaps ended no frame and the window stayed black.

use std::process::Command;
use std::time::Duration;

use crate::programs::{lib_dir, run_for, scratch};
use crate::x11::Xvfb;

/// Frames the program draws.
const FRAMES: u32 = 300;

/// The colour the program clears its texture to in frame `f` (as `frame_colour` in the C
/// source).
fn frame_colour(f: u32) -> [u32; 3] {
    [(f * 5) % 256, (f * 11) % 256, 255 - (f * 3) % 256]
}

/// `sample FRAME R G B SUM` lines of the program's output.
fn samples(stdout: &str) -> Vec<(u32, [u32; 3], u64)> {
    stdout
        .lines()
        .filter_map(|line| {
            let v: Vec<u64> = line.strip_prefix("sample ")?.split(' ').map(|s| s.parse().unwrap()).collect();
            Some((v[0] as u32, [v[1] as u32, v[2] as u32, v[3] as u32], v[4]))
        })
        .collect()
}

#[test]
fn sfml_style_window_changes_every_frame() {
    let source = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/programs/sfml_style.c");
    let program = scratch("sfml_style", "sfml_style");
    let lib = lib_dir();
    let built = Command::new("cc")
        .args(["-O1", "-o"])
        .arg(&program)
        .arg(source)
        .arg("-lX11")
        .arg(format!("-L{}", lib.display()))
        .arg("-l:libGL.so.1")
        .output()
        .expect("cc (a C compiler)");
    assert!(built.status.success(), "cc failed:\n{}", String::from_utf8_lossy(&built.stderr));

    let x = Xvfb::start(24);
    let frame_log = scratch("sfml_style", "frames.jsonl");
    let mut cmd = Command::new(&program);
    cmd.arg(FRAMES.to_string())
        .env("DISPLAY", &x.display)
        .env("LD_LIBRARY_PATH", &lib)
        .env("GLRT_FRAME_LOG", &frame_log)
        .env_remove("GLRT_PRESENT");
    let (out, stopped) = run_for(cmd, Duration::from_secs(300));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stopped && out.status.success(), "sfml_style failed ({:?}):\n{stderr}", out.status);

    let frames = std::fs::read_to_string(&frame_log).expect("frame log");
    assert_eq!(frames.lines().count(), FRAMES as usize, "every swap ends a frame; stderr:\n{stderr}");
    let samples = samples(&stdout);
    assert_eq!(samples.len(), FRAMES as usize / 10, "{stdout}");
    for &(f, pixel, _) in &samples {
        // The window shows this frame or one of the two before it (frames in flight).
        let shown = (f.saturating_sub(2)..=f).any(|g| frame_colour(g).iter().zip(pixel).all(|(&e, p)| e.abs_diff(p) <= 1));
        assert!(shown, "frame {f}: pixel {pixel:?}, expected the colour of frame {f} {:?}\n{stdout}", frame_colour(f));
    }
    for pair in samples.windows(2) {
        assert_ne!(pair[0].2, pair[1].2, "the window did not change between frames {} and {}\n{stdout}", pair[0].0, pair[1].0);
    }
}
