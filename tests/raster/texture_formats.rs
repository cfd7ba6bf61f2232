//! piglit's `teximage-colors` done through `translate::Context` on the Vulkan raster renderer
//! (Mesa lavapipe): for every internal format of its list, (1) random texels uploaded with the
//! format's own format and type come back byte for byte from `glGetTexImage`, and (2) texels
//! uploaded with every client format and type give the colours the test expects: unsigned
//! formats drawn with `GL_REPLACE` into an RGBA8 renderbuffer and read back as floats, signed
//! formats (whose drawing needs piglit's shader) read back as floats with `glGetTexImage`.
//! Tolerances are piglit's.

use crate::lavapipe;

use glrt::translate::{Context, dispatch, gl};
use gl::GLenum;

/// Texture width and height (piglit's `texture_size`).
const SIZE: usize = 31;
/// Tiles a row of the renderbuffer the drawn checks go to.
const TILES_X: usize = 16;
/// Tile rows.
const TILES_Y: usize = 7;

/// The internal formats of `teximage-colors` with their format and type (`GL_NONE`: no exact
/// check).
const FORMATS: [(GLenum, GLenum, GLenum); 60] = [
    (gl::GL_RED, gl::GL_RED, gl::GL_NONE),
    (gl::GL_R8, gl::GL_RED, gl::GL_UNSIGNED_BYTE),
    (gl::GL_R8_SNORM, gl::GL_RED, gl::GL_BYTE),
    (gl::GL_R16, gl::GL_RED, gl::GL_UNSIGNED_SHORT),
    (gl::GL_R16_SNORM, gl::GL_RED, gl::GL_SHORT),
    (gl::GL_R16F, gl::GL_RED, gl::GL_NONE),
    (gl::GL_R32F, gl::GL_RED, gl::GL_FLOAT),
    (gl::GL_RG, gl::GL_RG, gl::GL_NONE),
    (gl::GL_RG8, gl::GL_RG, gl::GL_UNSIGNED_BYTE),
    (gl::GL_RG8_SNORM, gl::GL_RG, gl::GL_BYTE),
    (gl::GL_RG16, gl::GL_RG, gl::GL_UNSIGNED_SHORT),
    (gl::GL_RG16_SNORM, gl::GL_RG, gl::GL_SHORT),
    (gl::GL_RG16F, gl::GL_RG, gl::GL_NONE),
    (gl::GL_RG32F, gl::GL_RG, gl::GL_FLOAT),
    (gl::GL_RGB, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_R3_G3_B2, gl::GL_RGB, gl::GL_UNSIGNED_BYTE_3_3_2),
    (gl::GL_RGB4, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB5, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB8, gl::GL_RGB, gl::GL_UNSIGNED_BYTE),
    (gl::GL_RGB8_SNORM, gl::GL_RGB, gl::GL_BYTE),
    (gl::GL_SRGB8, gl::GL_RGB, gl::GL_UNSIGNED_BYTE),
    (gl::GL_RGB10, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_R11F_G11F_B10F, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB12, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB9_E5, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB16, gl::GL_RGB, gl::GL_UNSIGNED_SHORT),
    (gl::GL_RGB16F, gl::GL_RGB, gl::GL_NONE),
    (gl::GL_RGB16_SNORM, gl::GL_RGB, gl::GL_SHORT),
    (gl::GL_RGB32F, gl::GL_RGB, gl::GL_FLOAT),
    (gl::GL_RGBA, gl::GL_RGBA, gl::GL_NONE),
    (gl::GL_RGBA2, gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_4_4_4_4),
    (gl::GL_RGBA4, gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_4_4_4_4),
    (gl::GL_RGB5_A1, gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_5_5_5_1),
    (gl::GL_RGBA8, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE),
    (gl::GL_RGB10_A2, gl::GL_RGBA, gl::GL_UNSIGNED_INT_10_10_10_2),
    (gl::GL_RGBA8_SNORM, gl::GL_RGBA, gl::GL_BYTE),
    (gl::GL_SRGB8_ALPHA8, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE),
    (gl::GL_RGBA12, gl::GL_RGBA, gl::GL_NONE),
    (gl::GL_RGBA16, gl::GL_RGBA, gl::GL_UNSIGNED_SHORT),
    (gl::GL_RGBA16_SNORM, gl::GL_RGBA, gl::GL_SHORT),
    (gl::GL_RGBA32F, gl::GL_RGBA, gl::GL_FLOAT),
    (gl::GL_ALPHA, gl::GL_ALPHA, gl::GL_NONE),
    (gl::GL_ALPHA4, gl::GL_ALPHA, gl::GL_NONE),
    (gl::GL_ALPHA8, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE),
    (gl::GL_ALPHA12, gl::GL_ALPHA, gl::GL_NONE),
    (gl::GL_ALPHA16, gl::GL_ALPHA, gl::GL_UNSIGNED_SHORT),
    (gl::GL_LUMINANCE, gl::GL_LUMINANCE, gl::GL_NONE),
    (gl::GL_LUMINANCE4, gl::GL_LUMINANCE, gl::GL_NONE),
    (gl::GL_LUMINANCE8, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE),
    (gl::GL_SLUMINANCE8, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE),
    (gl::GL_LUMINANCE12, gl::GL_LUMINANCE, gl::GL_NONE),
    (gl::GL_LUMINANCE16, gl::GL_LUMINANCE, gl::GL_UNSIGNED_SHORT),
    (gl::GL_LUMINANCE_ALPHA, gl::GL_LUMINANCE_ALPHA, gl::GL_NONE),
    (gl::GL_LUMINANCE4_ALPHA4, gl::GL_LUMINANCE_ALPHA, gl::GL_NONE),
    (gl::GL_LUMINANCE6_ALPHA2, gl::GL_LUMINANCE_ALPHA, gl::GL_NONE),
    (gl::GL_LUMINANCE8_ALPHA8, gl::GL_LUMINANCE_ALPHA, gl::GL_UNSIGNED_BYTE),
    (gl::GL_SLUMINANCE8_ALPHA8, gl::GL_LUMINANCE_ALPHA, gl::GL_UNSIGNED_BYTE),
    (gl::GL_LUMINANCE12_ALPHA4, gl::GL_LUMINANCE_ALPHA, gl::GL_NONE),
    (gl::GL_LUMINANCE12_ALPHA12, gl::GL_LUMINANCE_ALPHA, gl::GL_NONE),
    (gl::GL_LUMINANCE16_ALPHA16, gl::GL_LUMINANCE_ALPHA, gl::GL_UNSIGNED_SHORT),
];

/// Client formats of the drawn checks.
const CLIENT_FORMATS: [GLenum; 12] = [
    gl::GL_RED,
    gl::GL_GREEN,
    gl::GL_BLUE,
    gl::GL_ALPHA,
    gl::GL_RG,
    gl::GL_RGB,
    gl::GL_BGR,
    gl::GL_RGBA,
    gl::GL_BGRA,
    gl::GL_ABGR_EXT,
    gl::GL_LUMINANCE,
    gl::GL_LUMINANCE_ALPHA,
];

/// Client types of the drawn checks.
const CLIENT_TYPES: [GLenum; 19] = [
    gl::GL_UNSIGNED_BYTE_3_3_2,
    gl::GL_UNSIGNED_BYTE_2_3_3_REV,
    gl::GL_UNSIGNED_SHORT_5_6_5,
    gl::GL_UNSIGNED_SHORT_5_6_5_REV,
    gl::GL_UNSIGNED_SHORT_4_4_4_4,
    gl::GL_UNSIGNED_SHORT_4_4_4_4_REV,
    gl::GL_UNSIGNED_SHORT_5_5_5_1,
    gl::GL_UNSIGNED_SHORT_1_5_5_5_REV,
    gl::GL_UNSIGNED_INT_10_10_10_2,
    gl::GL_UNSIGNED_INT_2_10_10_10_REV,
    gl::GL_UNSIGNED_INT_8_8_8_8,
    gl::GL_UNSIGNED_INT_8_8_8_8_REV,
    gl::GL_BYTE,
    gl::GL_UNSIGNED_BYTE,
    gl::GL_SHORT,
    gl::GL_UNSIGNED_SHORT,
    gl::GL_FLOAT,
    gl::GL_INT,
    gl::GL_UNSIGNED_INT,
];

/// Packed types: (bytes, fields as (shift, bits) in component order).
fn packed(ty: GLenum) -> Option<(usize, &'static [(u32, u32)])> {
    Some(match ty {
        gl::GL_UNSIGNED_BYTE_3_3_2 => (1, &[(5, 3), (2, 3), (0, 2)]),
        gl::GL_UNSIGNED_BYTE_2_3_3_REV => (1, &[(0, 3), (3, 3), (6, 2)]),
        gl::GL_UNSIGNED_SHORT_5_6_5 => (2, &[(11, 5), (5, 6), (0, 5)]),
        gl::GL_UNSIGNED_SHORT_5_6_5_REV => (2, &[(0, 5), (5, 6), (11, 5)]),
        gl::GL_UNSIGNED_SHORT_4_4_4_4 => (2, &[(12, 4), (8, 4), (4, 4), (0, 4)]),
        gl::GL_UNSIGNED_SHORT_4_4_4_4_REV => (2, &[(0, 4), (4, 4), (8, 4), (12, 4)]),
        gl::GL_UNSIGNED_SHORT_5_5_5_1 => (2, &[(11, 5), (6, 5), (1, 5), (0, 1)]),
        gl::GL_UNSIGNED_SHORT_1_5_5_5_REV => (2, &[(0, 5), (5, 5), (10, 5), (15, 1)]),
        gl::GL_UNSIGNED_INT_10_10_10_2 => (4, &[(22, 10), (12, 10), (2, 10), (0, 2)]),
        gl::GL_UNSIGNED_INT_2_10_10_10_REV => (4, &[(0, 10), (10, 10), (20, 10), (30, 2)]),
        gl::GL_UNSIGNED_INT_8_8_8_8 => (4, &[(24, 8), (16, 8), (8, 8), (0, 8)]),
        gl::GL_UNSIGNED_INT_8_8_8_8_REV => (4, &[(0, 8), (8, 8), (16, 8), (24, 8)]),
        _ => return None,
    })
}

/// piglit's `valid_combination`.
fn valid(format: GLenum, ty: GLenum) -> bool {
    match packed(ty) {
        Some((_, f)) if f.len() == 3 => format == gl::GL_RGB,
        Some(_) => format == gl::GL_RGBA || format == gl::GL_BGRA,
        None => true,
    }
}

fn channels(format: GLenum) -> usize {
    match format {
        gl::GL_RG | gl::GL_LUMINANCE_ALPHA => 2,
        gl::GL_RGB | gl::GL_BGR => 3,
        gl::GL_RGBA | gl::GL_BGRA | gl::GL_ABGR_EXT => 4,
        _ => 1,
    }
}

fn bytes_per_pixel(format: GLenum, ty: GLenum) -> usize {
    packed(ty).map_or_else(
        || {
            channels(format)
                * match ty {
                    gl::GL_BYTE | gl::GL_UNSIGNED_BYTE => 1,
                    gl::GL_SHORT | gl::GL_UNSIGNED_SHORT => 2,
                    _ => 4,
                }
        },
        |(size, _)| size,
    )
}

fn un(bits: u32, v: u64) -> f32 {
    (v as f64 / ((1u64 << bits) - 1) as f64) as f32
}

fn sn(bits: u32, v: i64) -> f32 {
    let max = (1i64 << (bits - 1)) - 1;
    (v.max(-max) as f64 / max as f64) as f32
}

/// piglit's `to_float`: the components of one client pixel.
fn to_float(data: &[u8], n: usize, ty: GLenum) -> Vec<f32> {
    let word = |size: usize| data[..size].iter().rev().fold(0u64, |a, &b| a << 8 | u64::from(b));
    if let Some((size, fields)) = packed(ty) {
        let raw = word(size);
        return fields.iter().map(|&(shift, bits)| un(bits, (raw >> shift) & ((1 << bits) - 1))).collect();
    }
    (0..n)
        .map(|i| {
            let at = &data[i * bytes_per_pixel(gl::GL_RED, ty)..];
            match ty {
                gl::GL_BYTE => sn(8, i64::from(at[0] as i8)),
                gl::GL_UNSIGNED_BYTE => un(8, u64::from(at[0])),
                gl::GL_SHORT => sn(16, i64::from(i16::from_ne_bytes([at[0], at[1]]))),
                gl::GL_UNSIGNED_SHORT => un(16, u64::from(u16::from_ne_bytes([at[0], at[1]]))),
                gl::GL_INT => sn(32, i64::from(i32::from_ne_bytes([at[0], at[1], at[2], at[3]]))),
                gl::GL_UNSIGNED_INT => un(32, u64::from(u32::from_ne_bytes([at[0], at[1], at[2], at[3]]))),
                _ => f32::from_ne_bytes([at[0], at[1], at[2], at[3]]),
            }
        })
        .collect()
}

fn is_signed(internal: GLenum) -> bool {
    matches!(
        internal,
        gl::GL_R8_SNORM
            | gl::GL_R16_SNORM
            | gl::GL_R32F
            | gl::GL_RG8_SNORM
            | gl::GL_RG16_SNORM
            | gl::GL_RG32F
            | gl::GL_RGB8_SNORM
            | gl::GL_RGB16_SNORM
            | gl::GL_RGB32F
            | gl::GL_RGBA8_SNORM
            | gl::GL_RGBA16_SNORM
            | gl::GL_RGBA32F
    )
}

fn is_srgb(internal: GLenum) -> bool {
    matches!(internal, gl::GL_SRGB8 | gl::GL_SRGB8_ALPHA8 | gl::GL_SLUMINANCE8 | gl::GL_SLUMINANCE8_ALPHA8)
}

fn srgb_to_linear(s: f32) -> f32 {
    if s > 0.0405 { ((s + 0.055) / 1.055).powf(2.4) } else { s / 12.92 }
}

/// piglit's `to_expected`: the colour a texel of `internal` (stored as `base_format`) sampled
/// from one client pixel gives.
fn to_expected(internal: GLenum, base_format: GLenum, format: GLenum, ty: GLenum, raw: &[u8]) -> [f32; 4] {
    let up = to_float(raw, channels(format), ty);
    let mut e = [0.0, 0.0, 0.0, 1.0];
    match format {
        gl::GL_RED => e[0] = up[0],
        gl::GL_GREEN => e[1] = up[0],
        gl::GL_BLUE => e[2] = up[0],
        gl::GL_ALPHA => e[3] = up[0],
        gl::GL_RG => e[..2].copy_from_slice(&up[..2]),
        gl::GL_RGB => e[..3].copy_from_slice(&up[..3]),
        gl::GL_RGBA => e.copy_from_slice(&up[..4]),
        gl::GL_BGR | gl::GL_BGRA => {
            e[..3].copy_from_slice(&[up[2], up[1], up[0]]);
            if format == gl::GL_BGRA {
                e[3] = up[3];
            }
        }
        gl::GL_ABGR_EXT => e = [up[3], up[2], up[1], up[0]],
        gl::GL_LUMINANCE => e[..3].copy_from_slice(&[up[0]; 3]),
        _ => e = [up[0], up[0], up[0], up[1]],
    }
    match base_format {
        gl::GL_RED => e = [e[0], 0.0, 0.0, 1.0],
        gl::GL_RG => e = [e[0], e[1], 0.0, 1.0],
        gl::GL_RGB => e[3] = 1.0,
        gl::GL_ALPHA => e = [0.0, 0.0, 0.0, e[3]],
        gl::GL_LUMINANCE => e = [e[0], e[0], e[0], 1.0],
        gl::GL_LUMINANCE_ALPHA => e = [e[0], e[0], e[0], e[3]],
        _ => {}
    }
    if !is_signed(internal) {
        e = e.map(|v| v.max(0.0));
    }
    if is_srgb(internal) {
        for v in &mut e[..3] {
            *v = srgb_to_linear(*v);
        }
    }
    e
}

/// piglit's tolerances for an internal format and its own type.
fn tolerance(internal: GLenum, own_type: GLenum) -> [f32; 4] {
    let mut t = if is_srgb(internal) { [0.02; 4] } else { [0.01; 4] };
    if internal == gl::GL_R11F_G11F_B10F {
        t[..3].copy_from_slice(&[0.3; 3]);
    }
    match own_type {
        gl::GL_UNSIGNED_BYTE_3_3_2 | gl::GL_UNSIGNED_BYTE_2_3_3_REV => t[..3].copy_from_slice(&[0.3; 3]),
        gl::GL_UNSIGNED_SHORT_5_5_5_1 | gl::GL_UNSIGNED_SHORT_1_5_5_5_REV => t = [0.05, 0.05, 0.05, 0.6],
        gl::GL_UNSIGNED_SHORT_5_6_5 | gl::GL_UNSIGNED_SHORT_5_6_5_REV => t[..3].copy_from_slice(&[0.05; 3]),
        gl::GL_UNSIGNED_SHORT_4_4_4_4 | gl::GL_UNSIGNED_SHORT_4_4_4_4_REV => t = [0.1; 4],
        gl::GL_UNSIGNED_INT_10_10_10_2 | gl::GL_UNSIGNED_INT_2_10_10_10_REV => t[3] = 0.3,
        _ => {}
    }
    match internal {
        gl::GL_RGB4 | gl::GL_LUMINANCE4_ALPHA4 => t = [0.1; 4],
        gl::GL_RGB5 => t[..3].copy_from_slice(&[0.05; 3]),
        _ => {}
    }
    t
}

/// Random bytes (xorshift), as piglit fills `rand_data`.
fn random_bytes(len: usize) -> Vec<u8> {
    let mut s = 0x2545_f491_4f6c_dd1du64;
    (0..len)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 24) as u8
        })
        .collect()
}

/// The client data of an upload of `channels` × [`SIZE`]² values of `ty`: the random bytes,
/// or for `GL_FLOAT` the random 32-bit integers as normalized floats (piglit's sanitizing).
fn upload_data(random: &[u8], n: usize, ty: GLenum) -> Vec<u8> {
    if ty != gl::GL_FLOAT {
        return random.to_vec();
    }
    random.chunks_exact(4).take(SIZE * SIZE * n).flat_map(|c| sn(32, i64::from(i32::from_ne_bytes([c[0], c[1], c[2], c[3]]))).to_ne_bytes()).collect()
}

/// A new texture bound to `GL_TEXTURE_2D` with nearest filters holding `data`.
fn texture(ctx: &mut Context, internal: GLenum, format: GLenum, ty: GLenum, data: &[u8]) -> u32 {
    let mut tex = 0;
    unsafe {
        dispatch::glGenTextures(ctx, 1, &mut tex);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, tex);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glPixelStorei(ctx, gl::GL_UNPACK_ALIGNMENT, 1);
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, internal as i32, SIZE as i32, SIZE as i32, 0, format, ty, data.as_ptr().cast());
    }
    tex
}

/// piglit's `test_exact`: `None` when it passes, else what differed.
fn exact(ctx: &mut Context, (internal, format, ty): (GLenum, GLenum, GLenum), random: &[u8]) -> Option<String> {
    let n = channels(format);
    let data = upload_data(random, n, ty);
    let tex = texture(ctx, internal, format, ty, &data);
    let bpp = bytes_per_pixel(format, ty);
    let mut out = vec![0u8; SIZE * SIZE * bpp];
    unsafe {
        dispatch::glPixelStorei(ctx, gl::GL_PACK_ALIGNMENT, 1);
        dispatch::glGetTexImage(ctx, gl::GL_TEXTURE_2D, 0, format, ty, out.as_mut_ptr().cast());
        dispatch::glDeleteTextures(ctx, 1, &tex);
    }
    let error = unsafe { dispatch::glGetError(ctx) };
    let same = |i: usize| match ty {
        gl::GL_BYTE => data[i] == out[i] || (data[i] as i8 == -128 && out[i] as i8 == -127),
        gl::GL_SHORT if i.is_multiple_of(2) => {
            let (d, o) = (i16::from_ne_bytes([data[i], data[i + 1]]), i16::from_ne_bytes([out[i], out[i + 1]]));
            d == o || (d == -32768 && o == -32767)
        }
        gl::GL_SHORT => true,
        _ => data[i] == out[i],
    };
    let wrong = (0..out.len()).filter(|&i| !same(i)).count();
    (error != gl::GL_NO_ERROR || wrong > 0).then(|| format!("exact: error {error:#x}, {wrong} bytes differ"))
}

/// piglit's `run_test` for every client format and type: unsigned formats drawn into tiles of
/// the bound RGBA8 framebuffer and read back together, signed ones read with
/// `glGetTexImage`. `None` when every value is within tolerance.
fn drawn(ctx: &mut Context, (internal, base_format, own_type): (GLenum, GLenum, GLenum), random: &[u8]) -> Option<String> {
    let tol = tolerance(internal, own_type);
    let combos: Vec<(GLenum, GLenum)> = CLIENT_FORMATS.iter().flat_map(|&f| CLIENT_TYPES.iter().map(move |&t| (f, t))).filter(|&(f, t)| valid(f, t)).collect();
    assert!(combos.len() <= TILES_X * TILES_Y);
    let mut failures = Vec::new();
    let mut expected_tiles = Vec::new();
    for (i, &(format, ty)) in combos.iter().enumerate() {
        let n = channels(format);
        let data = upload_data(random, n, ty);
        let bpp = bytes_per_pixel(format, ty);
        let expected: Vec<[f32; 4]> = (0..SIZE * SIZE).map(|p| to_expected(internal, base_format, format, ty, &data[p * bpp..])).collect();
        let tex = texture(ctx, internal, format, ty, &data);
        let error = unsafe { dispatch::glGetError(ctx) };
        if error != gl::GL_NO_ERROR {
            failures.push(format!("{format:#x}/{ty:#x}: upload error {error:#x}"));
        }
        if is_signed(internal) {
            // The texels as floats, in the format's own components.
            let k = channels(base_format);
            let mut got = vec![0f32; SIZE * SIZE * k];
            unsafe {
                dispatch::glPixelStorei(ctx, gl::GL_PACK_ALIGNMENT, 1);
                dispatch::glGetTexImage(ctx, gl::GL_TEXTURE_2D, 0, base_format, gl::GL_FLOAT, got.as_mut_ptr().cast());
            }
            let bad = (0..SIZE * SIZE).filter(|&p| (0..k).any(|c| (got[p * k + c] - expected[p][c]).abs() > tol[c])).count();
            if bad > 0 {
                failures.push(format!("{format:#x}/{ty:#x}: {bad} texels off"));
            }
        } else {
            let (x, y) = ((i % TILES_X * SIZE) as f32, (i / TILES_X * SIZE) as f32);
            let s = SIZE as f32;
            unsafe {
                dispatch::glBegin(ctx, gl::GL_QUADS);
                for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                    dispatch::glTexCoord2f(ctx, u, v);
                    dispatch::glVertex2f(ctx, x + u * s, y + v * s);
                }
                dispatch::glEnd(ctx);
            }
            expected_tiles.push((i, format, ty, expected));
        }
        unsafe { dispatch::glDeleteTextures(ctx, 1, &tex) };
    }
    if !expected_tiles.is_empty() {
        let (w, h) = (TILES_X * SIZE, TILES_Y * SIZE);
        let mut got = vec![0f32; w * h * 4];
        unsafe { dispatch::glReadPixels(ctx, 0, 0, w as i32, h as i32, gl::GL_RGBA, gl::GL_FLOAT, got.as_mut_ptr().cast()) };
        for (i, format, ty, expected) in expected_tiles {
            let (x0, y0) = (i % TILES_X * SIZE, i / TILES_X * SIZE);
            let bad = (0..SIZE * SIZE)
                .filter(|&p| {
                    let at = ((y0 + p / SIZE) * w + x0 + p % SIZE) * 4;
                    (0..4).any(|c| (got[at + c] - expected[p][c]).abs() > tol[c])
                })
                .count();
            if bad > 0 {
                failures.push(format!("{format:#x}/{ty:#x}: {bad} pixels off"));
            }
        }
    }
    (!failures.is_empty()).then(|| failures.join(", "))
}

/// A context drawing textured quads with `GL_REPLACE` into an RGBA8 renderbuffer that holds
/// every tile, with an orthographic projection in pixels.
fn drawing_context() -> Context {
    let mut ctx = lavapipe::context(32);
    let (w, h) = ((TILES_X * SIZE) as i32, (TILES_Y * SIZE) as i32);
    let (mut rb, mut fbo) = (0, 0);
    unsafe {
        dispatch::glGenRenderbuffersEXT(&mut ctx, 1, &mut rb);
        dispatch::glBindRenderbufferEXT(&mut ctx, gl::GL_RENDERBUFFER_EXT, rb);
        dispatch::glRenderbufferStorageEXT(&mut ctx, gl::GL_RENDERBUFFER_EXT, gl::GL_RGBA, w, h);
        dispatch::glGenFramebuffersEXT(&mut ctx, 1, &mut fbo);
        dispatch::glBindFramebufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, fbo);
        dispatch::glFramebufferRenderbufferEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_RENDERBUFFER_EXT, rb);
        dispatch::glViewport(&mut ctx, 0, 0, w, h);
        dispatch::glMatrixMode(&mut ctx, gl::GL_PROJECTION);
        dispatch::glOrtho(&mut ctx, 0.0, f64::from(w), 0.0, f64::from(h), -1.0, 1.0);
        dispatch::glMatrixMode(&mut ctx, gl::GL_MODELVIEW);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glTexEnvi(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_MODE, gl::GL_REPLACE as i32);
        // GL_REPLACE takes the RGB of alpha textures from the fragment: black, as piglit's
        // shader gives.
        dispatch::glColor4f(&mut ctx, 0.0, 0.0, 0.0, 1.0);
        assert_eq!(dispatch::glCheckFramebufferStatusEXT(&mut ctx, gl::GL_FRAMEBUFFER_EXT), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
    }
    ctx
}

#[test]
fn teximage_colors_formats_round_trip_and_draw() {
    let mut ctx = drawing_context();
    let random = random_bytes(SIZE * SIZE * 128);
    let mut failures = Vec::new();
    for f in FORMATS {
        let name = gl::enum_name(f.0).unwrap_or("?");
        if f.2 != gl::GL_NONE
            && let Some(e) = exact(&mut ctx, f, &random)
        {
            failures.push(format!("{name}: {e}"));
        }
        if let Some(e) = drawn(&mut ctx, f, &random) {
            failures.push(format!("{name}: {e}"));
        }
    }
    assert!(failures.is_empty(), "{} of {} formats fail:\n{}", failures.len(), FORMATS.len(), failures.join("\n"));
}
