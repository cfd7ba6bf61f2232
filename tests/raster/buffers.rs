//! Front and back colour buffers of the Vulkan raster renderer on real GL calls (OpenGL 1.5
//! section 4.2.1): `glDrawBuffer` selects the images draws and clears write, `glReadBuffer`
//! the one `glReadPixels` and `glCopyPixels` read, and a swap copies the back buffer to the
//! front. Runs on Mesa lavapipe at 32×32.

use crate::lavapipe;

use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 32;
const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];

/// Reads the RGBA8 pixel at window (x, y) of the colour buffer `buffer`.
fn pixel(ctx: &mut Context, buffer: gl::GLenum, x: i32, y: i32) -> [u8; 4] {
    let mut out = [0u8; 4];
    unsafe {
        dispatch::glReadBuffer(ctx, buffer);
        dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast());
    }
    out
}

/// Clears the colour buffers `buffer` selects to `c`.
fn clear(ctx: &mut Context, buffer: gl::GLenum, c: [f32; 4]) {
    unsafe {
        dispatch::glDrawBuffer(ctx, buffer);
        dispatch::glClearColor(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
    }
}

/// Draws a rectangle of colour `c` covering window pixels [8, 16) × [8, 16) into `buffer`.
fn rect(ctx: &mut Context, buffer: gl::GLenum, c: [f32; 4]) {
    unsafe {
        dispatch::glDrawBuffer(ctx, buffer);
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(ctx);
        dispatch::glOrtho(ctx, 0.0, SIZE as f64, 0.0, SIZE as f64, -1.0, 1.0);
        dispatch::glColor4f(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glRectf(ctx, 8.0, 8.0, 16.0, 16.0);
    }
}

#[test]
fn back_and_front_hold_different_pictures() {
    let mut ctx = lavapipe::context(SIZE);
    clear(&mut ctx, gl::GL_FRONT, [1.0, 0.0, 0.0, 1.0]);
    clear(&mut ctx, gl::GL_BACK, [0.0, 1.0, 0.0, 1.0]);
    rect(&mut ctx, gl::GL_BACK, [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 10, 10), BLUE);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 2, 2), GREEN);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), RED);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 2, 2), RED);
    // Drawing to the front afterwards leaves the back alone.
    rect(&mut ctx, gl::GL_FRONT, [0.0, 1.0, 0.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), GREEN);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 10, 10), BLUE);
    assert_eq!(unsafe { dispatch::glGetError(&mut ctx) }, gl::GL_NO_ERROR);
}

#[test]
fn front_and_back_draws_both_with_depth_test() {
    let mut ctx = lavapipe::context(SIZE);
    clear(&mut ctx, gl::GL_FRONT_AND_BACK, [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 2, 2), RED);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 2, 2), RED);
    unsafe { dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST) };
    rect(&mut ctx, gl::GL_FRONT_AND_BACK, [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), BLUE, "the front pass sees the depth before the draw");
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 10, 10), BLUE);
    // Depth was written once (by the back pass): the same rectangle again fails GL_LESS.
    rect(&mut ctx, gl::GL_FRONT_AND_BACK, [0.0, 1.0, 0.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), BLUE);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 10, 10), BLUE);
}

#[test]
fn draw_buffer_none_writes_no_colour() {
    let mut ctx = lavapipe::context(SIZE);
    clear(&mut ctx, gl::GL_FRONT_AND_BACK, [1.0, 0.0, 0.0, 1.0]);
    rect(&mut ctx, gl::GL_NONE, [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), RED);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 10, 10), RED);
}

#[test]
fn swap_shows_the_back_buffer_in_front() {
    let mut ctx = lavapipe::context(SIZE);
    clear(&mut ctx, gl::GL_FRONT, [1.0, 0.0, 0.0, 1.0]);
    clear(&mut ctx, gl::GL_BACK, [0.0, 1.0, 0.0, 1.0]);
    rect(&mut ctx, gl::GL_BACK, [0.0, 0.0, 1.0, 1.0]);
    ctx.end_frame();
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), BLUE);
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 2, 2), GREEN);
    // Drawing to the front and flushing keeps the front as drawn; the next swap replaces it.
    rect(&mut ctx, gl::GL_FRONT, [1.0, 0.0, 0.0, 1.0]);
    unsafe { dispatch::glFlush(&mut ctx) };
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), RED);
    ctx.end_frame();
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 10, 10), BLUE);
}

#[test]
fn copy_pixels_reads_the_read_buffer() {
    let mut ctx = lavapipe::context(SIZE);
    clear(&mut ctx, gl::GL_FRONT, [1.0, 0.0, 0.0, 1.0]);
    clear(&mut ctx, gl::GL_BACK, [0.0, 1.0, 0.0, 1.0]);
    unsafe {
        dispatch::glReadBuffer(&mut ctx, gl::GL_FRONT);
        dispatch::glDrawBuffer(&mut ctx, gl::GL_BACK);
        dispatch::glWindowPos2i(&mut ctx, 20, 20);
        dispatch::glCopyPixels(&mut ctx, 0, 0, 4, 4, gl::GL_COLOR);
    }
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 21, 21), RED);
    assert_eq!(pixel(&mut ctx, gl::GL_BACK, 2, 2), GREEN);
}

#[test]
fn single_buffered_drawables_use_the_front_buffer() {
    let mut ctx = lavapipe::context(SIZE);
    ctx.set_double_buffered(false);
    clear(&mut ctx, gl::GL_FRONT, [0.0, 0.0, 1.0, 1.0]);
    unsafe { dispatch::glFlush(&mut ctx) };
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 3, 3), BLUE);
    // A swap of a single-buffered drawable changes nothing.
    ctx.end_frame();
    assert_eq!(pixel(&mut ctx, gl::GL_FRONT, 3, 3), BLUE);
}
