//! Raster + radiosity (issue 19) on the demo's capture: frame 3 rasterized with GL's ambient
//! light and with radiosity's indirect light in its place (`GLRT_RADIOSITY=1`, the matrix of
//! 192 patches precomputed in the run: `GLRT_RADIOSITY_BUDGET_MB=1`, an empty cache), both
//! against the converged path-traced frame `tests/reference/denoise/demo-3-converged.png`
//! (`bench/denoise.md`: traced at a quarter of the resolution, one bounce, ACES, lightmaps
//! ignored; the raster frames keep the demo's corner-darkening lightmap and are not tone
//! mapped). Compared as 4 × 4 pixel block means (the reference's own resolution), below the
//! HUD; numbers in `bench/radiosity.md`.

use std::path::Path;

use crate::images::Image;
use crate::pathtrace_replay::replay_frame_3_with;
use crate::programs::lib_dir;

/// Side of the blocks the images are compared in (the reference's resolution scale, 1/4).
const BLOCK: usize = 4;

/// The mean of each `BLOCK` × `BLOCK` block of `image`, per channel.
pub fn blocks(image: &Image) -> Vec<Vec<[f64; 3]>> {
    (0..image.height / BLOCK)
        .map(|by| {
            (0..image.width / BLOCK)
                .map(|bx| {
                    let mut sum = [0.0; 3];
                    for y in by * BLOCK..(by + 1) * BLOCK {
                        for x in bx * BLOCK..(bx + 1) * BLOCK {
                            let p = image.pixel(x, y);
                            for c in 0..3 {
                                sum[c] += f64::from(p[c]);
                            }
                        }
                    }
                    sum.map(|s| s / (BLOCK * BLOCK) as f64)
                })
                .collect()
        })
        .collect()
}

/// RMSE (0..255) of the blocks `rows` × `columns` of `a` against `b`, and `a`'s mean there.
pub fn region(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>], rows: std::ops::Range<usize>, columns: std::ops::Range<usize>) -> (f64, [f64; 3]) {
    let (mut squared, mut mean, mut n) = (0.0, [0.0; 3], 0.0);
    for y in rows {
        for x in columns.clone() {
            for c in 0..3 {
                squared += (a[y][x][c] - b[y][x][c]).powi(2);
                mean[c] += a[y][x][c];
            }
            n += 1.0;
        }
    }
    ((squared / (3.0 * n)).sqrt(), mean.map(|m| m / n))
}

#[test]
fn radiosity_brings_the_demos_raster_frame_towards_its_path_traced_reference() {
    let reference = blocks(&Image::load_png(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/denoise/demo-3-converged.png")));
    let cache = lib_dir().join("radiosity-raster-cache");
    let _ = std::fs::remove_dir_all(&cache);
    let raster = [("GLRT_MODE", "raster")];
    // Its own folder: `pathtrace_replay`'s raster test writes "demo-raster" at the same time.
    let plain_image = Image::load_png(&replay_frame_3_with("demo", "raster-plain", &[raster[0], ("GLRT_RADIOSITY", "0")]));
    let cache_var = cache.to_str().expect("a UTF-8 path");
    let lit_image = Image::load_png(&replay_frame_3_with(
        "demo",
        "raster-radiosity",
        &[raster[0], ("GLRT_RADIOSITY", "1"), ("GLRT_RADIOSITY_BUDGET_MB", "1"), ("GLRT_RADIOSITY_WAIT", "1"), ("XDG_CACHE_HOME", cache_var)],
    ));
    let cached = std::fs::read_dir(cache.join("glrt/radiosity")).map_or(0, |d| d.count());
    assert_eq!(cached, 1, "the run wrote its matrix to the cache");
    let (plain, lit) = (blocks(&plain_image), blocks(&lit_image));
    // Below the HUD (its 48 rows); the ceiling between the pillars, lit only indirectly
    // (the lights hang below it and face down).
    let (below_hud, ceiling) = ((12..60, 0..80), (12..17, 10..70));
    let (plain_all, _) = region(&plain, &reference, below_hud.0.clone(), below_hud.1.clone());
    let (lit_all, _) = region(&lit, &reference, below_hud.0, below_hud.1);
    let (plain_ceiling, plain_mean) = region(&plain, &reference, ceiling.0.clone(), ceiling.1.clone());
    let (lit_ceiling, lit_mean) = region(&lit, &reference, ceiling.0.clone(), ceiling.1.clone());
    let (_, reference_mean) = region(&reference, &reference, ceiling.0, ceiling.1);
    eprintln!(
        "demo frame 3 against its path-traced reference, RMSE of 0..255 (4x4 blocks): below the HUD raster {plain_all:.2}, raster + radiosity {lit_all:.2}; \
         ceiling {plain_ceiling:.2} -> {lit_ceiling:.2}, its mean {plain_mean:.1?} -> {lit_mean:.1?} (reference {reference_mean:.1?})"
    );
    // The bricks' red bounce light brightens the ceiling towards the reference's.
    assert!(lit_mean[0] > plain_mean[0] + 5.0 && lit_mean[0] < reference_mean[0], "ceiling red {} -> {} (reference {})", plain_mean[0], lit_mean[0], reference_mean[0]);
    assert!(lit_ceiling < 0.95 * plain_ceiling, "ceiling RMSE {plain_ceiling:.2} -> {lit_ceiling:.2}");
    assert!(lit_all < plain_all, "RMSE below the HUD {plain_all:.2} -> {lit_all:.2}");
}
