//! The denoiser's reprojection and disocclusion tests (`shaders/denoise/temporal.comp`), on
//! lavapipe, seen through `[denoise] view = "history"` (each pixel's history length in frames
//! as its grey level): a square in front of a wall creeps right for four frames, then jumps. Wall pixels the square uncovered start their history again (a disocclusion); wall
//! pixels it never covered, and the square's own pixels at its new place (reprojected with
//! the motion vector of its transform), keep theirs.

use crate::lavapipe;

use std::sync::{Arc, Mutex};

use glrt::render::denoise::settings::{DenoiseSettings, View};
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 32;

/// A tracing and denoising context showing history lengths, on a `SIZE`² drawable with a 60°
/// camera at the origin looking down −z.
fn context() -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    let settings = Settings { spp: 1, bounces: 0, sun_angle: 0.0, tonemap: Tonemap::Clamp, ..Settings::default() };
    renderer.enable_tracing(settings).expect("the tracer's pipelines");
    renderer.enable_denoising(DenoiseSettings { view: View::History, ..DenoiseSettings::default() }).expect("the denoiser's pipelines");
    let renderer = Arc::new(Mutex::new(renderer));
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(lavapipe::Shared(renderer)) });
    lavapipe::perspective_60(&mut ctx, SIZE);
    ctx
}

/// A quad facing the camera at depth `z` over `x0..x1` × `y0..y1`, moved by `dx` with
/// `glTranslatef` (the same vertices every frame: a movable draw).
fn square(ctx: &mut Context, z: f32, [x0, x1]: [f32; 2], [y0, y1]: [f32; 2], dx: f32) {
    // Safety: plain drawing calls on a current context.
    unsafe {
        dispatch::glPushMatrix(ctx);
        dispatch::glTranslatef(ctx, dx, 0.0, 0.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
        for [x, y] in [[x0, y0], [x1, y0], [x1, y1], [x0, y1]] {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
        dispatch::glPopMatrix(ctx);
    }
}

/// One frame: a lit wall at z = −6 and the small square at z = −3, moved right by `dx`.
fn frame(ctx: &mut Context, dx: f32) {
    // Safety: plain state calls on a current context.
    unsafe {
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        let position = [0.0f32, 0.0, 1.0, 0.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
    }
    square(ctx, -6.0, [-8.0, 8.0], [-8.0, 8.0], 0.0);
    square(ctx, -3.0, [-1.2, -0.2], [-0.5, 0.5], dx);
    ctx.end_frame();
}

/// The history length (frames) the window pixel showing eye-space point `p` has.
fn history_at(ctx: &mut Context, p: [f32; 3]) -> u8 {
    let window = |v: f32| ((v / (-p[2] * 30f32.to_radians().tan()) * 0.5 + 0.5) * SIZE as f32) as i32;
    lavapipe::pixel(ctx, window(p[0]), window(p[1]))[0]
}

#[test]
fn a_moved_square_keeps_its_history_and_the_wall_it_uncovered_starts_again() {
    let mut ctx = context();
    // The square creeps right (so that hash tracking sees it move from the start: a square
    // that stood still would join the static world), then jumps.
    for k in 0..4 {
        frame(&mut ctx, 0.1 * k as f32);
    }
    // Now it covers x −0.9..0.1 at z = −3: on the wall at z = −6 that is x −1.8..0.2.
    let wall = history_at(&mut ctx, [3.0, 3.0, -6.0]);
    let square = history_at(&mut ctx, [-0.4, 0.0, -3.0]);
    assert_eq!((wall, square), (4, 4), "four frames: every pixel has four frames of history");
    frame(&mut ctx, 1.7);
    // The square covers x 0.5..1.5 at z = −3 now.
    let wall = history_at(&mut ctx, [3.0, 3.0, -6.0]);
    let moved = history_at(&mut ctx, [1.0, 0.0, -3.0]);
    let uncovered = history_at(&mut ctx, [-1.2, 0.0, -6.0]);
    assert_eq!(wall, 5, "a wall pixel never covered keeps its history");
    assert_eq!(moved, 5, "the square's pixels at its new place are reprojected to where it was");
    assert_eq!(uncovered, 1, "the wall the square uncovered has no history (disocclusion)");
}
