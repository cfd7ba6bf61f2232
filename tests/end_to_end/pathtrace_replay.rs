//! The demo and glxgears path traced on lavapipe, replayed from their captures
//! (`tests/fixtures/*.glrtcap`) with `glrt replay --out` and `GLRT_MODE=pathtrace`, against
//! the images committed in `tests/reference/pathtrace/` (lavapipe's, and the NVIDIA H200's
//! of the same replay); and the demo's HUD text, which the path-traced frame must show
//! exactly as the rasterized one.
//!
//! Settings: traced at a quarter of the resolution (`GLRT_RESOLUTION_SCALE=0.25`, so a frame
//! costs about a second on lavapipe), 1 sample per pixel, 1 bounce, ACES tone mapping,
//! lightmaps ignored and the tracer's temporal filter (`GLRT_DENOISE=0`: the settings the
//! references were made with, on both machines; the denoiser's own test is `denoise.rs`).
//! The tracer's random numbers depend only on the pixel, the frame and the sample, so lavapipe
//! makes the same image again; the tolerance (`images::compare`, 24 per channel, 1% of the
//! pixels, mean difference below 2) leaves room for another processor's floating point.
//! To remake the references after a deliberate change, run this test and copy
//! `target/<profile>/pathtrace-replay/{demo,glxgears}-3.png` to `tests/reference/pathtrace/`;
//! on the GPU machine, `GLRT_MODE=pathtrace GLRT_RESOLUTION_SCALE=0.25 GLRT_SPP=1
//! GLRT_BOUNCES=1 GLRT_TONEMAP=aces GLRT_LIGHTMAPS=ignore GLRT_DENOISE=0 glrt replay
//! tests/fixtures/NAME.glrtcap --frames 0..4 --out DIR` makes `DIR/frame-00003.png`, the
//! `NAME-3-nvidia-h200.png` reference. The demo's lightmaps (unit 1) are light only where hash
//! tracking says so (`Instance::light_units`); otherwise the tracer takes them as colour.

use crate::images;

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::programs::lib_dir;
use images::{Image, compare, difference_image};

/// Largest fraction of pixels without a match within `TOLERANCE`.
const MAX_MISMATCHED: f64 = 0.01;
const TOLERANCE: u8 = 24;
/// Largest mean absolute difference per channel.
const MAX_MEAN_ABS: f64 = 2.0;

/// Replays frames 0..4 of fixture `name` with `mode`, drawing all four (the references were
/// traced after frames 0 to 2, which are their temporal history; `--frames 3..4` would trace
/// frame 3 alone), and returns the path of frame 3.
fn replay_frame_3(name: &str, mode: &str) -> PathBuf {
    replay_frame_3_with(name, mode, &[("GLRT_MODE", mode), ("GLRT_DENOISE", "0")])
}

/// Replays frames 0..4 of fixture `name` with the settings of the module doc and the
/// variables `env` (which override them) into a folder named by `tag`; returns the path of
/// frame 3.
pub fn replay_frame_3_with(name: &str, tag: &str, env: &[(&str, &str)]) -> PathBuf {
    let dir = lib_dir().join("pathtrace-replay").join(format!("{name}-{tag}"));
    let _ = std::fs::remove_dir_all(&dir);
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(format!("{name}.glrtcap"));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt"));
    cmd.arg("replay").arg(&fixture).args(["--frames", "0..4", "--out"]).arg(&dir);
    for key in ["GLRT_CAPTURE", "GLRT_FRAME_LOG", "GLRT_DUMP", "GLRT_CONFIG"] {
        cmd.env_remove(key);
    }
    cmd.env("GLRT_RESOLUTION_SCALE", "0.25").env("GLRT_SPP", "1").env("GLRT_BOUNCES", "1").env("GLRT_TONEMAP", "aces").env("GLRT_LIGHTMAPS", "ignore");
    cmd.envs(env.iter().copied());
    let lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
    if Path::new(lavapipe).exists() {
        cmd.env("VK_DRIVER_FILES", lavapipe);
    }
    let out = cmd.output().expect("run glrt replay");
    assert!(out.status.success(), "glrt replay {name}: {}", String::from_utf8_lossy(&out.stderr));
    dir.join("frame-00003.png")
}

/// Frame 3 of fixture `name`, path traced here, against the references: lavapipe's
/// (`NAME-3.png`) and the NVIDIA H200's (`NAME-3-nvidia-h200.png`, the same replay and
/// settings with a release build on the GPU machine: the tracer makes the same image on both).
fn matches_references(name: &str) -> Image {
    let dir = lib_dir().join("pathtrace-replay");
    let here = Image::load_png(&replay_frame_3(name, "pathtrace"));
    let kept = dir.join(format!("{name}-3.png"));
    here.save_png(&kept);
    for reference in [format!("{name}-3.png"), format!("{name}-3-nvidia-h200.png")] {
        let expected = Image::load_png(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/pathtrace").join(&reference));
        let diff = dir.join(format!("diff-{reference}"));
        difference_image(&here, &expected).save_png(&diff);
        let d = compare(&here, &expected, TOLERANCE);
        eprintln!("{name} against {reference}: {:.3}% mismatched, {:.3}% identical, mean |difference| {:.4}", d.mismatched * 100.0, d.identical * 100.0, d.mean_abs);
        assert!(
            d.mismatched <= MAX_MISMATCHED && d.mean_abs <= MAX_MEAN_ABS,
            "{name} against {reference}: {:.2}% of the pixels differ, mean {:.3} (this run: {}, difference: {})",
            d.mismatched * 100.0,
            d.mean_abs,
            kept.display(),
            diff.display()
        );
    }
    here
}

#[test]
fn the_demo_path_traced_matches_its_reference_and_keeps_the_raster_hud() {
    let traced = matches_references("demo");
    // The HUD's text colours (demo/scene/hud.rs): every pixel of text in the rasterized frame
    // is the same in the path-traced one.
    let raster = Image::load_png(&replay_frame_3("demo", "raster"));
    let text = [[255u8, 230, 77], [204, 242, 255]];
    let mut checked = 0;
    for y in 0..raster.height {
        for x in 0..raster.width {
            let p = raster.pixel(x, y);
            if text.contains(&p) {
                assert_eq!(traced.pixel(x, y), p, "HUD text pixel ({x}, {y})");
                checked += 1;
            }
        }
    }
    assert!(checked > 200, "the HUD text was found in the raster frame ({checked} pixels)");
    // The traced scene differs from the rasterized one (it is not the raster image).
    let d = compare(&traced, &raster, TOLERANCE);
    assert!(d.mismatched > 0.2, "the path-traced frame looks rasterized ({:.1}% of pixels differ)", d.mismatched * 100.0);
}

#[test]
fn glxgears_path_traced_matches_its_reference() {
    matches_references("glxgears");
}
