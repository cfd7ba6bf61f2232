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
