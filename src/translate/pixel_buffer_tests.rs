//! Tests of pixel buffer objects ([`super::pixel_buffers`]): every unpacking command reads the
//! bound unpack buffer at the offset it is given and every packing command writes the bound
//! pack buffer, with `GL_INVALID_OPERATION` (and nothing read or written) for a mapped buffer,
//! an access past the end or a misaligned offset; display lists take the buffer's bytes at
//! compile time; the bindings are queried, pushed with the pixel-store group and dropped with
//! their buffer.

use std::ffi::c_void;

use crate::frame::Frame;
use crate::frame::FrameSink;
use crate::frame::pixels::{PixelBuffer, PixelData, PixelKind};
use crate::translate::context::ContextConfig;
use crate::translate::{Context, dispatch, gl};

const PACK: gl::GLenum = gl::GL_PIXEL_PACK_BUFFER;
const UNPACK: gl::GLenum = gl::GL_PIXEL_UNPACK_BUFFER;

/// A buffer offset as the pointer argument that carries it.
fn at(offset: usize) -> *mut c_void {
    std::ptr::without_provenance_mut(offset)
}

/// Binds buffer `name` to `target` and gives it `bytes`.
fn buffer(ctx: &mut Context, target: gl::GLenum, name: u32, bytes: &[u8]) {
    ctx.glBindBuffer(target, name);
    unsafe { ctx.glBufferData(target, bytes.len() as isize, bytes.as_ptr().cast(), gl::GL_STREAM_DRAW) };
}

/// The whole data store of the buffer bound to `target`.
fn contents(ctx: &mut Context, target: gl::GLenum) -> Vec<u8> {
    let mut size = 0;
    unsafe { ctx.glGetBufferParameteriv(target, gl::GL_BUFFER_SIZE, &mut size) };
    let mut out = vec![0u8; size as usize];
    unsafe { ctx.glGetBufferSubData(target, 0, size as isize, out.as_mut_ptr().cast()) };
    out
}

fn int(ctx: &mut Context, pname: gl::GLenum) -> i32 {
    let mut v = -1;
    unsafe { ctx.glGetIntegerv(pname, &mut v) };
    v
}

/// The 2 × 2 RGBA bytes of level 0 of the bound 2D texture, read into client memory.
fn texels(ctx: &mut Context) -> [u8; 16] {
    let saved = std::mem::take(&mut ctx.pixels.store.pack_buffer);
    let mut out = [0u8; 16];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    ctx.pixels.store.pack_buffer = saved;
    out
}

#[test]
fn tex_image_from_one_buffer_and_get_tex_image_into_another_give_the_same_bytes() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let image: Vec<u8> = (0..16).map(|i| i * 13 + 7).collect();
    let mut store = vec![0xaa; 3];
    store.extend(&image);
    buffer(&mut ctx, UNPACK, 5, &store);
    ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
    unsafe { ctx.glTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(3)) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(texels(&mut ctx).to_vec(), image);
    buffer(&mut ctx, PACK, 6, &[0x55; 20]);
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(4)) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    let packed = contents(&mut ctx, PACK);
    assert_eq!((&packed[..4], &packed[4..]), (&[0x55u8; 4][..], &image[..]));
    // With an unpack buffer bound a null pointer is offset 0, not "no image".
    buffer(&mut ctx, UNPACK, 5, &image);
    unsafe { ctx.glTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE as i32, 2, 2, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
    assert_eq!(texels(&mut ctx)[..8], [7, 0, 0, 255, 20, 0, 0, 255], "luminance reads back as red");
    // Sub-images and 1D/3D images read the buffer too.
    unsafe { ctx.glTexSubImage2D(gl::GL_TEXTURE_2D, 0, 1, 1, 1, 1, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, at(15)) };
    assert_eq!(texels(&mut ctx)[12..], [202, 0, 0, 255]);
    ctx.glBindTexture(gl::GL_TEXTURE_3D, 2);
    unsafe { ctx.glTexImage3D(gl::GL_TEXTURE_3D, 0, gl::GL_ALPHA as i32, 1, 1, 2, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, at(1)) };
    ctx.glBindBuffer(PACK, 0);
    ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
    let mut alpha = [0u8; 2];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_3D, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, alpha.as_mut_ptr().cast()) };
    assert_eq!(alpha, [20, 33]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn out_of_range_misaligned_and_mapped_accesses_are_invalid_operation_and_change_nothing() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let first: Vec<u8> = (1..=16).collect();
    unsafe { ctx.glTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, first.as_ptr().cast()) };
    buffer(&mut ctx, UNPACK, 3, &[9; 32]);
    let upload = |ctx: &mut Context, type_, offset| {
        unsafe { ctx.glTexSubImage2D(gl::GL_TEXTURE_2D, 0, 0, 0, 2, 2, gl::GL_RGBA, type_, at(offset)) };
        ctx.glGetError()
    };
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_BYTE, 17), gl::GL_INVALID_OPERATION, "16 bytes from 17 run past 32");
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_SHORT, 2), gl::GL_INVALID_OPERATION, "32 bytes from 2 run past 32");
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_SHORT_4_4_4_4, 1), gl::GL_INVALID_OPERATION, "a ushort at an odd offset");
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_INT_8_8_8_8, 2), gl::GL_INVALID_OPERATION, "a uint at offset 2");
    assert_eq!(texels(&mut ctx).to_vec(), first, "a failed command changes nothing");
    let p = ctx.glMapBuffer(UNPACK, gl::GL_READ_ONLY);
    assert!(!p.is_null());
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_BYTE, 0), gl::GL_INVALID_OPERATION, "the buffer is mapped");
    assert_eq!(ctx.glUnmapBuffer(UNPACK), 1);
    assert_eq!(upload(&mut ctx, gl::GL_UNSIGNED_BYTE, 16), gl::GL_NO_ERROR, "exactly up to the end");
    assert_eq!(texels(&mut ctx), [9; 16]);

    // Packing: past the end, misaligned, mapped; the buffer keeps its bytes.
    buffer(&mut ctx, PACK, 4, &[0xee; 20]);
    let get = |ctx: &mut Context, type_, offset| {
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, type_, at(offset)) };
        ctx.glGetError()
    };
    assert_eq!(get(&mut ctx, gl::GL_UNSIGNED_BYTE, 5), gl::GL_INVALID_OPERATION);
    assert_eq!(get(&mut ctx, gl::GL_UNSIGNED_SHORT_5_5_5_1, 3), gl::GL_INVALID_OPERATION);
    ctx.glMapBuffer(PACK, gl::GL_WRITE_ONLY);
    assert_eq!(get(&mut ctx, gl::GL_UNSIGNED_BYTE, 0), gl::GL_INVALID_OPERATION);
    ctx.glUnmapBuffer(PACK);
    assert_eq!(contents(&mut ctx, PACK), [0xee; 20]);
    assert_eq!(get(&mut ctx, gl::GL_UNSIGNED_BYTE, 4), gl::GL_NO_ERROR);
    assert_eq!(contents(&mut ctx, PACK)[4..], [9; 16]);
}

/// A renderer whose colour pixel (x, y) is (x / 8, y / 8, 0.5, 1).
struct Ramp;

impl FrameSink for Ramp {
    fn present(&mut self, _frame: Frame) {}
    fn read_pixels(&mut self, _frame: &Frame, _buffer: PixelBuffer, [x, y, w, h]: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        Some((y..y + h).flat_map(|j| (x..x + w).map(move |i| [i as f32 / 8.0, j as f32 / 8.0, 0.5, 1.0])).collect())
    }
}

#[test]
fn read_pixels_writes_into_the_pack_buffer() {
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(Ramp) });
    ctx.bind_drawable(8, 8);
    buffer(&mut ctx, PACK, 7, &[0; 12]);
    ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
    unsafe { ctx.glReadPixels(2, 4, 2, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, at(6)) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(contents(&mut ctx, PACK), [0, 0, 0, 0, 0, 0, 64, 128, 128, 96, 128, 128]);
    unsafe { ctx.glReadPixels(2, 4, 2, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, at(7)) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { ctx.glReadPixels(0, 0, 1, 1, gl::GL_RED, gl::GL_FLOAT, at(2)) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a float at offset 2");
    unsafe { ctx.glReadPixels(1, 0, 1, 1, gl::GL_RED, gl::GL_FLOAT, at(8)) };
    assert_eq!(contents(&mut ctx, PACK)[8..], 0.125f32.to_ne_bytes());
}

#[test]
fn draw_pixels_bitmap_and_compressed_images_read_the_unpack_buffer() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glWindowPos3f(1.0, 1.0, 0.0);
    buffer(&mut ctx, UNPACK, 2, &[0, 0, 0xff, 0x80, 0x40, 0x20, 0xc0]);
    ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
    unsafe { ctx.glDrawPixels(1, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, at(2).cast_const()) };
    unsafe { ctx.glBitmap(2, 1, 0.0, 0.0, 3.0, 0.0, at(6).cast()) };
    unsafe { ctx.glBitmap(2, 1, 0.0, 0.0, 3.0, 0.0, at(7).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a bitmap byte past the end");
    let kinds: Vec<_> = ctx.frame.pixels.iter().map(|p| p.kind.clone()).collect();
    match &kinds[..] {
        [PixelKind::Image { data, .. }, PixelKind::Bitmap { mask, window_pos, .. }] => {
            assert!(*data == PixelData::Rgba8(vec![255, 128, 64, 255].into()), "the image's bytes");
            assert_eq!((&mask[..], window_pos[0]), (&[255u8, 255][..], 1.0));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(ctx.pixels.raster.window[0], 4.0, "the failed bitmap did not move the raster position");

    // A DXT1 block from the buffer, read back into the pack buffer.
    let block = [0xff, 0xff, 0x00, 0x00, 0, 0, 0, 0];
    let mut store = vec![0u8; 5];
    store.extend(block);
    buffer(&mut ctx, UNPACK, 2, &store);
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let dxt1 = gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
    unsafe { ctx.glCompressedTexImage2D(gl::GL_TEXTURE_2D, 0, dxt1, 4, 4, 0, 8, at(6).cast_const()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "8 bytes from 6 run past 13");
    unsafe { ctx.glCompressedTexImage2D(gl::GL_TEXTURE_2D, 0, dxt1, 4, 4, 0, 8, at(5).cast_const()) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "compressed data need no alignment");
    buffer(&mut ctx, PACK, 3, &[1; 9]);
    unsafe { ctx.glGetCompressedTexImage(gl::GL_TEXTURE_2D, 0, at(1)) };
    assert_eq!(contents(&mut ctx, PACK)[1..], block);
    unsafe { ctx.glGetCompressedTexImage(gl::GL_TEXTURE_2D, 0, at(2)) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
}

#[test]
fn stipple_pixel_maps_and_color_tables_use_the_buffers() {
    let (mut ctx, _) = Context::with_recording();
    let pattern: Vec<u8> = (0..128u32).map(|i| (i * 29 % 256) as u8).collect();
    let mut store = vec![0u8];
    store.extend(&pattern);
    buffer(&mut ctx, UNPACK, 1, &store);
    unsafe { ctx.glPolygonStipple(at(1).cast()) };
    assert_eq!(ctx.fixed.raster.stipple[0], u32::from_be_bytes([0, 29, 58, 87]));
    unsafe { ctx.glPolygonStipple(at(2).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    buffer(&mut ctx, PACK, 2, &[0; 130]);
    unsafe { ctx.glGetPolygonStipple(at(2).cast()) };
    assert_eq!(contents(&mut ctx, PACK)[2..], pattern[..]);

    let map: Vec<u8> = [0.25f32, 0.75].iter().flat_map(|v| v.to_ne_bytes()).collect();
    buffer(&mut ctx, UNPACK, 1, &[&[0u8; 4][..], &map].concat());
    unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_R_TO_R, 2, at(4).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_G_TO_G, 2, at(2).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a float at offset 2");
    unsafe { ctx.glPixelMapfv(gl::GL_PIXEL_MAP_G_TO_G, 2, at(8).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "8 bytes from 8 run past 12");
    assert_eq!(int(&mut ctx, gl::GL_PIXEL_MAP_G_TO_G_SIZE), 1);
    buffer(&mut ctx, PACK, 2, &[0; 6]);
    unsafe { ctx.glGetPixelMapusv(gl::GL_PIXEL_MAP_R_TO_R, at(2).cast()) };
    let shorts = contents(&mut ctx, PACK);
    assert_eq!([u16::from_ne_bytes([shorts[2], shorts[3]]), u16::from_ne_bytes([shorts[4], shorts[5]])], [16384, 49151]);
    unsafe { ctx.glGetPixelMapuiv(gl::GL_PIXEL_MAP_R_TO_R, at(0).cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "8 bytes do not fit in 6");

    buffer(&mut ctx, UNPACK, 1, &[0, 10, 20, 30, 40, 50, 60, 70, 80]);
    ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
    unsafe { ctx.glColorTableEXT(gl::GL_TEXTURE_2D, gl::GL_RGBA, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(1).cast_const()) };
    buffer(&mut ctx, PACK, 2, &[0; 8]);
    unsafe { ctx.glGetColorTableEXT(gl::GL_TEXTURE_2D, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(0)) };
    assert_eq!(contents(&mut ctx, PACK), [10, 20, 30, 40, 50, 60, 70, 80]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn display_lists_take_the_buffer_bytes_at_compile_time() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    unsafe { ctx.glTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
    let image: Vec<u8> = (100..116).collect();
    buffer(&mut ctx, UNPACK, 4, &image);
    unsafe {
        dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
        dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(0));
        dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 2, 2, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, at(1));
        dispatch::glEndList(&mut ctx);
    }
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "the second one reads past the end when compiled");
    assert_eq!(texels(&mut ctx), [0; 16], "compiling does not execute");
    // The list runs with other bytes in the buffer, and with the buffer bound or not.
    buffer(&mut ctx, UNPACK, 4, &[1; 16]);
    unsafe { dispatch::glCallList(&mut ctx, 1) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "only the first command was recorded");
    assert_eq!(texels(&mut ctx).to_vec(), image);
    assert_eq!(int(&mut ctx, gl::GL_PIXEL_UNPACK_BUFFER_BINDING), 4, "running the list keeps the binding");
}

#[test]
fn bindings_are_queried_pushed_and_dropped_with_their_buffer() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindBuffer(PACK, 3);
    ctx.glBindBuffer(UNPACK, 4);
    assert_eq!((int(&mut ctx, gl::GL_PIXEL_PACK_BUFFER_BINDING), int(&mut ctx, gl::GL_PIXEL_UNPACK_BUFFER_BINDING)), (3, 4));
    ctx.glPushClientAttrib(gl::GL_CLIENT_PIXEL_STORE_BIT);
    ctx.glBindBuffer(PACK, 0);
    ctx.glBindBuffer(UNPACK, 9);
    ctx.glPopClientAttrib();
    assert_eq!((int(&mut ctx, gl::GL_PIXEL_PACK_BUFFER_BINDING), int(&mut ctx, gl::GL_PIXEL_UNPACK_BUFFER_BINDING)), (3, 4));
    unsafe { ctx.glDeleteBuffers(2, [4u32, 3].as_ptr()) };
    assert_eq!((int(&mut ctx, gl::GL_PIXEL_PACK_BUFFER_BINDING), int(&mut ctx, gl::GL_PIXEL_UNPACK_BUFFER_BINDING)), (0, 0));
    // Buffer commands accept the pixel targets.
    buffer(&mut ctx, PACK, 5, &[1, 2, 3, 4]);
    unsafe { ctx.glBufferSubData(PACK, 1, 2, [8u8, 9].as_ptr().cast()) };
    assert_eq!(contents(&mut ctx, PACK), [1, 8, 9, 4]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}
