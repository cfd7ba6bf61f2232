//! Composition of the path-traced image with the raster path (issue 6, part 4; thesis 4.3.6):
//! glass (`Translucent`) blends over the traced image and is hidden behind traced surfaces by
//! the traced depth, and the HUD (`Overlay`) is drawn over everything, so both look as they do
//! in raster mode.
//!
//! The traced scene is noise-free (a lit wall at normal incidence under a directional light of
//! no angular size, one sample through each pixel centre, no bounce, a black sky), so each
//! comparison is exact up to 8-bit rounding: glass over the wall = the blend of the glass colour
//! with the wall's pixel of the same frame drawn without glass, in both modes; glass behind the
//! wall changes nothing; HUD pixels equal the raster HUD's.

use crate::lavapipe;

use std::sync::{Arc, Mutex};

use glrt::render::frame::Renderer;
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 24;
/// The glass colour (RGBA, blended with `GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA`).
const GLASS: [f32; 4] = [0.2, 0.4, 1.0, 0.5];
/// The HUD square's colour and its window rectangle (x0, y0, x1, y1).
const HUD: [f32; 3] = [1.0, 0.75, 0.0];
const HUD_RECT: [i32; 4] = [1, 1, 7, 5];

/// A context drawing into a `SIZE`² drawable, path traced when `traced`, with a perspective
/// camera at the origin looking down −z, and its renderer.
fn shared_context(traced: bool) -> (Context, Arc<Mutex<Renderer>>) {
    let renderer = Arc::new(Mutex::new(lavapipe::exact_renderer(traced)));
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(lavapipe::Shared(renderer.clone())) });
    ctx.bind_drawable(SIZE, SIZE);
    (ctx, renderer)
}

/// [`shared_context`]'s context.
fn context(traced: bool) -> Context {
    shared_context(traced).0
}

/// Draws two frames: a lit wall at z = −3 filling the view; with `extras`, then glass over
/// its left half (z = −2), glass behind it on the right (z = −5) and the HUD square. Returns
/// the RGBA8 image (rows bottom to top). With `read_before_hud` (and `extras`), the second
/// frame is also read back before its HUD, into it.
fn render(ctx: &mut Context, extras: bool, mut read_before_hud: Option<&mut Vec<[u8; 4]>>) -> Vec<[u8; 4]> {
    for frame in 0..2 {
        lavapipe::begin_frame_90(ctx, SIZE);
        lavapipe::lit_wall(ctx);
        unsafe {
            if extras {
                dispatch::glEnable(ctx, gl::GL_BLEND);
                dispatch::glBlendFunc(ctx, gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA);
                dispatch::glDepthMask(ctx, gl::GL_FALSE);
                dispatch::glColor4f(ctx, GLASS[0], GLASS[1], GLASS[2], GLASS[3]);
                lavapipe::wall(ctx, [-10.0, 0.0], -2.0);
                lavapipe::wall(ctx, [0.0, 10.0], -5.0);
                dispatch::glDisable(ctx, gl::GL_BLEND);
                dispatch::glDepthMask(ctx, gl::GL_TRUE);
                if frame == 1
                    && let Some(image) = read_before_hud.as_deref_mut()
                {
                    *image = lavapipe::read_rgba(ctx, SIZE);
                }

                lavapipe::window_ortho(ctx, SIZE);
                dispatch::glColor3f(ctx, HUD[0], HUD[1], HUD[2]);
                let [x0, y0, x1, y1] = HUD_RECT.map(|v| v as f32);
                dispatch::glRectf(ctx, x0, y0, x1, y1);
            }
        }
        ctx.end_frame();
    }
    lavapipe::read_rgba(ctx, SIZE)
}

/// Whether window pixel (x, y) lies in the HUD square.
fn in_hud(x: i32, y: i32) -> bool {
    let [x0, y0, x1, y1] = HUD_RECT;
    (x0..x1).contains(&x) && (y0..y1).contains(&y)
}

/// Checks one mode's image with extras against its image without: returns the number of
/// pixels checked in each region (glass in front, glass behind, HUD).
fn check_composition(mode: &str, plain: &[[u8; 4]], composed: &[[u8; 4]]) -> [usize; 3] {
    let mut counts = [0; 3];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let i = (y * SIZE + x) as usize;
            let (p, c) = (plain[i], composed[i]);
            if in_hud(x, y) {
                let hud = HUD.map(|v| (v * 255.0).round() as u8);
                assert_eq!(c[..3], hud, "{mode}: HUD pixel ({x}, {y})");
                counts[2] += 1;
            } else if x < SIZE / 2 - 1 {
                // Glass in front: alpha blending of the glass colour over the wall's pixel.
                for k in 0..3 {
                    let expected = GLASS[3] * GLASS[k] * 255.0 + (1.0 - GLASS[3]) * p[k] as f32;
                    assert!((c[k] as f32 - expected).abs() <= 1.5, "{mode}: glass pixel ({x}, {y}) channel {k}: {} against {expected} (wall {})", c[k], p[k]);
                }
                counts[0] += 1;
            } else if x > SIZE / 2 {
                assert_eq!(c[..3], p[..3], "{mode}: glass behind the wall must be hidden at ({x}, {y})");
                counts[1] += 1;
            }
        }
    }
    counts
}

#[test]
fn glass_and_hud_compose_over_the_traced_image_as_in_raster_mode() {
    let mut traced = context(true);
    let traced_plain = render(&mut traced, false, None);
    let traced_composed = render(&mut traced, true, None);
    let mut raster = context(false);
    let raster_plain = render(&mut raster, false, None);
    let raster_composed = render(&mut raster, true, None);

    // The traced wall is lit: encode(0.6 decoded · cos 0) = 0.6 · 255 after the round trip.
    let centre = traced_plain[(SIZE / 2 * SIZE + SIZE / 2) as usize];
    assert!((centre[0] as f32 - 153.0).abs() <= 2.0, "the traced wall: {centre:?}");

    let traced_counts = check_composition("path traced", &traced_plain, &traced_composed);
    let raster_counts = check_composition("raster", &raster_plain, &raster_composed);
    assert_eq!(traced_counts, raster_counts);
    assert!(traced_counts.iter().all(|&n| n >= 24), "every region was checked: {traced_counts:?}");
}

/// A traced frame read back before its end (after the glass, before the HUD) shows the traced
/// wall under the glass, and ends as the same frame read only at its end, traced once: the
/// traced stages ran at the read and not again, and the HUD drawn after the read is there.
#[test]
fn a_traced_frame_read_back_before_its_end_is_traced_once() {
    let (mut ctx, renderer) = shared_context(true);
    let traced_frames = || renderer.lock().unwrap().tracer().expect("tracing").statistics().frames;
    let plain = render(&mut ctx, false, None);
    let composed = render(&mut ctx, true, None);
    assert_eq!(traced_frames(), 4);
    let mut before_hud = Vec::new();
    let composed_after_read = render(&mut ctx, true, Some(&mut before_hud));
    assert_eq!(traced_frames(), 6, "each frame traced once");
    assert_eq!(composed_after_read, composed, "the frame read before its end, at its end");
    let mut hud = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let i = (y * SIZE + x) as usize;
            if in_hud(x, y) {
                assert_ne!(before_hud[i], composed[i], "no HUD yet at ({x}, {y})");
                hud += 1;
            } else {
                assert_eq!(before_hud[i], composed[i], "the traced wall and the glass at ({x}, {y})");
            }
        }
    }
    assert_eq!(hud, 24);
    assert_ne!(before_hud, plain, "the glass shows");
}
