//! The pixel path of the Vulkan raster renderer on real GL calls, read back with
//! `glReadPixels`: masked and scissored clears, `glBitmap`, `glDrawPixels` (colour, depth,
//! stencil, depth/stencil, zoom, per-fragment operations), `glCopyPixels` (overlapping
//! rectangles, depth/stencil) and the accumulation buffer. Runs on Mesa lavapipe at 32×32.

use crate::lavapipe;

use glrt::translate::{Context, dispatch, gl};
use lavapipe::pixel;

const SIZE: i32 = 32;

/// Reads the stencil value at (x, y).
fn stencil(ctx: &mut Context, x: i32, y: i32) -> u8 {
    let mut out = [0u8; 1];
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out[0]
}

/// Reads the depth value at (x, y).
fn depth(ctx: &mut Context, x: i32, y: i32) -> f32 {
    let mut out = [0f32; 1];
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, out.as_mut_ptr().cast()) };
    out[0]
}

/// Clears colour to `c`, depth to 1 and stencil to 0, without masks or scissor.
fn clear_all(ctx: &mut Context, c: [f32; 4]) {
    unsafe {
        dispatch::glClearColor(ctx, c[0], c[1], c[2], c[3]);
        dispatch::glClearDepth(ctx, 1.0);
        dispatch::glClearStencil(ctx, 0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT);
    }
}

#[test]
fn clears_honour_colour_mask_stencil_mask_and_scissor() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 1.0, 1.0]);
    unsafe {
        dispatch::glColorMask(&mut ctx, gl::GL_TRUE, gl::GL_FALSE, gl::GL_FALSE, gl::GL_FALSE);
        dispatch::glClearColor(&mut ctx, 1.0, 1.0, 0.0, 0.0);
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 0, 0, 8, 8);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
    }
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 0, 255, 255], "only red written, inside the scissor box");
    assert_eq!(pixel(&mut ctx, 20, 20), [0, 0, 255, 255], "outside the scissor box");
    unsafe {
        dispatch::glDisable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glStencilMask(&mut ctx, 0x0f);
        dispatch::glClearStencil(&mut ctx, 0xff);
        dispatch::glClear(&mut ctx, gl::GL_STENCIL_BUFFER_BIT);
    }
    assert_eq!(stencil(&mut ctx, 20, 20), 0x0f, "only the low four bits written");
    assert_eq!(pixel(&mut ctx, 20, 20), [0, 0, 255, 255], "a stencil clear leaves colour alone");
    unsafe {
        dispatch::glDepthMask(&mut ctx, gl::GL_FALSE);
        dispatch::glClearDepth(&mut ctx, 0.25);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT);
    }
    assert_eq!(depth(&mut ctx, 20, 20), 1.0, "depth mask off: no depth clear");
}

#[test]
fn bitmaps_draw_set_bits_in_the_raster_colour_through_the_alpha_test() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0; 4]);
    // 8×2 bitmap, rows bottom to top: 0b1010_0000, 0b0000_0001 (MSB first).
    let bits = [0b1010_0000u8, 0b0000_0001];
    unsafe {
        dispatch::glPixelStorei(&mut ctx, gl::GL_UNPACK_ALIGNMENT, 1);
        dispatch::glColor4f(&mut ctx, 0.0, 1.0, 0.0, 1.0);
        dispatch::glWindowPos2i(&mut ctx, 10, 5);
        dispatch::glBitmap(&mut ctx, 8, 2, 0.0, 0.0, 8.0, 0.0, bits.as_ptr());
    }
    assert_eq!(pixel(&mut ctx, 10, 5), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 11, 5), [0, 0, 0, 0]);
    assert_eq!(pixel(&mut ctx, 12, 5), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 17, 6), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 10, 6), [0, 0, 0, 0]);
    // The raster position moved by 8: a bitmap whose fragments fail the alpha test draws
    // nothing.
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_ALPHA_TEST);
        dispatch::glAlphaFunc(&mut ctx, gl::GL_GREATER, 0.5);
        dispatch::glColor4f(&mut ctx, 1.0, 0.0, 0.0, 0.25);
        dispatch::glWindowPos2i(&mut ctx, 10, 5);
        dispatch::glBitmap(&mut ctx, 8, 2, 0.0, 0.0, 8.0, 0.0, bits.as_ptr());
    }
    assert_eq!(pixel(&mut ctx, 10, 5), [0, 255, 0, 255], "alpha test failed: unchanged");
}

#[test]
fn draw_pixels_colour_with_zoom_blending_and_depth_test() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 0.0, 1.0]);
    // 2×2 image: bottom row red, green; top row blue, white.
    let image: [u8; 16] = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 4, 4);
        dispatch::glPixelZoom(&mut ctx, 3.0, 2.0);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    assert_eq!(pixel(&mut ctx, 4, 4), [255, 0, 0, 255]);
    assert_eq!(pixel(&mut ctx, 6, 5), [255, 0, 0, 255], "zoomed 3×2");
    assert_eq!(pixel(&mut ctx, 7, 5), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 9, 7), [255, 255, 255, 255]);
    assert_eq!(pixel(&mut ctx, 10, 7), [0, 0, 0, 255], "right of the image");
    // Negative zoom draws leftwards and downwards from the raster position.
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 24, 24);
        dispatch::glPixelZoom(&mut ctx, -1.0, -1.0);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    assert_eq!(pixel(&mut ctx, 23, 23), [255, 0, 0, 255]);
    assert_eq!(pixel(&mut ctx, 22, 22), [255, 255, 255, 255]);
    assert_eq!(pixel(&mut ctx, 24, 24), [0, 0, 0, 255]);
    // Blending applies: ONE, ONE adds the image to what is there.
    unsafe {
        dispatch::glPixelZoom(&mut ctx, 1.0, 1.0);
        dispatch::glEnable(&mut ctx, gl::GL_BLEND);
        dispatch::glBlendFunc(&mut ctx, gl::GL_ONE, gl::GL_ONE);
        dispatch::glWindowPos2i(&mut ctx, 4, 4);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image[4..].as_ptr().cast());
        dispatch::glDisable(&mut ctx, gl::GL_BLEND);
    }
    assert_eq!(pixel(&mut ctx, 4, 4), [255, 255, 0, 255], "red + green");
    // Depth test: the image at the raster depth 0.5 fails GL_LESS against a buffer at 0.25.
    unsafe {
        dispatch::glClearDepth(&mut ctx, 0.25);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glWindowPos3f(&mut ctx, 16.0, 0.0, 0.5);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
        dispatch::glWindowPos3f(&mut ctx, 16.0, 10.0, 0.125);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    assert_eq!(pixel(&mut ctx, 16, 0), [0, 0, 0, 255], "behind: discarded");
    assert_eq!(pixel(&mut ctx, 16, 10), [255, 0, 0, 255], "in front: drawn");
    assert!((depth(&mut ctx, 16, 10) - 0.125).abs() < 1e-4);
}

#[test]
fn draw_pixels_depth_and_stencil() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0; 4]);
    let depths: [f32; 4] = [0.0, 0.25, 0.5, 0.75];
    let stencils: [u8; 4] = [1, 2, 3, 0x85];
    unsafe {
        dispatch::glColor4f(&mut ctx, 1.0, 0.0, 1.0, 1.0);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_ALWAYS);
        dispatch::glWindowPos2i(&mut ctx, 3, 3);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depths.as_ptr().cast());
        dispatch::glDisable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glWindowPos2i(&mut ctx, 20, 20);
        dispatch::glPixelStorei(&mut ctx, gl::GL_UNPACK_ALIGNMENT, 1);
        dispatch::glStencilMask(&mut ctx, 0x7f);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_BYTE, stencils.as_ptr().cast());
    }
    assert!((depth(&mut ctx, 4, 3) - 0.25).abs() < 1e-4);
    assert!((depth(&mut ctx, 4, 4) - 0.75).abs() < 1e-4);
    assert_eq!(pixel(&mut ctx, 3, 4), [255, 0, 255, 255], "depth images draw the raster colour");
    assert_eq!(stencil(&mut ctx, 20, 20), 1);
    assert_eq!(stencil(&mut ctx, 21, 21), 0x05, "through the stencil write mask 0x7f");
    assert_eq!(pixel(&mut ctx, 20, 20), [0, 0, 0, 0], "stencil images leave colour alone");
}

#[test]
fn copy_pixels_with_overlap_and_depth() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0; 4]);
    // A 4×1 row of grey levels 10, 20, 30, 40 at (0, 0).
    let row: [u8; 16] = [10, 10, 10, 255, 20, 20, 20, 255, 30, 30, 30, 255, 40, 40, 40, 255];
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 0, 0);
        dispatch::glDrawPixels(&mut ctx, 4, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, row.as_ptr().cast());
        // Overlapping copy one pixel to the right: reads the source before writing.
        dispatch::glWindowPos2i(&mut ctx, 1, 0);
        dispatch::glCopyPixels(&mut ctx, 0, 0, 4, 1, gl::GL_COLOR);
    }
    let values: Vec<u8> = (0..5).map(|x| pixel(&mut ctx, x, 0)[0]).collect();
    assert_eq!(values, [10, 10, 20, 30, 40]);
    // Zoomed copy upwards.
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 0, 10);
        dispatch::glPixelZoom(&mut ctx, 2.0, 3.0);
        dispatch::glCopyPixels(&mut ctx, 2, 0, 2, 1, gl::GL_COLOR);
        dispatch::glPixelZoom(&mut ctx, 1.0, 1.0);
    }
    assert_eq!(pixel(&mut ctx, 1, 12)[0], 20);
    assert_eq!(pixel(&mut ctx, 3, 10)[0], 30);
    // Depth copies carry depth values.
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 0, 20, 4, 4);
        dispatch::glClearDepth(&mut ctx, 0.5);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glDisable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_ALWAYS);
        dispatch::glWindowPos2i(&mut ctx, 10, 20);
        dispatch::glCopyPixels(&mut ctx, 0, 20, 2, 2, gl::GL_DEPTH);
    }
    assert!((depth(&mut ctx, 11, 21) - 0.5).abs() < 1e-4);
    assert_eq!(depth(&mut ctx, 12, 21), 1.0);
}

#[test]
fn accumulation_buffer_load_accum_mult_add_return() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.4, 0.2, 0.0, 1.0]);
    unsafe {
        dispatch::glClearAccum(&mut ctx, 0.0, 0.0, 0.0, 0.0);
        dispatch::glClear(&mut ctx, gl::GL_ACCUM_BUFFER_BIT);
        dispatch::glAccum(&mut ctx, gl::GL_LOAD, 0.5);
    }
    clear_all(&mut ctx, [0.0, 0.2, 0.8, 1.0]);
    unsafe {
        dispatch::glAccum(&mut ctx, gl::GL_ACCUM, 0.5);
        dispatch::glAccum(&mut ctx, gl::GL_MULT, 2.0);
        dispatch::glAccum(&mut ctx, gl::GL_ADD, -0.2);
        // Return only inside a scissor box and only into the red and blue channels.
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 0, 0, 16, 32);
        dispatch::glColorMask(&mut ctx, gl::GL_TRUE, gl::GL_FALSE, gl::GL_TRUE, gl::GL_TRUE);
        dispatch::glAccum(&mut ctx, gl::GL_RETURN, 1.0);
    }
    // accum = 2 × (0.5 × c1 + 0.5 × c2) − 0.2 = (0.2, 0.2, 0.6, 1.8) → alpha clamps to 1.
    assert_eq!(pixel(&mut ctx, 4, 4), [51, 51, 153, 255]);
    assert_eq!(pixel(&mut ctx, 20, 4), [0, 51, 204, 255], "outside the scissor box");
}

#[test]
fn copy_tex_image_and_sub_image_take_the_framebuffer_pixels() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [1.0, 0.0, 0.0, 1.0]);
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 2, 0, 2, 4);
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 1.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glDisable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 3);
        dispatch::glCopyTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, 0, 0, 4, 4, 0);
    }
    let mut texels = [0u8; 64];
    unsafe { dispatch::glGetTexImage(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_mut_ptr().cast()) };
    assert_eq!(texels[0..4], [255, 0, 0, 255]);
    assert_eq!(texels[8..12], [0, 0, 255, 255], "texel (2, 0) from the scissored clear");
    // Sub-image: pixel (0, 0) of the window (red) into texel (3, 3).
    unsafe { dispatch::glCopyTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 3, 3, 0, 0, 1, 1) };
    unsafe { dispatch::glGetTexImage(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_mut_ptr().cast()) };
    assert_eq!(texels[60..64], [255, 0, 0, 255]);
    // Draws that use the texture sample the copy: a textured quad over the window shows
    // texel column 2 (blue) at window x = 20.
    clear_all(&mut ctx, [0.0; 4]);
    unsafe {
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glColor4f(&mut ctx, 1.0, 1.0, 1.0, 1.0);
        dispatch::glBegin(&mut ctx, gl::GL_QUADS);
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            dispatch::glTexCoord2f(&mut ctx, (x + 1.0) / 2.0, (y + 1.0) / 2.0);
            dispatch::glVertex2f(&mut ctx, x, y);
        }
        dispatch::glEnd(&mut ctx);
    }
    assert_eq!(pixel(&mut ctx, 20, 4), [0, 0, 255, 255]);
    assert_eq!(pixel(&mut ctx, 4, 4), [255, 0, 0, 255]);
}

#[test]
fn copy_pixels_from_outside_the_window_produce_no_fragments() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 1.0, 1.0]);
    let red: [u8; 4] = [255, 0, 0, 255];
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 0, 0);
        dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, red.as_ptr().cast());
        // Source x from -2: columns -2 and -1 are outside; window column 0 lands at x = 12.
        dispatch::glWindowPos2i(&mut ctx, 10, 10);
        dispatch::glCopyPixels(&mut ctx, -2, 0, 3, 1, gl::GL_COLOR);
    }
    assert_eq!(pixel(&mut ctx, 12, 10), [255, 0, 0, 255]);
    assert_eq!(pixel(&mut ctx, 10, 10), [0, 0, 255, 255], "no fragment from outside the window");
    assert_eq!(pixel(&mut ctx, 11, 10), [0, 0, 255, 255]);
}

#[test]
fn large_varied_images_are_drawn_as_textures_with_zoom() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 0.0, 1.0]);
    // 40×30 image, every pixel different from its neighbours (more than 1024 runs).
    let (w, h) = (40usize, 30usize);
    let image: Vec<u8> = (0..w * h).flat_map(|i| [(i % w) as u8 * 5, (i / w) as u8 * 7, ((i % 2) * 255) as u8, 255]).collect();
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 0, 0);
        dispatch::glDrawPixels(&mut ctx, w as i32, h as i32, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    for (x, y) in [(0, 0), (1, 0), (7, 3), (31, 29), (30, 12)] {
        let i = (y * w + x) * 4;
        assert_eq!(pixel(&mut ctx, x as i32, y as i32), [image[i], image[i + 1], image[i + 2], 255], "pixel ({x}, {y})");
    }
    // Zoom 2 with the same image: pixel (i, j) covers window (2i..2i+2, 2j..2j+2).
    unsafe {
        dispatch::glPixelZoom(&mut ctx, 2.0, 2.0);
        dispatch::glDrawPixels(&mut ctx, w as i32, h as i32, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    for (x, y) in [(0, 0), (3, 2), (15, 15)] {
        let i = (y * w + x) * 4;
        let expected = [image[i], image[i + 1], image[i + 2], 255];
        assert_eq!(pixel(&mut ctx, 2 * x as i32, 2 * y as i32), expected);
        assert_eq!(pixel(&mut ctx, 2 * x as i32 + 1, 2 * y as i32 + 1), expected);
    }
}

/// Reads a `w` × `h` rectangle as `GL_DEPTH_STENCIL`/`GL_UNSIGNED_INT_24_8` words.
fn depth_stencil_24_8(ctx: &mut Context, x: i32, y: i32, w: i32, h: i32) -> Vec<u32> {
    let mut out = vec![0u32; (w * h) as usize];
    unsafe { dispatch::glReadPixels(ctx, x, y, w, h, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, out.as_mut_ptr().cast()) };
    out
}

/// A `GL_UNSIGNED_INT_24_8` word: 24-bit depth above an 8-bit stencil index.
const fn packed(depth: u32, stencil: u32) -> u32 {
    (depth << 8) | stencil
}

/// Depth/stencil words of a 4×2 image: distinct 24-bit depths (low, middle, high, 1.0) and
/// stencil indices.
const PACKED: [u32; 8] = [
    packed(0x00_0001, 0x07),
    packed(0x12_3456, 0x21),
    packed(0x7f_ffff, 0x42),
    packed(0x80_0000, 0x63),
    packed(0xab_cdef, 0x84),
    packed(0xff_fffe, 0xa5),
    packed(0xff_ffff, 0xc6),
    packed(0x55_5555, 0xe7),
];

#[test]
fn depth_stencil_draw_pixels_write_both_buffers_exactly_and_skip_the_tests() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 1.0, 1.0]);
    unsafe {
        // Neither test applies to GL_DEPTH_STENCIL images (EXT_packed_depth_stencil 4.3.1).
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_NEVER);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST);
        dispatch::glStencilFunc(&mut ctx, gl::GL_NEVER, 0, 0xff);
        dispatch::glWindowPos2i(&mut ctx, 4, 6);
        dispatch::glDrawPixels(&mut ctx, 4, 2, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, PACKED.as_ptr().cast());
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    // Every bit comes back: the 24-bit depth buffer stores each drawn depth exactly.
    assert_eq!(depth_stencil_24_8(&mut ctx, 4, 6, 4, 2), PACKED);
    assert_eq!(pixel(&mut ctx, 5, 6), [0, 0, 255, 255], "no colour is written");
    assert_eq!(depth_stencil_24_8(&mut ctx, 3, 6, 1, 1), [packed(0xff_ffff, 0)], "outside the image");
    // The float type reads the same values.
    let mut words = [0u32; 2];
    unsafe { dispatch::glReadPixels(&mut ctx, 5, 6, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, words.as_mut_ptr().cast()) };
    assert_eq!(words, [((f64::from(0x12_3456u32) / 16_777_215.0) as f32).to_bits(), 0x21]);
    // Depth and stencil write masks apply; so does the scissor test.
    unsafe {
        dispatch::glDepthMask(&mut ctx, gl::GL_FALSE);
        dispatch::glStencilMask(&mut ctx, 0x0f);
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 0, 0, 6, 32);
        let zeros = [0u32; 8];
        dispatch::glDrawPixels(&mut ctx, 4, 2, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, zeros.as_ptr().cast());
    }
    let masked: Vec<u32> = PACKED.iter().enumerate().map(|(i, &p)| if i % 4 < 2 { p & !0x0f } else { p }).collect();
    assert_eq!(depth_stencil_24_8(&mut ctx, 4, 6, 4, 2), masked, "stencil low bits cleared in columns 4-5 only, depth kept");
}

#[test]
fn depth_stencil_copy_pixels_copies_both_buffers_with_pixel_transfer() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 1.0, 0.0, 1.0]);
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 2, 2);
        dispatch::glDrawPixels(&mut ctx, 4, 2, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, PACKED.as_ptr().cast());
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_NEVER);
        // Copy (2, 2)-(6, 4) to (20, 10), then again to (20, 20) with the index offset 1.
        dispatch::glWindowPos2i(&mut ctx, 20, 10);
        dispatch::glCopyPixels(&mut ctx, 2, 2, 4, 2, gl::GL_DEPTH_STENCIL);
        dispatch::glPixelTransferi(&mut ctx, gl::GL_INDEX_OFFSET, 1);
        dispatch::glWindowPos2i(&mut ctx, 20, 20);
        dispatch::glCopyPixels(&mut ctx, 2, 2, 4, 2, gl::GL_DEPTH_STENCIL);
        dispatch::glPixelTransferi(&mut ctx, gl::GL_INDEX_OFFSET, 0);
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(depth_stencil_24_8(&mut ctx, 20, 10, 4, 2), PACKED, "an exact copy");
    let offset: Vec<u32> = PACKED.iter().map(|&p| (p & !0xff) | ((p + 1) & 0xff)).collect();
    assert_eq!(depth_stencil_24_8(&mut ctx, 20, 20, 4, 2), offset, "stencil indices offset by 1");
    assert_eq!(pixel(&mut ctx, 21, 11), [0, 255, 0, 255], "no colour is written");
}

/// Binds a 2×1 texture, red then blue, sampled at the nearest texel with `GL_MODULATE`, and
/// enables 2D texturing.
fn red_blue_texture(ctx: &mut Context) {
    let texels = [255u8, 0, 0, 255, 0, 0, 255, 255];
    unsafe {
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexEnvi(ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_MODULATE as i32);
        dispatch::glEnable(ctx, gl::GL_TEXTURE_2D);
    }
}

#[test]
fn draw_pixels_and_bitmaps_are_textured_at_the_raster_position_texture_coordinates() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 0.0, 1.0]);
    red_blue_texture(&mut ctx);
    // The raster position keeps the coordinates current when it was set (s = 0.25: red),
    // not those current at the draw.
    let image = [[51u8, 255, 128, 255]; 16];
    unsafe {
        dispatch::glTexCoord2f(&mut ctx, 0.25, 0.5);
        dispatch::glWindowPos2i(&mut ctx, 2, 2);
        dispatch::glTexCoord2f(&mut ctx, 0.75, 0.5);
        dispatch::glDrawPixels(&mut ctx, 4, 4, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
    }
    assert_eq!(pixel(&mut ctx, 3, 3), [51, 0, 0, 255], "modulated by red");
    // A bitmap at s = 0.75 (blue) in a white raster colour.
    let bits = [0xffu8; 2];
    unsafe {
        dispatch::glPixelStorei(&mut ctx, gl::GL_UNPACK_ALIGNMENT, 1);
        dispatch::glColor3f(&mut ctx, 1.0, 1.0, 1.0);
        dispatch::glWindowPos2i(&mut ctx, 10, 10);
        dispatch::glBitmap(&mut ctx, 8, 2, 0.0, 0.0, 0.0, 0.0, bits.as_ptr());
    }
    assert_eq!(pixel(&mut ctx, 12, 11), [0, 0, 255, 255], "bitmap modulated by blue");
    // A large varied image (drawn as rectangles while textured) is modulated too.
    let (w, h) = (40usize, 30usize);
    let varied: Vec<u8> = (0..w * h).flat_map(|i| [(i % w) as u8 * 5, (i / w) as u8 * 7, ((i % 2) * 255) as u8, 255]).collect();
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 0, 0);
        dispatch::glDrawPixels(&mut ctx, w as i32, h as i32, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, varied.as_ptr().cast());
    }
    for (x, y) in [(1usize, 0usize), (7, 3), (30, 12)] {
        let i = (y * w + x) * 4;
        assert_eq!(pixel(&mut ctx, x as i32, y as i32), [0, 0, varied[i + 2], 255], "pixel ({x}, {y}) modulated by blue");
    }
}

#[test]
fn pixel_fragments_are_fogged_with_the_raster_distance() {
    let mut ctx = lavapipe::context(SIZE);
    clear_all(&mut ctx, [0.0, 0.0, 0.0, 1.0]);
    let white = [[255u8; 4]; 4];
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_FOG);
        dispatch::glFogi(&mut ctx, gl::GL_FOG_MODE, gl::GL_LINEAR as i32);
        dispatch::glFogf(&mut ctx, gl::GL_FOG_START, 0.0);
        dispatch::glFogf(&mut ctx, gl::GL_FOG_END, 1.0);
        // Identity matrices: eye (0, 0, -0.5) is at distance 0.5 and window (16, 16).
        dispatch::glRasterPos3f(&mut ctx, 0.0, 0.0, -0.5);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, white.as_ptr().cast());
    }
    let fogged = pixel(&mut ctx, 16, 16);
    assert!(fogged[..3].iter().all(|&c| c.abs_diff(128) <= 1), "half fogged to black: {fogged:?}");
    // glWindowPos sets the raster distance to 0: no fog.
    unsafe {
        dispatch::glWindowPos2i(&mut ctx, 4, 4);
        dispatch::glDrawPixels(&mut ctx, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, white.as_ptr().cast());
    }
    assert_eq!(pixel(&mut ctx, 4, 4), [255; 4]);
}
