//! The denoiser on lavapipe (`src/render/denoise`).
//!
//! Reprojection and disocclusion (`shaders/denoise/temporal.comp`), seen through
//! `[denoise] view = "history"` (each pixel's history length in frames as its grey level): a
//! square in front of a wall creeps right for four frames, then jumps. Wall pixels the
//! square uncovered start their history again (a disocclusion); wall pixels it never
//! covered, and the square's own pixels at its new place (reprojected with the motion vector
//! of its transform), keep theirs.
//!
//! Temporal gradients (`shaders/denoise/gradient.comp`): a room corner (wall and floor) lit
//! by a GL light switched on mid-sequence, with the camera still and while the corner moves
//! (forward projection of the gradient samples); the mean of the image
//! reaches the converged one within a few frames with gradients, and slowly without. And the
//! temporal stability of raw samples, the tracer's temporal filter and A-SVGF on the lit,
//! still scene: the mean frame-to-frame change.
//!
//! The specular channel (`shaders/trace/channels.glsl`): a glossy wall's highlight is in it
//! and not in the diffuse channels, seen through the channel views (`view = "specular"` and
//! the others), and the channels remodulated give back the raw traced image.

use crate::lavapipe;

use std::sync::{Arc, Mutex, OnceLock};

use glrt::render::denoise::settings::{DenoiseSettings, View};
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 32;

/// A tracing context on a `SIZE`² drawable with a 60° camera at the origin looking down −z,
/// tracing `bounces` bounces, temporal filter `temporal`, and denoising with `denoise` (none:
/// the tracer's own temporal filter resolves).
fn context_with(bounces: u32, temporal: bool, denoise: Option<DenoiseSettings>) -> Context {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    let settings = Settings { spp: 1, bounces, sun_angle: 0.0, tonemap: Tonemap::Clamp, temporal, ..Settings::default() };
    renderer.enable_tracing(settings).expect("the tracer's pipelines");
    if let Some(denoise) = denoise {
        renderer.enable_denoising(denoise).expect("the denoiser's pipelines");
    }
    let renderer = Arc::new(Mutex::new(renderer));
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(lavapipe::Shared(renderer)) });
    lavapipe::perspective_60(&mut ctx, SIZE);
    ctx
}

/// A tracing and denoising context showing history lengths.
fn context() -> Context {
    context_with(0, true, Some(DenoiseSettings { view: View::History, ..DenoiseSettings::default() }))
}

/// How the small square of [`frame`] moves.
#[derive(Clone, Copy, PartialEq)]
enum Motion {
    /// By `glTranslatef`, the same vertices every frame: a movable draw.
    Transform,
    /// By its vertices: a deforming mesh (hash tracking calls it dynamic).
    Vertices,
}

/// A quad facing the camera at depth `z` over `x0..x1` × `y0..y1`, moved by `dx` as `motion`
/// says.
fn square(ctx: &mut Context, z: f32, [x0, x1]: [f32; 2], [y0, y1]: [f32; 2], dx: f32, motion: Motion) {
    let (translate, shift) = match motion {
        Motion::Transform => (dx, 0.0),
        Motion::Vertices => (0.0, dx),
    };
    // Safety: plain drawing calls on a current context.
    unsafe {
        dispatch::glPushMatrix(ctx);
        dispatch::glTranslatef(ctx, translate, 0.0, 0.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
        for [x, y] in [[x0, y0], [x1, y0], [x1, y1], [x0, y1]] {
            dispatch::glVertex3f(ctx, x + shift, y, z);
        }
        dispatch::glEnd(ctx);
        dispatch::glPopMatrix(ctx);
    }
}

/// One frame: a lit wall at z = −6 and the small square at z = −3, moved right by `dx` as
/// `motion` says.
fn frame(ctx: &mut Context, dx: f32, motion: Motion) {
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
    square(ctx, -6.0, [-8.0, 8.0], [-8.0, 8.0], 0.0, Motion::Transform);
    square(ctx, -3.0, [-1.2, -0.2], [-0.5, 0.5], dx, motion);
    ctx.end_frame();
}

/// The history length (frames) the window pixel showing eye-space point `p` has.
fn history_at(ctx: &mut Context, p: [f32; 3]) -> u8 {
    let window = |v: f32| ((v / (-p[2] * 30f32.to_radians().tan()) * 0.5 + 0.5) * SIZE as f32) as i32;
    lavapipe::pixel(ctx, window(p[0]), window(p[1]))[0]
}

/// The square moves by `motion` for four frames and jumps; returns the history lengths of a
/// wall pixel never covered, of a square pixel at its new place and of the wall it uncovered.
fn histories_after_a_jump(motion: Motion) -> [u8; 3] {
    let mut ctx = context();
    // The square creeps right (so that hash tracking sees it move from the start: a square
    // that stood still would join the static world), then jumps.
    for k in 0..4 {
        frame(&mut ctx, 0.1 * k as f32, motion);
    }
    // Now it covers x −0.9..0.1 at z = −3: on the wall at z = −6 that is x −1.8..0.2.
    let wall = history_at(&mut ctx, [3.0, 3.0, -6.0]);
    let square = history_at(&mut ctx, [-0.4, 0.0, -3.0]);
    assert_eq!((wall, square), (4, 4), "four frames: every pixel has four frames of history");
    frame(&mut ctx, 1.7, motion);
    // The square covers x 0.5..1.5 at z = −3 now.
    [[3.0, 3.0, -6.0], [1.0, 0.0, -3.0], [-1.2, 0.0, -6.0]].map(|p| history_at(&mut ctx, p))
}

/// After the jump of [`histories_after_a_jump`]: the wall never covered and the square's
/// pixels at their new place (reprojected to where `where_it_was` says) keep their 5 frames of
/// history, the wall the square uncovered starts again (a disocclusion).
fn assert_reprojected(motion: Motion, where_it_was: &str) {
    let [wall, moved, uncovered] = histories_after_a_jump(motion);
    assert_eq!(wall, 5, "a wall pixel never covered keeps its history");
    assert_eq!(moved, 5, "the square's pixels at its new place are reprojected to where {where_it_was} had them");
    assert_eq!(uncovered, 1, "the wall the square uncovered has no history (disocclusion)");
}

#[test]
fn a_moved_square_keeps_its_history_and_the_wall_it_uncovered_starts_again() {
    assert_reprojected(Motion::Transform, "its last transform");
}

#[test]
fn a_deforming_square_is_reprojected_through_its_last_shape() {
    // Its transform never changes: only last frame's triangles say where its points were.
    assert_reprojected(Motion::Vertices, "its last shape");
}

/// One frame of the room corner: a wall at z = −6 and a floor at y = −2 (its light reaches
/// the wall as noisy indirect light), lit by GL light 0 from the upper right front when `lit`,
/// both moved right by `dx` (`glTranslatef`: the light stays, the camera sees the corner move).
fn corner(ctx: &mut Context, lit: bool, dx: f32) {
    // Safety: plain state and drawing calls on a current context.
    unsafe {
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        if lit {
            dispatch::glEnable(ctx, gl::GL_LIGHT0);
        } else {
            dispatch::glDisable(ctx, gl::GL_LIGHT0);
        }
        let position = [0.5f32, 1.0, 1.0, 0.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
    }
    square(ctx, -6.0, [-8.0, 8.0], [-8.0, 8.0], dx, Motion::Transform);
    // Safety: as above.
    unsafe {
        dispatch::glPushMatrix(ctx);
        dispatch::glTranslatef(ctx, dx, 0.0, 0.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 1.0, 0.0);
        for [x, z] in [[-8.0f32, -1.0], [8.0, -1.0], [8.0, -6.0], [-8.0, -6.0]] {
            dispatch::glVertex3f(ctx, x, -2.0, z);
        }
        dispatch::glEnd(ctx);
        dispatch::glPopMatrix(ctx);
    }
    ctx.end_frame();
}

/// The RGB values of the whole `SIZE`² image.
fn image(ctx: &mut Context) -> Vec<f64> {
    let mut rgba = vec![0u8; (SIZE * SIZE * 4) as usize];
    // Safety: `rgba` holds SIZE² RGBA pixels.
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, rgba.as_mut_ptr().cast()) };
    rgba.chunks(4).flat_map(|p| p[..3].iter().map(|&v| f64::from(v))).collect()
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// Dark frames before the light is switched on, and lit frames looked at after.
const DARK_FRAMES: usize = 3;
const LIT_FRAMES: usize = 4;

/// Frames after the switch (1: the first lit frame) until the image's mean lies within 10 %
/// of the converged lit mean `converged`, with gradients `gradients`: the light is switched
/// on after `DARK_FRAMES` and `LIT_FRAMES` are looked at, the corner moved right by `step`
/// each frame; `None` if none came within 10 %. Also the means of the lit frames.
fn frames_to_converge(gradients: bool, converged: f64, step: f32) -> (Option<usize>, Vec<f64>) {
    let mut ctx = context_with(1, true, Some(DenoiseSettings { gradients, ..DenoiseSettings::default() }));
    for k in 0..DARK_FRAMES {
        corner(&mut ctx, false, k as f32 * step);
    }
    let means: Vec<f64> = (DARK_FRAMES..DARK_FRAMES + LIT_FRAMES)
        .map(|k| {
            corner(&mut ctx, true, k as f32 * step);
            mean(&image(&mut ctx))
        })
        .collect();
    (means.iter().position(|m| (m - converged).abs() <= 0.1 * converged).map(|k| k + 1), means)
}

/// The mean of the converged lit corner: the light on from the start, 16 still frames
/// accumulated. Made once for the tests that share it (a context costs more than its frames).
fn converged_corner() -> f64 {
    static CONVERGED: OnceLock<f64> = OnceLock::new();
    *CONVERGED.get_or_init(|| {
        let mut ctx = context_with(1, true, Some(DenoiseSettings::default()));
        for _ in 0..16 {
            corner(&mut ctx, true, 0.0);
        }
        mean(&image(&mut ctx))
    })
}

/// The light switched on with gradients and without, the corner moved by `step` a frame:
/// asserts at most 2 frames to within 10 % of the converged mean with gradients, and none of
/// the `LIT_FRAMES` within 10 % without.
fn switched_on_light_converges_with_gradients(step: f32) {
    let converged = converged_corner();
    let (with, with_means) = frames_to_converge(true, converged, step);
    let (without, without_means) = frames_to_converge(false, converged, step);
    let shown = |m: &[f64]| m.iter().map(|v| format!("{:.1}", v)).collect::<Vec<_>>().join(" ");
    eprintln!("light switched on, corner moving {step} a frame; converged mean {converged:.2}; means of the lit frames with gradients: {}; without: {}", shown(&with_means), shown(&without_means));
    eprintln!("frames to within 10 %: with gradients {with:?}, without {without:?}");
    assert!(converged > 20.0, "the lit corner is lit: mean {converged:.2}");
    assert!(with.is_some_and(|k| k <= 2), "with gradients: {with:?} frames ({})", shown(&with_means));
    assert!(without.is_none(), "without gradients: {without:?} frames ({})", shown(&without_means));
}

#[test]
fn a_light_switched_on_reaches_its_converged_image_within_two_frames_with_gradients_and_not_within_four_without() {
    switched_on_light_converges_with_gradients(0.0);
}

/// While the corner moves (about 0.7 traced pixels a frame on the wall), gradient samples are
/// forward projected (`shaders/trace/forward_projection.glsl`): traced through the point last
/// frame's sample saw, with its random numbers.
#[test]
fn a_light_switched_on_while_the_corner_moves_reaches_its_converged_image_within_two_frames_with_gradients_and_not_within_four_without() {
    switched_on_light_converges_with_gradients(0.15);
}

/// The mean absolute change of the values from one frame to the next over frames 3 to 8 of
/// the lit, still corner, in 0..255.
fn frame_to_frame_change(mut ctx: Context) -> f64 {
    let mut previous: Vec<f64> = Vec::new();
    let mut changes = Vec::new();
    for k in 0..8 {
        corner(&mut ctx, true, 0.0);
        let now = image(&mut ctx);
        if k >= 3 {
            changes.push(mean(&now.iter().zip(&previous).map(|(a, b)| (a - b).abs()).collect::<Vec<_>>()));
        }
        previous = now;
    }
    mean(&changes)
}

#[test]
fn denoised_frames_of_a_still_scene_change_less_from_frame_to_frame_than_raw_ones() {
    let raw = frame_to_frame_change(context_with(1, false, None));
    let temporal = frame_to_frame_change(context_with(1, true, None));
    let denoised = frame_to_frame_change(context_with(1, true, Some(DenoiseSettings::default())));
    eprintln!("mean frame-to-frame change of the still corner, frames 3..8, 0..255: raw {raw:.3}, temporal filter {temporal:.3}, A-SVGF {denoised:.3}");
    assert!(raw > 0.5, "raw samples are noisy: {raw:.3}");
    assert!(temporal < raw, "the temporal filter: raw {raw:.3}, temporal {temporal:.3}");
    assert!(denoised < 0.25 * raw && denoised < 0.25 * temporal, "raw {raw:.3}, temporal {temporal:.3}, A-SVGF {denoised:.3}");
}

/// One frame of two walls side by side facing the camera at z = −6, diffuse 0.6, lit by GL
/// light 0, a directional light from the front right (next-event estimation without noise),
/// under a grey clear colour (the environment continuation rays find): on the left (x < 0)
/// Lambertian, on the right glossy (`GL_SPECULAR` white, shininess 64: dielectric F0 0.04,
/// roughness 0.42), its highlight where the light's mirror direction meets the eye, about a
/// quarter of the image right of the centre.
fn glossy_and_matte_walls(ctx: &mut Context) {
    let black = [0.0f32, 0.0, 0.0, 1.0];
    // Safety: plain state calls on a current context; the arrays outlive them.
    unsafe {
        dispatch::glClearColor(ctx, 0.3, 0.3, 0.3, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, [0.3f32, 0.0, 1.0, 0.0].as_ptr());
        dispatch::glLightModelfv(ctx, gl::GL_LIGHT_MODEL_AMBIENT, black.as_ptr());
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_AMBIENT, black.as_ptr());
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, [0.6f32, 0.6, 0.6, 1.0].as_ptr());
        dispatch::glMaterialf(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SHININESS, 64.0);
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, black.as_ptr());
    }
    square(ctx, -6.0, [-8.0, 0.0], [-8.0, 8.0], 0.0, Motion::Transform);
    // Safety: as above.
    unsafe { dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, [1.0f32; 4].as_ptr()) };
    square(ctx, -6.0, [0.0, 8.0], [-8.0, 8.0], 0.0, Motion::Transform);
    ctx.end_frame();
}

/// The red values of the Lambertian wall's pixels (columns 0 to 14) and of the glossy wall's
/// (17 to 31) of [`glossy_and_matte_walls`] (0 bounces: direct light, and the environment
/// through the continuation ray), traced in a context that denoises with `denoise` (none: the
/// raw samples, no temporal filter).
fn walls_image(denoise: Option<DenoiseSettings>) -> [Vec<i32>; 2] {
    let mut ctx = context_with(0, denoise.is_some(), denoise);
    glossy_and_matte_walls(&mut ctx);
    let image = lavapipe::read_rgba(&mut ctx, SIZE);
    let columns = |xs: std::ops::Range<i32>| (0..SIZE).flat_map(|y| xs.clone().map(move |x| (y * SIZE + x) as usize)).map(|i| i32::from(image[i][0])).collect();
    [columns(0..15), columns(17..SIZE)]
}

/// [`walls_image`] showing `view`, specular split off or not.
fn channel_image(view: View, specular: bool) -> [Vec<i32>; 2] {
    walls_image(Some(DenoiseSettings { view, specular, ..DenoiseSettings::default() }))
}

fn largest(values: &[i32]) -> i32 {
    values.iter().copied().max().unwrap_or(0)
}

fn smallest(values: &[i32]) -> i32 {
    values.iter().copied().min().unwrap_or(0)
}

fn mean_of(values: &[i32]) -> f64 {
    values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len().max(1) as f64
}

/// The tracer's specular channel (`shaders/trace/channels.glsl`, `FRAME_SPECULAR`) holds the
/// light the glossy wall's specular lobe reflects and the diffuse channels do not; the
/// channels remodulated give back the raw traced image; with `[denoise] specular = false`
/// specular light rides the direct channel again.
#[test]
fn specular_light_is_a_channel_of_its_own_and_the_channels_remodulated_give_the_traced_image() {
    let [matte_specular, glossy_specular] = channel_image(View::Specular, true);
    let [matte_direct, glossy_direct] = channel_image(View::Direct, true);
    let [matte_indirect, glossy_indirect] = channel_image(View::Indirect, true);
    let unfiltered = channel_image(View::Unfiltered, true);
    let raw = walls_image(None);
    let [_, glossy_specular_off] = channel_image(View::Specular, false);
    let [_, glossy_direct_off] = channel_image(View::Direct, false);
    let difference = unfiltered.concat().iter().zip(&raw.concat()).map(|(a, b)| (a - b).abs()).max().unwrap_or(0);
    eprintln!(
        "red 0..255, Lambertian / glossy wall: specular channel largest {} / {}, smallest {} / {}; direct largest {} / {}; indirect mean {:.2} / {:.2}; \
         unfiltered against raw: largest difference {difference}, means {:.2} / {:.2}; specular off: glossy wall's specular channel largest {}, direct largest {}",
        largest(&matte_specular),
        largest(&glossy_specular),
        smallest(&matte_specular),
        smallest(&glossy_specular),
        largest(&matte_direct),
        largest(&glossy_direct),
        mean_of(&matte_indirect),
        mean_of(&glossy_indirect),
        mean_of(&unfiltered.concat()),
        mean_of(&raw.concat()),
        largest(&glossy_specular_off),
        largest(&glossy_direct_off),
    );
    // A Lambertian wall reflects nothing specular; the glossy wall's highlight is in the
    // specular channel.
    assert_eq!(largest(&matte_specular), 0, "the Lambertian wall's specular channel is black");
    let (peak, least) = (largest(&glossy_specular), smallest(&glossy_specular));
    assert!(peak >= 60 && peak > least + 30, "the glossy wall's highlight is in the specular channel: {least}..{peak}");
    // The diffuse channels hold no specular light: the glossy wall's diffuse lobe reflects
    // (1 − F0) of the Lambertian wall's (the same everywhere under a directional light), never
    // more.
    assert!(smallest(&matte_direct) >= 100, "the direct channel holds the diffuse light");
    assert!(largest(&glossy_direct) <= smallest(&matte_direct), "direct: the glossy wall's at most the Lambertian wall's");
    assert!(mean_of(&glossy_indirect) <= mean_of(&matte_indirect) + 1.0, "indirect: the glossy wall's at most the Lambertian wall's");
    // Emission plus the three channels remodulated is what was traced.
    assert!(difference <= 1, "the channels remodulated against the raw image: {difference}");
    // Without the specular channel the highlight rides the direct channel.
    assert_eq!(largest(&glossy_specular_off), 0, "specular off: the specular channel is black");
    assert!(largest(&glossy_direct_off) >= largest(&glossy_direct) + 20, "specular off: the direct channel holds the highlight");
}
