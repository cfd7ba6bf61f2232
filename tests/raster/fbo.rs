//! Framebuffer objects (`GL_EXT_framebuffer_object`) on the Vulkan raster renderer: drawing
//! into renderbuffers and texture levels, reading them back with `glReadPixels` and
//! `glGetTexImage`, sampling a rendered texture in the window, and what is left of the
//! window's framebuffer meanwhile. Runs on Mesa lavapipe at small sizes.

use crate::lavapipe;

use glrt::translate::{Context, dispatch, gl};
use lavapipe::pixel;

/// Clears the colour buffer to `c`.
fn clear(ctx: &mut Context, c: [f32; 4]) {
    unsafe {
        dispatch::glClearColor(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
    }
}

/// Draws the window-coordinate rectangle `x0, y0` – `x1, y1` in `color` at eye-space `z` (nearer
/// when larger, with an
/// orthographic projection of a `size`-pixel framebuffer).
fn rect(ctx: &mut Context, size: f64, [x0, y0, x1, y1]: [f32; 4], z: f32, color: [f32; 3]) {
    unsafe {
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(ctx);
        dispatch::glOrtho(ctx, 0.0, size, 0.0, size, -1.0, 1.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(ctx);
        dispatch::glColor3f(ctx, color[0], color[1], color[2]);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glVertex3f(ctx, x0, y0, z);
        dispatch::glVertex3f(ctx, x1, y0, z);
        dispatch::glVertex3f(ctx, x1, y1, z);
        dispatch::glVertex3f(ctx, x0, y1, z);
        dispatch::glEnd(ctx);
    }
}

/// A new framebuffer object, bound.
fn bound_fbo(ctx: &mut Context) -> u32 {
    let mut fbo = 0;
    unsafe {
        dispatch::glGenFramebuffersEXT(ctx, 1, &mut fbo);
        dispatch::glBindFramebufferEXT(ctx, gl::GL_FRAMEBUFFER_EXT, fbo);
    }
    fbo
}

/// A renderbuffer of `format` and 16×16, attached at `attachment` of the bound framebuffer.
fn attach_renderbuffer(ctx: &mut Context, format: gl::GLenum, attachment: gl::GLenum) -> u32 {
    let mut rb = 0;
    unsafe {
        dispatch::glGenRenderbuffersEXT(ctx, 1, &mut rb);
        dispatch::glBindRenderbufferEXT(ctx, gl::GL_RENDERBUFFER_EXT, rb);
        dispatch::glRenderbufferStorageEXT(ctx, gl::GL_RENDERBUFFER_EXT, format, 16, 16);
        dispatch::glFramebufferRenderbufferEXT(ctx, gl::GL_FRAMEBUFFER_EXT, attachment, gl::GL_RENDERBUFFER_EXT, rb);
    }
    rb
}

/// A 16×16 RGBA texture whose texels are all `texel`, bound to `GL_TEXTURE_2D`.
fn texture(ctx: &mut Context, texel: [u8; 4]) -> u32 {
    let mut tex = 0;
    let texels: Vec<u8> = texel.repeat(16 * 16);
    unsafe {
        dispatch::glGenTextures(ctx, 1, &mut tex);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, tex);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA8 as i32, 16, 16, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
    }
    tex
}

#[test]
fn renderbuffers_take_draws_with_depth_test_and_leave_the_window_alone() {
    let mut ctx = lavapipe::context(32);
    clear(&mut ctx, [0.0, 0.0, 1.0, 1.0]);
    bound_fbo(&mut ctx);
    attach_renderbuffer(&mut ctx, gl::GL_RGBA8, gl::GL_COLOR_ATTACHMENT0_EXT);
    attach_renderbuffer(&mut ctx, gl::GL_DEPTH24_STENCIL8, gl::GL_DEPTH_ATTACHMENT_EXT);
    assert_eq!(unsafe { dispatch::glCheckFramebufferStatusEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT) }, gl::GL_FRAMEBUFFER_COMPLETE_EXT);
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, 16, 16);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
    }
    clear(&mut ctx, [1.0, 0.0, 0.0, 1.0]);
    rect(&mut ctx, 16.0, [0.0, 0.0, 8.0, 16.0], 0.5, [0.0, 1.0, 0.0]);
    // Behind the green half: hidden by the depth test.
    rect(&mut ctx, 16.0, [0.0, 0.0, 16.0, 16.0], -0.5, [1.0, 1.0, 1.0]);
    assert_eq!(pixel(&mut ctx, 2, 2), [0, 255, 0, 255], "green in front");
    assert_eq!(pixel(&mut ctx, 12, 12), [255, 255, 255, 255], "white where nothing was in front");
    assert_eq!(unsafe { dispatch::glGetError(&mut ctx) }, gl::GL_NO_ERROR);
    unsafe { dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, 0) };
    assert_eq!(pixel(&mut ctx, 2, 2), [0, 0, 255, 255], "the window keeps its clear colour");
    assert_eq!(pixel(&mut ctx, 30, 30), [0, 0, 255, 255]);
}

#[test]
fn rendered_texture_levels_are_read_back_and_sampled() {
    let mut ctx = lavapipe::context(32);
    let tex = texture(&mut ctx, [255, 255, 0, 255]);
    bound_fbo(&mut ctx);
    unsafe {
        dispatch::glFramebufferTexture2DEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_2D, tex, 0);
        dispatch::glViewport(&mut ctx, 0, 0, 16, 16);
    }
    assert_eq!(unsafe { dispatch::glCheckFramebufferStatusEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT) }, gl::GL_FRAMEBUFFER_COMPLETE_EXT);
    // No clear: the right half keeps the texture's yellow texels.
    rect(&mut ctx, 16.0, [0.0, 0.0, 8.0, 16.0], 0.0, [0.0, 0.0, 1.0]);
    assert_eq!(pixel(&mut ctx, 3, 3), [0, 0, 255, 255]);
    assert_eq!(pixel(&mut ctx, 12, 3), [255, 255, 0, 255], "the texture's texels were there before drawing");
    unsafe { dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, 0) };

    let mut texels = vec![0u8; 16 * 16 * 4];
    unsafe { dispatch::glGetTexImage(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_mut_ptr().cast()) };
    assert_eq!(texels[..4], [0, 0, 255, 255], "texel (0, 0) was drawn blue");
    assert_eq!(texels[(5 * 16 + 12) * 4..][..4], [255, 255, 0, 255], "texel (12, 5) kept yellow");

    // The window samples the rendered texture.
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, 32, 32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(&mut ctx);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(&mut ctx);
        dispatch::glBegin(&mut ctx, gl::GL_QUADS);
        dispatch::glTexCoord2f(&mut ctx, 0.0, 0.0);
        dispatch::glVertex2f(&mut ctx, -1.0, -1.0);
        dispatch::glTexCoord2f(&mut ctx, 1.0, 0.0);
        dispatch::glVertex2f(&mut ctx, 1.0, -1.0);
        dispatch::glTexCoord2f(&mut ctx, 1.0, 1.0);
        dispatch::glVertex2f(&mut ctx, 1.0, 1.0);
        dispatch::glTexCoord2f(&mut ctx, 0.0, 1.0);
        dispatch::glVertex2f(&mut ctx, -1.0, 1.0);
        dispatch::glEnd(&mut ctx);
    }
    assert_eq!(pixel(&mut ctx, 4, 16), [0, 0, 255, 255], "left half of the window samples blue");
    assert_eq!(pixel(&mut ctx, 28, 16), [255, 255, 0, 255], "right half samples yellow");
    assert_eq!(unsafe { dispatch::glGetError(&mut ctx) }, gl::GL_NO_ERROR);
}

#[test]
fn depth_textures_take_depth_clears_of_a_depth_only_framebuffer() {
    let mut ctx = lavapipe::context(32);
    let mut tex = 0;
    unsafe {
        dispatch::glGenTextures(&mut ctx, 1, &mut tex);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, tex);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_DEPTH_COMPONENT24 as i32, 16, 16, 0, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, std::ptr::null());
    }
    bound_fbo(&mut ctx);
    unsafe {
        dispatch::glFramebufferTexture2DEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, gl::GL_DEPTH_ATTACHMENT_EXT, gl::GL_TEXTURE_2D, tex, 0);
    }
    assert_eq!(
        unsafe { dispatch::glCheckFramebufferStatusEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT) },
        gl::GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER_EXT,
        "the draw buffer names a colour attachment that has no image"
    );
    unsafe {
        dispatch::glDrawBuffer(&mut ctx, gl::GL_NONE);
        dispatch::glReadBuffer(&mut ctx, gl::GL_NONE);
    }
    assert_eq!(unsafe { dispatch::glCheckFramebufferStatusEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT) }, gl::GL_FRAMEBUFFER_COMPLETE_EXT);
    unsafe {
        dispatch::glClearDepth(&mut ctx, 0.25);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, 0);
    }
    let mut depths = vec![0f32; 16 * 16];
    unsafe { dispatch::glGetTexImage(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depths.as_mut_ptr().cast()) };
    assert!(depths.iter().all(|d| (d - 0.25).abs() < 1e-4), "depth texels {:?}", &depths[..4]);
    assert_eq!(unsafe { dispatch::glGetError(&mut ctx) }, gl::GL_NO_ERROR);
}

/// The depth value at window pixel (x, y).
fn depth_at(ctx: &mut Context, x: i32, y: i32) -> f32 {
    let mut d = 0f32;
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, (&mut d as *mut f32).cast()) };
    d
}

#[test]
fn blits_scale_mirror_and_copy_depth_between_framebuffers() {
    let mut ctx = lavapipe::context(32);
    clear(&mut ctx, [0.0, 0.0, 1.0, 1.0]);
    let fbo = bound_fbo(&mut ctx);
    attach_renderbuffer(&mut ctx, gl::GL_RGBA8, gl::GL_COLOR_ATTACHMENT0_EXT);
    unsafe { dispatch::glViewport(&mut ctx, 0, 0, 16, 16) };
    clear(&mut ctx, [1.0, 0.0, 0.0, 1.0]);
    rect(&mut ctx, 16.0, [0.0, 0.0, 8.0, 16.0], 0.0, [0.0, 1.0, 0.0]);

    // Read from the object, draw into the window: twice the size, mirrored left to right.
    unsafe {
        dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_DRAW_FRAMEBUFFER_EXT, 0);
        dispatch::glBlitFramebufferEXT(&mut ctx, 0, 0, 16, 16, 32, 0, 0, 32, gl::GL_COLOR_BUFFER_BIT, gl::GL_NEAREST);
    }
    assert_eq!(unsafe { dispatch::glGetError(&mut ctx) }, gl::GL_NO_ERROR);
    let mut binding = [0i32; 2];
    unsafe {
        dispatch::glGetIntegerv(&mut ctx, gl::GL_READ_FRAMEBUFFER_BINDING_EXT, &mut binding[0]);
        dispatch::glGetIntegerv(&mut ctx, gl::GL_FRAMEBUFFER_BINDING_EXT, &mut binding[1]);
    }
    assert_eq!(binding, [fbo as i32, 0]);
    unsafe { dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_READ_FRAMEBUFFER_EXT, 0) };
    assert_eq!(pixel(&mut ctx, 30, 5), [0, 255, 0, 255], "the object's green left half lands on the right");
    assert_eq!(pixel(&mut ctx, 17, 28), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 2, 5), [255, 0, 0, 255], "and its red right half on the left");

    // Depth within the window: the upper-right quarter copied to the lower-left one.
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, 32, 32);
        dispatch::glClearDepth(&mut ctx, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_ALWAYS);
    }
    rect(&mut ctx, 32.0, [16.0, 16.0, 32.0, 32.0], 0.5, [1.0, 1.0, 1.0]);
    let upper = depth_at(&mut ctx, 20, 20);
    assert!((upper - 0.25).abs() < 1e-3, "z = 0.5 in [-1, 1] is depth 0.25, got {upper}");
    unsafe {
        dispatch::glBlitFramebufferEXT(&mut ctx, 16, 16, 32, 32, 0, 0, 16, 16, gl::GL_DEPTH_BUFFER_BIT, gl::GL_LINEAR);
        assert_eq!(dispatch::glGetError(&mut ctx), gl::GL_INVALID_OPERATION, "depth blits are NEAREST only");
        dispatch::glBlitFramebufferEXT(&mut ctx, 16, 16, 32, 32, 0, 0, 16, 16, gl::GL_DEPTH_BUFFER_BIT, gl::GL_NEAREST);
        dispatch::glBlitFramebufferEXT(&mut ctx, 0, 0, 1, 1, 0, 0, 1, 1, 0x8000, gl::GL_NEAREST);
        assert_eq!(dispatch::glGetError(&mut ctx), gl::GL_INVALID_VALUE);
    }
    assert!((depth_at(&mut ctx, 4, 4) - upper).abs() < 1e-3, "the lower-left quarter took the copied depth");
    assert_eq!(depth_at(&mut ctx, 4, 20), 1.0, "the upper-left quarter kept the clear depth");
    assert_eq!(pixel(&mut ctx, 4, 4), [255, 0, 0, 255], "a depth blit leaves colour alone");
}
