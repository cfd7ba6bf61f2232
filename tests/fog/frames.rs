//! Whole frames fogged by the height fog, in raster and path-traced modes: a lit wall filling
//! the view (noise-free when traced, as in `tests/pathtrace/composite.rs`: one sample through
//! each pixel centre, no bounce, a black sky, clamped tone curve), so each pixel can be checked
//! exactly against `mix(wall, fog, F)` with `F` integrated numerically here; glass in front of
//! the fogged wall (alpha blended, and an additive clear pass) counts the fog behind it once;
//! and the two modes give the same fogged wall.

use crate::lavapipe;
use glam::{DVec3, Vec3};
use glrt::render::fog::settings::{FogColor, FogSettings};
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 24;
/// The glass colour (RGBA, blended with `GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA`).
const GLASS: [f32; 4] = [0.2, 0.4, 1.0, 0.5];
/// The fog: density 0.15 at eye height −1, falloff 0.4 upwards (eye space is the world).
const FOG: FogSettings = FogSettings {
    enabled: true,
    density: 0.15,
    falloff: 0.4,
    height: -1.0,
    up: Vec3::Y,
    color: FogColor::Fixed([0.8, 0.5, 0.2]),
};

/// A context drawing into a `SIZE`² drawable, path traced when `traced` (noise-free:
/// [`lavapipe::exact_renderer`]), fogged by `fog`.
fn context(traced: bool, fog: Option<FogSettings>) -> Context {
    let mut renderer = lavapipe::exact_renderer(traced);
    if let Some(fog) = fog {
        renderer.set_fog(fog);
    }
    let mut ctx = lavapipe::context_on(renderer);
    ctx.bind_drawable(SIZE, SIZE);
    ctx
}

/// Draws two frames of the lit wall at z = −3 (diffuse 0.6 under a white light at normal
/// incidence); with `glass`, then alpha-blended glass over its left half and an additive black
/// (clear) pass over its right half, both at z = −2. Returns the RGBA8 image, rows bottom up.
fn render(ctx: &mut Context, glass: bool) -> Vec<[u8; 4]> {
    for _ in 0..2 {
        lavapipe::begin_frame_90(ctx, SIZE);
        lavapipe::lit_wall(ctx);
        unsafe {
            if glass {
                dispatch::glEnable(ctx, gl::GL_BLEND);
                dispatch::glDepthMask(ctx, gl::GL_FALSE);
                dispatch::glBlendFunc(ctx, gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA);
                dispatch::glColor4f(ctx, GLASS[0], GLASS[1], GLASS[2], GLASS[3]);
                lavapipe::wall(ctx, [-10.0, 0.0], -2.0);
                dispatch::glBlendFunc(ctx, gl::GL_ONE, gl::GL_ONE);
                dispatch::glColor4f(ctx, 0.0, 0.0, 0.0, 1.0);
                lavapipe::wall(ctx, [0.0, 10.0], -2.0);
                dispatch::glDisable(ctx, gl::GL_BLEND);
                dispatch::glDepthMask(ctx, gl::GL_TRUE);
            }
        }
        ctx.end_frame();
    }
    lavapipe::read_rgba(ctx, SIZE)
}

/// The fog amount on the segment from the eye to the point of eye depth `depth` seen through
/// the centre of pixel (x, y): the density of [`FOG`] integrated numerically (Simpson, f64).
fn fog_amount(x: i32, y: i32, depth: f64) -> f64 {
    let ndc = |i: i32| (i as f64 + 0.5) / SIZE as f64 * 2.0 - 1.0;
    // The frustum's sides are at ±0.1 at the near plane 0.1: x_eye = x_ndc · depth.
    let p = DVec3::new(ndc(x) * depth, ndc(y) * depth, -depth);
    let (rho0, b, origin) = (FOG.density as f64, FOG.falloff as f64, FOG.height as f64);
    let density = |t: f64| rho0 * (-b * (p.y * t - origin)).exp();
    let n = 1000;
    let sum: f64 = (0..=n).map(|i| density(i as f64 / n as f64) * if i == 0 || i == n { 1.0 } else if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
    sum / (3.0 * n as f64) * p.length()
}

/// `mix(color, target, clamp(f, 0, 1))` in 8-bit units.
fn fogged(color: f64, target: f64, f: f64) -> f64 {
    let f = f.clamp(0.0, 1.0);
    color * (1.0 - f) + target * 255.0 * f
}

/// The fog colour's channel `k`.
fn fog_color(k: usize) -> f64 {
    let FogColor::Fixed(c) = FOG.color else { unreachable!("a fixed colour") };
    c[k] as f64
}

/// Each pixel of `image` against `mix(plain, fog colour, F)` of the wall at depth 3; returns
/// the largest difference in 8-bit units and the range of F over the image.
fn check_fogged_wall(mode: &str, plain: &[[u8; 4]], image: &[[u8; 4]]) -> (f64, [f64; 2]) {
    let (mut worst, mut range) = (0.0f64, [f64::MAX, 0.0f64]);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let i = (y * SIZE + x) as usize;
            let f = fog_amount(x, y, 3.0);
            range = [range[0].min(f), range[1].max(f)];
            for k in 0..3 {
                let want = fogged(plain[i][k] as f64, fog_color(k), f);
                let error = (image[i][k] as f64 - want).abs();
                worst = worst.max(error);
                assert!(error <= 1.5, "{mode}: pixel ({x}, {y}) channel {k}: {} against {want:.2} (F = {f:.4})", image[i][k]);
            }
        }
    }
    (worst, range)
}

/// Fogged frames equal the formula in both modes, and the modes agree.
#[test]
fn both_modes_fog_the_wall_as_the_formula_says() {
    let mut images = Vec::new();
    for traced in [false, true] {
        let mode = if traced { "path traced" } else { "raster" };
        let plain = render(&mut context(traced, None), false);
        let centre = plain[(SIZE / 2 * SIZE + SIZE / 2) as usize];
        assert!((centre[0] as f32 - 153.0).abs() <= 2.0, "{mode}: the wall unfogged: {centre:?}");
        let image = render(&mut context(traced, Some(FOG)), false);
        let (worst, range) = check_fogged_wall(mode, &plain, &image);
        assert!(range[0] > 0.2 && range[1] < 1.0 && range[1] - range[0] > 0.1, "F varies with height over the image: {range:?}");
        eprintln!("{mode}: fogged wall within {worst:.2}/255 of the formula (F from {:.3} to {:.3})", range[0], range[1]);
        images.push(image);
    }
    let difference = images[0].iter().zip(&images[1]).flat_map(|(a, b)| (0..3).map(move |k| a[k].abs_diff(b[k]))).max().unwrap_or(0);
    eprintln!("raster against path traced, fogged: largest difference {difference}/255");
    assert!(difference <= 2, "the two modes fog the same wall alike: {difference}/255");
}

/// Glass in front of the fogged wall: alpha-blended glass shows `a · mix(glass, fog, F_n) +
/// (1 − a) · (the fogged wall without glass)`, so the segment behind the glass is counted
/// once; a clear additive pass changes nothing (within 1/255), where fogging it towards the
/// fog colour would add the fog of its segment a second time.
#[test]
fn glass_in_front_of_a_fogged_wall_counts_the_fog_once() {
    for traced in [false, true] {
        let mode = if traced { "path traced" } else { "raster" };
        let wall = render(&mut context(traced, Some(FOG)), false);
        let glass = render(&mut context(traced, Some(FOG)), true);
        let (mut checked, mut worst_clear, mut worst_alpha) = ([0; 2], 0u8, 0.0f64);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let i = (y * SIZE + x) as usize;
                if x < SIZE / 2 - 1 {
                    let f_n = fog_amount(x, y, 2.0);
                    for k in 0..3 {
                        let glass_fogged = fogged(GLASS[k] as f64 * 255.0, fog_color(k), f_n);
                        let want = GLASS[3] as f64 * glass_fogged + (1.0 - GLASS[3] as f64) * wall[i][k] as f64;
                        let error = (glass[i][k] as f64 - want).abs();
                        worst_alpha = worst_alpha.max(error);
                        assert!(error <= 1.5, "{mode}: glass pixel ({x}, {y}) channel {k}: {} against {want:.2}", glass[i][k]);
                    }
                    checked[0] += 1;
                } else if x > SIZE / 2 {
                    for k in 0..3 {
                        let error = glass[i][k].abs_diff(wall[i][k]);
                        worst_clear = worst_clear.max(error);
                        assert!(error <= 1, "{mode}: clear glass at ({x}, {y}) channel {k}: {} against the wall's {}", glass[i][k], wall[i][k]);
                    }
                    checked[1] += 1;
                }
            }
        }
        assert!(checked.iter().all(|&n| n >= 200), "{mode}: both halves checked: {checked:?}");
        eprintln!("{mode}: alpha glass within {worst_alpha:.2}/255 of the expected blend; clear glass within {worst_clear}/255 of no glass");
    }
}
