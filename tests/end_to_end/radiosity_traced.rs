//! Radiosity in the path tracer (issue 19) on the demo's capture: frame 3 traced with one
//! bounce whose first diffuse vertex on the static world reads radiosity's indirect light and
//! ends (`GLRT_RADIOSITY=1`, the matrix of 192 patches: `GLRT_RADIOSITY_BUDGET_MB=1`), against
//! the same frame traced without radiosity with 4 bounces (the reference), and with 1 and 0
//! bounces (what one more bounce adds: the direct light of the second vertex, which radiosity
//! must not add again); 2 samples per pixel each (lavapipe traces on one thread: the 4-bounce
//! frame takes minutes at 16). Settings of `pathtrace_replay` (quarter resolution, lightmaps
//! ignored) with clamp tone mapping (no curve between the light and the pixel below 1) and
//! neither temporal filter nor denoiser, so each frame is its own samples. Compared as the
//! traced pixels (4 × 4 blocks of the window) below the HUD and on the ceiling between the
//! pillars, which only indirect light reaches: region means (thousands of paths each) and
//! noise, the mean difference between neighbouring pixels; numbers in `bench/radiosity.md`.

use crate::images::Image;
use crate::pathtrace_replay::replay_frame_3_with;
use crate::programs::lib_dir;
use crate::radiosity_raster::{blocks, region};

/// Traced pixels (4 × 4 blocks) below the HUD, and on the ceiling between the pillars.
const BELOW_HUD: (std::ops::Range<usize>, std::ops::Range<usize>) = (12..60, 0..80);
const CEILING: (std::ops::Range<usize>, std::ops::Range<usize>) = (12..17, 10..70);

/// Frame 3 traced with `bounces` and `spp`, radiosity on or off, as traced pixels.
fn traced(tag: &str, bounces: &str, spp: &str, radiosity: bool) -> Vec<Vec<[f64; 3]>> {
    let cache = lib_dir().join("radiosity-traced-cache");
    let cache = cache.to_str().expect("a UTF-8 path");
    let env = [
        ("GLRT_MODE", "pathtrace"),
        ("GLRT_DENOISE", "0"),
        ("GLRT_TEMPORAL", "0"),
        ("GLRT_TONEMAP", "clamp"),
        ("GLRT_BOUNCES", bounces),
        ("GLRT_SPP", spp),
        ("GLRT_RADIOSITY", if radiosity { "1" } else { "0" }),
        ("GLRT_RADIOSITY_BUDGET_MB", "1"),
        ("GLRT_RADIOSITY_WAIT", "1"),
        ("XDG_CACHE_HOME", cache),
    ];
    blocks(&Image::load_png(&replay_frame_3_with("demo", tag, &env)))
}

/// The mean of the three channels' means over `area` of `image`.
fn mean(image: &[Vec<[f64; 3]>], area: &(std::ops::Range<usize>, std::ops::Range<usize>)) -> f64 {
    let (_, m) = region(image, image, area.0.clone(), area.1.clone());
    m.iter().sum::<f64>() / 3.0
}

/// Noise over `area` of `image`: the mean absolute difference between horizontally
/// neighbouring traced pixels (per channel, 0..255).
fn noise(image: &[Vec<[f64; 3]>], area: &(std::ops::Range<usize>, std::ops::Range<usize>)) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for y in area.0.clone() {
        for x in area.1.start..area.1.end - 1 {
            for c in 0..3 {
                sum += (image[y][x + 1][c] - image[y][x][c]).abs();
            }
            n += 3.0;
        }
    }
    sum / n
}

#[test]
fn radiosity_at_the_first_diffuse_bounce_matches_many_bounces_with_less_noise() {
    let lit = traced("trace-b1-radiosity", "1", "2", true);
    let reference = traced("trace-b4", "4", "2", false);
    let one = traced("trace-b1", "1", "2", false);
    let zero = traced("trace-b0", "0", "2", false);
    for (name, area) in [("below the HUD", &BELOW_HUD), ("ceiling", &CEILING)] {
        let m = |image: &[Vec<[f64; 3]>]| mean(image, area);
        let (r, o, z, l) = (m(&reference), m(&one), m(&zero), m(&lit));
        let rmse = |image: &[Vec<[f64; 3]>]| region(image, &reference, area.0.clone(), area.1.clone()).0;
        eprintln!(
            "{name}: mean (0..255) 4 bounces {r:.2}, 1 bounce {o:.2}, 0 bounces {z:.2}, 1 bounce + radiosity {l:.2} \
             (error {:+.2}, {:+.1} %); noise (neighbour difference) 4 bounces {:.2}, 1 bounce {:.2}, 1 bounce + radiosity {:.2}; \
             RMSE against 4 bounces: 1 bounce {:.2}, 1 bounce + radiosity {:.2}",
            l - r,
            100.0 * (l - r) / r,
            noise(&reference, area),
            noise(&one, area),
            noise(&lit, area),
            rmse(&one),
            rmse(&lit),
        );
    }
    let m = |image: &[Vec<[f64; 3]>]| mean(image, &BELOW_HUD);
    let (r, o, z, l) = (m(&reference), m(&one), m(&zero), m(&lit));
    // Close to the reference: within 10 % below the HUD.
    assert!((l - r).abs() < 0.1 * r, "1 bounce + radiosity {l:.2} against the reference {r:.2}");
    // The direct light of the second vertex counted twice would add about what the first
    // bounce adds (1 bounce − 0 bounces); radiosity left out would leave the 1-bounce image.
    assert!((l - r).abs() < 0.5 * (o - z), "1 bounce + radiosity {l:.2}, reference {r:.2}: off by half the second vertex's direct light ({o:.2} - {z:.2})");
    assert!((l - r).abs() < 0.5 * (r - o), "1 bounce + radiosity {l:.2}, reference {r:.2}: off by half of what bounces after the first add ({r:.2} - {o:.2})");
    // Less noise than 4 bounces at the same samples, where the indirect light dominates.
    assert!(noise(&lit, &CEILING) < noise(&reference, &CEILING), "ceiling noise: 1 bounce + radiosity {:.2}, 4 bounces {:.2}", noise(&lit, &CEILING), noise(&reference, &CEILING));
}
