//! The denoiser's quality (issue 20) on the demo's capture, a replay with a moving camera:
//! frame 3, traced at one sample per pixel after frames 0 to 2 (its history), raw (no
//! temporal reuse), with the tracer's temporal filter and with A-SVGF (`src/render/denoise`),
//! against the converged reference of the same frame, `tests/reference/denoise/demo-3-converged.png`
//! (frame 3 alone, its animation frozen, drawn 256 times while nothing moves: 256 samples per
//! pixel through the pixel centres, as the frames compared with it). The settings are
//! `pathtrace_replay`'s; the numbers are in `bench/denoise.md`, which says how to remake the
//! reference.

use std::path::Path;

use crate::images::{Image, rmse};
use crate::pathtrace_replay::replay_frame_3_with;
use crate::programs::lib_dir;

#[test]
fn a_svgf_brings_the_demo_closer_to_its_converged_frame_than_raw_samples_and_the_temporal_filter() {
    let reference = Image::load_png(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/denoise/demo-3-converged.png"));
    let pathtrace = ("GLRT_MODE", "pathtrace");
    let raw = Image::load_png(&replay_frame_3_with("demo", "raw", &[pathtrace, ("GLRT_DENOISE", "0"), ("GLRT_TEMPORAL", "false")]));
    let temporal = Image::load_png(&replay_frame_3_with("demo", "temporal", &[pathtrace, ("GLRT_DENOISE", "0")]));
    let denoised = Image::load_png(&replay_frame_3_with("demo", "a-svgf", &[pathtrace, ("GLRT_DENOISE", "1")]));
    let [raw_rmse, temporal_rmse, denoised_rmse] = [&raw, &temporal, &denoised].map(|image| rmse(image, &reference));
    eprintln!("demo frame 3 against its converged reference, RMSE of 0..255: raw {raw_rmse:.2}, temporal filter {temporal_rmse:.2}, A-SVGF {denoised_rmse:.2}");
    let kept = lib_dir().join("pathtrace-replay");
    for (image, name) in [(&raw, "raw"), (&temporal, "temporal"), (&denoised, "a-svgf")] {
        image.save_png(&kept.join(format!("demo-3-{name}.png")));
    }
    assert!(denoised_rmse < 0.75 * raw_rmse, "A-SVGF {denoised_rmse:.2} against raw {raw_rmse:.2}");
    assert!(denoised_rmse < 0.9 * temporal_rmse, "A-SVGF {denoised_rmse:.2} against the temporal filter {temporal_rmse:.2}");
}
