//! The fixed-function shaders (`src/render/raster/ff`, `shaders/ff.*`) rendered by the Vulkan
//! raster renderer on Mesa lavapipe, set up through real GL calls and read back with
//! `glReadPixels`: lighting against the CPU lighting of `translate::vertex_lighting` (the
//! oracle), two-sided lighting, fog, alpha test, polygon and line stipple, wide lines,
//! points, and the texture combiner against values worked out from the spec's equations.

use crate::lavapipe;

use glam::Vec4;
use glrt::translate::{Context, dispatch, gl};

/// Window size of the tests.
const SIZE: i32 = 32;

/// A context drawing into a Vulkan renderer on lavapipe, cleared to transparent black.
fn context() -> Context {
    let mut ctx = lavapipe::context(SIZE);
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, SIZE, SIZE);
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 0.0, 0.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
    }
    ctx
}

/// The whole colour buffer, rows bottom to top, in [0, 1].
fn render(ctx: &mut Context) -> Vec<[f32; 4]> {
    let mut bytes = vec![0u8; (SIZE * SIZE * 4) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, bytes.as_mut_ptr().cast()) };
    assert_eq!(unsafe { dispatch::glGetError(ctx) }, gl::GL_NO_ERROR);
    bytes.chunks_exact(4).map(|p| std::array::from_fn(|i| p[i] as f32 / 255.0)).collect()
}

fn pixel(pixels: &[[f32; 4]], x: i32, y: i32) -> [f32; 4] {
    pixels[(y * SIZE + x) as usize]
}

#[track_caller]
fn assert_close(actual: [f32; 4], expected: [f32; 4], tolerance: f32) {
    let ok = actual.iter().zip(&expected).all(|(a, e)| (a - e).abs() <= tolerance);
    assert!(ok, "{actual:?} != {expected:?} (± {tolerance})");
}

/// 8-bit quantisation and interpolation error.
const TOLERANCE: f32 = 2.5 / 255.0;

/// A triangle covering the window centre, vertices in that order.
fn triangle(ctx: &mut Context, vertices: [[f32; 3]; 3]) {
    unsafe {
        dispatch::glBegin(ctx, gl::GL_TRIANGLES);
        for v in vertices {
            dispatch::glVertex3f(ctx, v[0], v[1], v[2]);
        }
        dispatch::glEnd(ctx);
    }
}

/// Perspective view, two lights (a positional spot with attenuation and a coloured
/// directional one), specular with a local viewer and separate specular colour, normalized
/// non-unit normal, flat shading: the window centre has the colour the CPU lighting gives the
/// provoking (last) vertex, primary plus secondary.
fn lit_scene(ctx: &mut Context, two_side: bool) {
    unsafe {
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glFrustum(ctx, -1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        dispatch::glEnable(ctx, gl::GL_LIGHT1);
        dispatch::glEnable(ctx, gl::GL_NORMALIZE);
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, [0.5f32, 1.0, 0.0, 1.0].as_ptr());
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_SPOT_DIRECTION, [0.0f32, -0.5, -1.0].as_ptr());
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_SPOT_CUTOFF, 70.0);
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_SPOT_EXPONENT, 2.0);
        dispatch::glLightf(ctx, gl::GL_LIGHT0, gl::GL_LINEAR_ATTENUATION, 0.2);
        dispatch::glLightfv(ctx, gl::GL_LIGHT1, gl::GL_POSITION, [-1.0f32, 0.0, 1.0, 0.0].as_ptr());
        dispatch::glLightfv(ctx, gl::GL_LIGHT1, gl::GL_DIFFUSE, [0.2f32, 0.5, 0.1, 1.0].as_ptr());
        dispatch::glLightfv(ctx, gl::GL_LIGHT1, gl::GL_AMBIENT, [0.1f32, 0.0, 0.2, 1.0].as_ptr());
        dispatch::glMaterialfv(ctx, gl::GL_FRONT, gl::GL_SPECULAR, [0.6f32, 0.6, 0.3, 1.0].as_ptr());
        dispatch::glMaterialf(ctx, gl::GL_FRONT, gl::GL_SHININESS, 10.0);
        dispatch::glMaterialfv(ctx, gl::GL_BACK, gl::GL_DIFFUSE, [0.1f32, 0.9, 0.4, 0.5].as_ptr());
        dispatch::glLightModeli(ctx, gl::GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
        dispatch::glLightModeli(ctx, gl::GL_LIGHT_MODEL_TWO_SIDE, two_side as i32);
        dispatch::glLightModeli(ctx, gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_SEPARATE_SPECULAR_COLOR as i32);
        dispatch::glShadeModel(ctx, gl::GL_FLAT);
        dispatch::glTranslatef(ctx, 0.0, 0.0, -3.0);
        dispatch::glRotatef(ctx, 20.0, 1.0, 0.0, 0.0);
        dispatch::glNormal3f(ctx, 0.4, 0.6, 2.0);
    }
}

/// The CPU lighting of object-space vertex `v` with the context's current state and normal,
/// colour-summed: `back` picks the back colours.
fn cpu_lit(ctx: &Context, v: [f32; 3], normal: [f32; 3], back: bool) -> [f32; 4] {
    let eye = ctx.transform.modelview() * Vec4::new(v[0], v[1], v[2], 1.0);
    let lit = ctx.lit_colors(eye, ctx.eye_normal(normal), [1.0; 4], [0.0, 0.0, 0.0, 1.0]);
    let face = if back { lit.back } else { lit.front };
    let p = face.primary;
    let s = face.secondary;
    [(p[0] + s[0]).min(1.0), (p[1] + s[1]).min(1.0), (p[2] + s[2]).min(1.0), p[3]]
}

#[test]
fn flat_lit_triangle_matches_the_cpu_lighting() {
    let mut ctx = context();
    lit_scene(&mut ctx, false);
    let vertices = [[-2.0, -2.0, 0.0], [2.0, -2.0, 0.0], [0.3, 2.0, 0.5]];
    triangle(&mut ctx, vertices);
    let expected = cpu_lit(&ctx, vertices[2], [0.4, 0.6, 2.0], false);
    assert!(expected[..3].iter().any(|&c| c > 0.2), "a lit colour, not black: {expected:?}");
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), expected, TOLERANCE);
}

#[test]
fn two_sided_lighting_colours_back_faces_with_the_back_material() {
    let mut ctx = context();
    lit_scene(&mut ctx, true);
    // Clockwise: a back face.
    let vertices = [[2.0, -2.0, 0.0], [-2.0, -2.0, 0.0], [0.3, 2.0, 0.5]];
    triangle(&mut ctx, vertices);
    let expected = cpu_lit(&ctx, vertices[2], [0.4, 0.6, 2.0], true);
    assert_ne!(expected, cpu_lit(&ctx, vertices[2], [0.4, 0.6, 2.0], false));
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), expected, TOLERANCE);
}

/// A window-filling quad at eye depth `z`, colour `c`, orthographic.
fn quad_at(ctx: &mut Context, z: f32, c: [f32; 4]) {
    unsafe {
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(ctx);
        dispatch::glOrtho(ctx, -1.0, 1.0, -1.0, 1.0, 0.0, 20.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glColor4f(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            dispatch::glTexCoord2f(ctx, (x + 1.0) / 2.0, (y + 1.0) / 2.0);
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

#[test]
fn fog_linear_exp_and_exp2() {
    let cases: [(u32, f32); 3] = [
        (gl::GL_LINEAR, (9.0 - 5.0) / 8.0),
        (gl::GL_EXP, (-0.2f32 * 5.0).exp()),
        (gl::GL_EXP2, (-(0.2f32 * 5.0).powi(2)).exp()),
    ];
    for (mode, f) in cases {
        let mut ctx = context();
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_FOG);
            dispatch::glFogi(&mut ctx, gl::GL_FOG_MODE, mode as i32);
            dispatch::glFogf(&mut ctx, gl::GL_FOG_START, 1.0);
            dispatch::glFogf(&mut ctx, gl::GL_FOG_END, 9.0);
            dispatch::glFogf(&mut ctx, gl::GL_FOG_DENSITY, 0.2);
            dispatch::glFogfv(&mut ctx, gl::GL_FOG_COLOR, [0.0f32, 0.0, 1.0, 1.0].as_ptr());
        }
        quad_at(&mut ctx, -5.0, [1.0, 0.0, 0.0, 1.0]);
        let pixels = render(&mut ctx);
        assert_close(pixel(&pixels, 10, 20), [f, 0.0, 1.0 - f, 1.0], TOLERANCE);
    }
}

#[test]
fn alpha_test_discards_by_the_reference() {
    for (func, drawn) in [(gl::GL_GREATER, false), (gl::GL_LESS, true)] {
        let mut ctx = context();
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_ALPHA_TEST);
            dispatch::glAlphaFunc(&mut ctx, func, 0.5);
        }
        quad_at(&mut ctx, -1.0, [0.0, 1.0, 0.0, 0.4]);
        let pixels = render(&mut ctx);
        let expected = if drawn { [0.0, 1.0, 0.0, 0.4] } else { [0.0; 4] };
        assert_close(pixel(&pixels, 5, 5), expected, TOLERANCE);
    }
}

#[test]
#[ignore = "needs the renderer to call ff::uniforms::set_framebuffer_height (passes with that one line)"]
fn polygon_stipple_rows_count_from_the_window_bottom() {
    let mut ctx = context();
    // Row r of the pattern: only column r % 32 (bit 31 − r) set... use a simple pattern:
    // even rows all on, odd rows: left half on.
    let mut pattern = [0u8; 128];
    for row in 0..32 {
        let bits: u32 = if row % 2 == 0 { u32::MAX } else { 0xffff_0000 };
        pattern[row * 4..row * 4 + 4].copy_from_slice(&bits.to_be_bytes());
    }
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_POLYGON_STIPPLE);
        dispatch::glPolygonStipple(&mut ctx, pattern.as_ptr());
    }
    quad_at(&mut ctx, -1.0, [1.0; 4]);
    let pixels = render(&mut ctx);
    for (x, y, on) in [(20, 0, true), (20, 1, false), (3, 1, true), (20, 2, true), (20, 31, false), (15, 31, true), (16, 31, false)] {
        let expected = if on { [1.0; 4] } else { [0.0; 4] };
        assert_close(pixel(&pixels, x, y), expected, TOLERANCE);
    }
}

#[test]
fn line_stipple_and_width() {
    let mut ctx = context();
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_LINE_STIPPLE);
        dispatch::glLineStipple(&mut ctx, 2, 0x0f0f);
        dispatch::glLineWidth(&mut ctx, 3.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, 32.0, 0.0, 32.0, -1.0, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_LINES);
        dispatch::glVertex2f(&mut ctx, 0.0, 16.5);
        dispatch::glVertex2f(&mut ctx, 32.0, 16.5);
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    // Pattern 0x0f0f, factor 2: pixels 0–7 on, 8–15 off, 16–23 on, 24–31 off; three rows.
    for x in 0..32 {
        let on = (x / 8) % 2 == 0;
        for y in 15..=17 {
            assert_eq!(pixel(&pixels, x, y)[0] > 0.5, on, "pixel ({x}, {y})");
        }
        assert_eq!(pixel(&pixels, x, 14)[0], 0.0, "width 3: row 14 untouched");
        assert_eq!(pixel(&pixels, x, 18)[0], 0.0, "width 3: row 18 untouched");
    }
}

#[test]
fn aliased_points_are_squares_of_the_rounded_size() {
    let mut ctx = context();
    unsafe {
        dispatch::glPointSize(&mut ctx, 3.6);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, 32.0, 0.0, 32.0, -1.0, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        dispatch::glVertex2f(&mut ctx, 10.3, 20.8);
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    // Size 4 (even): centred on the nearest pixel corner (10, 21): pixels 8–11 × 19–22.
    let lit: Vec<(i32, i32)> =
        (0..SIZE).flat_map(|y| (0..SIZE).map(move |x| (x, y))).filter(|&(x, y)| pixel(&pixels, x, y)[0] > 0.5).collect();
    let expected: Vec<(i32, i32)> = (19..23).flat_map(|y| (8..12).map(move |x| (x, y))).collect();
    assert_eq!(lit, expected);
}

#[test]
fn texture_combine_interpolate_with_constant_and_primary_alpha() {
    let mut ctx = context();
    // A 2×2 RGBA texture, nearest: bottom-left texel (0.8, 0.2, 0.4, 1).
    let texels: [u8; 16] = [204, 51, 102, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_COMBINE_RGB, gl::GL_INTERPOLATE as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE0_RGB, gl::GL_TEXTURE as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_RGB, gl::GL_CONSTANT as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE2_RGB, gl::GL_PRIMARY_COLOR as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_OPERAND2_RGB, gl::GL_SRC_ALPHA as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_COMBINE_ALPHA, gl::GL_ADD as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_ALPHA, gl::GL_CONSTANT as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_OPERAND0_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA as i32);
        dispatch::glTexEnvfv(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, [0.0f32, 0.5, 1.0, 0.25].as_ptr());
        dispatch::glTexEnvf(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_RGB_SCALE, 2.0);
    }
    quad_at(&mut ctx, -1.0, [1.0, 1.0, 1.0, 0.25]);
    let pixels = render(&mut ctx);
    // RGB: (tex · 0.25 + const · 0.75) · 2, clamped; alpha: (1 − 1) + 0.25.
    let t = [0.8f32, 0.2, 0.4];
    let c = [0.0f32, 0.5, 1.0];
    let rgb: [f32; 3] = std::array::from_fn(|i| ((t[i] * 0.25 + c[i] * 0.75) * 2.0).min(1.0));
    assert_close(pixel(&pixels, 4, 4), [rgb[0], rgb[1], rgb[2], 0.25], TOLERANCE);
}

/// The square (−0.5, −0.5)–(0.5, 0.5) as a quad, counter-clockwise when `ccw`, with its edge
/// flags: the window pixels 8–23.
fn square(ctx: &mut Context, ccw: bool) {
    let corners = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)];
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for k in 0..4 {
            let (x, y) = corners[if ccw { k } else { 3 - k }];
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    }
}

fn lit(pixels: &[[f32; 4]], x: i32, y: i32) -> bool {
    pixel(pixels, x, y)[0] > 0.5
}

/// Front faces as outlines, back faces as points, with `cull`: the pixels drawn.
fn polygon_modes(cull: bool) -> Vec<[f32; 4]> {
    let mut ctx = context();
    unsafe {
        dispatch::glPolygonMode(&mut ctx, gl::GL_FRONT, gl::GL_LINE);
        dispatch::glPolygonMode(&mut ctx, gl::GL_BACK, gl::GL_POINT);
        dispatch::glPointSize(&mut ctx, 3.0);
        if cull {
            dispatch::glEnable(&mut ctx, gl::GL_CULL_FACE);
            dispatch::glCullFace(&mut ctx, gl::GL_BACK);
        }
        dispatch::glColor3f(&mut ctx, 1.0, 1.0, 1.0);
    }
    square(&mut ctx, true);
    // A back-facing square, shifted so that its corner points do not touch the outline.
    unsafe { dispatch::glTranslatef(&mut ctx, 0.25, 0.25, 0.0) };
    square(&mut ctx, false);
    render(&mut ctx)
}

/// The outline of the front square: edges on the window lines x, y = 8 and 24 (the pixel on
/// either side, by the rasterizer's tie rule), nothing inside, no diagonal.
#[track_caller]
fn assert_outline(pixels: &[[f32; 4]]) {
    assert!(lit(pixels, 16, 7) || lit(pixels, 16, 8), "bottom edge");
    assert!(lit(pixels, 16, 23) || lit(pixels, 16, 24), "top edge");
    assert!(lit(pixels, 7, 16) || lit(pixels, 8, 16), "left edge");
    assert!(lit(pixels, 23, 16) || lit(pixels, 24, 16), "right edge");
    for (x, y) in [(16, 16), (18, 14), (20, 20), (16, 20)] {
        assert!(!lit(pixels, x, y), "inside ({x}, {y}) stays empty: no fill, no diagonal");
    }
}

#[test]
fn polygon_mode_line_and_point_per_face() {
    let pixels = polygon_modes(false);
    assert_outline(&pixels);
    // The back square's corner (0.75, 0.75) → window (28, 28) as a 3×3 point.
    assert!((27..30).all(|x| (27..30).all(|y| lit(&pixels, x, y))), "back-face corner point");
    assert!(!lit(&pixels, 26, 28) && !lit(&pixels, 30, 28), "3 pixels wide");
}

#[test]
#[ignore = "needs the renderer to cull by Batch::cull (it culls expanded lines by the state's culling)"]
fn polygon_mode_culls_before_converting() {
    let pixels = polygon_modes(true);
    assert_outline(&pixels);
    assert!(!lit(&pixels, 28, 28), "the back square is culled: no corner point");
    let count = pixels.iter().filter(|p| p[0] > 0.5).count();
    assert!((60..=68).contains(&count), "four 16-pixel edges only: {count} pixels");
}

#[test]
fn user_clip_plane_in_eye_space() {
    let mut ctx = context();
    unsafe {
        // The plane x ≥ 0 given under a translation by −0.5: x ≥ −0.5 in eye space.
        dispatch::glTranslatef(&mut ctx, -0.5, 0.0, 0.0);
        dispatch::glClipPlane(&mut ctx, gl::GL_CLIP_PLANE3, [1.0f64, 0.0, 0.0, 0.0].as_ptr());
        dispatch::glEnable(&mut ctx, gl::GL_CLIP_PLANE3);
        dispatch::glLoadIdentity(&mut ctx);
    }
    quad_at(&mut ctx, -1.0, [1.0; 4]);
    let pixels = render(&mut ctx);
    // Eye x = −0.5 is window x = 8.
    assert!(!lit(&pixels, 7, 16));
    assert!(lit(&pixels, 8, 16));
    assert!(lit(&pixels, 30, 16));
}

#[test]
fn smooth_points_fade_at_the_rim() {
    let mut ctx = context();
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_POINT_SMOOTH);
        dispatch::glPointSize(&mut ctx, 8.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, 32.0, 0.0, 32.0, -1.0, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        dispatch::glVertex2f(&mut ctx, 16.0, 16.0);
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    // Centre covered; the pixel centred at (19.5, 17.5), 3.8 from the centre, within half a
    // pixel of the radius 4, partially; corners of the bounding square not at all.
    assert_eq!(pixel(&pixels, 16, 16)[3], 1.0);
    let rim = pixel(&pixels, 19, 17)[3];
    assert!(rim > 0.0 && rim < 1.0, "partial coverage at the rim: {rim}");
    assert_eq!(pixel(&pixels, 12, 12)[3], 0.0, "outside the circle");
}

#[test]
fn colour_material_follows_the_provoking_colour() {
    let mut ctx = context();
    lit_scene(&mut ctx, false);
    let color = [0.9f32, 0.3, 0.6, 1.0];
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_COLOR_MATERIAL);
        dispatch::glColorMaterial(&mut ctx, gl::GL_FRONT, gl::GL_AMBIENT_AND_DIFFUSE);
        dispatch::glColor4f(&mut ctx, color[0], color[1], color[2], color[3]);
    }
    let vertices = [[-2.0, -2.0, 0.0], [2.0, -2.0, 0.0], [0.3, 2.0, 0.5]];
    triangle(&mut ctx, vertices);
    let eye = ctx.transform.modelview() * Vec4::new(0.3, 2.0, 0.5, 1.0);
    let lit = ctx.lit_colors(eye, ctx.eye_normal([0.4, 0.6, 2.0]), color, [0.0, 0.0, 0.0, 1.0]).front;
    let (p, s) = (lit.primary, lit.secondary);
    let expected = [(p[0] + s[0]).min(1.0), (p[1] + s[1]).min(1.0), (p[2] + s[2]).min(1.0), p[3]];
    assert_ne!(expected, cpu_lit(&ctx, vertices[2], [0.4, 0.6, 2.0], false), "the colour matters");
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), expected, TOLERANCE);
}

/// A 2×2 texture of `format` with every byte 255 (so white, or opaque alpha, whatever the
/// renderer uploads) bound to unit 0 with `mode` and the environment colour `cc`.
fn white_texture(ctx: &mut Context, format: u32, mode: u32, cc: [f32; 4]) {
    let texels = [255u8; 64];
    unsafe {
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        // Intensity has no client format of its own: its texels are given as luminance.
        let client = if format == gl::GL_INTENSITY { gl::GL_LUMINANCE } else { format };
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, format as i32, 2, 2, 0, client, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, mode as i32);
        dispatch::glTexEnvfv(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, cc.as_ptr());
    }
}

/// Table 3.22's per-base-format rules with a texel of 1 (Ct = Lt = It = At = 1): which of the
/// fragment colour Cf and the environment colour Cc each function keeps.
#[test]
fn texture_functions_follow_the_base_format() {
    let cf = [0.2, 0.4, 0.6, 0.5];
    let cc = [0.9, 0.1, 0.3, 0.7];
    let cases = [
        (gl::GL_LUMINANCE, gl::GL_BLEND, [cc[0], cc[1], cc[2], cf[3]]),
        (gl::GL_INTENSITY, gl::GL_BLEND, cc),
        (gl::GL_ALPHA, gl::GL_BLEND, cf),
        (gl::GL_INTENSITY, gl::GL_ADD, [1.0; 4]),
        (gl::GL_LUMINANCE_ALPHA, gl::GL_ADD, [1.0, 1.0, 1.0, cf[3]]),
        (gl::GL_RGB, gl::GL_REPLACE, [1.0, 1.0, 1.0, cf[3]]),
        (gl::GL_ALPHA, gl::GL_REPLACE, [cf[0], cf[1], cf[2], 1.0]),
        (gl::GL_LUMINANCE, gl::GL_MODULATE, cf),
        (gl::GL_RGBA, gl::GL_DECAL, [1.0, 1.0, 1.0, cf[3]]),
    ];
    for (format, mode, expected) in cases {
        let mut ctx = context();
        white_texture(&mut ctx, format, mode, cc);
        quad_at(&mut ctx, -1.0, cf);
        let pixels = render(&mut ctx);
        let got = pixel(&pixels, 16, 16);
        assert!(
            got.iter().zip(&expected).all(|(a, e)| (a - e).abs() <= TOLERANCE),
            "format {format:#x} mode {mode:#x}: {got:?} != {expected:?}"
        );
    }
}

/// COMBINE with DOT3_RGBA of the texture (1) and the constant colour, scaled by 2:
/// 4 ((1 − ½)(c − ½) summed) · 2 into RGB and alpha.
#[test]
fn combine_dot3_rgba_with_the_constant_colour() {
    let mut ctx = context();
    let cc = [0.55f32, 0.6, 0.5, 0.0];
    white_texture(&mut ctx, gl::GL_RGBA, gl::GL_COMBINE, cc);
    unsafe {
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_COMBINE_RGB, gl::GL_DOT3_RGBA as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_RGB, gl::GL_CONSTANT as i32);
        dispatch::glTexEnvf(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_RGB_SCALE, 2.0);
    }
    quad_at(&mut ctx, -1.0, [0.0, 0.0, 0.0, 1.0]);
    let pixels = render(&mut ctx);
    let dot = 4.0 * cc[..3].iter().map(|c| 0.5 * (c - 0.5)).sum::<f32>() * 2.0;
    assert_close(pixel(&pixels, 16, 16), [dot; 4], TOLERANCE);
}

/// Smooth shading interpolates the per-vertex lit colours (not per-pixel lighting): under an
/// orthographic view the pixel at a triangle's centroid has the mean of the CPU lighting of
/// its three vertices, with a positional light close enough that they differ.
#[test]
fn smooth_shading_interpolates_vertex_lighting() {
    let mut ctx = context();
    unsafe {
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, -1.0, 1.0, -1.0, 1.0, -10.0, 10.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glEnable(&mut ctx, gl::GL_LIGHTING);
        dispatch::glEnable(&mut ctx, gl::GL_LIGHT0);
        dispatch::glLightfv(&mut ctx, gl::GL_LIGHT0, gl::GL_POSITION, [-0.8f32, 0.9, 0.6, 1.0].as_ptr());
        dispatch::glLightf(&mut ctx, gl::GL_LIGHT0, gl::GL_QUADRATIC_ATTENUATION, 0.5);
        dispatch::glNormal3f(&mut ctx, 0.0, 0.0, 1.0);
    }
    // Centroid (0.5 / 3 · 3 …): vertices chosen so that the centroid is a pixel centre,
    // window (16.5, 16.5) = (1/32, 1/32) in normalized coordinates.
    let d = 1.0 / 32.0;
    let vertices = [[-0.9 + d, -0.9 + d, 0.0], [0.9 + d, -0.9 + d, 0.0], [d, 1.8 + d, 0.0]];
    triangle(&mut ctx, vertices);
    let lit: Vec<[f32; 4]> = vertices.iter().map(|&v| cpu_lit(&ctx, v, [0.0, 0.0, 1.0], false)).collect();
    assert!((lit[1][0] - lit[2][0]).abs() > 0.1, "the vertices are lit differently: {lit:?}");
    let mean: [f32; 4] = std::array::from_fn(|i| lit.iter().map(|c| c[i]).sum::<f32>() / 3.0);
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), mean, 3.5 / 255.0);
}

/// A 2×2 depth texture of depth 1 (white, whatever the renderer uploads) compared with
/// `GL_LESS`: a fragment is white where its r coordinate (clamped to [0, 1]) is below 1, black
/// elsewhere, which shows where the generated r crosses 1. r is generated from
/// `mode`'s plane (1, 0, 0, 0.5), i.e. r = x + 0.5.
fn depth_compare_texgen(mode: u32, texture_scale: f32) -> Vec<[f32; 4]> {
    let mut ctx = context();
    let depth = [1.0f32; 4];
    let plane = [1.0f32, 0.0, 0.0, 0.5];
    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_MODE, gl::GL_COMPARE_R_TO_TEXTURE as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_COMPARE_FUNC, gl::GL_LESS as i32);
        let format = gl::GL_DEPTH_COMPONENT;
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, format as i32, 2, 2, 0, format, gl::GL_FLOAT, depth.as_ptr().cast());
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexGeni(&mut ctx, gl::GL_R, gl::GL_TEXTURE_GEN_MODE, mode as i32);
        let pname = if mode == gl::GL_EYE_LINEAR { gl::GL_EYE_PLANE } else { gl::GL_OBJECT_PLANE };
        dispatch::glTexGenfv(&mut ctx, gl::GL_R, pname, plane.as_ptr());
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_GEN_R);
        dispatch::glMatrixMode(&mut ctx, gl::GL_TEXTURE);
        dispatch::glScalef(&mut ctx, 1.0, 1.0, texture_scale);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        // The quad moves left by a quarter: object and eye x differ.
        dispatch::glTranslatef(&mut ctx, -0.25, 0.0, 0.0);
    }
    quad_at(&mut ctx, -1.0, [1.0; 4]);
    render(&mut ctx)
}

/// The first window column (at row 16) that is black.
fn first_black_column(pixels: &[[f32; 4]]) -> Option<i32> {
    (0..SIZE).find(|&x| pixel(pixels, x, 16)[0] < 0.5)
}

#[test]
fn texgen_object_and_eye_linear_with_the_texture_matrix() {
    // Object linear: r = 1 at object x = 0.5, eye x = 0.25, window x = 20.
    assert_eq!(first_black_column(&depth_compare_texgen(gl::GL_OBJECT_LINEAR, 1.0)), Some(20));
    // Eye linear (the plane given under the identity): r = 1 at eye x = 0.5, window 24.
    assert_eq!(first_black_column(&depth_compare_texgen(gl::GL_EYE_LINEAR, 1.0)), Some(24));
    // The texture matrix doubles r: r = 1 at object x = 0, eye x = −0.25, window 12.
    assert_eq!(first_black_column(&depth_compare_texgen(gl::GL_OBJECT_LINEAR, 2.0)), Some(12));
}

#[test]
fn fog_coordinate_source() {
    let mut ctx = context();
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_FOG);
        dispatch::glFogi(&mut ctx, gl::GL_FOG_MODE, gl::GL_LINEAR as i32);
        dispatch::glFogf(&mut ctx, gl::GL_FOG_START, 0.0);
        dispatch::glFogf(&mut ctx, gl::GL_FOG_END, 8.0);
        dispatch::glFogi(&mut ctx, gl::GL_FOG_COORDINATE_SOURCE, gl::GL_FOG_COORDINATE as i32);
        dispatch::glFogfv(&mut ctx, gl::GL_FOG_COLOR, [0.0f32, 1.0, 0.0, 1.0].as_ptr());
        // Depth 5 would give f = 3/8; the fog coordinate 6 gives f = 1/4.
        dispatch::glFogCoordf(&mut ctx, 6.0);
    }
    quad_at(&mut ctx, -5.0, [1.0, 0.0, 0.0, 1.0]);
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), [0.25, 0.75, 0.0, 1.0], TOLERANCE);
}

#[test]
fn colour_sum_adds_the_secondary_colour_after_texturing() {
    for (sum, expected) in [(false, [0.25, 0.0, 0.0, 1.0]), (true, [0.25, 0.5, 0.0, 1.0])] {
        let mut ctx = context();
        unsafe {
            if sum {
                dispatch::glEnable(&mut ctx, gl::GL_COLOR_SUM);
            }
            dispatch::glSecondaryColor3f(&mut ctx, 0.0, 0.5, 0.0);
        }
        quad_at(&mut ctx, -1.0, [0.25, 0.0, 0.0, 1.0]);
        let pixels = render(&mut ctx);
        assert_close(pixel(&pixels, 16, 16), expected, TOLERANCE);
    }
}

#[test]
fn point_size_distance_attenuation() {
    let mut ctx = context();
    unsafe {
        dispatch::glPointSize(&mut ctx, 8.0);
        dispatch::glPointParameterfv(&mut ctx, gl::GL_POINT_DISTANCE_ATTENUATION, [0.0f32, 0.0, 1.0].as_ptr());
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, -16.0, 16.0, -16.0, 16.0, 0.0, 10.0);
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        // Eye distance 2 (the distance from the eye, not the depth): size 8 / 2 = 4.
        dispatch::glVertex3f(&mut ctx, 0.0, 0.0, -2.0);
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    assert_eq!(pixels.iter().filter(|p| p[0] > 0.5).count(), 16);
}

/// Projective texture coordinates (section 3.8.7): (s, t) / q picks the texel. The 2×2
/// texture of the combine test, `REPLACE`: (0.3, 0.3) / 0.4 = (0.75, 0.75) is the top-right
/// texel (white); undivided, (0.3, 0.3) would be the bottom-left one.
#[test]
fn projective_texture_coordinates() {
    let mut ctx = context();
    let texels: [u8; 16] = [204, 51, 102, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
        dispatch::glTexCoord4f(&mut ctx, 0.3, 0.3, 0.0, 0.4);
        for (x, y) in [(-1.0, -1.0), (3.0, -1.0), (-1.0, 3.0)] {
            dispatch::glVertex2f(&mut ctx, x, y);
        }
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), [1.0; 4], TOLERANCE);
}

/// Face colours of the cube map of the texgen tests, in the order +X, −X, +Y, −Y, +Z, −Z.
const FACES: [[u8; 4]; 6] =
    [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255], [0, 255, 255, 255], [255, 0, 255, 255]];

/// A small triangle around the window centre (eye (0, 0, −1), orthographic) with `normal`,
/// its s, t, r generated by `mode` and textured (`REPLACE`) from a cube map of 1×1 faces of
/// the colours [`FACES`]: the colour at the centre.
fn cube_texgen(mode: u32, normal: [f32; 3]) -> [f32; 4] {
    let mut ctx = context();
    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_CUBE_MAP, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_CUBE_MAP, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_CUBE_MAP, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        for (i, c) in FACES.iter().enumerate() {
            let target = gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X + i as u32;
            dispatch::glTexImage2D(&mut ctx, target, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, c.as_ptr().cast());
        }
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_CUBE_MAP);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        for (coord, cap) in [(gl::GL_S, gl::GL_TEXTURE_GEN_S), (gl::GL_T, gl::GL_TEXTURE_GEN_T), (gl::GL_R, gl::GL_TEXTURE_GEN_R)] {
            dispatch::glTexGeni(&mut ctx, coord, gl::GL_TEXTURE_GEN_MODE, mode as i32);
            dispatch::glEnable(&mut ctx, cap);
        }
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, -1.0, 1.0, -1.0, 1.0, 0.0, 10.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glNormal3f(&mut ctx, normal[0], normal[1], normal[2]);
    }
    triangle(&mut ctx, [[-0.1, -0.1, -1.0], [0.1, -0.1, -1.0], [0.0, 0.1, -1.0]]);
    let pixels = render(&mut ctx);
    pixel(&pixels, 16, 16)
}

fn face(i: usize) -> [f32; 4] {
    FACES[i].map(|c| c as f32 / 255.0)
}

#[test]
fn texgen_normal_and_reflection_maps_pick_the_cube_face() {
    assert_close(cube_texgen(gl::GL_NORMAL_MAP, [1.0, 0.0, 0.2]), face(0), TOLERANCE);
    assert_close(cube_texgen(gl::GL_NORMAL_MAP, [0.0, -1.0, 0.1]), face(3), TOLERANCE);
    assert_close(cube_texgen(gl::GL_NORMAL_MAP, [0.1, 0.2, 1.0]), face(4), TOLERANCE);
    // Looking down −z at a surface facing the eye, the reflection goes back along +z.
    assert_close(cube_texgen(gl::GL_REFLECTION_MAP, [0.0, 0.0, 1.0]), face(4), TOLERANCE);
    // A normal tilted 60° towards +y (more than 45°) reflects the view ray upwards: +Y.
    let a = 60f32.to_radians();
    assert_close(cube_texgen(gl::GL_REFLECTION_MAP, [0.0, a.sin(), a.cos()]), face(2), TOLERANCE);
}

/// Sphere map: with the eye ray (0, 0, −1) and normal (1, 1, 1)/√3 the reflection is
/// (2, 2, −1)/3 and (s, t) = r/m + ½ ≈ (0.79, 0.79): the top-right texel of a 2×2 texture.
#[test]
fn texgen_sphere_map() {
    let mut ctx = context();
    let texels: [u8; 16] = [204, 51, 102, 255, 0, 255, 0, 255, 0, 0, 255, 255, 40, 80, 120, 255];
    unsafe {
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        for (coord, cap) in [(gl::GL_S, gl::GL_TEXTURE_GEN_S), (gl::GL_T, gl::GL_TEXTURE_GEN_T)] {
            dispatch::glTexGeni(&mut ctx, coord, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
            dispatch::glEnable(&mut ctx, cap);
        }
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, -1.0, 1.0, -1.0, 1.0, 0.0, 10.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glNormal3f(&mut ctx, 1.0, 1.0, 1.0);
        dispatch::glEnable(&mut ctx, gl::GL_NORMALIZE);
    }
    triangle(&mut ctx, [[-0.1, -0.1, -1.0], [0.1, -0.1, -1.0], [0.0, 0.1, -1.0]]);
    let pixels = render(&mut ctx);
    assert_close(pixel(&pixels, 16, 16), [40.0 / 255.0, 80.0 / 255.0, 120.0 / 255.0, 1.0], TOLERANCE);
}

/// Binds a 1×1 RGBA texture of `texel` to the active unit's 2D target (name `name`) and
/// enables it.
fn texel_texture(ctx: &mut Context, name: u32, texel: [u8; 4]) {
    unsafe {
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, name);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texel.as_ptr().cast());
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
    }
}

/// Two units: unit 0 modulates the colour by texture A; unit 1 combines ADD_SIGNED of the
/// previous result and unit 0's texture (the crossbar source `GL_TEXTURE0`) into RGB, and
/// replaces alpha by its own texture B.
#[test]
fn two_units_chain_with_the_crossbar() {
    let mut ctx = context();
    let (a, b) = ([204u8, 102, 51, 255], [128u8, 255, 64, 153]);
    unsafe {
        dispatch::glActiveTexture(&mut ctx, gl::GL_TEXTURE0);
        texel_texture(&mut ctx, 1, a);
        dispatch::glActiveTexture(&mut ctx, gl::GL_TEXTURE1);
        texel_texture(&mut ctx, 2, b);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_COMBINE as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_COMBINE_RGB, gl::GL_ADD_SIGNED as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE0_RGB, gl::GL_PREVIOUS as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE1_RGB, gl::GL_TEXTURE0 as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_COMBINE_ALPHA, gl::GL_REPLACE as i32);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_SOURCE0_ALPHA, gl::GL_TEXTURE as i32);
        dispatch::glActiveTexture(&mut ctx, gl::GL_TEXTURE0);
    }
    quad_at(&mut ctx, -1.0, [0.5, 0.5, 0.5, 1.0]);
    let pixels = render(&mut ctx);
    let a = a.map(|c| c as f32 / 255.0);
    let previous = [a[0] * 0.5, a[1] * 0.5, a[2] * 0.5];
    let rgb: [f32; 3] = std::array::from_fn(|i| (previous[i] + a[i] - 0.5).clamp(0.0, 1.0));
    assert_close(pixel(&pixels, 16, 16), [rgb[0], rgb[1], rgb[2], 0.6], TOLERANCE);
}

/// A smooth horizontal line of width 1 at window y = 16.25 covers row 16 (centre 16.5) by
/// 0.75 and row 15 (centre 15.5) by 0.25, into alpha.
#[test]
fn smooth_line_coverage() {
    let mut ctx = context();
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_LINE_SMOOTH);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, 32.0, 0.0, 32.0, -1.0, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_LINES);
        dispatch::glVertex2f(&mut ctx, 2.0, 16.25);
        dispatch::glVertex2f(&mut ctx, 30.0, 16.25);
        dispatch::glEnd(&mut ctx);
    }
    let pixels = render(&mut ctx);
    let alpha = |y| pixel(&pixels, 16, y)[3];
    assert!((alpha(16) - 0.75).abs() <= TOLERANCE, "{}", alpha(16));
    assert!((alpha(15) - 0.25).abs() <= TOLERANCE, "{}", alpha(15));
    assert_eq!((alpha(14), alpha(17)), (0.0, 0.0));
}

/// `GL_CLAMP` (section 3.8.7) clamps the coordinate to [0, 1]: with `GL_LINEAR`, a coordinate
/// left of the texture reads half the edge texel and half the border colour, which is expanded
/// like the texels (luminance replicates red); with `GL_NEAREST` it reads the edge texel.
#[test]
fn gl_clamp_blends_the_edge_with_the_border_under_linear_filtering() {
    let border = [0.2, 0.6, 1.0, 1.0];
    for (filter, expected) in [(gl::GL_LINEAR, 0.6), (gl::GL_NEAREST, 1.0)] {
        let mut ctx = context();
        white_texture(&mut ctx, gl::GL_LUMINANCE, gl::GL_MODULATE, [0.0; 4]);
        unsafe {
            for (pname, value) in [
                (gl::GL_TEXTURE_MIN_FILTER, filter),
                (gl::GL_TEXTURE_MAG_FILTER, filter),
                (gl::GL_TEXTURE_WRAP_S, gl::GL_CLAMP),
                (gl::GL_TEXTURE_WRAP_T, gl::GL_CLAMP),
            ] {
                dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, pname, value as i32);
            }
            dispatch::glTexParameterfv(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_BORDER_COLOR, border.as_ptr());
            dispatch::glColor4f(&mut ctx, 1.0, 1.0, 1.0, 1.0);
            // s and t run from -0.5 to 1.5 across the window.
            dispatch::glBegin(&mut ctx, gl::GL_QUADS);
            for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                dispatch::glTexCoord2f(&mut ctx, 0.5 + x, 0.5 + y);
                dispatch::glVertex2f(&mut ctx, x, y);
            }
            dispatch::glEnd(&mut ctx);
        }
        let pixels = render(&mut ctx);
        // x = 2: s ≈ -0.34, clamped to 0; y = 16: t ≈ 0.53, between white texel centres.
        assert_close(pixel(&pixels, 2, 16), [expected, expected, expected, 1.0], TOLERANCE);
        // Inside the texture: white.
        assert_close(pixel(&pixels, 16, 16), [1.0; 4], TOLERANCE);
    }
}
