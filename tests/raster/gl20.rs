//! The fixed-function features of OpenGL 2.0 on the Vulkan raster renderer (Mesa lavapipe):
//! separate stencil for front and back faces (and `GL_EXT_stencil_two_side`), separate blend
//! equations, non-power-of-two mipmapped textures and point sprites.

use crate::lavapipe;

use glrt::translate::{Context, dispatch, gl};
use lavapipe::pixel;

const SIZE: i32 = 64;

/// A context with an orthographic projection in window pixels.
fn context() -> Context {
    let mut ctx = lavapipe::context(SIZE);
    unsafe {
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, SIZE as f64, 0.0, SIZE as f64, -1.0, 1.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
    }
    ctx
}

/// The window rectangle `x0, y0` – `x1, y1`, counter-clockwise (front-facing) or clockwise.
fn rect(ctx: &mut Context, [x0, y0, x1, y1]: [f32; 4], ccw: bool) {
    let mut corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    if !ccw {
        corners.reverse();
    }
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for [x, y] in corners {
            dispatch::glTexCoord2f(ctx, (x - x0) / (x1 - x0), (y - y0) / (y1 - y0));
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    }
}

/// The stencil value at window (x, y).
fn stencil(ctx: &mut Context, x: i32, y: i32) -> u8 {
    let mut out = [0u8];
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out[0]
}

/// Front faces, back faces, lines and points each update the stencil buffer with their own
/// face's state: back faces only when they are back-facing polygons.
#[test]
fn separate_stencil_follows_gl_facing() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearStencil(&mut ctx, 0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST);
        dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_FRONT, gl::GL_ALWAYS, 0, 0xff);
        dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_BACK, gl::GL_ALWAYS, 9, 0xff);
        dispatch::glStencilOpSeparate(&mut ctx, gl::GL_FRONT, gl::GL_KEEP, gl::GL_KEEP, gl::GL_INCR);
        dispatch::glStencilOpSeparate(&mut ctx, gl::GL_BACK, gl::GL_KEEP, gl::GL_KEEP, gl::GL_REPLACE);
    }
    rect(&mut ctx, [0.0, 0.0, 16.0, 16.0], true);
    rect(&mut ctx, [16.0, 0.0, 32.0, 16.0], false);
    unsafe {
        // With GL_CW front faces the windings swap roles.
        dispatch::glFrontFace(&mut ctx, gl::GL_CW);
        rect(&mut ctx, [32.0, 0.0, 48.0, 16.0], true);
        dispatch::glFrontFace(&mut ctx, gl::GL_CCW);
        // Lines and points are front-facing, whatever their expanded triangles' winding.
        dispatch::glBegin(&mut ctx, gl::GL_LINES);
        dispatch::glVertex2f(&mut ctx, 40.0, 30.5);
        dispatch::glVertex2f(&mut ctx, 0.0, 30.5);
        dispatch::glEnd(&mut ctx);
        dispatch::glPointSize(&mut ctx, 4.0);
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        dispatch::glVertex2f(&mut ctx, 56.0, 40.0);
        dispatch::glEnd(&mut ctx);
        // Back faces drawn as lines keep the back state.
        dispatch::glPolygonMode(&mut ctx, gl::GL_BACK, gl::GL_LINE);
        dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_BACK, gl::GL_ALWAYS, 5, 0xff);
    }
    rect(&mut ctx, [4.5, 44.5, 28.5, 60.5], false);
    assert_eq!(stencil(&mut ctx, 8, 8), 1, "front face: incremented");
    assert_eq!(stencil(&mut ctx, 24, 8), 9, "back face: replaced with the back reference");
    assert_eq!(stencil(&mut ctx, 40, 8), 9, "counter-clockwise is back with GL_CW");
    assert_eq!(stencil(&mut ctx, 20, 30), 1, "a line is front-facing");
    assert_eq!(stencil(&mut ctx, 56, 40), 1, "a point is front-facing");
    assert_eq!(stencil(&mut ctx, 4, 52), 5, "the edge of a back face");
    assert_eq!(stencil(&mut ctx, 16, 52), 0, "inside the outlined back face");

    // Back faces pass or fail by their own function and reference.
    unsafe {
        dispatch::glPolygonMode(&mut ctx, gl::GL_BACK, gl::GL_FILL);
        dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_FRONT, gl::GL_EQUAL, 1, 0xff);
        dispatch::glStencilFuncSeparate(&mut ctx, gl::GL_BACK, gl::GL_EQUAL, 9, 0xff);
        dispatch::glStencilOp(&mut ctx, gl::GL_KEEP, gl::GL_KEEP, gl::GL_KEEP);
        dispatch::glColor3f(&mut ctx, 0.0, 1.0, 0.0);
    }
    rect(&mut ctx, [0.0, 0.0, 32.0, 16.0], true);
    rect(&mut ctx, [0.0, 0.0, 32.0, 16.0], false);
    assert_eq!(pixel(&mut ctx, 8, 8), [0, 255, 0, 255], "front passes where the stencil is 1");
    assert_eq!(pixel(&mut ctx, 24, 8), [0, 255, 0, 255], "back passes where the stencil is 9");
}

/// `GL_EXT_stencil_two_side`: back faces take the extension's back state while
/// `GL_STENCIL_TEST_TWO_SIDE_EXT` is on, the front state otherwise.
#[test]
fn stencil_two_side_ext() {
    let mut ctx = context();
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_STENCIL_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST_TWO_SIDE_EXT);
        dispatch::glActiveStencilFaceEXT(&mut ctx, gl::GL_BACK);
        dispatch::glStencilOp(&mut ctx, gl::GL_KEEP, gl::GL_KEEP, gl::GL_DECR_WRAP);
        dispatch::glActiveStencilFaceEXT(&mut ctx, gl::GL_FRONT);
        dispatch::glStencilOp(&mut ctx, gl::GL_KEEP, gl::GL_KEEP, gl::GL_INCR_WRAP);
    }
    // Shadow volume style: front and back faces over the same pixels.
    rect(&mut ctx, [0.0, 0.0, 32.0, 32.0], true);
    rect(&mut ctx, [16.0, 0.0, 48.0, 32.0], false);
    unsafe { dispatch::glDisable(&mut ctx, gl::GL_STENCIL_TEST_TWO_SIDE_EXT) };
    rect(&mut ctx, [40.0, 40.0, 64.0, 64.0], false);
    assert_eq!(stencil(&mut ctx, 8, 8), 1);
    assert_eq!(stencil(&mut ctx, 24, 8), 0, "incremented by the front, decremented by the back");
    assert_eq!(stencil(&mut ctx, 44, 8), 255, "decremented with wrap");
    assert_eq!(stencil(&mut ctx, 50, 50), 1, "two-side off: the back face uses the front state");
}

/// `glBlendEquationSeparate`: the colour channels and alpha blend with their own equations.
#[test]
fn separate_blend_equations() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.5, 0.5, 0.5, 0.5);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_BLEND);
        dispatch::glBlendFunc(&mut ctx, gl::GL_ONE, gl::GL_ONE);
        dispatch::glBlendEquationSeparate(&mut ctx, gl::GL_FUNC_REVERSE_SUBTRACT, gl::GL_MIN);
        dispatch::glColor4f(&mut ctx, 0.25, 0.0, 0.5, 0.25);
    }
    rect(&mut ctx, [0.0, 0.0, 32.0, 32.0], true);
    unsafe { dispatch::glBlendEquationSeparate(&mut ctx, gl::GL_MAX, gl::GL_FUNC_ADD) };
    rect(&mut ctx, [32.0, 0.0, 64.0, 32.0], true);
    let near = |a: [u8; 4], b: [u8; 4]| a.iter().zip(b).all(|(&x, y)| x.abs_diff(y) <= 1);
    let (left, right) = (pixel(&mut ctx, 8, 8), pixel(&mut ctx, 40, 8));
    assert!(near(left, [64, 128, 0, 64]), "rgb: D - S, alpha: min(S, D): {left:?}");
    assert!(near(right, [128, 128, 128, 191]), "rgb: max(S, D), alpha: S + D: {right:?}");
}

/// A textured window rectangle `x0, y0` – `x1, y1` whose texture coordinates run from 0 to
/// `s`, `t`.
fn textured_rect(ctx: &mut Context, [x0, y0, x1, y1]: [f32; 4], [s, t]: [f32; 2]) {
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for [x, y, u, v] in [[x0, y0, 0.0, 0.0], [x1, y0, s, 0.0], [x1, y1, s, t], [x0, y1, 0.0, t]] {
            dispatch::glTexCoord2f(ctx, u, v);
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    }
}

/// Uploads a `w` × `h` level of one colour to the bound 2D texture.
fn level(ctx: &mut Context, level: i32, w: i32, h: i32, rgba: [u8; 4]) {
    let texels: Vec<u8> = (0..w * h).flat_map(|_| rgba).collect();
    unsafe { dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, level, gl::GL_RGBA as i32, w, h, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast()) };
}

/// Non-power-of-two textures with mipmaps whose sizes halve with the floor (12×5, 6×2, 3×1,
/// 1×1): complete, and each level sampled where its level of detail applies; a generated
/// chain (`GL_GENERATE_MIPMAP`) of a 7×3 image is complete down to 1×1.
#[test]
fn non_power_of_two_mipmaps_are_sampled() {
    let mut ctx = context();
    let colors = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255]];
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        for (i, (w, h)) in [(12, 5), (6, 2), (3, 1), (1, 1)].into_iter().enumerate() {
            level(&mut ctx, i as i32, w, h, colors[i]);
        }
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST_MIPMAP_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glColor3f(&mut ctx, 0.0, 0.0, 0.0);
    }
    // 16-pixel squares whose s runs over `r` × 16 / 12 repeats: `r` texels of level 0 per pixel.
    for (i, r) in [0.5f32, 2.5, 5.0, 12.0].into_iter().enumerate() {
        let x = 16.0 * i as f32;
        textured_rect(&mut ctx, [x, 0.0, x + 16.0, 16.0], [r * 16.0 / 12.0, 0.1]);
    }
    for (i, color) in colors.iter().enumerate() {
        assert_eq!(pixel(&mut ctx, 16 * i as i32 + 8, 8), *color, "level {i}");
    }

    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 2);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST_MIPMAP_NEAREST as i32);
    }
    level(&mut ctx, 0, 7, 3, [40, 80, 120, 255]);
    textured_rect(&mut ctx, [0.0, 32.0, 16.0, 48.0], [16.0, 16.0]);
    assert_eq!(pixel(&mut ctx, 8, 40), [40, 80, 120, 255], "the 1×1 level of a generated chain");
    let mut w = 0;
    unsafe { dispatch::glGetTexLevelParameteriv(&mut ctx, gl::GL_TEXTURE_2D, 1, gl::GL_TEXTURE_WIDTH, &mut w) };
    assert_eq!(w, 3);
}

/// Draws a point of `size` at window (x, y).
fn point(ctx: &mut Context, x: f32, y: f32, size: f32) {
    unsafe {
        dispatch::glPointSize(ctx, size);
        dispatch::glBegin(ctx, gl::GL_POINTS);
        dispatch::glTexCoord2f(ctx, 0.75, 0.75);
        dispatch::glVertex2f(ctx, x, y);
        dispatch::glEnd(ctx);
    }
}

/// Point sprites: with `GL_COORD_REPLACE` s runs from 0 to 1 left to right and t from 0 to 1
/// top to bottom (`GL_UPPER_LEFT`) or bottom to top (`GL_LOWER_LEFT`) across the point; a
/// unit without it keeps the vertex's coordinates.
#[test]
fn point_sprite_coordinates() {
    let mut ctx = context();
    let (red, green, blue, white) = ([255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255; 4]);
    // Texel rows bottom first: red, green / blue, white.
    let texels: Vec<u8> = [red, green, blue, white].concat();
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glEnable(&mut ctx, gl::GL_POINT_SPRITE);
        // Ignored by sprites: the corners stay opaque.
        dispatch::glEnable(&mut ctx, gl::GL_POINT_SMOOTH);
    }
    point(&mut ctx, 16.0, 16.0, 16.0);
    unsafe { dispatch::glTexEnvi(&mut ctx, gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, 1) };
    point(&mut ctx, 48.0, 16.0, 16.0);
    unsafe { dispatch::glPointParameteri(&mut ctx, gl::GL_POINT_SPRITE_COORD_ORIGIN, gl::GL_LOWER_LEFT as i32) };
    point(&mut ctx, 48.0, 48.0, 16.0);
    // A sprite of size 5 at an exact position that is no pixel centre: the pixels whose
    // centres are inside [7.7, 12.7] × [39.2, 44.2].
    point(&mut ctx, 10.2, 41.7, 5.0);

    assert_eq!(pixel(&mut ctx, 9, 9), white, "no replacement: the vertex's (0.75, 0.75)");
    assert_eq!(pixel(&mut ctx, 9, 23), white, "a square, its corners covered");
    let quadrants = |ctx: &mut Context, cx: i32, cy: i32| [(-6, 6), (6, 6), (-6, -6), (6, -6)].map(|(dx, dy)| pixel(ctx, cx + dx, cy + dy));
    assert_eq!(quadrants(&mut ctx, 48, 16), [red, green, blue, white], "upper left origin: t = 0 at the top");
    assert_eq!(quadrants(&mut ctx, 48, 48), [blue, white, red, green], "lower left origin: t = 0 at the bottom");
    assert_eq!(pixel(&mut ctx, 8, 40), red, "s and t below 1/2 at the bottom left");
    assert_eq!((pixel(&mut ctx, 12, 40), pixel(&mut ctx, 8, 43)), (green, blue));
    let outside = [(7, 41), (13, 41), (10, 38), (10, 44)].map(|(x, y)| pixel(&mut ctx, x, y));
    assert_eq!(outside, [[0, 0, 0, 0]; 4], "outside the unrounded square");
}

/// `GL_ARB_texture_rectangle`: coordinates in texels (a 3×2 texture, one colour per texel),
/// `GL_CLAMP_TO_EDGE` beyond the edge, and the rectangle target's priority over 2D.
#[test]
fn rectangle_textures_take_texel_coordinates() {
    let mut ctx = context();
    let colors: [[u8; 4]; 6] = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255], [0, 255, 255, 255], [255, 0, 255, 255]];
    let texels = colors.concat();
    let rect = gl::GL_TEXTURE_RECTANGLE_ARB;
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        level(&mut ctx, 0, 1, 1, [255; 4]);
        dispatch::glBindTexture(&mut ctx, rect, 2);
        dispatch::glTexImage2D(&mut ctx, rect, 0, gl::GL_RGBA as i32, 3, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glTexParameteri(&mut ctx, rect, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, rect, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glEnable(&mut ctx, rect);
    }
    // 48 × 32 pixels over s in [0, 3], t in [0, 2]: 16 pixels per texel; then s up to 6, with
    // GL_TEXTURE_2D enabled too.
    textured_rect(&mut ctx, [0.0, 0.0, 48.0, 32.0], [3.0, 2.0]);
    unsafe { dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D) };
    textured_rect(&mut ctx, [0.0, 32.0, 64.0, 64.0], [6.0, 2.0]);
    for (i, color) in colors.iter().enumerate() {
        let (x, y) = (16 * (i % 3) as i32 + 8, 16 * (i / 3) as i32 + 8);
        assert_eq!(pixel(&mut ctx, x, y), *color, "texel {i}");
    }
    assert_eq!(pixel(&mut ctx, 60, 40), colors[2], "clamped to the edge texel");
}

/// `GL_NV_point_sprite`'s r mode: a replaced coordinate set takes r = 0, the vertex's s, or
/// its r, here read from a 3D texture of two slices (red below r = 1/2, green above).
#[test]
fn point_sprite_r_mode() {
    let mut ctx = context();
    let (red, green) = ([255, 0, 0, 255], [0, 255, 0, 255]);
    let texels = [red, green].concat();
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_3D, 1);
        dispatch::glTexImage3D(&mut ctx, gl::GL_TEXTURE_3D, 0, gl::GL_RGBA as i32, 1, 1, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_3D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_3D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_3D);
        dispatch::glEnable(&mut ctx, gl::GL_POINT_SPRITE);
        dispatch::glTexEnvi(&mut ctx, gl::GL_POINT_SPRITE, gl::GL_COORD_REPLACE, 1);
        dispatch::glPointSize(&mut ctx, 8.0);
    }
    // (mode, vertex s, vertex r, expected colour)
    let cases = [(gl::GL_ZERO, 0.9, 0.8, red), (gl::GL_S, 0.9, 0.2, green), (gl::GL_S, 0.1, 0.8, red), (gl::GL_R, 0.1, 0.8, green)];
    for (i, &(mode, s, r, _)) in cases.iter().enumerate() {
        unsafe {
            dispatch::glPointParameteriNV(&mut ctx, gl::GL_POINT_SPRITE_R_MODE_NV, mode as i32);
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glTexCoord3f(&mut ctx, s, 0.5, r);
            dispatch::glVertex2f(&mut ctx, 8.0 + 16.0 * i as f32, 8.0);
            dispatch::glEnd(&mut ctx);
        }
    }
    for (i, &(mode, _, _, color)) in cases.iter().enumerate() {
        assert_eq!(pixel(&mut ctx, 8 + 16 * i as i32, 8), color, "case {i}, mode {mode:#x}");
    }
}
