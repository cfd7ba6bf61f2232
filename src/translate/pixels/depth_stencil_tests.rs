//! Tests of `GL_DEPTH_STENCIL` pixels (EXT_packed_depth_stencil, ARB_depth_buffer_float):
//! `glDrawPixels` records depth and stencil together after pixel transfer, `glReadPixels` packs
//! what the renderer's depth and stencil buffers hold, and `glCopyPixels(GL_DEPTH_STENCIL)`
//! reads, transfers and redraws them, clipped to the window; `glCopyTexImage` of a depth/stencil
//! internal format copies both buffers.

use crate::frame::Frame;
use crate::frame::FrameSink;
use crate::frame::pixels::{PixelBuffer, PixelData, PixelKind};
use crate::translate::context::ContextConfig;
use crate::translate::{Context, dispatch, gl};

/// A renderer whose pixel (x, y) has depth x / 8 and stencil 16 y + x.
struct Ramp;

impl FrameSink for Ramp {
    fn present(&mut self, _frame: Frame) {}
    fn read_pixels(&mut self, _frame: &Frame, buffer: PixelBuffer, [x, y, w, h]: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        let mut out = Vec::new();
        for j in y..y + h {
            for i in x..x + w {
                out.push(match buffer {
                    PixelBuffer::Depth => [i as f32 / 8.0, 0.0, 0.0, 0.0],
                    PixelBuffer::Stencil => [(16 * j + i) as f32, 0.0, 0.0, 0.0],
                    PixelBuffer::Color => [1.0; 4],
                });
            }
        }
        Some(out)
    }
}

/// A context on an 8 × 8 drawable drawn by [`Ramp`].
fn ramp_context() -> Context {
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(Ramp) });
    ctx.bind_drawable(8, 8);
    ctx
}

/// The depth/stencil image of the last pixel operation: position, size, depths, indices.
fn last_image(ctx: &Context) -> ([f32; 3], [u32; 2], Vec<f32>, Vec<u32>) {
    match ctx.frame.pixels.last().map(|p| &p.kind) {
        Some(PixelKind::Image { window_pos, size, data: PixelData::DepthStencil(d, s), .. }) => (*window_pos, *size, d.to_vec(), s.to_vec()),
        other => panic!("not a depth/stencil image: {other:?}"),
    }
}

#[test]
fn draw_pixels_records_depth_and_stencil_after_transfer() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glWindowPos3f(3.0, 4.0, 0.0);
    let packed = [0xffff_ff05u32, 0x8000_0003];
    unsafe { dispatch::glDrawPixels(&mut ctx, 2, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, packed.as_ptr().cast()) };
    let (pos, size, depth, stencil) = last_image(&ctx);
    assert_eq!((pos, size), ([3.0, 4.0, 0.0], [2, 1]));
    assert_eq!(depth, [1.0, (f64::from(0x80_0000u32) / 16_777_215.0) as f32]);
    assert_eq!(stencil, [5, 3]);
    ctx.glPixelTransferf(gl::GL_DEPTH_SCALE, 0.5);
    ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 2);
    let words = [0.5f32.to_bits(), 0xffff_ff10];
    unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, words.as_ptr().cast()) };
    let (_, _, depth, stencil) = last_image(&ctx);
    assert_eq!((depth, stencil), (vec![0.25], vec![0x12]));
    unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT, words.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_INT_24_8, words.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    assert_eq!(ctx.frame.pixels.len(), 2);
}

#[test]
fn read_pixels_packs_depth_and_stencil() {
    let mut ctx = ramp_context();
    let mut packed = [0u32; 2];
    unsafe { dispatch::glReadPixels(&mut ctx, 4, 1, 2, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, packed.as_mut_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    // Depth 4/8 → round(0.5 × (2^24 − 1)) = 0x800000, 5/8 → round(10485759.375) = 0x9fffff;
    // stencil 16 + 4 and 16 + 5.
    assert_eq!(packed, [0x8000_0000 | 20, (0x9f_ffffu32 << 8) | 21]);
    let mut words = [0xdead_beefu32; 2];
    ctx.glPixelTransferi(gl::GL_INDEX_SHIFT, 1);
    unsafe { dispatch::glReadPixels(&mut ctx, 2, 3, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, words.as_mut_ptr().cast()) };
    // (16 × 3 + 2) << 1 = 100; only the low 8 bits are kept.
    assert_eq!(words, [0.25f32.to_bits(), 100]);
    unsafe { dispatch::glReadPixels(&mut ctx, 0, 0, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT, words.as_mut_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
}

#[test]
fn copy_pixels_reads_transfers_and_redraws_inside_the_window() {
    let mut ctx = ramp_context();
    ctx.glWindowPos3f(1.0, 2.0, 0.0);
    ctx.glPixelTransferf(gl::GL_DEPTH_BIAS, 0.125);
    ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 1);
    // Columns −1 and 8 and row 8 lie outside the 8 × 8 window: they make no fragments.
    ctx.glCopyPixels(-1, 7, 10, 2, gl::GL_DEPTH_STENCIL);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    let (pos, size, depth, stencil) = last_image(&ctx);
    assert_eq!((pos, size), ([2.0, 2.0, 0.0], [8, 1]));
    assert_eq!(depth, (0..8).map(|x| x as f32 / 8.0 + 0.125).collect::<Vec<_>>());
    assert_eq!(stencil, (0..8).map(|x| 16 * 7 + x + 1).collect::<Vec<_>>());
    ctx.glCopyPixels(0, 0, 1, 1, gl::GL_DEPTH_STENCIL_TO_RGBA_NV);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    ctx.glCopyPixels(20, 20, 1, 1, gl::GL_DEPTH_STENCIL);
    assert_eq!(ctx.frame.pixels.len(), 1, "a source wholly outside the window copies nothing");
}

#[test]
fn copy_tex_image_of_a_depth_stencil_format_copies_depth_and_stencil() {
    let mut ctx = ramp_context();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 3);
    ctx.glCopyTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_DEPTH24_STENCIL8, 4, 1, 2, 1, 0);
    ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 0x100 + 1);
    ctx.glCopyTexSubImage2D(gl::GL_TEXTURE_2D, 0, 1, 0, 2, 3, 1, 1);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    // glGetTexImage applies pixel transfer too: read without the offset.
    ctx.glPixelTransferi(gl::GL_INDEX_OFFSET, 0);
    let mut packed = [0u32; 2];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, packed.as_mut_ptr().cast()) };
    // (4, 1): depth 0.5, stencil 20. (2, 3) copied over texel 1: depth 0.25, stencil
    // 50 + 257 masked to 8 bits = 51.
    assert_eq!(packed, [(0x80_0000 << 8) | 20, (0x40_0000 << 8) | 51]);
}
