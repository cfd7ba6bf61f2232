//! EXT_texture_integer at the command level: integer texels round-trip exactly through
//! `glTexImage2D`/`glGetTexImage`, the `*_INTEGER` formats' errors, size and type queries, and
//! the refusals of the framebuffer paths (glrt's colour buffers are never integer).

use crate::translate::{Context, dispatch, gl};

/// Uploads `w` × 1 texels of `format`/`type_` into a 2D texture of `internal`; the error.
fn upload<T>(ctx: &mut Context, internal: u32, w: i32, format: u32, type_: u32, data: &[T]) -> u32 {
    unsafe { dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, internal as i32, w, 1, 0, format, type_, data.as_ptr().cast()) };
    ctx.glGetError()
}

/// Reads level 0 of the 2D texture as `format`/`type_` into `out`; the error.
fn read<T>(ctx: &mut Context, format: u32, type_: u32, out: &mut [T]) -> u32 {
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, format, type_, out.as_mut_ptr().cast()) };
    ctx.glGetError()
}

fn level_param(ctx: &mut Context, pname: u32) -> i32 {
    let mut v = -7;
    unsafe { ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, pname, &mut v) };
    v
}

#[test]
fn integer_texels_round_trip_exactly() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
    ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);

    // 32-bit unsigned: every bit survives, beyond what an f32 holds.
    let u32s = [0u32, 1, 16_777_217, u32::MAX, 0x8000_0001, 7, 123_456_789, 4_000_000_000];
    assert_eq!(upload(&mut ctx, gl::GL_RGBA32UI_EXT, 2, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT, &u32s), gl::GL_NO_ERROR);
    let mut back = [0u32; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT, &mut back), gl::GL_NO_ERROR);
    assert_eq!(back, u32s);
    // BGRA reorders, and narrower types clamp to their range.
    let mut bgra = [0u32; 8];
    assert_eq!(read(&mut ctx, gl::GL_BGRA_INTEGER_EXT, gl::GL_UNSIGNED_INT, &mut bgra), gl::GL_NO_ERROR);
    assert_eq!(bgra[..4], [16_777_217, 1, 0, u32::MAX]);
    let mut shorts = [0u16; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &mut shorts), gl::GL_NO_ERROR);
    assert_eq!(shorts, [0, 1, 65535, 65535, 65535, 7, 65535, 65535]);
    let mut ints = [0i32; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &mut ints), gl::GL_NO_ERROR);
    assert_eq!(ints[..4], [0, 1, 16_777_217, i32::MAX]);

    // 32-bit signed through GL_INT.
    let i32s = [i32::MIN, -1, 0, i32::MAX, -16_777_217, 5, -6, 1 << 30];
    assert_eq!(upload(&mut ctx, gl::GL_RGBA32I_EXT, 2, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &i32s), gl::GL_NO_ERROR);
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &mut ints), gl::GL_NO_ERROR);
    assert_eq!(ints, i32s);
    let mut bytes = [0i8; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_BYTE, &mut bytes), gl::GL_NO_ERROR);
    assert_eq!(bytes, [-128, -1, 0, 127, -128, 5, -6, 127]);

    // 16-bit signed from GL_SHORT, RGB: alpha reads back as 1.
    let i16s = [-32768i16, 32767, -2, 300, -300, 0];
    assert_eq!(upload(&mut ctx, gl::GL_RGB16I_EXT, 2, gl::GL_RGB_INTEGER_EXT, gl::GL_SHORT, &i16s), gl::GL_NO_ERROR);
    let mut rgba16 = [0i16; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_SHORT, &mut rgba16), gl::GL_NO_ERROR);
    assert_eq!(rgba16, [-32768, 32767, -2, 1, 300, -300, 0, 1]);

    // 8-bit unsigned from GL_INT values: clamped to the format's [0, 255] when stored.
    let wide = [-5i32, 256, 200, 1000];
    assert_eq!(upload(&mut ctx, gl::GL_RGBA8UI_EXT, 1, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &wide), gl::GL_NO_ERROR);
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT, &mut ints[..4]), gl::GL_NO_ERROR);
    assert_eq!(ints[..4], [0, 255, 200, 255]);

    // Luminance-alpha: L from R, as packing forms luminance for integer formats.
    let la = [-100i8, 50, 7, -7];
    assert_eq!(upload(&mut ctx, gl::GL_LUMINANCE_ALPHA8I_EXT, 2, gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, gl::GL_BYTE, &la), gl::GL_NO_ERROR);
    let mut la_back = [0i8; 4];
    assert_eq!(read(&mut ctx, gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, gl::GL_BYTE, &mut la_back), gl::GL_NO_ERROR);
    assert_eq!(la_back, la);
    let mut rgba8 = [0i8; 8];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_BYTE, &mut rgba8), gl::GL_NO_ERROR);
    assert_eq!(rgba8, [-100, 0, 0, 50, 7, 0, 0, -7]);

    // Alpha from an RGBA image; sub-images replace exactly.
    let alpha = [1u16, 2, 3, 40000, 5, 6, 7, 65535];
    assert_eq!(upload(&mut ctx, gl::GL_ALPHA16UI_EXT, 2, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &alpha), gl::GL_NO_ERROR);
    let mut a = [0u16; 2];
    assert_eq!(read(&mut ctx, gl::GL_ALPHA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &mut a), gl::GL_NO_ERROR);
    assert_eq!(a, [40000, 65535]);
    let one = [12345u32];
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 1, 0, 1, 1, gl::GL_ALPHA_INTEGER_EXT, gl::GL_UNSIGNED_INT, one.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(read(&mut ctx, gl::GL_ALPHA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &mut a), gl::GL_NO_ERROR);
    assert_eq!(a, [40000, 12345]);

    // Packed types (OpenGL 3.0's table 3.8) carry unnormalized fields, as piglit's
    // ext_texture_integer-texformats uploads and reads them.
    let packed = [0x0403_0201u32, 0xfffe_fdfc];
    assert_eq!(upload(&mut ctx, gl::GL_RGBA8UI_EXT, 2, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT_8_8_8_8, &packed), gl::GL_NO_ERROR);
    let mut packed_back = [0u32; 2];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT_8_8_8_8, &mut packed_back), gl::GL_NO_ERROR);
    assert_eq!(packed_back, packed);
    let mut unpacked = [0u8; 4];
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_BYTE, &mut unpacked), gl::GL_NO_ERROR);
    assert_eq!(unpacked, [4, 3, 2, 1]);

    // ARB_texture_rg's integer formats with GL_RG_INTEGER.
    let rg = [u32::MAX, 3];
    assert_eq!(upload(&mut ctx, gl::GL_RG32UI, 1, gl::GL_RG_INTEGER, gl::GL_UNSIGNED_INT, &rg), gl::GL_NO_ERROR);
    let mut rg_back = [0u32; 3];
    assert_eq!(read(&mut ctx, gl::GL_RGB_INTEGER_EXT, gl::GL_UNSIGNED_INT, &mut rg_back), gl::GL_NO_ERROR);
    assert_eq!(rg_back, [u32::MAX, 3, 0]);
}

#[test]
fn integer_format_errors() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let px = [0u32; 64];
    // Integer formats with GL_FLOAT: GL_INVALID_ENUM; with packed types of another component
    // count, or the packed float types: GL_INVALID_OPERATION.
    assert_eq!(upload(&mut ctx, gl::GL_RGBA16UI_EXT, 1, gl::GL_RGBA_INTEGER_EXT, gl::GL_FLOAT, &px), gl::GL_INVALID_ENUM);
    assert_eq!(upload(&mut ctx, gl::GL_RGB8UI_EXT, 1, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT_5_6_5, &px), gl::GL_INVALID_OPERATION);
    assert_eq!(upload(&mut ctx, gl::GL_RGB8UI_EXT, 1, gl::GL_RGB_INTEGER_EXT, gl::GL_UNSIGNED_INT_10F_11F_11F_REV, &px), gl::GL_INVALID_OPERATION);
    // Integer data into a non-integer texture and the reverse.
    assert_eq!(upload(&mut ctx, gl::GL_RGBA, 4, gl::GL_RGBA_INTEGER_EXT, gl::GL_SHORT, &px), gl::GL_INVALID_OPERATION);
    assert_eq!(upload(&mut ctx, gl::GL_RGBA8I_EXT, 4, gl::GL_RGBA, gl::GL_BYTE, &px), gl::GL_INVALID_OPERATION);
    assert_eq!(upload(&mut ctx, gl::GL_RGBA8I_EXT, 4, gl::GL_COLOR_INDEX, gl::GL_BYTE, &px), gl::GL_INVALID_OPERATION);
    assert_eq!(upload(&mut ctx, gl::GL_DEPTH_COMPONENT, 4, gl::GL_RED_INTEGER_EXT, gl::GL_INT, &px), gl::GL_INVALID_OPERATION);
    assert_eq!(upload(&mut ctx, gl::GL_RGBA16UI_EXT, 4, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_SHORT, &px), gl::GL_NO_ERROR);
    let sub = |ctx: &mut Context, format, type_| {
        unsafe { dispatch::glTexSubImage2D(ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 4, 1, format, type_, px.as_ptr().cast()) };
        ctx.glGetError()
    };
    assert_eq!(sub(&mut ctx, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE), gl::GL_INVALID_OPERATION);
    assert_eq!(sub(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_FLOAT), gl::GL_INVALID_ENUM);
    assert_eq!(sub(&mut ctx, gl::GL_BGRA_INTEGER_EXT, gl::GL_UNSIGNED_BYTE), gl::GL_NO_ERROR);
    // glGetTexImage: a non-integer format from an integer level and the reverse.
    let mut out = [0u8; 64];
    assert_eq!(read(&mut ctx, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, &mut out), gl::GL_INVALID_OPERATION);
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_FLOAT, &mut out), gl::GL_INVALID_ENUM);
    // Copies from the (never integer) framebuffer into integer textures.
    ctx.glCopyTexSubImage2D(gl::GL_TEXTURE_2D, 0, 0, 0, 0, 0, 4, 1);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    ctx.glCopyTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA8UI_EXT, 0, 0, 4, 4, 0);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_INTERNAL_FORMAT), gl::GL_RGBA16UI_EXT as i32);
    assert_eq!(upload(&mut ctx, gl::GL_RGBA, 4, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, &px), gl::GL_NO_ERROR);
    assert_eq!(sub(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_INT), gl::GL_INVALID_OPERATION);
    assert_eq!(read(&mut ctx, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_BYTE, &mut out), gl::GL_INVALID_OPERATION);
    // glDrawPixels refuses integer formats (any type), glReadPixels too (GL_FLOAT first).
    unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT, px.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { dispatch::glDrawPixels(&mut ctx, 1, 1, gl::GL_RGBA_INTEGER_EXT, gl::GL_FLOAT, px.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { ctx.glReadPixels(0, 0, 4, 4, gl::GL_RGBA_INTEGER_EXT, gl::GL_FLOAT, out.as_mut_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    unsafe { ctx.glReadPixels(0, 0, 4, 4, gl::GL_RGBA_INTEGER_EXT, gl::GL_UNSIGNED_INT, out.as_mut_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
}

#[test]
fn integer_levels_answer_queries_and_are_never_sampled() {
    let (mut ctx, _) = Context::with_recording();
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let px = [0i32; 4];
    assert_eq!(upload(&mut ctx, gl::GL_LUMINANCE_ALPHA32I_EXT, 1, gl::GL_LUMINANCE_ALPHA_INTEGER_EXT, gl::GL_INT, &px), gl::GL_NO_ERROR);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_LUMINANCE_SIZE), 32);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_ALPHA_SIZE), 32);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_RED_SIZE), 0);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_LUMINANCE_TYPE), gl::GL_INT as i32);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_RED_TYPE), gl::GL_NONE as i32);
    assert_eq!(upload(&mut ctx, gl::GL_INTENSITY8UI_EXT, 1, gl::GL_RED_INTEGER_EXT, gl::GL_UNSIGNED_BYTE, &px), gl::GL_NO_ERROR);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_INTENSITY_SIZE), 8);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_INTENSITY_TYPE), gl::GL_UNSIGNED_INT as i32);
    // Complete with nearest filtering, yet fixed-function texturing leaves the unit unbound.
    ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
    ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
    ctx.glEnable(gl::GL_TEXTURE_2D);
    assert!(ctx.texture_snapshot()[0].is_none());
    let rgba = [255u8; 4];
    assert_eq!(upload(&mut ctx, gl::GL_RGBA8, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, &rgba), gl::GL_NO_ERROR);
    assert!(ctx.texture_snapshot()[0].is_some());
    // GL_GENERATE_MIPMAP averages integer levels exactly.
    ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
    let four = [1u32, 2, 3_000_000_001, 4_000_000_001];
    unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE32UI_EXT as i32, 2, 2, 0, gl::GL_LUMINANCE_INTEGER_EXT, gl::GL_UNSIGNED_INT, four.as_ptr().cast()) };
    let mut l = [0u32; 1];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 1, gl::GL_LUMINANCE_INTEGER_EXT, gl::GL_UNSIGNED_INT, l.as_mut_ptr().cast()) };
    assert_eq!((ctx.glGetError(), l[0]), (gl::GL_NO_ERROR, 1_750_000_001));
    // State of the extension.
    let mut b = [1u8];
    unsafe { ctx.glGetBooleanv(gl::GL_RGBA_INTEGER_MODE_EXT, b.as_mut_ptr()) };
    assert_eq!(b[0], 0);
    ctx.glClearColorIiEXT(-1, 2, -3, 4);
    assert_eq!(ctx.fixed.clear.color_integer, [-1, 2, -3, 4]);
    ctx.glClearColorIuiEXT(u32::MAX, 0, 1, 2);
    assert_eq!(ctx.fixed.clear.color_integer, [i64::from(u32::MAX), 0, 1, 2]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}
