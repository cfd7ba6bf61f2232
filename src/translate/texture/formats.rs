//! Texture internal formats (OpenGL 1.5 tables 3.15–3.16, ARB_texture_compression,
//! EXT_texture_compression_s3tc, EXT_paletted_texture, EXT_packed_depth_stencil,
//! ARB_depth_buffer_float) and the conversion of pixels to the canonical RGBA8 texels glrt
//! stores (depth also at full precision), and back (table 6.1).
//!
//! Depth/stencil formats (`GL_DEPTH_STENCIL`, `GL_DEPTH24_STENCIL8`, `GL_DEPTH32F_STENCIL8`)
//! have the depth base format for sampling, which sees only their depth
//! (EXT_packed_depth_stencil section 3.8.9-1/2); their stencil indices are kept beside the
//! level for `glGetTexImage` ([`stencil_bits`] tells them apart).

use super::super::gl::{self, GLenum};
use crate::frame::texture::TexelFormat;

/// The base internal format of a texture image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// A colour or depth format.
    Texel(TexelFormat),
    /// Colour indices looked up in a palette (EXT_paletted_texture).
    ColorIndex,
}

/// An S3TC block format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum S3tc {
    /// DXT1 without alpha.
    Dxt1Rgb,
    /// DXT1 with 1-bit alpha.
    Dxt1Rgba,
    /// DXT3 (explicit 4-bit alpha).
    Dxt3,
    /// DXT5 (interpolated alpha).
    Dxt5,
}

impl S3tc {
    /// Bytes of one 4×4 block.
    pub fn block_bytes(self) -> usize {
        match self {
            S3tc::Dxt1Rgb | S3tc::Dxt1Rgba => 8,
            S3tc::Dxt3 | S3tc::Dxt5 => 16,
        }
    }

    /// The format of an S3TC internal format enum.
    pub fn of(internal: GLenum) -> Option<S3tc> {
        Some(match internal {
            gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT => S3tc::Dxt1Rgb,
            gl::GL_COMPRESSED_RGBA_S3TC_DXT1_EXT => S3tc::Dxt1Rgba,
            gl::GL_COMPRESSED_RGBA_S3TC_DXT3_EXT => S3tc::Dxt3,
            gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT => S3tc::Dxt5,
            _ => return None,
        })
    }
}

/// The compressed internal formats glrt accepts (`GL_COMPRESSED_TEXTURE_FORMATS`).
pub const COMPRESSED_FORMATS: [GLenum; 4] = [
    gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT,
    gl::GL_COMPRESSED_RGBA_S3TC_DXT1_EXT,
    gl::GL_COMPRESSED_RGBA_S3TC_DXT3_EXT,
    gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT,
];

/// An accepted internal format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Internal {
    /// What `GL_TEXTURE_INTERNAL_FORMAT` reports: the format given, except that the generic
    /// compressed formats (`GL_COMPRESSED_RGB`...) are stored uncompressed and report their
    /// base format, as ARB_texture_compression allows. S3TC formats are compressed.
    pub reported: GLenum,
    /// Base format.
    pub base: Base,
}

/// The internal format `internal` of `glTexImage`/`glCopyTexImage`, if accepted.
pub fn internal_format(internal: GLenum) -> Option<Internal> {
    use TexelFormat::*;
    let texel = |f| Base::Texel(f);
    let base = match internal {
        1 | gl::GL_LUMINANCE | gl::GL_LUMINANCE4 | gl::GL_LUMINANCE8 | gl::GL_LUMINANCE12 | gl::GL_LUMINANCE16 => texel(Luminance),
        2 | gl::GL_LUMINANCE_ALPHA
        | gl::GL_LUMINANCE4_ALPHA4
        | gl::GL_LUMINANCE6_ALPHA2
        | gl::GL_LUMINANCE8_ALPHA8
        | gl::GL_LUMINANCE12_ALPHA4
        | gl::GL_LUMINANCE12_ALPHA12
        | gl::GL_LUMINANCE16_ALPHA16 => texel(LuminanceAlpha),
        3 | gl::GL_RGB | gl::GL_R3_G3_B2 | gl::GL_RGB4 | gl::GL_RGB5 | gl::GL_RGB8 | gl::GL_RGB10 | gl::GL_RGB12 | gl::GL_RGB16 => texel(Rgb),
        4 | gl::GL_RGBA | gl::GL_RGBA2 | gl::GL_RGBA4 | gl::GL_RGB5_A1 | gl::GL_RGBA8 | gl::GL_RGB10_A2 | gl::GL_RGBA12 | gl::GL_RGBA16 => texel(Rgba),
        gl::GL_ALPHA | gl::GL_ALPHA4 | gl::GL_ALPHA8 | gl::GL_ALPHA12 | gl::GL_ALPHA16 => texel(Alpha),
        gl::GL_INTENSITY | gl::GL_INTENSITY4 | gl::GL_INTENSITY8 | gl::GL_INTENSITY12 | gl::GL_INTENSITY16 => texel(Intensity),
        gl::GL_DEPTH_COMPONENT
        | gl::GL_DEPTH_COMPONENT16
        | gl::GL_DEPTH_COMPONENT24
        | gl::GL_DEPTH_COMPONENT32
        | gl::GL_DEPTH_COMPONENT32F
        | gl::GL_DEPTH_STENCIL
        | gl::GL_DEPTH24_STENCIL8
        | gl::GL_DEPTH32F_STENCIL8 => texel(Depth),
        gl::GL_COLOR_INDEX1_EXT
        | gl::GL_COLOR_INDEX2_EXT
        | gl::GL_COLOR_INDEX4_EXT
        | gl::GL_COLOR_INDEX8_EXT
        | gl::GL_COLOR_INDEX12_EXT
        | gl::GL_COLOR_INDEX16_EXT => Base::ColorIndex,
        gl::GL_COMPRESSED_ALPHA => texel(Alpha),
        gl::GL_COMPRESSED_LUMINANCE => texel(Luminance),
        gl::GL_COMPRESSED_LUMINANCE_ALPHA => texel(LuminanceAlpha),
        gl::GL_COMPRESSED_INTENSITY => texel(Intensity),
        gl::GL_COMPRESSED_RGB | gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT => texel(Rgb),
        gl::GL_COMPRESSED_RGBA
        | gl::GL_COMPRESSED_RGBA_S3TC_DXT1_EXT
        | gl::GL_COMPRESSED_RGBA_S3TC_DXT3_EXT
        | gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT => texel(Rgba),
        _ => return None,
    };
    let generic = matches!(internal, gl::GL_COMPRESSED_ALPHA..=gl::GL_COMPRESSED_RGBA);
    let reported = if generic { base_enum(base) } else { internal };
    Some(Internal { reported, base })
}

/// The unsized enum of a base format.
pub fn base_enum(base: Base) -> GLenum {
    match base {
        Base::ColorIndex => gl::GL_COLOR_INDEX,
        Base::Texel(f) => match f {
            TexelFormat::Alpha => gl::GL_ALPHA,
            TexelFormat::Luminance => gl::GL_LUMINANCE,
            TexelFormat::LuminanceAlpha => gl::GL_LUMINANCE_ALPHA,
            TexelFormat::Intensity => gl::GL_INTENSITY,
            TexelFormat::Rgb => gl::GL_RGB,
            TexelFormat::Rgba => gl::GL_RGBA,
            TexelFormat::Depth => gl::GL_DEPTH_COMPONENT,
        },
    }
}

/// Bits of each stored component, for `glGetTexLevelParameter` (`GL_TEXTURE_RED_SIZE` ...
/// `GL_TEXTURE_INTENSITY_SIZE`, `GL_TEXTURE_DEPTH_SIZE`, `GL_TEXTURE_STENCIL_SIZE`): glrt
/// stores 8 bits for each colour component the base format has, depth with [`depth_bits`]
/// and stencil with [`stencil_bits`] of `internal`.
pub fn component_bits(base: Base, internal: GLenum, pname: GLenum) -> Option<i64> {
    if pname == gl::GL_TEXTURE_STENCIL_SIZE {
        return Some(if base == Base::Texel(TexelFormat::Depth) { i64::from(stencil_bits(internal)) } else { 0 });
    }
    use TexelFormat::*;
    let has = match (pname, base) {
        (_, Base::ColorIndex) => false,
        (gl::GL_TEXTURE_RED_SIZE | gl::GL_TEXTURE_GREEN_SIZE | gl::GL_TEXTURE_BLUE_SIZE, Base::Texel(f)) => matches!(f, Rgb | Rgba),
        (gl::GL_TEXTURE_ALPHA_SIZE, Base::Texel(f)) => matches!(f, Alpha | LuminanceAlpha | Rgba),
        (gl::GL_TEXTURE_LUMINANCE_SIZE, Base::Texel(f)) => matches!(f, Luminance | LuminanceAlpha),
        (gl::GL_TEXTURE_INTENSITY_SIZE, Base::Texel(f)) => f == Intensity,
        (gl::GL_TEXTURE_DEPTH_SIZE, Base::Texel(f)) => f == Depth,
        _ => return None,
    };
    Some(match (has, pname) {
        (false, _) => 0,
        (true, gl::GL_TEXTURE_DEPTH_SIZE) => i64::from(depth_bits(internal)),
        (true, _) => 8,
    })
}

/// Bits of the depth values of a depth internal format: 16 and 32 as named (`f32` for
/// `GL_DEPTH_COMPONENT32F` and `GL_DEPTH32F_STENCIL8`), 24 for `GL_DEPTH_COMPONENT24`,
/// `GL_DEPTH24_STENCIL8` and the unsized `GL_DEPTH_COMPONENT` and `GL_DEPTH_STENCIL`. 32-bit
/// depth is kept as an `f32` (24 bits of mantissa).
pub fn depth_bits(internal: GLenum) -> u32 {
    match internal {
        gl::GL_DEPTH_COMPONENT16 => 16,
        gl::GL_DEPTH_COMPONENT32 | gl::GL_DEPTH_COMPONENT32F | gl::GL_DEPTH32F_STENCIL8 => 32,
        _ => 24,
    }
}

/// Bits of the stencil indices of an internal format: 8 for the depth/stencil formats
/// (EXT_packed_depth_stencil and ARB_depth_buffer_float table 3.16), 0 for any other.
pub fn stencil_bits(internal: GLenum) -> u32 {
    match internal {
        gl::GL_DEPTH_STENCIL | gl::GL_DEPTH24_STENCIL8 | gl::GL_DEPTH32F_STENCIL8 => 8,
        _ => 0,
    }
}

/// A depth value as a depth internal format of `bits` stores it: clamped to [0, 1] and
/// rounded to the nearest multiple of 1 / (2^bits − 1) for 16 and 24 bits (section 2.1.2's
/// fixed-point conversion); 32-bit depth keeps the `f32`.
pub fn stored_depth(d: f32, bits: u32) -> f32 {
    let d = d.clamp(0.0, 1.0);
    if bits >= 32 {
        return d;
    }
    let max = f64::from((1u32 << bits) - 1);
    ((f64::from(d) * max).round() / max) as f32
}

/// Bits of the indices of a paletted internal format (`GL_TEXTURE_INDEX_SIZE_EXT`); 16 for
/// any other.
pub fn index_bits(internal: GLenum) -> u32 {
    match internal {
        gl::GL_COLOR_INDEX1_EXT => 1,
        gl::GL_COLOR_INDEX2_EXT => 2,
        gl::GL_COLOR_INDEX4_EXT => 4,
        gl::GL_COLOR_INDEX8_EXT => 8,
        gl::GL_COLOR_INDEX12_EXT => 12,
        _ => 16,
    }
}

/// An RGBA colour (or a depth value in R) as a base format's texels hold it: table 3.15's
/// component choice, expanded as [`crate::frame::texture`] describes. The border colour is
/// expanded the same way, so that the sampler's border matches the texels (section 3.8.7).
pub fn expand(base: TexelFormat, c: [f32; 4]) -> [f32; 4] {
    let [r, g, b, a] = c;
    match base {
        TexelFormat::Alpha => [0.0, 0.0, 0.0, a],
        TexelFormat::Luminance | TexelFormat::Depth => [r, r, r, 1.0],
        TexelFormat::LuminanceAlpha => [r, r, r, a],
        TexelFormat::Intensity => [r, r, r, r],
        TexelFormat::Rgb => [r, g, b, 1.0],
        TexelFormat::Rgba => [r, g, b, a],
    }
}

/// The canonical texel of an RGBA colour (or a depth value in R) for a base format:
/// [`expand`] at 8 bits.
pub fn texel(base: TexelFormat, c: [f32; 4]) -> [u8; 4] {
    expand(base, c).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The RGBA colour of a canonical texel for `glGetTexImage` (table 6.1): luminance and
/// intensity go to R with G = B = 0.
pub fn texel_to_rgba(base: TexelFormat, t: [u8; 4]) -> [f32; 4] {
    let [r, g, b, a] = t.map(|v| f32::from(v) / 255.0);
    match base {
        TexelFormat::Alpha => [0.0, 0.0, 0.0, a],
        TexelFormat::Luminance | TexelFormat::Intensity | TexelFormat::Depth => [r, 0.0, 0.0, 1.0],
        TexelFormat::LuminanceAlpha => [r, 0.0, 0.0, a],
        TexelFormat::Rgb => [r, g, b, 1.0],
        TexelFormat::Rgba => [r, g, b, a],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn internal_formats_map_to_bases() {
        assert_eq!(internal_format(3).unwrap().base, Base::Texel(TexelFormat::Rgb));
        assert_eq!(internal_format(gl::GL_LUMINANCE8_ALPHA8).unwrap().reported, gl::GL_LUMINANCE8_ALPHA8);
        assert_eq!(internal_format(gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT).unwrap().reported, gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT);
        assert_eq!(internal_format(gl::GL_COMPRESSED_LUMINANCE).unwrap().reported, gl::GL_LUMINANCE);
        assert_eq!(internal_format(gl::GL_COLOR_INDEX8_EXT).unwrap().base, Base::ColorIndex);
        assert!(internal_format(5).is_none());
        assert!(internal_format(gl::GL_BGRA).is_none());
        assert_eq!(texel(TexelFormat::Intensity, [0.5, 0.0, 0.0, 0.0]), [128; 4]);
        assert_eq!(texel_to_rgba(TexelFormat::LuminanceAlpha, [255, 255, 255, 0]), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(component_bits(Base::Texel(TexelFormat::Alpha), gl::GL_ALPHA, gl::GL_TEXTURE_RED_SIZE), Some(0));
        assert_eq!(stored_depth(0.5, 16), (32768.0 / 65535.0) as f32);
        assert_eq!(stored_depth(-1.0, 24), 0.0);
        assert_eq!(stored_depth(0.1, 32), 0.1);
        for (internal, depth, stencil) in [
            (gl::GL_DEPTH_STENCIL, 24, 8),
            (gl::GL_DEPTH24_STENCIL8, 24, 8),
            (gl::GL_DEPTH32F_STENCIL8, 32, 8),
            (gl::GL_DEPTH_COMPONENT32F, 32, 0),
            (gl::GL_DEPTH_COMPONENT16, 16, 0),
        ] {
            let base = internal_format(internal).unwrap().base;
            assert_eq!(base, Base::Texel(TexelFormat::Depth), "{internal:#x}");
            assert_eq!(component_bits(base, internal, gl::GL_TEXTURE_DEPTH_SIZE), Some(depth), "{internal:#x}");
            assert_eq!(component_bits(base, internal, gl::GL_TEXTURE_STENCIL_SIZE), Some(stencil), "{internal:#x}");
            assert_eq!(component_bits(base, internal, gl::GL_TEXTURE_LUMINANCE_SIZE), Some(0), "{internal:#x}");
        }
        assert_eq!(component_bits(Base::Texel(TexelFormat::Rgba), gl::GL_RGBA8, gl::GL_TEXTURE_STENCIL_SIZE), Some(0));
    }
}
