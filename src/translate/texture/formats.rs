//! Texture internal formats (OpenGL 1.5 tables 3.15–3.16, ARB_texture_compression,
//! EXT_texture_compression_s3tc, EXT_paletted_texture, EXT_packed_depth_stencil,
//! ARB_depth_buffer_float, ARB_texture_rg, EXT_texture_snorm, ARB_texture_float,
//! EXT_texture_sRGB, EXT_packed_float, EXT_texture_shared_exponent, EXT_texture_integer (with
//! ARB_texture_rg's integer red and red-green formats); how each stores its
//! components is [`super::storage`]'s) and the conversion of pixels to the canonical RGBA8 texels glrt
//! stores (depth also at full precision), and back (table 6.1).
//!
//! Depth/stencil formats (`GL_DEPTH_STENCIL`, `GL_DEPTH24_STENCIL8`, `GL_DEPTH32F_STENCIL8`)
//! have the depth base format for sampling, which sees only their depth
//! (EXT_packed_depth_stencil section 3.8.9-1/2); their stencil indices are kept beside the
//! level for `glGetTexImage` ([`stencil_bits`] tells them apart).

use super::super::gl::{self, GLenum};
use super::storage::{self, Storage};
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
            gl::GL_COMPRESSED_RGBA_S3TC_DXT1_EXT | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT => S3tc::Dxt1Rgba,
            gl::GL_COMPRESSED_RGBA_S3TC_DXT3_EXT | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT => S3tc::Dxt3,
            gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT => S3tc::Dxt5,
            gl::GL_COMPRESSED_SRGB_S3TC_DXT1_EXT => S3tc::Dxt1Rgb,
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
    /// How the colour components are stored.
    pub storage: Storage,
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
        gl::GL_RED | gl::GL_COMPRESSED_RED | gl::GL_R8 | gl::GL_R16 | gl::GL_R16F | gl::GL_R32F | gl::GL_RED_SNORM | gl::GL_R8_SNORM | gl::GL_R16_SNORM => texel(Red),
        gl::GL_RG | gl::GL_COMPRESSED_RG | gl::GL_RG8 | gl::GL_RG16 | gl::GL_RG16F | gl::GL_RG32F | gl::GL_RG_SNORM | gl::GL_RG8_SNORM | gl::GL_RG16_SNORM => texel(Rg),
        gl::GL_RGB_SNORM | gl::GL_RGB8_SNORM | gl::GL_RGB16_SNORM | gl::GL_RGB16F | gl::GL_RGB32F => texel(Rgb),
        gl::GL_R11F_G11F_B10F | gl::GL_RGB9_E5 => texel(Rgb),
        gl::GL_SRGB | gl::GL_SRGB8 | gl::GL_COMPRESSED_SRGB | gl::GL_COMPRESSED_SRGB_S3TC_DXT1_EXT => texel(Rgb),
        gl::GL_RGBA_SNORM | gl::GL_RGBA8_SNORM | gl::GL_RGBA16_SNORM | gl::GL_RGBA16F | gl::GL_RGBA32F => texel(Rgba),
        gl::GL_SRGB_ALPHA
        | gl::GL_SRGB8_ALPHA8
        | gl::GL_COMPRESSED_SRGB_ALPHA
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT => texel(Rgba),
        gl::GL_ALPHA_SNORM | gl::GL_ALPHA8_SNORM | gl::GL_ALPHA16_SNORM | gl::GL_ALPHA16F_ARB | gl::GL_ALPHA32F_ARB => texel(Alpha),
        gl::GL_LUMINANCE_SNORM
        | gl::GL_LUMINANCE8_SNORM
        | gl::GL_LUMINANCE16_SNORM
        | gl::GL_LUMINANCE16F_ARB
        | gl::GL_LUMINANCE32F_ARB
        | gl::GL_SLUMINANCE
        | gl::GL_SLUMINANCE8
        | gl::GL_COMPRESSED_SLUMINANCE => texel(Luminance),
        gl::GL_LUMINANCE_ALPHA_SNORM
        | gl::GL_LUMINANCE8_ALPHA8_SNORM
        | gl::GL_LUMINANCE16_ALPHA16_SNORM
        | gl::GL_LUMINANCE_ALPHA16F_ARB
        | gl::GL_LUMINANCE_ALPHA32F_ARB
        | gl::GL_SLUMINANCE_ALPHA
        | gl::GL_SLUMINANCE8_ALPHA8
        | gl::GL_COMPRESSED_SLUMINANCE_ALPHA => texel(LuminanceAlpha),
        gl::GL_INTENSITY_SNORM | gl::GL_INTENSITY8_SNORM | gl::GL_INTENSITY16_SNORM | gl::GL_INTENSITY16F_ARB | gl::GL_INTENSITY32F_ARB => texel(Intensity),
        gl::GL_RGBA8I | gl::GL_RGBA16I | gl::GL_RGBA32I | gl::GL_RGBA8UI | gl::GL_RGBA16UI | gl::GL_RGBA32UI => texel(Rgba),
        gl::GL_RGB8I | gl::GL_RGB16I | gl::GL_RGB32I | gl::GL_RGB8UI | gl::GL_RGB16UI | gl::GL_RGB32UI => texel(Rgb),
        gl::GL_RG8I | gl::GL_RG16I | gl::GL_RG32I | gl::GL_RG8UI | gl::GL_RG16UI | gl::GL_RG32UI => texel(Rg),
        gl::GL_R8I | gl::GL_R16I | gl::GL_R32I | gl::GL_R8UI | gl::GL_R16UI | gl::GL_R32UI => texel(Red),
        gl::GL_ALPHA8I_EXT | gl::GL_ALPHA16I_EXT | gl::GL_ALPHA32I_EXT | gl::GL_ALPHA8UI_EXT | gl::GL_ALPHA16UI_EXT | gl::GL_ALPHA32UI_EXT => texel(Alpha),
        gl::GL_INTENSITY8I_EXT
        | gl::GL_INTENSITY16I_EXT
        | gl::GL_INTENSITY32I_EXT
        | gl::GL_INTENSITY8UI_EXT
        | gl::GL_INTENSITY16UI_EXT
        | gl::GL_INTENSITY32UI_EXT => texel(Intensity),
        gl::GL_LUMINANCE8I_EXT
        | gl::GL_LUMINANCE16I_EXT
        | gl::GL_LUMINANCE32I_EXT
        | gl::GL_LUMINANCE8UI_EXT
        | gl::GL_LUMINANCE16UI_EXT
        | gl::GL_LUMINANCE32UI_EXT => texel(Luminance),
        gl::GL_LUMINANCE_ALPHA8I_EXT
        | gl::GL_LUMINANCE_ALPHA16I_EXT
        | gl::GL_LUMINANCE_ALPHA32I_EXT
        | gl::GL_LUMINANCE_ALPHA8UI_EXT
        | gl::GL_LUMINANCE_ALPHA16UI_EXT
        | gl::GL_LUMINANCE_ALPHA32UI_EXT => texel(LuminanceAlpha),
        _ => return None,
    };
    // The generic compressed formats are stored uncompressed and report their uncompressed
    // counterpart (ARB_texture_compression; EXT_texture_sRGB's generic ones the unsized sRGB
    // formats).
    let reported = match internal {
        gl::GL_COMPRESSED_ALPHA..=gl::GL_COMPRESSED_RGBA | gl::GL_COMPRESSED_RED | gl::GL_COMPRESSED_RG => base_enum(base),
        gl::GL_COMPRESSED_SRGB => gl::GL_SRGB,
        gl::GL_COMPRESSED_SRGB_ALPHA => gl::GL_SRGB_ALPHA,
        gl::GL_COMPRESSED_SLUMINANCE => gl::GL_SLUMINANCE,
        gl::GL_COMPRESSED_SLUMINANCE_ALPHA => gl::GL_SLUMINANCE_ALPHA,
        _ => internal,
    };
    let has = match base {
        Base::Texel(f) => components(f),
        Base::ColorIndex => [true; 4],
    };
    Some(Internal { reported, base, storage: storage::of(internal, has) })
}

/// Which of R, G, B and A of a colour the texels of a base format keep (table 3.15;
/// luminance and intensity come from R).
pub fn components(base: TexelFormat) -> [bool; 4] {
    use TexelFormat::*;
    match base {
        Alpha => [false, false, false, true],
        Luminance | Intensity | Red | Depth => [true, false, false, false],
        LuminanceAlpha => [true, false, false, true],
        Rg => [true, true, false, false],
        Rgb => [true, true, true, false],
        Rgba => [true; 4],
    }
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
            TexelFormat::Red => gl::GL_RED,
            TexelFormat::Rg => gl::GL_RG,
        },
    }
}

/// What a size or type query of `glGetTexLevelParameter` asks about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Queried {
    /// A component the base format does not have.
    Absent,
    /// Colour component 0–3 (R, G, B, A of the colour the texels are made from).
    Color(usize),
    /// The depth component.
    Depth,
}

/// The component `pname` (`GL_TEXTURE_RED_SIZE` ... `GL_TEXTURE_DEPTH_SIZE`, or
/// ARB_texture_float's `GL_TEXTURE_RED_TYPE_ARB` ... `GL_TEXTURE_DEPTH_TYPE_ARB`) names in a
/// level of `base`; `None` for another `pname`.
fn queried(base: Base, pname: GLenum) -> Option<Queried> {
    use TexelFormat::*;
    let (index, has): (usize, fn(TexelFormat) -> bool) = match pname {
        gl::GL_TEXTURE_RED_SIZE | gl::GL_TEXTURE_RED_TYPE => (0, |f| matches!(f, Red | Rg | Rgb | Rgba)),
        gl::GL_TEXTURE_GREEN_SIZE | gl::GL_TEXTURE_GREEN_TYPE => (1, |f| matches!(f, Rg | Rgb | Rgba)),
        gl::GL_TEXTURE_BLUE_SIZE | gl::GL_TEXTURE_BLUE_TYPE => (2, |f| matches!(f, Rgb | Rgba)),
        gl::GL_TEXTURE_ALPHA_SIZE | gl::GL_TEXTURE_ALPHA_TYPE => (3, |f| matches!(f, Alpha | LuminanceAlpha | Rgba)),
        gl::GL_TEXTURE_LUMINANCE_SIZE | gl::GL_TEXTURE_LUMINANCE_TYPE => (0, |f| matches!(f, Luminance | LuminanceAlpha)),
        gl::GL_TEXTURE_INTENSITY_SIZE | gl::GL_TEXTURE_INTENSITY_TYPE => (0, |f| f == Intensity),
        gl::GL_TEXTURE_DEPTH_SIZE | gl::GL_TEXTURE_DEPTH_TYPE => {
            return Some(if base == Base::Texel(Depth) { Queried::Depth } else { Queried::Absent });
        }
        _ => return None,
    };
    Some(match base {
        Base::Texel(f) if has(f) => Queried::Color(index),
        _ => Queried::Absent,
    })
}

/// The storage of a colour level of `base` and (reported) internal format `internal`.
pub fn level_storage(base: Base, internal: GLenum) -> Storage {
    let has = match base {
        Base::Texel(f) => components(f),
        Base::ColorIndex => [true; 4],
    };
    storage::of(internal, has)
}

/// Bits of each stored component, for `glGetTexLevelParameter` (`GL_TEXTURE_RED_SIZE` ...
/// `GL_TEXTURE_INTENSITY_SIZE`, `GL_TEXTURE_DEPTH_SIZE`, `GL_TEXTURE_STENCIL_SIZE`): colour
/// components as [`super::storage`] keeps them, depth with [`depth_bits`] and stencil with
/// [`stencil_bits`] of `internal`.
pub fn component_bits(base: Base, internal: GLenum, pname: GLenum) -> Option<i64> {
    if pname == gl::GL_TEXTURE_STENCIL_SIZE {
        return Some(if base == Base::Texel(TexelFormat::Depth) { i64::from(stencil_bits(internal)) } else { 0 });
    }
    if pname == gl::GL_TEXTURE_SHARED_SIZE {
        return Some(if internal == gl::GL_RGB9_E5 { 5 } else { 0 });
    }
    if matches!(pname, gl::GL_TEXTURE_RED_TYPE..=gl::GL_TEXTURE_DEPTH_TYPE) {
        return None;
    }
    Some(match queried(base, pname)? {
        Queried::Absent => 0,
        Queried::Depth => i64::from(depth_bits(internal)),
        Queried::Color(i) => i64::from(level_storage(base, internal).bits[i]),
    })
}

/// The data type of a component (ARB_texture_float's `GL_TEXTURE_RED_TYPE_ARB` ...
/// `GL_TEXTURE_DEPTH_TYPE_ARB`): `GL_NONE` for a missing component, else
/// `GL_UNSIGNED_NORMALIZED_ARB`, `GL_SIGNED_NORMALIZED`, `GL_FLOAT` (32-bit float depth), or
/// EXT_texture_integer's `GL_INT` and `GL_UNSIGNED_INT`.
pub fn component_type(base: Base, internal: GLenum, pname: GLenum) -> Option<GLenum> {
    if !matches!(pname, gl::GL_TEXTURE_RED_TYPE..=gl::GL_TEXTURE_DEPTH_TYPE) {
        return None;
    }
    Some(match queried(base, pname)? {
        Queried::Absent => gl::GL_NONE,
        Queried::Depth if matches!(internal, gl::GL_DEPTH_COMPONENT32F | gl::GL_DEPTH32F_STENCIL8) => gl::GL_FLOAT,
        Queried::Depth => gl::GL_UNSIGNED_NORMALIZED,
        Queried::Color(_) => level_storage(base, internal).component_type(),
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
/// Generic over the component type: `f32` colours, and the `i64` components of integer
/// formats (EXT_texture_integer), whose missing components are 0 and 1 as well.
pub fn expand<T: Copy + From<u8>>(base: TexelFormat, c: [T; 4]) -> [T; 4] {
    let [r, g, b, a] = c;
    let (zero, one) = (T::from(0), T::from(1));
    match base {
        TexelFormat::Alpha => [zero, zero, zero, a],
        TexelFormat::Luminance | TexelFormat::Depth => [r, r, r, one],
        TexelFormat::LuminanceAlpha => [r, r, r, a],
        TexelFormat::Intensity => [r, r, r, r],
        TexelFormat::Red => [r, zero, zero, one],
        TexelFormat::Rg => [r, g, zero, one],
        TexelFormat::Rgb => [r, g, b, one],
        TexelFormat::Rgba => [r, g, b, a],
    }
}

/// The canonical texel of an RGBA colour (or a depth value in R) for a base format:
/// [`expand`] at 8 bits.
pub fn texel(base: TexelFormat, c: [f32; 4]) -> [u8; 4] {
    expand(base, c).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The RGBA colour of a stored texel (the 8-bit texel's components over 255, or the `f32`
/// values of a float level) for `glGetTexImage` (table 6.1): luminance and intensity go to R
/// with G = B = 0. Generic as [`expand`] is (the integers of integer levels).
pub fn texel_to_rgba<T: Copy + From<u8>>(base: TexelFormat, t: [T; 4]) -> [T; 4] {
    let [r, g, b, a] = t;
    let (zero, one) = (T::from(0), T::from(1));
    match base {
        TexelFormat::Alpha => [zero, zero, zero, a],
        TexelFormat::Luminance | TexelFormat::Intensity | TexelFormat::Depth | TexelFormat::Red => [r, zero, zero, one],
        TexelFormat::LuminanceAlpha => [r, zero, zero, a],
        TexelFormat::Rg => [r, g, zero, one],
        TexelFormat::Rgb => [r, g, b, one],
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
        assert_eq!(texel_to_rgba(TexelFormat::LuminanceAlpha, [1.0, 1.0, 1.0, 0.0]), [1.0, 0.0, 0.0, 0.0]);
        let rg16f = internal_format(gl::GL_RG16F).unwrap();
        assert_eq!(rg16f.base, Base::Texel(TexelFormat::Rg));
        assert_eq!(component_bits(rg16f.base, gl::GL_RG16F, gl::GL_TEXTURE_GREEN_SIZE), Some(16));
        assert_eq!(component_bits(rg16f.base, gl::GL_RG16F, gl::GL_TEXTURE_BLUE_SIZE), Some(0));
        assert_eq!(component_type(rg16f.base, gl::GL_RG16F, gl::GL_TEXTURE_RED_TYPE), Some(gl::GL_FLOAT));
        assert_eq!(component_type(rg16f.base, gl::GL_RG16F, gl::GL_TEXTURE_ALPHA_TYPE), Some(gl::GL_NONE));
        let l16 = internal_format(gl::GL_LUMINANCE16_ALPHA16).unwrap().base;
        assert_eq!(component_bits(l16, gl::GL_LUMINANCE16_ALPHA16, gl::GL_TEXTURE_LUMINANCE_SIZE), Some(16));
        assert_eq!(component_type(l16, gl::GL_LUMINANCE16_ALPHA16, gl::GL_TEXTURE_LUMINANCE_TYPE), Some(gl::GL_UNSIGNED_NORMALIZED));
        assert_eq!(component_type(internal_format(gl::GL_R8_SNORM).unwrap().base, gl::GL_R8_SNORM, gl::GL_TEXTURE_RED_TYPE), Some(gl::GL_SIGNED_NORMALIZED));
        assert_eq!(internal_format(gl::GL_COMPRESSED_SLUMINANCE).unwrap().reported, gl::GL_SLUMINANCE);
        assert_eq!(internal_format(gl::GL_COMPRESSED_RG).unwrap().reported, gl::GL_RG);
        assert_eq!(component_bits(Base::Texel(TexelFormat::Rgb), gl::GL_RGB9_E5, gl::GL_TEXTURE_SHARED_SIZE), Some(5));
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

    #[test]
    fn integer_formats_report_sizes_and_types() {
        for (internal, base, pname, bits, ty) in [
            (gl::GL_RGBA32UI_EXT, TexelFormat::Rgba, gl::GL_TEXTURE_ALPHA_SIZE, 32, gl::GL_UNSIGNED_INT),
            (gl::GL_RGB16I_EXT, TexelFormat::Rgb, gl::GL_TEXTURE_BLUE_SIZE, 16, gl::GL_INT),
            (gl::GL_ALPHA8I_EXT, TexelFormat::Alpha, gl::GL_TEXTURE_ALPHA_SIZE, 8, gl::GL_INT),
            (gl::GL_INTENSITY16UI_EXT, TexelFormat::Intensity, gl::GL_TEXTURE_INTENSITY_SIZE, 16, gl::GL_UNSIGNED_INT),
            (gl::GL_LUMINANCE32I_EXT, TexelFormat::Luminance, gl::GL_TEXTURE_LUMINANCE_SIZE, 32, gl::GL_INT),
            (gl::GL_LUMINANCE_ALPHA8UI_EXT, TexelFormat::LuminanceAlpha, gl::GL_TEXTURE_ALPHA_SIZE, 8, gl::GL_UNSIGNED_INT),
            (gl::GL_RG32I, TexelFormat::Rg, gl::GL_TEXTURE_GREEN_SIZE, 32, gl::GL_INT),
            (gl::GL_R8UI, TexelFormat::Red, gl::GL_TEXTURE_RED_SIZE, 8, gl::GL_UNSIGNED_INT),
        ] {
            let i = internal_format(internal).unwrap();
            assert_eq!((i.base, i.reported), (Base::Texel(base), internal), "{internal:#x}");
            assert!(i.storage.is_integer(), "{internal:#x}");
            assert_eq!(component_bits(i.base, internal, pname), Some(bits), "{internal:#x}");
            let type_pname = pname - gl::GL_TEXTURE_RED_SIZE + gl::GL_TEXTURE_RED_TYPE;
            assert_eq!(component_type(i.base, internal, type_pname), Some(ty), "{internal:#x}");
            assert_eq!(component_type(i.base, internal, gl::GL_TEXTURE_DEPTH_TYPE), Some(gl::GL_NONE));
        }
        assert_eq!(component_bits(Base::Texel(TexelFormat::Alpha), gl::GL_ALPHA16UI_EXT, gl::GL_TEXTURE_RED_SIZE), Some(0));
        assert_eq!(expand(TexelFormat::LuminanceAlpha, [-7i64, 0, 0, 9]), [-7, -7, -7, 9]);
        assert_eq!(texel_to_rgba(TexelFormat::Rgb, [1i64 << 32, 2, 3, 0]), [1 << 32, 2, 3, 1]);
    }
}
