//! How the compute tracer keeps geometry across frames (issue 6, part 1), on lavapipe:
//! - the persistent static world of hash tracking (`src/render/trace/chunks.rs`): a wall the
//!   program stopped drawing (culled outside the view) still casts its shadow, and a static
//!   draw whose triangles the world holds is traced once, through the world's chunks, not a
//!   second time as a draw;
//! - dynamic geometry (`src/render/trace/tracks.rs`, `resident.rs`): a mesh whose vertices
//!   move every frame refits its BVH, updated in place on the GPU, and is seen where it is now.

use crate::lavapipe;

use std::sync::{Arc, Mutex};

use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::render::trace::stats::SceneCounts;
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 24;

/// A tracing context (direct light only, hard shadows, tone mapping off) on a `SIZE`²
/// drawable with a 60° perspective camera at the origin looking down −z, and its renderer.
fn context() -> (Context, Arc<Mutex<Renderer>>) {
    context_with(Settings::default())
}

/// [`context`] with the rest of `settings`.
fn context_with(settings: Settings) -> (Context, Arc<Mutex<Renderer>>) {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    let settings = Settings { spp: 1, bounces: 0, sun_angle: 0.0, tonemap: Tonemap::Clamp, exposure: 0.0, ..settings };
    renderer.enable_tracing(settings).expect("the tracer's pipelines");
    let renderer = Arc::new(Mutex::new(renderer));
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(lavapipe::Shared(renderer.clone())) });
    lavapipe::perspective_60(&mut ctx, SIZE);
    (ctx, renderer)
}

/// A horizontal quad at height `y` over `x0..x1` × `z0..z1` (`x0 < x1`, `z0 > z1`), facing up.
fn horizontal(ctx: &mut Context, y: f32, [x0, x1]: [f32; 2], [z0, z1]: [f32; 2]) {
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 1.0, 0.0);
        for [x, z] in [[x0, z0], [x1, z0], [x1, z1], [x0, z1]] {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

/// Lighting on, light 0 directional from `towards`, a Lambertian material of albedo 0.8.
fn light(ctx: &mut Context, towards: [f32; 3]) {
    unsafe {
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        let position = [towards[0], towards[1], towards[2], 0.0];
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, position.as_ptr());
        let diffuse = [0.8f32, 0.8, 0.8, 1.0];
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, diffuse.as_ptr());
        let black = [0.0f32, 0.0, 0.0, 1.0];
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, black.as_ptr());
    }
}

/// Clears colour (black) and depth, and enables the depth test.
fn clear(ctx: &mut Context) {
    unsafe {
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
    }
}

/// The red channel of the window pixel showing eye-space point `p` (in front of the camera).
fn pixel_of(ctx: &mut Context, p: [f32; 3]) -> u8 {
    let window = |v: f32| ((v / (-p[2] * 30f32.to_radians().tan()) * 0.5 + 0.5) * SIZE as f32) as i32;
    let mut out = [0u8; 4];
    unsafe { dispatch::glReadPixels(ctx, window(p[0]), window(p[1]), 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out[0]
}

/// Draws one frame: a lit floor (albedo 0.8) under a directional light straight above, and,
/// with `occluder`, a roof over `x −1..1`, `z −5..−3` high above the view (the program draws
/// it although it is culled: it is outside the frustum).
fn frame(ctx: &mut Context, occluder: bool) {
    clear(ctx);
    light(ctx, [0.0, 1.0, 0.0]);
    horizontal(ctx, -1.0, [-4.0, 4.0], [-1.0, -9.0]);
    if occluder {
        horizontal(ctx, 4.0, [-1.0, 1.0], [-3.0, -5.0]);
    }
    ctx.end_frame();
}

fn counts(renderer: &Arc<Mutex<Renderer>>) -> SceneCounts {
    renderer.lock().unwrap().tracer().expect("tracing").statistics().scene
}

/// The roof, drawn in the first two frames (so that it joins the static world) and then
/// culled by the program, still shades the floor under it; a floor never roofed is lit there.
/// From the second frame on, the floor is traced through the world's chunks only.
#[test]
fn a_culled_static_wall_still_casts_its_shadow_and_world_draws_are_traced_once() {
    let (mut ctx, renderer) = context();
    frame(&mut ctx, true);
    let first = counts(&renderer);
    // glrt batches the two quads into one draw of 4 triangles.
    assert_eq!((first.draw_instances, first.chunk_instances, first.covered_draws, first.triangles), (1, 0, 0, 4), "new triangles are traced as a draw");
    frame(&mut ctx, true);
    let joined = counts(&renderer);
    assert_eq!((joined.draw_instances, joined.covered_draws, joined.triangles), (0, 1, 4), "{joined:?}: the draw is in the world, traced once");
    assert!(joined.chunk_instances >= 2, "{joined:?}");
    for _ in 0..3 {
        frame(&mut ctx, false);
    }
    let culled = counts(&renderer);
    assert_eq!((culled.draw_instances, culled.covered_draws, culled.triangles), (0, 1, 4), "{culled:?}: the roof stays in the world");
    assert_eq!(culled.built, 0, "{culled:?}: nothing new to build");
    let shadowed = pixel_of(&mut ctx, [0.0, -1.0, -4.0]);
    let beside = pixel_of(&mut ctx, [1.8, -1.0, -4.0]);

    let (mut open, _) = context();
    for _ in 0..5 {
        frame(&mut open, false);
    }
    let lit = pixel_of(&mut open, [0.0, -1.0, -4.0]);
    // Radiance albedo / π · E · cos 0 with E = π (GL's white light): the albedo, GL's 0.8
    // (204, sRGB-encoded), so the pixel reads 204.
    assert!(lit.abs_diff(204) <= 2, "the floor without a roof is lit: {lit}");
    assert!(beside.abs_diff(204) <= 2, "beside the roof's shadow the floor is lit: {beside}");
    assert!(shadowed <= 2, "under the culled roof the floor is in shadow: {shadowed}");
}

/// The window's pixels, RGBA rows.
fn pixels(ctx: &mut Context) -> Vec<u8> {
    let mut out = vec![0u8; (SIZE * SIZE * 4) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// A lit floor of four quads and a small roof over part of it, all on one side of the world's
/// grid origin (x > 0, y < 0, z < 0), so that with `chunk_regions` = 64 their chunks lie in one
/// region; the light straight above.
fn region_frame(ctx: &mut Context) {
    clear(ctx);
    light(ctx, [0.0, 1.0, 0.0]);
    for (x, z) in [([0.1, 2.0], [-1.0, -5.0]), ([2.0, 4.0], [-1.0, -5.0]), ([0.1, 2.0], [-5.0, -9.0]), ([2.0, 4.0], [-5.0, -9.0])] {
        horizontal(ctx, -1.0, x, z);
    }
    horizontal(ctx, -0.5, [0.5, 2.0], [-3.0, -5.0]);
    ctx.end_frame();
}

/// The scene of [`region_frame`] with its chunks in one region (`chunk_regions` = 64, the grid
/// being 8 cells across) and in regions of their own (0): once its chunks have stayed the same
/// for `SETTLE_FRAMES` frames, the compute tracer traces the region through one merged BVH
/// (built once, then one instance in the top level for them all), and the image is the same
/// pixel for pixel: hits in it shade as the chunks' own, the roof's shadow (any-hit rays
/// through it) falls on the floor as before.
#[test]
fn a_merged_region_shades_as_its_chunks() {
    let (mut merged, merged_renderer) = context_with(Settings { chunk_regions: 64, ..Settings::default() });
    let (mut apart, apart_renderer) = context_with(Settings { chunk_regions: 0, ..Settings::default() });
    let mut merged_at = None;
    for k in 0..14 {
        region_frame(&mut merged);
        region_frame(&mut apart);
        let (c, a) = (counts(&merged_renderer), counts(&apart_renderer));
        if c.top_instances < c.chunk_instances {
            assert_eq!((merged_at.is_none(), c.top_instances, c.built), (true, 1, 1), "frame {k}: merged once, into one instance: {c:?}");
            merged_at = Some(k);
            break;
        }
        assert_eq!((a.top_instances, a.chunk_instances), (c.top_instances, c.chunk_instances), "frame {k}: {c:?}");
    }
    let at = merged_at.expect("the region is merged within 14 frames");
    assert!(at >= 8, "not before its chunks have stayed the same for SETTLE_FRAMES frames: {at}");
    region_frame(&mut merged);
    region_frame(&mut apart);
    let (c, a) = (counts(&merged_renderer), counts(&apart_renderer));
    assert!(a.chunk_instances >= 3 && a.top_instances == a.chunk_instances && a.draw_instances == 0, "{a:?}");
    assert_eq!((c.chunk_instances, c.top_instances, c.built), (a.chunk_instances, 1, 0), "the merged BVH is kept: {c:?}");
    let shadowed = pixel_of(&mut merged, [1.2, -1.0, -4.0]);
    let beside = pixel_of(&mut merged, [1.2, -1.0, -7.5]);
    assert!(beside.abs_diff(204) <= 2, "the floor through the merged BVH is lit as a chunk: {beside}");
    assert!(shadowed <= 2, "the roof through the merged BVH shadows it: {shadowed}");
    assert!(pixels(&mut merged) == pixels(&mut apart), "merged and apart make the same image");
}

/// A lit quad facing the camera that slides right every frame (new vertices, same indices):
/// hash tracking makes it dynamic, and from its third frame on its BVH is refitted (nothing
/// built); the image shows it where it is now, not where it was.
#[test]
fn a_moving_mesh_refits_its_bvh_and_is_seen_where_it_is() {
    let (mut ctx, renderer) = context();
    let mut last = SceneCounts::default();
    for k in 0..5 {
        clear(&mut ctx);
        light(&mut ctx, [0.0, 0.0, 1.0]);
        let x0 = -1.5 + 0.5 * k as f32;
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_QUADS);
            dispatch::glNormal3f(&mut ctx, 0.0, 0.0, 1.0);
            for [x, y] in [[x0, -0.5], [x0 + 1.0, -0.5], [x0 + 1.0, 0.5], [x0, 0.5]] {
                dispatch::glVertex3f(&mut ctx, x, y, -3.0);
            }
            dispatch::glEnd(&mut ctx);
        }
        ctx.end_frame();
        last = counts(&renderer);
        let expected = if k < 2 { (1, 0) } else { (0, 1) };
        assert_eq!((last.built, last.refitted), expected, "frame {k}: {last:?}");
    }
    assert_eq!((last.draw_instances, last.chunk_instances, last.triangles), (1, 0, 2), "{last:?}");
    // The quad now spans x 0.5..1.5; it started at −1.5..−0.5.
    let now = pixel_of(&mut ctx, [1.0, 0.0, -3.0]);
    let before = pixel_of(&mut ctx, [-1.0, 0.0, -3.0]);
    assert!(now.abs_diff(204) <= 2, "the quad where it is now is lit: {now}");
    assert_eq!(before, 0, "where the quad was there is nothing now");
}

/// `tracer = "auto"` (the default) on a device without the ray-tracing extensions (lavapipe)
/// makes the compute tracer at once: no trial of the hardware one (`trace::auto`), whose
/// first frames would trace with the hardware tracer.
#[test]
fn auto_keeps_the_compute_tracer_without_the_extensions() {
    let (_ctx, renderer) = context();
    let renderer = renderer.lock().unwrap();
    assert!(!renderer.device().ray_tracing, "lavapipe has no VK_KHR_ray_tracing_pipeline");
    assert_eq!(renderer.tracer().map(|t| t.name()), Some("compute"));
}
