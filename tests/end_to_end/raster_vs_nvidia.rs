//! The same frame on two Vulkan drivers: `glrt-demo` at scene frame 206, rendered headless
//! through glrt on this machine's device (lavapipe in CI), against the image the NVIDIA H100
//! driver produced from the same binary, committed as
//! `tests/reference/demo-206-nvidia-h100.png`. Made on the GPU machine with
//! `GLRT_MODE=raster GLRT_DUMP=... LD_LIBRARY_PATH=<dir of libGL.so.1 → libglrt.so> glrt-demo --headless
//! --frames 1 --first-frame 206 --size 320x240 --screenshot demo-206-nvidia-h100.png`.
//! Same metric and tolerance as `raster_vs_mesa.rs`.

use crate::images;
use crate::programs;

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use images::{Image, compare, difference_image};
use programs::{lib_dir, run_for};

/// Largest per-channel difference of matching pixels (0..=255).
const TOLERANCE: u8 = 24;

/// Largest fraction of pixels without a match.
const MAX_MISMATCHED: f64 = 0.01;

#[test]
fn demo_frame_matches_the_nvidia_reference() {
    let dir = lib_dir().join("raster-vs-nvidia");
    std::fs::create_dir_all(&dir).expect("image directory");
    let shot = dir.join("demo-206-here.png");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    cmd.env("LD_LIBRARY_PATH", lib_dir())
        .args(["--headless", "--frames", "1", "--first-frame", "206", "--size", "320x240", "--screenshot"])
        .arg(&shot);
    let (out, stopped) = run_for(cmd, Duration::from_secs(120));
    assert!(!stopped && out.status.success(), "glrt-demo: {:?}\n{}", out.status, String::from_utf8_lossy(&out.stderr));
    let here = Image::load_png(&shot);
    let nvidia = Image::load_png(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/demo-206-nvidia-h100.png"));
    difference_image(&here, &nvidia).save_png(&dir.join("demo-206-diff.png"));
    let d = compare(&here, &nvidia, TOLERANCE);
    eprintln!(
        "demo vs NVIDIA: {:.3}% mismatched, {:.3}% identical, mean |difference| {:.4}",
        d.mismatched * 100.0,
        d.identical * 100.0,
        d.mean_abs
    );
    assert!(d.mismatched <= MAX_MISMATCHED, "{:.2}% of the pixels differ from the NVIDIA image (images in {})", d.mismatched * 100.0, dir.display());
}
