//! Surfaces of several passes, baked light and emitters (issue 16), on lavapipe, on frames
//! classified as hash tracking classifies them ([`classified`]):
//!
//! - a base texture with a lightmap pass (`GL_DST_COLOR, GL_ZERO`), a lightmap on unit 1, a
//!   detail pass (`GL_DST_COLOR, GL_SRC_COLOR`) and an additive glow pass, each surface traced
//!   `Baked`, show their raster colours through the default tone curve; their passes are not
//!   rasterized a second time over the traced image; with `lightmaps = "ignore"` only the
//!   glow's emission remains;
//! - a vertex-lit model under a baked ceiling is lit by it as a Lambertian surface of white
//!   albedo under a uniform emitter is: its radiance is the ceiling's times the view factor;
//! - an additive glow pass lights the floor under it by the same law, with next-event
//!   estimation of emitters and without (continuation rays alone): the two estimators of one
//!   integral agree, which is what multiple importance sampling promises;
//! - a dynamic light lights a traced floor and not a vertex-lit one (whose colours hold it);
//! - a vertex-lit model reflects the ambient light of its colours, and not the level's light
//!   besides;
//! - a texture environment changed between still frames restarts the accumulation of the
//!   pixels it shows.

use crate::classified;
use crate::lavapipe;

use std::sync::{Arc, Mutex};

use glam::DVec3;
use glrt::frame::Frame;
use glrt::frame::class::{DynamicLight, SurfaceLighting};
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Lightmaps, Settings};
use glrt::render::trace::stats::SceneCounts;
use glrt::translate::{Context, dispatch, gl};

/// Largest difference, per 8-bit channel, between a traced and a raster pixel of a baked
/// surface (8-bit rounding between passes in the raster, the sRGB round trip of the tracer).
const TOLERANCE: i32 = 3;

/// The linear value of an 8-bit sRGB-encoded component.
fn linear(c: f64) -> f64 {
    let c = c / 255.0;
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The 8-bit sRGB encoding of linear value `v`.
fn encoded(v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    255.0 * if v <= 0.0031308 { v * 12.92 } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 }
}

/// A context on lavapipe, path traced with `traced` (else rasterized), its frames classified
/// by `classify`, with a `size`² drawable.
fn context(traced: Option<Settings>, size: i32, classify: impl Fn(&mut Frame) + Send + 'static) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    if let Some(settings) = traced {
        renderer.enable_tracing(settings).expect("the tracer's pipelines");
    }
    let mut ctx = lavapipe::classified_context_on(renderer, classify);
    ctx.bind_drawable(size, size);
    ctx
}

/// The drawable's RGBA8 image (rows bottom to top).
fn read(ctx: &mut Context, size: i32) -> Vec<[u8; 4]> {
    let mut out = vec![[0u8; 4]; (size * size) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, size, size, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    assert_eq!(unsafe { dispatch::glGetError(ctx) }, gl::GL_NO_ERROR);
    out
}

/// Clears colour (black) and depth, enables the depth test.
fn clear(ctx: &mut Context) {
    unsafe {
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
    }
}

// The bands: four surfaces, each a band of 8 rows of a 32² image.

/// Width and height of the bands' image.
const SIZE: i32 = 32;
/// The base texture: 2 × 2 RGBA, rows bottom to top.
const ALBEDO: [u8; 16] = [200, 40, 120, 255, 30, 180, 90, 255, 150, 120, 10, 255, 60, 100, 220, 255];
/// The lightmap.
const LIGHTMAP: [u8; 16] = [180, 180, 180, 255, 90, 140, 200, 255, 255, 230, 200, 255, 120, 120, 120, 255];
/// The detail texture (about 0.5: a 2× modulation keeps the colour near what it was).
const DETAIL: [u8; 16] = [128, 140, 110, 255, 100, 128, 150, 255, 140, 120, 128, 255, 128, 128, 128, 255];
/// The glow texture.
const GLOW: [u8; 16] = [40, 10, 0, 255, 0, 60, 20, 255, 60, 60, 0, 255, 0, 0, 50, 255];

/// How the band's surface is drawn (every result stays below the tone curve's knee, display
/// 231, where it is the identity).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Band {
    /// The base texture, then the lightmap as a pass `GL_DST_COLOR, GL_ZERO`.
    LightmapPass,
    /// The base texture on unit 0, the lightmap modulating on unit 1.
    LightmapUnit,
    /// [`Band::LightmapPass`], then the detail texture as a pass `GL_DST_COLOR, GL_SRC_COLOR`.
    Detail,
    /// [`Band::LightmapPass`], then the glow texture as a pass `GL_ONE, GL_ONE`.
    Glow,
}

const BANDS: [Band; 4] = [Band::LightmapPass, Band::LightmapUnit, Band::Detail, Band::Glow];

/// The quad of band `i` (window rows 8i to 8i + 8): at z = −2, as wide as the 90° view there,
/// (s, t) from (0, 0) to (1, 1) across it on units 0 and 1, white.
fn band_quad(ctx: &mut Context, i: usize) {
    let (y0, y1) = (i as f32 - 2.0, i as f32 - 1.0);
    unsafe {
        dispatch::glColor4f(ctx, 1.0, 1.0, 1.0, 1.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for (x, y, s, t) in [(-2.0, y0, 0.0, 0.0), (2.0, y0, 1.0, 0.0), (2.0, y1, 1.0, 1.0), (-2.0, y1, 0.0, 1.0)] {
            dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE0, s, t);
            dispatch::glMultiTexCoord2f(ctx, gl::GL_TEXTURE1, s, t);
            dispatch::glVertex3f(ctx, x, y, -2.0);
        }
        dispatch::glEnd(ctx);
    }
}

/// Band `i` again as a pass of `texture` on unit 0 blended with (`src`, `dst`), depth-tested
/// `GL_LEQUAL` without depth writes, as Quake 3 draws the later stages of a shader.
fn pass(ctx: &mut Context, i: usize, texture: u32, src: u32, dst: u32) {
    unsafe {
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, texture);
        dispatch::glEnable(ctx, gl::GL_BLEND);
        dispatch::glBlendFunc(ctx, src, dst);
        dispatch::glDepthFunc(ctx, gl::GL_LEQUAL);
        dispatch::glDepthMask(ctx, gl::GL_FALSE);
    }
    band_quad(ctx, i);
    unsafe {
        dispatch::glDisable(ctx, gl::GL_BLEND);
        dispatch::glDepthFunc(ctx, gl::GL_LESS);
        dispatch::glDepthMask(ctx, gl::GL_TRUE);
    }
}

/// The textures of the bands: albedo, lightmap, detail, glow.
type Textures = [u32; 4];

/// Draws band `i` as `band` says.
fn draw_band(ctx: &mut Context, i: usize, band: Band, [albedo, lightmap, detail, glow]: Textures) {
    unsafe {
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE as i32);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, albedo);
        if band == Band::LightmapUnit {
            dispatch::glActiveTexture(ctx, gl::GL_TEXTURE1);
            dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
            dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE as i32);
            dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, lightmap);
        }
    }
    band_quad(ctx, i);
    unsafe {
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE1);
        dispatch::glDisable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glActiveTexture(ctx, gl::GL_TEXTURE0);
    }
    if band != Band::LightmapUnit {
        pass(ctx, i, lightmap, gl::GL_DST_COLOR, gl::GL_ZERO);
    }
    match band {
        Band::Detail => pass(ctx, i, detail, gl::GL_DST_COLOR, gl::GL_SRC_COLOR),
        Band::Glow => pass(ctx, i, glow, gl::GL_ONE, gl::GL_ONE),
        _ => {}
    }
    unsafe { dispatch::glDisable(ctx, gl::GL_TEXTURE_2D) };
}

/// Two frames of the bands under a 90° perspective camera at the origin looking down −z,
/// traced with `traced` (else rasterized), read back.
fn bands(traced: Option<Settings>) -> Vec<[u8; 4]> {
    let mut ctx = context(traced, SIZE, |frame| {
        classified::passes(frame);
        classified::lightmap_units(frame);
    });
    let textures = [ALBEDO, LIGHTMAP, DETAIL, GLOW].map(|t| lavapipe::texture_2x2(&mut ctx, &t));
    for _ in 0..2 {
        clear(&mut ctx);
        unsafe {
            dispatch::glViewport(&mut ctx, 0, 0, SIZE, SIZE);
            dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
            dispatch::glLoadIdentity(&mut ctx);
            dispatch::glFrustum(&mut ctx, -1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
            dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
            dispatch::glLoadIdentity(&mut ctx);
        }
        for (i, band) in BANDS.into_iter().enumerate() {
            draw_band(&mut ctx, i, band, textures);
        }
        ctx.end_frame();
    }
    read(&mut ctx, SIZE)
}

/// The compared pixels of band `i`: away from its texel edges (columns 15, 16; its rows 3, 4)
/// and from its own edges; with the texel (0..4) each shows.
fn compared(i: usize) -> impl Iterator<Item = ((i32, i32), usize)> {
    let y0 = 8 * i as i32;
    (0..SIZE)
        .flat_map(move |x| (y0..y0 + 8).map(move |y| (x, y)))
        .filter(move |&(x, y)| !(15..=16).contains(&x) && !(3..=4).contains(&(y - y0)) && y != y0 && y != y0 + 7)
        .map(move |(x, y)| ((x, y), usize::from(x >= 16) + 2 * usize::from(y - y0 >= 4)))
}

/// The largest RGB difference over band `i`'s compared pixels between `image` and `want`
/// (per pixel and texel), with the pixel where it is.
fn largest_difference(image: &[[u8; 4]], i: usize, want: impl Fn((i32, i32), usize) -> [f64; 3]) -> (f64, (i32, i32)) {
    compared(i)
        .map(|((x, y), texel)| {
            let p = image[(y * SIZE + x) as usize];
            let w = want((x, y), texel);
            ((0..3).map(|c| (p[c] as f64 - w[c]).abs()).fold(0.0, f64::max), (x, y))
        })
        .fold((0.0, (0, 0)), |a, b| if b.0 > a.0 { b } else { a })
}

/// Channel `c` of texel `t` of `texels`, 0 to 1.
fn texel(texels: &[u8; 16], t: usize, c: usize) -> f64 {
    texels[4 * t + c] as f64 / 255.0
}

/// The surfaces of several passes, traced baked, show their raster colours: the tone curve is
/// the identity where they are, baked surfaces emit their raster colour, and the stack of
/// units and passes is the rasterizer's (texture environments, then blend functions in
/// program order).
#[test]
fn baked_surfaces_of_several_passes_match_their_raster_colours() {
    let raster = bands(None);
    let traced = bands(Some(Settings::default()));
    let pixel = |image: &[[u8; 4]], (x, y): (i32, i32)| image[(y * SIZE + x) as usize];
    for (i, band) in BANDS.into_iter().enumerate() {
        assert!(compared(i).count() >= 90, "{band:?}: pixels compared");
        let (d, at) = largest_difference(&traced, i, |p, _| pixel(&raster, p).map(f64::from)[..3].try_into().unwrap());
        assert!(d <= TOLERANCE as f64, "{band:?}: traced {:?} against raster {:?} at {at:?}", pixel(&traced, at), pixel(&raster, at));
        // The raster colour is the stack's: albedo × lightmap (× 2 detail, + glow).
        let stack = |_, t: usize| -> [f64; 3] {
            std::array::from_fn(|c| {
                let lit = texel(&ALBEDO, t, c) * texel(&LIGHTMAP, t, c);
                255.0 * match band {
                    Band::Detail => 2.0 * lit * texel(&DETAIL, t, c),
                    Band::Glow => (lit + texel(&GLOW, t, c)).min(1.0),
                    _ => lit,
                }
            })
        };
        let (d, at) = largest_difference(&raster, i, stack);
        assert!(d <= 2.0, "{band:?}: the raster reads {:?} at {at:?}, not the stack's colour", pixel(&raster, at));
    }
}

/// The passes of a traced surface are evaluated in it, not rasterized over the traced image
/// as well: drawn twice, the glow would add twice and the lightmap multiply twice. In raster
/// mode the same layer draws are rasterized as drawn (the raster image is the stack's,
/// `baked_surfaces_of_several_passes_match_their_raster_colours`).
#[test]
fn passes_of_traced_surfaces_are_not_drawn_again_over_the_traced_image() {
    let traced = bands(Some(Settings::default()));
    let raster = bands(None);
    let twice = |band: Band, p: (i32, i32), t: usize| -> [f64; 3] {
        let r = raster[(p.1 * SIZE + p.0) as usize];
        std::array::from_fn(|c| match band {
            Band::Glow => (r[c] as f64 + 255.0 * texel(&GLOW, t, c)).min(255.0),
            _ => r[c] as f64 * texel(&LIGHTMAP, t, c),
        })
    };
    for (i, band) in [(0, Band::LightmapPass), (3, Band::Glow)] {
        // Some texel of each band shows the difference (the glow is 0 in some channels).
        let (d, at) = largest_difference(&traced, i, |p, t| twice(band, p, t));
        assert!(d > (4 * TOLERANCE) as f64, "{band:?}: the traced band reads {:?} at {at:?}, as if its pass were drawn twice", traced[(at.1 * SIZE + at.0) as usize]);
        let (d, _) = largest_difference(&traced, i, |p, _| raster[(p.1 * SIZE + p.0) as usize].map(f64::from)[..3].try_into().unwrap());
        assert!(d <= TOLERANCE as f64, "{band:?}: and it is the raster colour");
    }
}

/// With `lightmaps = "ignore"` the surfaces are reflectors of their albedo (the lightmaps left
/// out) in a scene without light: black, but for what the glow pass emits, the light it adds
/// to the display: linear(albedo × lightmap + glow) − linear(albedo × lightmap).
#[test]
fn ignored_lightmaps_leave_the_glow_alone() {
    let traced = bands(Some(Settings { lightmaps: Lightmaps::Ignore, ..Settings::default() }));
    for (i, band) in BANDS.into_iter().enumerate() {
        let (d, at) = largest_difference(&traced, i, |_, t| {
            std::array::from_fn(|c| {
                let base = 255.0 * texel(&ALBEDO, t, c) * texel(&LIGHTMAP, t, c);
                let glow = if band == Band::Glow { 255.0 * texel(&GLOW, t, c) } else { 0.0 };
                encoded(linear((base + glow).min(255.0)) - linear(base))
            })
        });
        assert!(d <= TOLERANCE as f64, "{band:?}: {:?} at {at:?}", traced[(at.1 * SIZE + at.0) as usize]);
    }
}

// Light from a ceiling onto a floor.

/// Width and height of the floor scenes' image.
const FLOOR_SIZE: i32 = 24;
/// The floor: y = −1, x in −1.5..1.5, z in −5..−2, facing up.
const FLOOR: [f64; 4] = [-1.5, 1.5, -5.0, -2.0];
/// Height of the ceilings (2 above the floor), facing down.
const CEILING_Y: f64 = 1.0;

/// A horizontal quad at height `y` over `[x0, x1, z0, z1]` of colour `color`.
fn horizontal(ctx: &mut Context, y: f64, [x0, x1, z0, z1]: [f64; 4], color: f32) {
    unsafe {
        dispatch::glColor3f(ctx, color, color, color);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for [x, z] in [[x0, z1], [x1, z1], [x1, z0], [x0, z0]] {
            dispatch::glVertex3f(ctx, x as f32, y as f32, z as f32);
        }
        dispatch::glEnd(ctx);
    }
}

/// A tracing context (`settings`, the default tone curve) with a 60° perspective camera at
/// the origin looking down −z, its frames classified by `classify`, and its renderer.
fn floor_context(settings: Settings, classify: impl Fn(&mut Frame) + Send + 'static) -> (Context, Arc<Mutex<Renderer>>) {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    renderer.enable_tracing(settings).expect("the tracer's pipelines");
    let renderer = Arc::new(Mutex::new(renderer));
    let mut ctx = lavapipe::classified_context_on(lavapipe::Shared(renderer.clone()), classify);
    lavapipe::perspective_60(&mut ctx, FLOOR_SIZE);
    (ctx, renderer)
}

/// What the last traced frame of `renderer` held.
fn counts(renderer: &Arc<Mutex<Renderer>>) -> SceneCounts {
    renderer.lock().unwrap().tracer().expect("tracing").statistics().scene
}

/// The eye-space direction through window position (x, y) (pixel units).
fn window_ray(x: f64, y: f64) -> DVec3 {
    let t = 30f64.to_radians().tan();
    let ndc = |i: f64| (2.0 * i / FLOOR_SIZE as f64 - 1.0) * t;
    DVec3::new(ndc(x), ndc(y), -1.0)
}

/// The pixels that see nothing but the horizontal rectangle `rect` at height `y` (all their
/// corners see it at least `margin` inside its edges), with the point their centre sees.
fn pixels_on(rect: [f64; 4], y: f64, margin: f64) -> Vec<((i32, i32), DVec3)> {
    let on = |d: DVec3| {
        let p = d * (y / d.y);
        d.y * y > 0.0 && p.x > rect[0] + margin && p.x < rect[1] - margin && p.z > rect[2] + margin && p.z < rect[3] - margin
    };
    let mut out = Vec::new();
    for py in 0..FLOOR_SIZE {
        for px in 0..FLOOR_SIZE {
            let (x, y0) = (px as f64, py as f64);
            if [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].iter().all(|&(dx, dy)| on(window_ray(x + dx, y0 + dy))) {
                let d = window_ray(x + 0.5, y0 + 0.5);
                out.push(((px, py), d * (y / d.y)));
            }
        }
    }
    out
}

/// The view factor from a point `p` of the floor (facing up) to the rectangle `rect` at
/// height `CEILING_Y` facing down: ∫ cos θ cos θ' / (π r²) dA = ∫ h² / (π r⁴) dA (h the height
/// above `p`), by the midpoint rule on a 256² grid.
fn view_factor(p: DVec3, rect: [f64; 4]) -> f64 {
    let n = 256;
    let h = CEILING_Y - p.y;
    let (dx, dz) = ((rect[1] - rect[0]) / n as f64, (rect[3] - rect[2]) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let q = DVec3::new(rect[0] + (i as f64 + 0.5) * dx, CEILING_Y, rect[2] + (j as f64 + 0.5) * dz);
            let r2 = (q - p).length_squared();
            sum += h * h / (std::f64::consts::PI * r2 * r2);
        }
    }
    sum * dx * dz
}

/// Over the floor pixels of `image`, the mean of the linear radiance, the mean of `expected`
/// at their points, and the standard error of the first mean (from the residuals, so it
/// holds the tracer's noise and the 8-bit rounding).
fn floor_means(image: &[[u8; 4]], pixels: &[((i32, i32), DVec3)], expected: impl Fn(DVec3) -> f64) -> (f64, f64, f64) {
    let n = pixels.len() as f64;
    let got: Vec<f64> = pixels.iter().map(|&((x, y), _)| linear(f64::from(image[(y * FLOOR_SIZE + x) as usize][0]))).collect();
    let want: Vec<f64> = pixels.iter().map(|&(_, p)| expected(p)).collect();
    let residual: Vec<f64> = got.iter().zip(&want).map(|(g, w)| g - w).collect();
    let mean_residual = residual.iter().sum::<f64>() / n;
    let variance = residual.iter().map(|r| (r - mean_residual).powi(2)).sum::<f64>() / (n - 1.0);
    (got.iter().sum::<f64>() / n, want.iter().sum::<f64>() / n, (variance / n).sqrt())
}

/// A ceiling baked into its vertex colours (grey 0.5: it emits linear(128) = 0.216) over a
/// model whose vertex colours are its lighting (0.1: dark, as a vertex-lit model is in a dim
/// corner): traced, the model takes white for its vertex colours and reflects the ceiling's
/// light. A Lambertian surface of albedo 1 under a uniform emitter of radiance L filling view
/// factor F of its hemisphere reflects exactly L · F: with one bounce, the floor's mean over
/// its pixels is that within 4 standard errors and 3 %, and at least 80 % of it, where the
/// raster image shows 0.1 (linear 0.01). The ceiling itself shows its raster colour.
#[test]
fn a_vertex_lit_model_is_lit_by_the_baked_ceiling_beside_it() {
    const FRAMES: usize = 6;
    let ceiling = [-3.0, 3.0, -7.0, -1.0];
    let (mut ctx, renderer) = floor_context(Settings { spp: 8, bounces: 1, ..Settings::default() }, |frame| {
        classified::lit(frame, |d| d.vertices.position[0][1] > 0.0, SurfaceLighting::Baked);
        classified::lit(frame, |d| d.vertices.position[0][1] < 0.0, SurfaceLighting::VertexLit);
    });
    for _ in 0..FRAMES {
        clear(&mut ctx);
        // Flat shading keeps the ceiling a draw of its own.
        unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_FLAT) };
        horizontal(&mut ctx, CEILING_Y, ceiling, 0.5);
        unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_SMOOTH) };
        horizontal(&mut ctx, -1.0, FLOOR, 0.1);
        ctx.end_frame();
    }
    let image = read(&mut ctx, FLOOR_SIZE);
    assert_eq!(counts(&renderer).emitters, 0, "a baked surface's light is everywhere: not in the emitter list");
    let light = linear(128.0);
    let floor = pixels_on(FLOOR, -1.0, 0.02);
    assert!(floor.len() >= 30, "{} floor pixels", floor.len());
    let (got, want, error) = floor_means(&image, &floor, |p| light * view_factor(p, ceiling));
    eprintln!("vertex-lit floor under the baked ceiling: {got:.4} ± {error:.4}, the law {want:.4}, over {} pixels", floor.len());
    assert!(want > 0.08, "the ceiling fills a good part of the floor's sky: {want:.3}");
    assert!((got - want).abs() <= 4.0 * error + 0.03 * want, "the floor reads {got:.4} in the mean, the ceiling's light times the view factor {want:.4} (± {error:.4})");
    assert!(got >= 0.8 * want && got > 10.0 * linear(26.0), "lit, not dark: {got:.4}");
    let ceiling_pixels = pixels_on(ceiling, CEILING_Y, 0.02);
    assert!(!ceiling_pixels.is_empty());
    for ((x, y), _) in ceiling_pixels {
        let p = image[(y * FLOOR_SIZE + x) as usize];
        assert!(p[..3].iter().all(|&c| c.abs_diff(128) <= 1), "the baked ceiling shows its raster colour: {p:?} at ({x}, {y})");
    }
}

/// A dynamic light (white, 0.5 above the floor's middle, radius 2) over a grey floor of two
/// halves: the left one a vertex-lit model (games add the dynamic lights near a model to its
/// colours, as Quake 3's `R_SetupEntityLighting` does: lit again, it would be lit twice), the
/// right one traced. With nothing else lighting them, the right half is lit (its pixels' mean
/// at least 20 levels above the frame without the light; 32 measured) and the left one
/// stays as dark as without the light (its pixels' mean within 0.5 of a level of the frame
/// without it, in which both are black).
#[test]
fn a_dynamic_light_does_not_light_a_vertex_lit_model_again() {
    let image = |light: bool| {
        let (mut ctx, _renderer) = floor_context(Settings { spp: 4, bounces: 1, ..Settings::default() }, move |frame| {
            classified::lit(frame, |d| d.vertices.position[0][0] < 0.0, SurfaceLighting::VertexLit);
            if light {
                frame.lights.push(DynamicLight { position: [0.0, -0.5, -3.5], color: [1.0; 3], radius: 2.0, falloff: 0.25, axis: [0.0, 1.0, 0.0], floor: 0.3, modulates: false });
            }
        });
        for _ in 0..2 {
            clear(&mut ctx);
            unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_FLAT) };
            horizontal(&mut ctx, -1.0, [FLOOR[0], 0.0, FLOOR[2], FLOOR[3]], 0.5);
            unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_SMOOTH) };
            horizontal(&mut ctx, -1.0, [0.0, FLOOR[1], FLOOR[2], FLOOR[3]], 0.5);
            ctx.end_frame();
        }
        read(&mut ctx, FLOOR_SIZE)
    };
    let (lit, dark) = (image(true), image(false));
    let mean = |image: &[[u8; 4]], rect: [f64; 4]| {
        let pixels = pixels_on(rect, -1.0, 0.02);
        assert!(pixels.len() >= 30, "{} pixels", pixels.len());
        pixels.iter().map(|&((x, y), _)| f64::from(image[(y * FLOOR_SIZE + x) as usize][0])).sum::<f64>() / pixels.len() as f64
    };
    let (left, right) = ([FLOOR[0], 0.0, FLOOR[2], FLOOR[3]], [0.0, FLOOR[1], FLOOR[2], FLOOR[3]]);
    let (model_lit, model_dark, floor_lit, floor_dark) = (mean(&lit, left), mean(&dark, left), mean(&lit, right), mean(&dark, right));
    eprintln!("dynamic light: vertex-lit half {model_lit:.2} (without it {model_dark:.2}), traced half {floor_lit:.2} (without it {floor_dark:.2})");
    assert!(floor_lit >= floor_dark + 20.0, "the light lights the traced half: {floor_lit:.2} against {floor_dark:.2}");
    assert!((model_lit - model_dark).abs() <= 0.5, "the vertex-lit half is not lit again: {model_lit:.2} against {model_dark:.2}");
}

/// A sphere of `radius` around `centre` (eye space), its vertices' colours lit as Quake 3
/// lights a model: `ambient + max(0, n · towards) · directed` (grey), with their normals; 12
/// rows of 24 quads as separate triangles.
fn lit_sphere(ctx: &mut Context, centre: DVec3, radius: f64, towards: DVec3, [ambient, directed]: [f64; 2]) {
    let (rows, columns) = (12, 24);
    let normal = |r: usize, c: usize| {
        let (theta, phi) = (std::f64::consts::PI * r as f64 / rows as f64, std::f64::consts::TAU * c as f64 / columns as f64);
        DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
    };
    unsafe {
        dispatch::glBegin(ctx, gl::GL_TRIANGLES);
        for r in 0..rows {
            for c in 0..columns {
                for (r, c) in [(r, c), (r + 1, c), (r + 1, c + 1), (r, c), (r + 1, c + 1), (r, c + 1)] {
                    let n = normal(r, c);
                    let light = (ambient + directed * n.dot(towards).max(0.0)).min(1.0) as f32;
                    let p = centre + n * radius;
                    dispatch::glColor3f(ctx, light, light, light);
                    dispatch::glNormal3f(ctx, n.x as f32, n.y as f32, n.z as f32);
                    dispatch::glVertex3f(ctx, p.x as f32, p.y as f32, p.z as f32);
                }
            }
        }
        dispatch::glEnd(ctx);
    }
}

/// The mean 8-bit red of the pixels of `image` that see the sphere of `radius` around
/// `centre` at least `margin` inside its outline (all four corners' rays).
fn sphere_mean(image: &[[u8; 4]], centre: DVec3, radius: f64, margin: f64) -> (f64, usize) {
    let inside = |d: DVec3| {
        let d = d.normalize();
        (centre - d * d.dot(centre)).length() < radius - margin
    };
    let pixels: Vec<f64> = (0..FLOOR_SIZE * FLOOR_SIZE)
        .filter(|i| {
            let (x, y) = (f64::from(i % FLOOR_SIZE), f64::from(i / FLOOR_SIZE));
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].iter().all(|&(dx, dy)| inside(window_ray(x + dx, y + dy)))
        })
        .map(|i| f64::from(image[i as usize][0]))
        .collect();
    (pixels.iter().sum::<f64>() / pixels.len() as f64, pixels.len())
}

/// A vertex-lit model's ambient light is light from every direction: a sphere whose colours
/// are lit as Quake 3 lights a model, ambient 0.3 and directed 0.6 from straight behind it,
/// shows the camera its side that only the ambient lights (the raster image: 0.3, 76.5 of
/// 255). Traced with nothing else in the scene, it reflects that ambient (its mean within
/// 6 % of 76.5; black without it); under a bright baked ceiling (grey 0.8) farther from it
/// than it is wide, it shows the same, not the ceiling's light besides (the ambient is the
/// level's light at the model: both would count it twice): the two means within 2 levels.
#[test]
fn a_vertex_lit_model_takes_its_ambient_light_from_every_direction_once() {
    let (centre, radius) = (DVec3::new(0.0, 0.0, -4.0), 1.5);
    let image = |ceiling: bool| {
        let (mut ctx, _renderer) = floor_context(Settings { spp: 16, bounces: 1, ..Settings::default() }, |frame| {
            classified::without_world(frame);
            classified::lit(frame, |d| d.vertices.position[0][1] > 4.0, SurfaceLighting::Baked);
            classified::lit(frame, |d| d.vertices.position[0][1] <= 4.0, SurfaceLighting::VertexLit);
        });
        for _ in 0..3 {
            clear(&mut ctx);
            if ceiling {
                unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_FLAT) };
                horizontal(&mut ctx, 5.0, [-10.0, 10.0, -14.0, 0.0], 0.8);
                unsafe { dispatch::glShadeModel(&mut ctx, gl::GL_SMOOTH) };
            }
            lit_sphere(&mut ctx, centre, radius, DVec3::NEG_Z, [0.3, 0.6]);
            ctx.end_frame();
        }
        read(&mut ctx, FLOOR_SIZE)
    };
    let ((alone, pixels), (under, _)) = (sphere_mean(&image(false), centre, radius, 0.1), sphere_mean(&image(true), centre, radius, 0.1));
    let raster = 0.3 * 255.0;
    eprintln!("vertex-lit sphere's ambient side over {pixels} pixels: alone {alone:.2}, under a baked ceiling {under:.2}, raster {raster:.1}");
    assert!(pixels >= 100, "{pixels} pixels");
    assert!((alone - raster).abs() <= 0.06 * raster, "lit by its ambient as the raster shows it: {alone:.2} against {raster:.1}");
    assert!((under - alone).abs() <= 2.0, "not lit a second time by the ceiling: {under:.2} against {alone:.2}");
}

/// The image of a floor (unlit, white: albedo 1, its light traced) under a black patch of
/// ceiling with an additive glow pass of grey 0.8 (emission linear(204) = 0.604), accumulated
/// over `frames` frames, emitters sampled as `sample_emitters` says; with what the last frame
/// held.
fn glow_over_floor(glow: [f64; 4], sample_emitters: bool, frames: usize) -> (Vec<[u8; 4]>, SceneCounts) {
    let (mut ctx, renderer) = floor_context(Settings { spp: 16, bounces: 1, sample_emitters, ..Settings::default() }, classified::passes);
    for _ in 0..frames {
        clear(&mut ctx);
        horizontal(&mut ctx, CEILING_Y, glow, 0.0);
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_BLEND);
            dispatch::glBlendFunc(&mut ctx, gl::GL_ONE, gl::GL_ONE);
            dispatch::glDepthFunc(&mut ctx, gl::GL_LEQUAL);
            dispatch::glDepthMask(&mut ctx, gl::GL_FALSE);
        }
        horizontal(&mut ctx, CEILING_Y, glow, 0.8);
        unsafe {
            dispatch::glDisable(&mut ctx, gl::GL_BLEND);
            dispatch::glDepthFunc(&mut ctx, gl::GL_LESS);
            dispatch::glDepthMask(&mut ctx, gl::GL_TRUE);
        }
        horizontal(&mut ctx, -1.0, FLOOR, 1.0);
        ctx.end_frame();
    }
    (read(&mut ctx, FLOOR_SIZE), counts(&renderer))
}

/// An additive glow pass is light: the floor under it reflects its emission times the view
/// factor (albedo 1), found by next-event estimation of the emitter list and by continuation
/// rays, weighted by multiple importance sampling, or by continuation rays alone. Both
/// estimate the same integral: their means agree within 4 standard errors of their
/// difference, and each is the view-factor law's within 4 standard errors and 3 %.
/// Sampling the emitters (the glow's two triangles) makes the floor much less noisy.
#[test]
fn a_glow_pass_lights_the_floor_beside_it_with_and_without_emitter_sampling() {
    const FRAMES: usize = 8;
    let glow = [-1.0, 1.0, -4.5, -2.5];
    let emission = linear(204.0);
    let floor = pixels_on(FLOOR, -1.0, 0.02);
    let law = |p| emission * view_factor(p, glow);
    let (image, with) = glow_over_floor(glow, true, FRAMES);
    let (sampled, want, sampled_error) = floor_means(&image, &floor, law);
    let (image, without) = glow_over_floor(glow, false, FRAMES);
    let (found, _, found_error) = floor_means(&image, &floor, law);
    assert_eq!((with.passes, with.emitters, without.passes, without.emitters), (1, 2, 1, 0), "the glow is a pass of its surface, and its two triangles the emitter list");
    eprintln!("floor under the glow: sampled {sampled:.4} ± {sampled_error:.4}, continuation rays alone {found:.4} ± {found_error:.4}, the law {want:.4}, over {} pixels", floor.len());
    assert!(want > 0.05, "the glow lights the floor measurably: {want:.3}");
    for (what, got, error) in [("sampled", sampled, sampled_error), ("found by continuation rays", found, found_error)] {
        assert!((got - want).abs() <= 4.0 * error + 0.03 * want, "{what}: the floor reads {got:.4} in the mean, the glow's light times the view factor {want:.4} (± {error:.4})");
    }
    let both = (sampled_error.powi(2) + found_error.powi(2)).sqrt();
    assert!((sampled - found).abs() <= 4.0 * both, "with emitter sampling {sampled:.4}, without {found:.4} (± {both:.4})");
    assert!(sampled_error < 0.5 * found_error, "emitter sampling lowers the noise: ± {sampled_error:.4} against ± {found_error:.4}");
}

// Accumulation.

/// Frames of a still camera accumulate into one mean, but a surface whose texture environment
/// changes shows its new colour at once: the material is part of what a pixel's history is
/// of. A baked quad textured `GL_REPLACE` (the texture's colour) for four frames, then
/// `GL_MODULATE` by its vertex colour 0.5 (half of it), traced: the fifth frame shows the
/// raster's fifth frame, not a mean of the two. (The static world is left out: it keeps the
/// quad of the old material as a chunk for a few frames, until it releases it.)
#[test]
fn a_new_texture_environment_restarts_the_accumulation_of_its_pixels() {
    let render = |traced: Option<Settings>| {
        let mut ctx = context(traced, SIZE, |frame| {
            classified::without_world(frame);
            classified::lit(frame, |_| true, SurfaceLighting::Baked);
        });
        let albedo = lavapipe::texture_2x2(&mut ctx, &ALBEDO);
        let mut images = Vec::new();
        for frame in 0..5 {
            clear(&mut ctx);
            unsafe {
                dispatch::glViewport(&mut ctx, 0, 0, SIZE, SIZE);
                dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
                dispatch::glLoadIdentity(&mut ctx);
                dispatch::glFrustum(&mut ctx, -1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
                dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
                dispatch::glLoadIdentity(&mut ctx);
                dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
                dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, albedo);
                let mode = if frame < 4 { gl::GL_REPLACE } else { gl::GL_MODULATE };
                dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, mode as i32);
                dispatch::glColor3f(&mut ctx, 0.5, 0.5, 0.5);
                dispatch::glBegin(&mut ctx, gl::GL_QUADS);
                for (x, y, s, t) in [(-2.0, -2.0, 0.0, 0.0), (2.0, -2.0, 1.0, 0.0), (2.0, 2.0, 1.0, 1.0), (-2.0, 2.0, 0.0, 1.0)] {
                    dispatch::glTexCoord2f(&mut ctx, s, t);
                    dispatch::glVertex3f(&mut ctx, x, y, -2.0);
                }
                dispatch::glEnd(&mut ctx);
                dispatch::glDisable(&mut ctx, gl::GL_TEXTURE_2D);
            }
            ctx.end_frame();
            if frame >= 3 {
                images.push(read(&mut ctx, SIZE));
            }
        }
        images
    };
    let raster = render(None);
    let traced = render(Some(Settings::default()));
    // Texel centres: pixels (8, 8), (24, 8), (8, 24), (24, 24).
    let centres = [(8, 8), (24, 8), (8, 24), (24, 24)];
    let at = |image: &[[u8; 4]], (x, y): (i32, i32)| image[(y * SIZE + x) as usize];
    assert!(centres.iter().any(|&p| at(&raster[0], p)[0].abs_diff(at(&raster[1], p)[0]) > 4 * TOLERANCE as u8), "the two environments show other colours");
    for (frame, (traced, raster)) in traced.iter().zip(&raster).enumerate() {
        for &p in &centres {
            let (t, r) = (at(traced, p), at(raster, p));
            assert!((0..3).all(|c| (t[c] as i32 - r[c] as i32).abs() <= TOLERANCE), "frame {}: traced {t:?} against raster {r:?} at {p:?}", frame + 3);
        }
    }
}
