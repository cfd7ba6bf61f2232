//! glrt's raster back end against Mesa's llvmpipe (the system `libGL.so.1`) on the same
//! programs and the same frames:
//! - `glrt-demo` at a fixed scene frame, read back by the demo itself (`--screenshot`, which
//!   uses `glReadPixels`): Mesa in a window under Xvfb, glrt headless;
//! - Mesa's `glxgears` with its clock frozen (`tests/frozen_clock.c`, preloaded) (so both draw the gears at the same
//!   angle), shown in a window under Xvfb and read back from the X server with `xwd`.
//!
//! The metric ([`images::compare`]): a pixel matches when the other image has, at its position
//! or one pixel around it, a pixel within [`TOLERANCE`] on every channel; at most
//! [`MAX_MISMATCHED`] of the pixels may fail. The images (glrt, Mesa, difference) are written to
//! `target/raster-vs-mesa/` for looking at; `scripts/compare.sh` copies them to `bench/`.

use crate::images;
use crate::programs;
use crate::x11::Xvfb;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use images::{Image, compare, difference_image};
use programs::{lib_dir, run_for};

/// Largest per-channel difference of matching pixels (0..=255).
const TOLERANCE: u8 = 24;

/// Largest fraction of pixels without a match.
const MAX_MISMATCHED: f64 = 0.01;

/// Mesa's libGL, as Debian installs it (through glvnd).
const MESA_LIBGL: &str = "/usr/lib/x86_64-linux-gnu/libGL.so.1";

/// Where the images go.
fn out_dir() -> PathBuf {
    let dir = lib_dir().join("raster-vs-mesa");
    std::fs::create_dir_all(&dir).expect("creating the image directory");
    dir
}

/// Writes the pair and their difference, compares them and asserts the tolerance.
fn assert_close(name: &str, glrt: &Image, mesa: &Image) {
    let dir = out_dir();
    glrt.save_png(&dir.join(format!("{name}-glrt.png")));
    mesa.save_png(&dir.join(format!("{name}-mesa.png")));
    assert_eq!((glrt.width, glrt.height), (mesa.width, mesa.height), "{name}: image sizes");
    difference_image(glrt, mesa).save_png(&dir.join(format!("{name}-diff.png")));
    let d = compare(glrt, mesa, TOLERANCE);
    eprintln!(
        "{name}: {:.3}% of pixels mismatched, {:.3}% identical, mean |difference| {:.4}",
        d.mismatched * 100.0,
        d.identical * 100.0,
        d.mean_abs
    );
    assert!(
        d.mismatched <= MAX_MISMATCHED,
        "{name}: {:.2}% of the pixels differ from Mesa's by more than {TOLERANCE} (allowed {:.2}%); images in {}",
        d.mismatched * 100.0,
        MAX_MISMATCHED * 100.0,
        dir.display()
    );
}

/// Demo options shared by both runs: one frame at scene frame 206 (the door is open).
const DEMO_ARGS: [&str; 6] = ["--frames", "1", "--first-frame", "206", "--size", "320x240"];

fn run_demo(mut cmd: Command, shot: &Path) -> Image {
    cmd.args(DEMO_ARGS).arg("--screenshot").arg(shot);
    let (out, stopped) = run_for(cmd, Duration::from_secs(120));
    assert!(
        !stopped && out.status.success(),
        "glrt-demo: {:?}\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    Image::load_png(shot)
}

#[test]
fn demo_frame_matches_mesa() {
    let dir = out_dir();
    let x = Xvfb::with_screen("1024x768x24");
    let mut mesa = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    mesa.env_remove("LD_LIBRARY_PATH").env("DISPLAY", &x.display).args(["--lib", MESA_LIBGL]);
    let mesa = run_demo(mesa, &dir.join("demo-mesa-shot.png"));
    let mut glrt = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    glrt.env("LD_LIBRARY_PATH", lib_dir()).arg("--headless");
    let glrt = run_demo(glrt, &dir.join("demo-glrt-shot.png"));
    assert_close("demo", &glrt, &mesa);
}

/// Builds `tests/frozen_clock.c` (a `gettimeofday` that always answers the same instant) into
/// a library to preload into glxgears, so every frame shows the gears at angle 0.
fn frozen_clock() -> PathBuf {
    let lib = out_dir().join("frozen_clock.so");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/frozen_clock.c");
    let out = Command::new("cc").args(["-shared", "-fPIC", "-O2", "-o"]).arg(&lib).arg(&src).output().expect("cc (a C compiler)");
    assert!(out.status.success(), "building {}: {}", src.display(), String::from_utf8_lossy(&out.stderr));
    lib
}

/// Size of the glxgears window, placed at the screen's top-left corner.
const GEARS_SIZE: usize = 300;

/// Runs glxgears with a frozen clock on a private Xvfb screen (through glrt when `glrt`), and
/// returns the window's pixels once two screenshots a second apart agree and show something.
fn glxgears_image(glrt: bool) -> Image {
    for tool in ["/usr/bin/glxgears", "/usr/bin/xwd"] {
        assert!(Path::new(tool).exists(), "{tool} missing: run `bash scripts/setup.sh`");
    }
    let x = Xvfb::with_screen("320x320x24");
    let mut cmd = Command::new("/usr/bin/glxgears");
    cmd.args(["-geometry", "300x300+0+0"])
        .env("LD_PRELOAD", frozen_clock())
        .env("DISPLAY", &x.display)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    if glrt {
        cmd.env("LD_LIBRARY_PATH", lib_dir());
    } else {
        cmd.env_remove("LD_LIBRARY_PATH");
    }
    let mut child = cmd.spawn().expect("spawn glxgears");
    let screenshot = || {
        let out = Command::new("xwd").args(["-root", "-silent", "-display", &x.display]).output().expect("xwd");
        assert!(out.status.success(), "xwd: {}", String::from_utf8_lossy(&out.stderr));
        Image::from_xwd(&out.stdout).crop(GEARS_SIZE, GEARS_SIZE)
    };
    let start = Instant::now();
    let mut last: Option<Image> = None;
    let image = loop {
        std::thread::sleep(Duration::from_secs(1));
        let now = screenshot();
        let drawn = now.rgb.iter().any(|&c| c > 64);
        if drawn && last.as_ref() == Some(&now) {
            break now;
        }
        if child.try_wait().expect("wait").is_some() || start.elapsed() > Duration::from_secs(90) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("glxgears (through glrt: {glrt}) showed no stable image in its window within 90 s");
        }
        last = Some(now);
    };
    let _ = child.kill();
    let _ = child.wait();
    image
}

#[test]
fn glxgears_frame_matches_mesa() {
    let mesa = glxgears_image(false);
    let glrt = glxgears_image(true);
    assert_close("glxgears", &glrt, &mesa);
}
