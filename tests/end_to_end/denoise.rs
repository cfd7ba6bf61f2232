//! The denoiser's quality (issue 20) on two replays with a moving camera, the demo's and the
//! Quake-3-like demo's (`glrt-demo --q3`) captures: frame 3, traced at one sample per pixel
//! after frames 0 to 2 (its history), raw (no temporal reuse), with the tracer's temporal
//! filter and with A-SVGF (`src/render/denoise`), against the converged reference of the same
//! frame, `tests/reference/denoise/NAME-3-converged.png` (frame 3 alone, its animation frozen,
//! drawn again and again while nothing moves: one sample per pixel per repetition through the
//! pixel centres, as the frames compared with it), by RMSE and FLIP. The settings are
//! `pathtrace_replay`'s; the numbers are in `bench/denoise.md`, which says how to remake the
//! references. Each test keeps its images and a figure of frames 1 to 3 (raw, temporal filter,
//! A-SVGF; the reference beside frame 3) in `target/<profile>/pathtrace-replay/`.

use std::path::{Path, PathBuf};

use crate::images::{Image, flip, montage, rmse};
use crate::pathtrace_replay::replay_frame_3_with;
use crate::programs::lib_dir;

/// RMSE (0..255) and mean FLIP of raw samples, the temporal filter and A-SVGF, in that order.
struct Quality {
    rmse: [f64; 3],
    flip: [f64; 3],
}

/// Replays fixture `name` raw, with the temporal filter and with A-SVGF, measures frame 3
/// against its converged reference and keeps the images and the figure.
fn quality(name: &str) -> Quality {
    let reference = Image::load_png(&Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/reference/denoise/{name}-3-converged.png")));
    let pathtrace = ("GLRT_MODE", "pathtrace");
    let runs: [(&str, &[(&str, &str)]); 3] = [
        ("raw", &[pathtrace, ("GLRT_DENOISE", "0"), ("GLRT_TEMPORAL", "false")]),
        ("temporal", &[pathtrace, ("GLRT_DENOISE", "0")]),
        ("a-svgf", &[pathtrace, ("GLRT_DENOISE", "1")]),
    ];
    let frames: Vec<PathBuf> = runs.iter().map(|(tag, env)| replay_frame_3_with(name, tag, env)).collect();
    let frame = |run: usize, n: usize| Image::load_png(&frames[run].with_file_name(format!("frame-{n:05}.png")));
    let third: Vec<Image> = (0..3).map(|run| frame(run, 3)).collect();
    let quality = Quality {
        rmse: [0, 1, 2].map(|run| rmse(&third[run], &reference)),
        flip: [0, 1, 2].map(|run| flip(&third[run], &reference)),
    };
    let [r, f] = [quality.rmse, quality.flip];
    eprintln!(
        "{name} frame 3 against its converged reference: RMSE of 0..255 raw {:.2}, temporal filter {:.2}, A-SVGF {:.2}; FLIP raw {:.4}, temporal filter {:.4}, A-SVGF {:.4}",
        r[0], r[1], r[2], f[0], f[1], f[2]
    );
    let kept = lib_dir().join("pathtrace-replay");
    for (image, (tag, _)) in third.iter().zip(&runs) {
        image.save_png(&kept.join(format!("{name}-3-{tag}.png")));
    }
    let earlier: Vec<Vec<Image>> = [1, 2].iter().map(|&n| (0..3).map(|run| frame(run, n)).collect()).collect();
    let mut rows: Vec<Vec<Option<&Image>>> = earlier.iter().map(|row| row.iter().map(Some).collect()).collect();
    rows.push(third.iter().map(Some).chain([Some(&reference)]).collect());
    montage(&rows).save_png(&kept.join(format!("denoise-{name}-frames.png")));
    quality
}

/// A-SVGF's frame 3 of fixture `name` is closer to the converged frame than raw samples and
/// the temporal filter, by RMSE and FLIP.
fn assert_denoised_closer(name: &str) {
    let Quality { rmse: [raw, temporal, denoised], flip: [raw_flip, temporal_flip, denoised_flip] } = quality(name);
    assert!(denoised < 0.75 * raw, "RMSE: A-SVGF {denoised:.2} against raw {raw:.2}");
    assert!(denoised < 0.9 * temporal, "RMSE: A-SVGF {denoised:.2} against the temporal filter {temporal:.2}");
    assert!(denoised_flip < 0.9 * raw_flip, "FLIP: A-SVGF {denoised_flip:.4} against raw {raw_flip:.4}");
    assert!(denoised_flip < temporal_flip, "FLIP: A-SVGF {denoised_flip:.4} against the temporal filter {temporal_flip:.4}");
}

#[test]
fn a_svgf_brings_the_demo_closer_to_its_converged_frame_than_raw_samples_and_the_temporal_filter() {
    assert_denoised_closer("demo");
}

#[test]
fn a_svgf_brings_the_quake_3_like_demo_closer_to_its_converged_frame_than_raw_samples_and_the_temporal_filter() {
    assert_denoised_closer("q3");
}
