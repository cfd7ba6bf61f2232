//! Selection and feedback tests: hits, names and depths; token streams of every feedback type;
//! clipping by the view volume and user planes; culling and polygon mode; overflow; errors.

use crate::translate::gl::{GL_2D, GL_3D, GL_3D_COLOR, GL_4D_COLOR_TEXTURE};
use super::select::depth_to_uint;
use super::{CpuPrimitive, CpuVertex, RasterRules, RasterEvent, WindowVertex};
use crate::translate::Context;
use crate::translate::dispatch;
use crate::translate::gl::{self, GLenum};

/// A 100 × 100 viewport, identity matrices: window x = (x + 1) · 50, z = (z + 1) / 2.
fn ctx() -> Context {
    let (mut c, _) = Context::with_recording();
    c.bind_drawable(100, 100);
    c
}

fn v(x: f32, y: f32, z: f32) -> CpuVertex {
    CpuVertex { position: [x, y, z, 1.0], color: [1.0, 0.5, 0.0, 1.0], back_color: [1.0, 0.5, 0.0, 1.0], texcoord: [0.5, 0.25, 0.0, 1.0], edge_flag: true }
}

fn draw(c: &mut Context, mode: GLenum, vs: &[CpuVertex]) -> bool {
    c.render_mode_primitive(&CpuPrimitive { mode, vertices: vs }, &RasterRules::default(), &[])
}

fn tok(t: GLenum) -> f32 {
    t as f32
}

#[test]
fn render_mode_passes_primitives_through() {
    let mut c = ctx();
    assert!(!draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.0, 0.0)]));
    assert!(!c.render_mode_raster_event(RasterEvent::Bitmap, None));
}

#[test]
fn selection_hits_names_and_depths() {
    let mut c = ctx();
    let mut buf = [0u32; 32];
    unsafe {
        dispatch::glSelectBuffer(&mut c, 32, buf.as_mut_ptr());
        assert_eq!(dispatch::glRenderMode(&mut c, gl::GL_SELECT), 0);
        dispatch::glInitNames(&mut c);
        dispatch::glPushName(&mut c, 7);
    }
    // Inside: a triangle from z = -0.5 to 0.5 → window z 0.25 .. 0.75.
    assert!(draw(&mut c, gl::GL_TRIANGLES, &[v(0.0, 0.0, -0.5), v(0.5, 0.0, 0.5), v(0.0, 0.5, 0.0)]));
    unsafe { dispatch::glLoadName(&mut c, 8) };
    // Outside the view volume: no hit, no record at the next name change.
    draw(&mut c, gl::GL_TRIANGLES, &[v(2.0, 0.0, 0.0), v(3.0, 0.0, 0.0), v(2.0, 1.0, 0.0)]);
    unsafe {
        dispatch::glPushName(&mut c, 9);
        let mut depth = 0;
        dispatch::glGetIntegerv(&mut c, gl::GL_NAME_STACK_DEPTH, &mut depth);
        assert_eq!(depth, 2);
    }
    // A point on the near plane; recorded when leaving selection mode.
    draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.0, -1.0)]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 2);
    assert_eq!(&buf[..4], &[1, depth_to_uint(0.25), depth_to_uint(0.75), 7]);
    assert_eq!(&buf[4..9], &[2, 0, 0, 8, 9]);
    assert_eq!(buf[9], 0, "nothing more written");
    assert_eq!(depth_to_uint(1.0), u32::MAX);
    assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn user_clip_plane_limits_hits() {
    let mut c = ctx();
    let mut buf = [0u32; 16];
    unsafe {
        dispatch::glSelectBuffer(&mut c, 16, buf.as_mut_ptr());
        dispatch::glRenderMode(&mut c, gl::GL_SELECT);
        dispatch::glPushName(&mut c, 1);
    }
    let keep_right = [[1.0, 0.0, 0.0, 0.0]]; // x ≥ 0 in eye space
    let rules = RasterRules::default();
    // Entirely on the clipped side.
    let left = [v(-0.9, 0.0, 0.0), v(-0.1, 0.0, 0.0), v(-0.5, 0.5, 0.0)];
    c.render_mode_primitive(&CpuPrimitive { mode: gl::GL_TRIANGLES, vertices: &left }, &rules, &keep_right);
    assert_eq!(c.render_mode.select.hit, None);
    // A line from (-1, 0, -1) to (1, 0, 1): only x ≥ 0 stays, z from 0 to 1 → window 0.5 .. 1.
    let line = [v(-1.0, 0.0, -1.0), v(1.0, 0.0, 1.0)];
    c.render_mode_primitive(&CpuPrimitive { mode: gl::GL_LINES, vertices: &line }, &rules, &keep_right);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 1);
    assert_eq!(&buf[..4], &[1, depth_to_uint(0.5), u32::MAX, 1]);
}

fn feedback(c: &mut Context, ty: GLenum, buf: &mut [f32]) {
    unsafe {
        dispatch::glFeedbackBuffer(c, buf.len() as i32, ty, buf.as_mut_ptr());
        assert_eq!(dispatch::glRenderMode(c, gl::GL_FEEDBACK), 0);
    }
}

#[test]
fn feedback_points_3d_color_and_clipping() {
    let mut c = ctx();
    let mut buf = [0.0f32; 32];
    feedback(&mut c, GL_3D_COLOR, &mut buf);
    draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.5, 0.0), v(0.0, 1.5, 0.0)]);
    unsafe { dispatch::glPassThrough(&mut c, 42.0) };
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 10);
    assert_eq!(&buf[..8], &[tok(gl::GL_POINT_TOKEN), 50.0, 75.0, 0.5, 1.0, 0.5, 0.0, 1.0]);
    assert_eq!(&buf[8..10], &[tok(gl::GL_PASS_THROUGH_TOKEN), 42.0]);
}

#[test]
fn feedback_lines_with_reset_tokens() {
    let mut c = ctx();
    let mut buf = [0.0f32; 64];
    feedback(&mut c, GL_2D, &mut buf);
    let pts = [v(-1.0, -1.0, 0.0), v(0.0, -1.0, 0.0), v(0.0, 0.0, 0.0)];
    draw(&mut c, gl::GL_LINE_LOOP, &pts);
    draw(&mut c, gl::GL_LINES, &pts[..2]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 20);
    let expected = [
        tok(gl::GL_LINE_RESET_TOKEN), 0.0, 0.0, 50.0, 0.0,
        tok(gl::GL_LINE_TOKEN), 50.0, 0.0, 50.0, 50.0,
        tok(gl::GL_LINE_TOKEN), 50.0, 50.0, 0.0, 0.0,
        tok(gl::GL_LINE_RESET_TOKEN), 0.0, 0.0, 50.0, 0.0,
    ];
    assert_eq!(&buf[..20], &expected);
}

#[test]
fn feedback_polygons_clipped_and_culled() {
    let mut c = ctx();
    let mut buf = [0.0f32; 64];
    feedback(&mut c, GL_3D, &mut buf);
    // A quad is one polygon of 4 vertices.
    draw(&mut c, gl::GL_QUADS, &[v(0.0, 0.0, 0.0), v(0.5, 0.0, 0.0), v(0.5, 0.5, 0.0), v(0.0, 0.5, 0.0)]);
    assert_eq!(&buf[..2], &[tok(gl::GL_POLYGON_TOKEN), 4.0]);
    assert_eq!(&buf[2..5], &[50.0, 50.0, 0.5]);
    // A triangle crossing x = 1 loses a corner and gains two vertices.
    draw(&mut c, gl::GL_TRIANGLES, &[v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(0.0, 0.5, 0.0)]);
    assert_eq!(&buf[14..16], &[tok(gl::GL_POLYGON_TOKEN), 4.0]);
    let n = unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) };
    assert_eq!(n, 14 + 2 + 12);
    // Back faces culled; front faces drawn as lines in GL_LINE mode.
    feedback(&mut c, GL_2D, &mut buf);
    let ccw = [v(0.0, 0.0, 0.0), v(0.5, 0.0, 0.0), v(0.0, 0.5, 0.0)];
    let cw = [ccw[0], ccw[2], ccw[1]];
    let rules = RasterRules { cull: Some(gl::GL_BACK), mode: [gl::GL_LINE, gl::GL_FILL], ..RasterRules::default() };
    c.render_mode_primitive(&CpuPrimitive { mode: gl::GL_TRIANGLES, vertices: &cw }, &rules, &[]);
    let mut flagged = ccw;
    flagged[1].edge_flag = false; // edge 1 → 2 is not a boundary
    c.render_mode_primitive(&CpuPrimitive { mode: gl::GL_TRIANGLES, vertices: &flagged }, &rules, &[]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 10);
    assert_eq!(&buf[..5], &[tok(gl::GL_LINE_RESET_TOKEN), 50.0, 50.0, 75.0, 50.0]);
    assert_eq!(&buf[5..10], &[tok(gl::GL_LINE_RESET_TOKEN), 50.0, 75.0, 50.0, 50.0]);
}

#[test]
fn feedback_4d_color_texture_and_raster_tokens() {
    let mut c = ctx();
    let mut buf = [0.0f32; 64];
    unsafe {
        dispatch::glMatrixMode(&mut c, gl::GL_TEXTURE);
        dispatch::glScalef(&mut c, 2.0, 2.0, 1.0);
    }
    feedback(&mut c, GL_4D_COLOR_TEXTURE, &mut buf);
    let mut p = v(0.0, 0.0, 0.0);
    p.position = [0.5, 0.0, 0.0, 2.0]; // clip w = 2 → window x = 62.5
    draw(&mut c, gl::GL_POINTS, &[p]);
    let raster = WindowVertex { window: [3.0, 4.0, 0.5, 1.0], color: [0.0, 0.0, 1.0, 1.0], texcoord: [0.0, 0.0, 0.0, 1.0] };
    assert!(c.render_mode_raster_event(RasterEvent::Bitmap, Some(&raster)));
    assert!(c.render_mode_raster_event(RasterEvent::DrawPixels, None), "invalid raster position: nothing");
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 26);
    assert_eq!(
        &buf[..13],
        &[tok(gl::GL_POINT_TOKEN), 62.5, 50.0, 0.5, 2.0, 1.0, 0.5, 0.0, 1.0, 1.0, 0.5, 0.0, 1.0]
    );
    assert_eq!(&buf[13..18], &[tok(gl::GL_BITMAP_TOKEN), 3.0, 4.0, 0.5, 1.0]);
}

#[test]
fn overflow_returns_minus_one_and_stays_in_bounds() {
    let mut c = ctx();
    let mut buf = [0.0f32; 4];
    unsafe { dispatch::glFeedbackBuffer(&mut c, 3, GL_2D, buf.as_mut_ptr()) };
    unsafe { dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK) };
    draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.0, 0.0)]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK) }, 3, "exactly full is not an overflow");
    draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.0, 0.0), v(0.5, 0.0, 0.0)]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, -1);
    assert_eq!(buf[3], 0.0, "never written past the size given");
    let mut sel = [0u32; 3];
    unsafe {
        dispatch::glSelectBuffer(&mut c, 2, sel.as_mut_ptr());
        dispatch::glRenderMode(&mut c, gl::GL_SELECT);
    }
    draw(&mut c, gl::GL_POINTS, &[v(0.0, 0.0, 0.0)]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, -1);
    assert_eq!(sel, [0, depth_to_uint(0.5), 0]);
}

#[test]
fn render_mode_errors_and_queries() {
    let mut c = ctx();
    let mut buf = [0u32; 4];
    let mut fb = [0.0f32; 4];
    unsafe {
        assert_eq!(dispatch::glRenderMode(&mut c, gl::GL_SELECT), 0);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "no selection buffer yet");
        assert_eq!(dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK), 0);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "no feedback buffer yet");
        dispatch::glRenderMode(&mut c, gl::GL_POINTS);
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
        let mut mode = 0;
        dispatch::glGetIntegerv(&mut c, gl::GL_RENDER_MODE, &mut mode);
        assert_eq!(mode as GLenum, gl::GL_RENDER);
        // Name stack commands are ignored outside selection mode.
        dispatch::glPopName(&mut c);
        dispatch::glLoadName(&mut c, 3);
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glSelectBuffer(&mut c, -1, buf.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE);
        dispatch::glFeedbackBuffer(&mut c, 4, gl::GL_RGBA, fb.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_ENUM);
        dispatch::glFeedbackBuffer(&mut c, -2, GL_2D, fb.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_VALUE);
        dispatch::glSelectBuffer(&mut c, 4, buf.as_mut_ptr());
        dispatch::glRenderMode(&mut c, gl::GL_SELECT);
        dispatch::glGetIntegerv(&mut c, gl::GL_RENDER_MODE, &mut mode);
        assert_eq!(mode as GLenum, gl::GL_SELECT);
        dispatch::glSelectBuffer(&mut c, 4, buf.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "glSelectBuffer in selection mode");
        dispatch::glLoadName(&mut c, 3);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "glLoadName on an empty stack");
        dispatch::glPopName(&mut c);
        assert_eq!(c.glGetError(), gl::GL_STACK_UNDERFLOW);
        for i in 0..64 {
            dispatch::glPushName(&mut c, i);
        }
        assert_eq!(c.glGetError(), gl::GL_NO_ERROR);
        dispatch::glPushName(&mut c, 64);
        assert_eq!(c.glGetError(), gl::GL_STACK_OVERFLOW);
        let mut v = [0i32; 1];
        dispatch::glGetIntegerv(&mut c, gl::GL_MAX_NAME_STACK_DEPTH, v.as_mut_ptr());
        assert_eq!(v[0], 64);
        dispatch::glGetIntegerv(&mut c, gl::GL_SELECTION_BUFFER_SIZE, v.as_mut_ptr());
        assert_eq!(v[0], 4);
        assert_eq!(c.render_mode_pointer(gl::GL_SELECTION_BUFFER_POINTER), Some(buf.as_mut_ptr().cast()));
        assert_eq!(dispatch::glRenderMode(&mut c, gl::GL_RENDER), 0, "no hits");
        dispatch::glGetIntegerv(&mut c, gl::GL_NAME_STACK_DEPTH, v.as_mut_ptr());
        assert_eq!(v[0], 0);
        dispatch::glFeedbackBuffer(&mut c, 4, GL_3D, fb.as_mut_ptr());
        dispatch::glGetIntegerv(&mut c, gl::GL_FEEDBACK_BUFFER_TYPE, v.as_mut_ptr());
        assert_eq!(v[0] as GLenum, GL_3D);
        dispatch::glRenderMode(&mut c, gl::GL_FEEDBACK);
        dispatch::glFeedbackBuffer(&mut c, 4, GL_3D, fb.as_mut_ptr());
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION, "glFeedbackBuffer in feedback mode");
        // Not allowed between glBegin and glEnd.
        dispatch::glBegin(&mut c, gl::GL_POINTS);
        dispatch::glRenderMode(&mut c, gl::GL_RENDER);
        assert_eq!(c.glGetError(), gl::GL_INVALID_OPERATION);
        dispatch::glEnd(&mut c);
    }
}

#[test]
fn flat_shading_feeds_back_the_provoking_colour() {
    let mut c = ctx();
    let mut buf = [0.0f32; 32];
    feedback(&mut c, GL_3D_COLOR, &mut buf);
    let mut a = v(0.0, 0.0, 0.0);
    a.color = [0.0, 0.0, 1.0, 1.0];
    let b = v(0.5, 0.0, 0.0);
    let rules = RasterRules { flat_shading: true, ..RasterRules::default() };
    c.render_mode_primitive(&CpuPrimitive { mode: gl::GL_LINES, vertices: &[a, b] }, &rules, &[]);
    assert_eq!(unsafe { dispatch::glRenderMode(&mut c, gl::GL_RENDER) }, 15);
    // The second vertex provokes an independent line: both ends get its colour.
    assert_eq!(&buf[4..8], &[1.0, 0.5, 0.0, 1.0]);
    assert_eq!(&buf[11..15], &[1.0, 0.5, 0.0, 1.0]);
}
