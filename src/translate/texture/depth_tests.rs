//! Tests of depth textures: values keep the precision of their internal format through
//! `glTexImage`, `glTexSubImage`, `GL_GENERATE_MIPMAP` and `glGetTexImage`, the renderer sees
//! them in `TexImage::depth_values`, and `GL_TEXTURE_DEPTH_SIZE` reports the format's bits.

use super::Target;
use crate::translate::{Context, dispatch, gl};

/// `glGetTexLevelParameteriv` of level 0 of the bound 2D texture.
fn level_param(ctx: &mut Context, pname: u32) -> i32 {
    let mut v = -7;
    unsafe { ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, pname, &mut v) };
    v
}

/// Uploads a 2×1 depth image of `internal` from `values` (`type_` data) to texture 1.
fn depth_image<T>(ctx: &mut Context, internal: u32, type_: u32, values: &[T; 2]) {
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    let (w, h) = (2, 1);
    unsafe { dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, internal as i32, w, h, 0, gl::GL_DEPTH_COMPONENT, type_, values.as_ptr().cast()) };
}

/// Reads level `level` of texture 1 back as two `T` depth values.
fn read_depth<T: Copy + Default>(ctx: &mut Context, level: i32, type_: u32) -> [T; 2] {
    let mut out = [T::default(); 2];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, level, gl::GL_DEPTH_COMPONENT, type_, out.as_mut_ptr().cast()) };
    out
}

#[test]
fn depth_textures_keep_full_precision() {
    let (mut ctx, _) = Context::with_recording();
    let want = [1.0f64 / 31.0, 17.0 / 31.0];
    let tolerance = 2f64.powi(-24);
    let uint_max = f64::from(u32::MAX);
    for internal in [gl::GL_DEPTH_COMPONENT, gl::GL_DEPTH_COMPONENT24, gl::GL_DEPTH_COMPONENT32] {
        depth_image(&mut ctx, internal, gl::GL_FLOAT, &want.map(|v| v as f32));
        let floats: [f32; 2] = read_depth(&mut ctx, 0, gl::GL_FLOAT);
        let uints: [u32; 2] = read_depth(&mut ctx, 0, gl::GL_UNSIGNED_INT);
        for k in 0..2 {
            assert!((f64::from(floats[k]) - want[k]).abs() <= tolerance, "{internal:#x}: {floats:?}");
            assert!((f64::from(uints[k]) / uint_max - want[k]).abs() <= tolerance, "{internal:#x}: {uints:?}");
        }
        // The same values given as unsigned integers.
        depth_image(&mut ctx, internal, gl::GL_UNSIGNED_INT, &want.map(|v| (v * uint_max).round() as u32));
        let floats: [f32; 2] = read_depth(&mut ctx, 0, gl::GL_FLOAT);
        assert!(floats.iter().zip(want).all(|(&f, w)| (f64::from(f) - w).abs() <= tolerance), "{internal:#x}: {floats:?}");
    }
    // 16-bit depth: unsigned shorts come back exactly, floats at 16 bits.
    depth_image(&mut ctx, gl::GL_DEPTH_COMPONENT16, gl::GL_UNSIGNED_SHORT, &[2114u16, 35000]);
    assert_eq!(read_depth::<u16>(&mut ctx, 0, gl::GL_UNSIGNED_SHORT), [2114, 35000]);
    depth_image(&mut ctx, gl::GL_DEPTH_COMPONENT16, gl::GL_FLOAT, &want.map(|v| v as f32));
    let floats: [f32; 2] = read_depth(&mut ctx, 0, gl::GL_FLOAT);
    assert_eq!(floats[0], (2114.0 / 65535.0) as f32, "1/31 rounds to 2114/65535");
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn depth_sub_images_and_mipmaps_keep_full_precision() {
    let (mut ctx, _) = Context::with_recording();
    let third = 1.0f32 / 3.0;
    depth_image(&mut ctx, gl::GL_DEPTH_COMPONENT32, gl::GL_FLOAT, &[0.0f32, 0.0]);
    ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 1, 0, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, [third].as_ptr().cast()) };
    assert_eq!(read_depth::<f32>(&mut ctx, 0, gl::GL_FLOAT), [0.0, third]);
    let mut level1 = [0.0f32; 1];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, level1.as_mut_ptr().cast()) };
    assert_eq!(level1, [third / 2.0], "the generated level averages the depth values");
    let image = ctx.with_bound_texture(Target::D2, |o| o.level(0, 0).map(|l| l.image.clone()));
    let image = image.expect("level 0 exists");
    assert_eq!(image.depth_values, [0.0, third], "the renderer sees the full-precision values");
    assert_eq!(&image.texels[4..8], &[85, 85, 85, 255], "and their 8-bit expansion");
}

#[test]
fn depth_size_follows_the_internal_format() {
    let (mut ctx, _) = Context::with_recording();
    for (internal, bits) in [
        (gl::GL_DEPTH_COMPONENT, 24),
        (gl::GL_DEPTH_COMPONENT16, 16),
        (gl::GL_DEPTH_COMPONENT24, 24),
        (gl::GL_DEPTH_COMPONENT32, 32),
    ] {
        depth_image(&mut ctx, internal, gl::GL_FLOAT, &[0.5f32, 0.25]);
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_DEPTH_SIZE), bits, "{internal:#x}");
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_LUMINANCE_SIZE), 0);
    }
    unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA8 as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, [0u8; 4].as_ptr().cast()) };
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_DEPTH_SIZE), 0);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_RED_SIZE), 8);
}

/// Uploads a 2×1 `GL_DEPTH_STENCIL` image of `internal` (`type_` data) to texture 1.
fn depth_stencil_image<T>(ctx: &mut Context, internal: u32, type_: u32, data: &[T]) {
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    unsafe { dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, internal as i32, 2, 1, 0, gl::GL_DEPTH_STENCIL, type_, data.as_ptr().cast()) };
}

/// Reads level 0 of texture 1 back as `N` words of `format`/`type_`.
fn read_words<const N: usize>(ctx: &mut Context, format: u32, type_: u32) -> [u32; N] {
    let mut out = [0xdead_beefu32; N];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, format, type_, out.as_mut_ptr().cast()) };
    out
}

#[test]
fn depth_stencil_textures_keep_depth_and_stencil_bits() {
    let (mut ctx, _) = Context::with_recording();
    // 24-bit depth and 8-bit stencil come back bit for bit, in either packed type.
    let raw = [0x4000_00bbu32, 0xabcd_ef42];
    depth_stencil_image(&mut ctx, gl::GL_DEPTH24_STENCIL8, gl::GL_UNSIGNED_INT_24_8, &raw);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(read_words::<2>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8), raw);
    let floats = read_words::<4>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV);
    assert_eq!([floats[1], floats[3]], [0xbb, 0x42]);
    assert_eq!(f32::from_bits(floats[0]), (f64::from(0x40_0000u32) / 16_777_215.0) as f32);
    let depth = read_words::<2>(&mut ctx, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT).map(f32::from_bits);
    assert_eq!(depth, [f32::from_bits(floats[0]), f32::from_bits(floats[2])], "the depth alone");
    assert_eq!((level_param(&mut ctx, gl::GL_TEXTURE_DEPTH_SIZE), level_param(&mut ctx, gl::GL_TEXTURE_STENCIL_SIZE)), (24, 8));
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_INTERNAL_FORMAT), gl::GL_DEPTH24_STENCIL8 as i32);
    let image = ctx.with_bound_texture(Target::D2, |o| o.level(0, 0).map(|l| l.image.clone())).expect("level 0 exists");
    assert_eq!(image.depth_values, depth, "the renderer samples the depth");
    // 32-bit float depth keeps the float; the unused 24 bits are dropped.
    let words = [0.3f32.to_bits(), 0xffff_ff07, 1.0f32.to_bits(), 0x0000_0100];
    depth_stencil_image(&mut ctx, gl::GL_DEPTH32F_STENCIL8, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &words);
    let back = read_words::<4>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV);
    assert_eq!(back, [0.3f32.to_bits(), 0x07, 1.0f32.to_bits(), 0x00]);
    assert_eq!((level_param(&mut ctx, gl::GL_TEXTURE_DEPTH_SIZE), level_param(&mut ctx, gl::GL_TEXTURE_STENCIL_SIZE)), (32, 8));
    // A sub-image replaces depth and stencil of its texels only.
    let one = [0xffff_ff01u32];
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 1, 0, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, one.as_ptr().cast()) };
    let back = read_words::<4>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV);
    assert_eq!(back, [0.3f32.to_bits(), 0x07, 1.0f32.to_bits(), 0x01]);
    // Generated levels average the depth and hold stencil 0, which sub-images replace.
    ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
    depth_stencil_image(&mut ctx, gl::GL_DEPTH24_STENCIL8, gl::GL_UNSIGNED_INT_24_8, &[0x0000_0009u32, 0x4000_000a]);
    let mut level1 = [0u32; 1];
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, level1.as_mut_ptr().cast()) };
    assert_eq!(level1, [0x2000_0000]);
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 1, 0, 0, 1, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, [0xffff_ff33u32].as_ptr().cast()) };
    unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 1, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8, level1.as_mut_ptr().cast()) };
    assert_eq!(level1, [0xffff_ff33]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

#[test]
fn depth_stencil_texture_errors() {
    let (mut ctx, _) = Context::with_recording();
    let raw = [0u32; 2];
    // Depth/stencil pixels go with any depth internal format, not with colour ones.
    depth_stencil_image(&mut ctx, gl::GL_RGBA8, gl::GL_UNSIGNED_INT_24_8, &raw);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    depth_stencil_image(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT, &raw);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    depth_stencil_image(&mut ctx, gl::GL_DEPTH_COMPONENT32F, gl::GL_UNSIGNED_INT_24_8, &[0xffff_ff00u32, 0]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    assert_eq!(read_words::<2>(&mut ctx, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT).map(f32::from_bits), [1.0, 0.0]);
    assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_STENCIL_SIZE), 0);
    // GL_DEPTH_STENCIL is read only from a level that has stencil.
    read_words::<2>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA8 as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, [0u8; 4].as_ptr().cast()) };
    read_words::<1>(&mut ctx, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    depth_stencil_image(&mut ctx, gl::GL_DEPTH24_STENCIL8, gl::GL_UNSIGNED_INT_24_8, &raw);
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 1, 1, gl::GL_RGBA, gl::GL_FLOAT, [0.0f32; 4].as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    read_words::<2>(&mut ctx, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    depth_stencil_image(&mut ctx, gl::GL_DEPTH24_STENCIL8, gl::GL_INT, &raw);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM, "GL_DEPTH_STENCIL with GL_INT");
    ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
    unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_DEPTH24_STENCIL8 as i32, 1, 1, 0, gl::GL_STENCIL_INDEX, gl::GL_INT, raw.as_ptr().cast()) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "stencil indices alone are no depth data");
    // Depth and depth/stencil images are 1D, 2D or cube map images, never 3D.
    ctx.glBindTexture(gl::GL_TEXTURE_3D, 2);
    for (target, internal, format, type_) in [
        (gl::GL_TEXTURE_3D, gl::GL_DEPTH_COMPONENT16, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT),
        (gl::GL_PROXY_TEXTURE_3D, gl::GL_DEPTH_COMPONENT32F, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT),
        (gl::GL_TEXTURE_3D, gl::GL_DEPTH24_STENCIL8, gl::GL_DEPTH_STENCIL, gl::GL_UNSIGNED_INT_24_8),
        (gl::GL_PROXY_TEXTURE_3D, gl::GL_DEPTH32F_STENCIL8, gl::GL_DEPTH_STENCIL, gl::GL_FLOAT_32_UNSIGNED_INT_24_8_REV),
    ] {
        unsafe { dispatch::glTexImage3D(&mut ctx, target, 0, internal as i32, 2, 2, 2, 0, format, type_, std::ptr::null()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "{internal:#x}");
    }
}
