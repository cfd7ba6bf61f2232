//! The path tracer applies the texture environment as the rasterizer does (issue 15, item 5):
//! both evaluate `shaders/texenv.glsl`, so draws combined with `GL_COMBINE` look the same
//! traced and rasterized. The scene is four unlit bands of vertex-coloured, textured quads
//! facing a perspective camera, each band one environment:
//!
//! - `GL_INTERPOLATE` of the texture and the constant colour by the primary colour's alpha;
//! - `GL_ADD_SIGNED` of the texture and the constant colour, `RGB_SCALE` 2;
//! - unit 0 modulating the primary colour, unit 1 `GL_MODULATE` of unit 0's texture (crossbar
//!   `GL_TEXTURE0`) and its own, `RGB_SCALE` 2: a modulate × 2 of two units;
//! - a control: `GL_MODULATE` with the unit-1 texture on unit 0.
//!
//! Unlit traced draws show their colour as emitted light: the unit-0 texture is tagged
//! `emissive` in the process's `glrt.toml` (its emission is its albedo, the texture
//! environment's result decoded to linear), the camera sees it directly (no bounce, no light,
//! black environment) and the output is its encoding (tone mapping off), so each traced pixel
//! is the raster pixel up to 8-bit rounding. The control band's texture is not tagged: traced,
//! it emits nothing and stays black, which shows that the bands are traced, not rasterized.
//! Textures are 2 × 2, nearest-filtered, with texel edges on pixel edges (each quad fills the
//! view's width at its depth); the pixels next to a texel edge are not compared.

mod lavapipe;

use std::sync::Arc;

use glrt::frame::texture::{TexImage, TextureContent};
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Lightmaps, Settings, Tonemap};
use glrt::translate::classify::texture_hash::content_hash;
use glrt::translate::{Context, dispatch, gl};

/// Window size: four bands of 8 rows.
const SIZE: i32 = 32;
/// Largest difference, per 8-bit channel, between a traced and a raster pixel (interpolation
/// and the sRGB round trip of the tracer's radiance).
const TOLERANCE: i32 = 3;
/// The unit-0 texture: 2 × 2 RGBA, rows bottom to top.
const TEXTURE0: [u8; 16] = [200, 40, 120, 255, 30, 180, 90, 128, 250, 250, 10, 64, 60, 100, 220, 200];
/// The unit-1 texture.
const TEXTURE1: [u8; 16] = [128, 200, 60, 255, 255, 64, 180, 255, 90, 140, 240, 255, 170, 120, 30, 255];
/// `GL_TEXTURE_ENV_COLOR` of the combiners.
const CONSTANT: [f32; 4] = [0.2, 0.6, 0.9, 0.5];

/// The bands' environments.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Band {
    Interpolate,
    AddSigned,
    TwoUnitsModulateX2,
    /// `GL_MODULATE` of an untagged texture: not emissive.
    Control,
}

const BANDS: [Band; 4] = [Band::Interpolate, Band::AddSigned, Band::TwoUnitsModulateX2, Band::Control];

/// Points `GLRT_CONFIG` at a `glrt.toml` tagging the unit-0 texture `emissive` (its hash is
/// that of its canonical RGBA8 level 0), before any context reads the configuration.
fn tag_texture0_emissive() {
    let image = TexImage { width: 2, height: 2, depth: 1, texels: TEXTURE0.to_vec(), ..TexImage::default() };
    let content = TextureContent { faces: vec![vec![Some(Arc::new(image))]], ..TextureContent::default() };
    let path = std::env::temp_dir().join(format!("glrt-pathtrace-texenv-{}.toml", std::process::id()));
    std::fs::write(&path, format!("emissive = [\"{:#x}\"]\n", content_hash(&content))).expect("writing glrt.toml");
    // Safety: set before this binary's first context reads the configuration; the one test
    // sets it.
    unsafe { std::env::set_var("GLRT_CONFIG", &path) };
}

/// A context drawing into a `SIZE`² drawable, path traced (one sample through each pixel
/// centre, no bounce, tone mapping off) when `traced`.
fn context(traced: bool) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    if traced {
        // Lightmaps ignored: every band reflects traced light (none here), so only the emissive tag lights
        // a band; the control band, unlit and not emissive, stays black (with `keep` its varying
        // colours would make it a baked surface showing its raster colour).
        let settings = Settings { spp: 1, bounces: 0, tonemap: Tonemap::Clamp, exposure: 0.0, lightmaps: Lightmaps::Ignore, ..Settings::default() };
        renderer.enable_tracing(settings).expect("the tracer's pipelines");
    }
    let mut ctx = lavapipe::context_on(renderer);
    ctx.bind_drawable(SIZE, SIZE);
    ctx
}

/// `glTexEnvi(GL_TEXTURE_ENV, pname, value)` on the active unit.
fn env(ctx: &mut Context, pname: u32, value: u32) {
    unsafe { dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, pname, value as i32) };
}

/// One combiner of `GL_COMBINE`: function, sources, operands and scale.
type Combiner = (u32, [u32; 3], [u32; 3], f32);

/// The active unit in `GL_COMBINE` mode with every parameter of both combiners set.
fn combine(ctx: &mut Context, rgb: Combiner, alpha: Combiner) {
    env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE);
    for (c, (function, sources, operands, scale)) in [rgb, alpha].into_iter().enumerate() {
        let [function_name, source0, operand0, scale_name] = if c == 0 {
            [gl::GL_COMBINE_RGB, gl::GL_SOURCE0_RGB, gl::GL_OPERAND0_RGB, gl::GL_RGB_SCALE]
        } else {
            [gl::GL_COMBINE_ALPHA, gl::GL_SOURCE0_ALPHA, gl::GL_OPERAND0_ALPHA, gl::GL_ALPHA_SCALE]
        };
        env(ctx, function_name, function);
        for i in 0..3 {
            env(ctx, source0 + i as u32, sources[i]);
            env(ctx, operand0 + i as u32, operands[i]);
        }
        unsafe { dispatch::glTexEnvf(ctx, gl::GL_TEXTURE_ENV, scale_name, scale) };
    }
}

/// Sets up the texture units for `band`, or plain `GL_MODULATE` on unit 0 alone when
/// `modulate` (what the tracer used to fall back to). Every parameter a band uses is set, so
/// no band inherits another's.
fn setup(ctx: &mut Context, band: Band, textures: [u32; 2], modulate: bool) {
    unsafe {
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, textures[usize::from(band == Band::Control)]);
        dispatch::glTexEnvfv(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, CONSTANT.as_ptr());
    }
    let (texture, constant, primary, previous) = (gl::GL_TEXTURE, gl::GL_CONSTANT, gl::GL_PRIMARY_COLOR, gl::GL_PREVIOUS);
    let (color, alpha) = (gl::GL_SRC_COLOR, gl::GL_SRC_ALPHA);
    if modulate || band == Band::Control {
        env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE);
        return;
    }
    match band {
        Band::Interpolate => combine(
            ctx,
            (gl::GL_INTERPOLATE, [texture, constant, primary], [color, color, alpha], 1.0),
            (gl::GL_ADD, [texture, constant, primary], [alpha, alpha, alpha], 1.0),
        ),
        Band::AddSigned => combine(
            ctx,
            (gl::GL_ADD_SIGNED, [texture, constant, primary], [color, gl::GL_ONE_MINUS_SRC_COLOR, color], 2.0),
            (gl::GL_MODULATE, [texture, primary, constant], [alpha, alpha, alpha], 1.0),
        ),
        Band::TwoUnitsModulateX2 => {
            env(ctx, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE);
            unsafe {
                dispatch::glActiveTexture(ctx, gl::GL_TEXTURE1);
                dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
                dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, textures[1]);
            }
            combine(
                ctx,
                (gl::GL_MODULATE, [gl::GL_TEXTURE0, texture, constant], [color, color, color], 2.0),
                (gl::GL_MODULATE, [texture, previous, constant], [alpha, alpha, alpha], 1.0),
            );
        }
        Band::Control => unreachable!("set up above"),
    }
}

/// Leaves both units disabled, unit 0 active.
fn teardown(ctx: &mut Context) {
    unsafe {
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE1);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
    }
}

/// The quad of band `i` (window rows 8i to 8i + 8): at z = −2, as wide as the view there,
/// both units' (s, t) from (0, 0) to (1, 1) across it, with a primary colour of its own at
/// each corner.
fn band_quad(ctx: &mut Context, i: usize) {
    let (y0, y1) = (i as f32 - 2.0, i as f32 - 1.0);
    let colors: [[u8; 4]; 4] = [[255, 102, 51, 255], [51, 204, 153, 102], [153, 51, 255, 0], [255, 255, 102, 204]];
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for ((x, y, s, t), c) in [(-2.0, y0, 0.0, 0.0), (2.0, y0, 1.0, 0.0), (2.0, y1, 1.0, 1.0), (-2.0, y1, 0.0, 1.0)].into_iter().zip(colors) {
            dispatch::glColor4ub(ctx, c[0], c[1], c[2], c[3]);
            dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE0, s, t);
            dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE1, s, t);
            dispatch::glVertex3f(ctx, x, y, -2.0);
        }
        dispatch::glEnd(ctx);
    }
}

/// Draws two frames of the bands (each `GL_MODULATE` instead when `modulate`) under a 90°
/// perspective camera at the origin looking down −z, and reads the RGBA8 image back (rows
/// bottom to top).
fn render(ctx: &mut Context, modulate: bool) -> Vec<[u8; 4]> {
    let textures = [lavapipe::texture_2x2(ctx, &TEXTURE0), lavapipe::texture_2x2(ctx, &TEXTURE1)];
    for _ in 0..2 {
        unsafe {
            dispatch::glViewport(ctx, 0, 0, SIZE, SIZE);
            dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
            dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
            dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
            dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
            dispatch::glLoadIdentity(ctx);
            dispatch::glFrustum(ctx, -1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
            dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
            dispatch::glLoadIdentity(ctx);
        }
        for (i, band) in BANDS.into_iter().enumerate() {
            setup(ctx, band, textures, modulate);
            band_quad(ctx, i);
            teardown(ctx);
        }
        ctx.end_frame();
    }
    let mut out = vec![[0u8; 4]; (SIZE * SIZE) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    assert_eq!(unsafe { dispatch::glGetError(ctx) }, gl::GL_NO_ERROR);
    out
}

/// The compared pixels of band `i`: away from its texel edges (columns 15, 16; its rows 3, 4)
/// and from its own edges.
fn compared(i: usize) -> impl Iterator<Item = (i32, i32)> {
    let y0 = 8 * i as i32;
    (0..SIZE).flat_map(move |x| (y0..y0 + 8).map(move |y| (x, y))).filter(move |&(x, y)| !(15..=16).contains(&x) && !(3..=4).contains(&(y - y0)) && y != y0 && y != y0 + 7)
}

/// The largest channel difference (RGB) between `a` and `b` over band `i`'s compared pixels,
/// with the pixel where it is.
fn largest_difference(a: &[[u8; 4]], b: &[[u8; 4]], i: usize) -> (i32, (i32, i32)) {
    compared(i)
        .map(|(x, y)| {
            let k = (y * SIZE + x) as usize;
            ((0..3).map(|c| (a[k][c] as i32 - b[k][c] as i32).abs()).max().unwrap_or(0), (x, y))
        })
        .max()
        .unwrap_or_default()
}

#[test]
fn traced_combiners_match_their_raster_colours() {
    tag_texture0_emissive();
    let raster = render(&mut context(false), false);
    let traced = render(&mut context(true), false);
    // The scene tells the environments apart: with plain GL_MODULATE (the tracer's old
    // fallback for GL_COMBINE, which also left unit 1 out) every band reads other colours.
    let modulated = render(&mut context(false), true);
    let control = BANDS.len() - 1;
    let black = vec![[0, 0, 0, 255]; (SIZE * SIZE) as usize];
    let (lit, at) = largest_difference(&traced, &black, control);
    assert_eq!(lit, 0, "the control band is traced (unlit, not emissive: black), but {:?} at {at:?}", traced[(at.1 * SIZE + at.0) as usize]);
    assert!(largest_difference(&raster, &black, control).0 > 4 * TOLERANCE, "rasterized, the control band is not black");
    for (i, band) in BANDS.into_iter().enumerate().take(control) {
        assert!(compared(i).count() >= 90, "{band:?}: pixels compared");
        let (fallback, at) = largest_difference(&raster, &modulated, i);
        assert!(fallback > 4 * TOLERANCE, "{band:?}: GL_MODULATE differs by {fallback} at most (at {at:?})");
        let (d, at) = largest_difference(&traced, &raster, i);
        let k = (at.1 * SIZE + at.0) as usize;
        assert!(d <= TOLERANCE, "{band:?}: traced {:?} against raster {:?} at {at:?}", traced[k], raster[k]);
    }
}
