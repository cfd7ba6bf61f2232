//! Drawables without destination alpha (RGB GLX configurations) on the Vulkan raster renderer:
//! `GL_ALPHA_BITS` is 0 and destination alpha is 1 wherever it is read (OpenGL 1.5 section
//! 4.1.8): read-back after drawing and clearing with other alphas, the blend factors
//! `GL_DST_ALPHA`, `GL_ONE_MINUS_DST_ALPHA` and `GL_SRC_ALPHA_SATURATE`, accumulation returns
//! and `glCopyTexImage2D`. Each check also runs on an RGBA drawable, where alpha is kept, so
//! that it tells the two apart. Runs on Mesa lavapipe at 16×16.

use crate::lavapipe;

use glrt::frame::{Surface, Target};
use glrt::render::frame::Renderer;
use glrt::translate::{Context, dispatch, gl};
use lavapipe::pixel;

const SIZE: i32 = 16;

/// A context drawing into a Vulkan renderer on lavapipe, with a 16×16 drawable with or
/// without destination `alpha`.
fn context(alpha: bool) -> Context {
    let mut ctx = lavapipe::context_on(lavapipe::renderer_with(Renderer::new));
    ctx.bind_target(Target { size: [SIZE as u32; 2], surface: Surface::Offscreen, swap_interval: 0, samples: 1, alpha });
    ctx
}

/// Clears the colour buffer to `c`.
fn clear(ctx: &mut Context, c: [f32; 4]) {
    unsafe {
        dispatch::glClearColor(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT);
    }
}

/// Fills the window with a rectangle of colour `c`.
fn fill(ctx: &mut Context, c: [f32; 4]) {
    unsafe {
        dispatch::glColor4f(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glRectf(ctx, -1.0, -1.0, 1.0, 1.0);
    }
}

#[test]
fn alpha_reads_one_after_clearing_and_drawing_other_alphas() {
    for alpha in [false, true] {
        let mut ctx = context(alpha);
        let mut bits = 0;
        unsafe { dispatch::glGetIntegerv(&mut ctx, gl::GL_ALPHA_BITS, &mut bits) };
        assert_eq!(bits, if alpha { 8 } else { 0 });
        clear(&mut ctx, [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(pixel(&mut ctx, 3, 3), [0, 0, 255, if alpha { 0 } else { 255 }], "cleared, alpha {alpha}");
        fill(&mut ctx, [1.0, 0.0, 0.0, 0.4]);
        assert_eq!(pixel(&mut ctx, 3, 3), [255, 0, 0, if alpha { 102 } else { 255 }], "drawn, alpha {alpha}");
        // A partial colour mask draws the clear; alpha stays 1 without alpha bitplanes.
        unsafe { dispatch::glColorMask(&mut ctx, gl::GL_FALSE, gl::GL_TRUE, gl::GL_FALSE, gl::GL_TRUE) };
        clear(&mut ctx, [0.0, 1.0, 0.0, 0.2]);
        assert_eq!(pixel(&mut ctx, 3, 3), [255, 255, 0, if alpha { 51 } else { 255 }], "masked clear, alpha {alpha}");
    }
}

#[test]
fn destination_alpha_blend_factors_see_one() {
    for alpha in [false, true] {
        let mut ctx = context(alpha);
        let blend = |ctx: &mut Context, src, dst, c: [f32; 4]| unsafe {
            clear(ctx, [0.0, 0.0, 1.0, 0.0]);
            dispatch::glEnable(ctx, gl::GL_BLEND);
            dispatch::glBlendFunc(ctx, src, dst);
            fill(ctx, c);
            dispatch::glDisable(ctx, gl::GL_BLEND);
            pixel(ctx, 8, 8)
        };
        let a = if alpha { 0 } else { 255 };
        // Destination alpha 1: the source passes whole; with alpha bitplanes it is 0.
        assert_eq!(blend(&mut ctx, gl::GL_DST_ALPHA, gl::GL_ZERO, [1.0, 0.0, 0.0, 1.0]), [a, 0, 0, a], "GL_DST_ALPHA, alpha {alpha}");
        assert_eq!(blend(&mut ctx, gl::GL_ONE, gl::GL_ONE_MINUS_DST_ALPHA, [1.0, 0.0, 0.0, 1.0]), [255, 0, 255 - a, 255], "GL_ONE_MINUS_DST_ALPHA, alpha {alpha}");
        // min(As, 1 − Ad) is 0 when Ad is 1; 0.5 × 255 may round either way (lavapipe 128,
        // NVIDIA 127).
        let saturate = blend(&mut ctx, gl::GL_SRC_ALPHA_SATURATE, gl::GL_ONE, [1.0, 0.0, 0.0, 0.5]);
        let expected: &[u8] = if alpha { &[127, 128] } else { &[0] };
        assert!(expected.contains(&saturate[0]), "GL_SRC_ALPHA_SATURATE, alpha {alpha}: {} not in {expected:?}", saturate[0]);
    }
}

#[test]
fn accumulation_and_texture_copies_read_alpha_one() {
    for alpha in [false, true] {
        let mut ctx = context(alpha);
        clear(&mut ctx, [0.0, 1.0, 0.0, 0.0]);
        fill(&mut ctx, [0.0, 1.0, 0.0, 0.4]);
        let mut texels = [0u8; 4];
        unsafe {
            dispatch::glAccum(&mut ctx, gl::GL_LOAD, 1.0);
            dispatch::glCopyTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA8, 0, 0, 1, 1, 0);
            dispatch::glGetTexImage(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_mut_ptr().cast());
        }
        assert_eq!(texels, [0, 255, 0, if alpha { 102 } else { 255 }], "glCopyTexImage2D, alpha {alpha}");
        clear(&mut ctx, [0.0; 4]);
        unsafe { dispatch::glAccum(&mut ctx, gl::GL_RETURN, 0.5) };
        assert_eq!(pixel(&mut ctx, 5, 5), [0, 128, 0, if alpha { 51 } else { 255 }], "accumulation return, alpha {alpha}");
    }
}
