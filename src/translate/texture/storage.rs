//! How an internal format stores colour components: the encoding and bits of each component
//! (what `GL_TEXTURE_RED_SIZE`... and ARB_texture_float's `GL_TEXTURE_RED_TYPE_ARB`... report),
//! the [`Precision`] of the level that holds them, and the rounding of an unpacked colour to
//! what the format keeps, so that `glGetTexImage` with the format's own type gives back the
//! uploaded bytes.
//!
//! Formats of at most 8 bits a component are kept at 8 bits (RGBA8 texels; `GL_RGBA4` reports
//! 8 bits, as the specification allows an implementation to store more). Unsigned-normalized
//! formats of more bits (`GL_RGB10`, `GL_RGBA12`, `GL_R16`...), signed-normalized
//! (EXT_texture_snorm), floating-point (ARB_texture_float, ARB_texture_rg), packed-float
//! (EXT_packed_float) and shared-exponent (EXT_texture_shared_exponent) formats keep `f32`
//! values rounded to the format's bits; sRGB formats (EXT_texture_sRGB) keep sRGB-encoded
//! bytes. Integer formats (EXT_texture_integer, and ARB_texture_rg's `GL_R8I`...) keep their
//! components exactly as integers ([`Precision::Integer`]), clamped to the format's range.

use super::super::convert::{norm_i8, norm_i16};
use super::super::gl::{self, GLenum};
use super::super::pixels::small_float;
use crate::frame::texture::Precision;

/// The encoding of the colour components of an internal format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Unsigned normalized, in [0, 1].
    Unorm,
    /// Signed normalized, in [−1, 1] (EXT_texture_snorm).
    Snorm,
    /// Floating point: 16-bit half or 32-bit float (ARB_texture_float).
    Float,
    /// sRGB-encoded unsigned normalized colour, linear alpha (EXT_texture_sRGB).
    Srgb,
    /// Unsigned 11- and 10-bit floats (EXT_packed_float).
    PackedFloat,
    /// 9-bit mantissas with a shared 5-bit exponent (EXT_texture_shared_exponent).
    SharedExponent,
    /// Signed integers (EXT_texture_integer).
    Int,
    /// Unsigned integers (EXT_texture_integer).
    Uint,
}

/// The storage of an internal format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Storage {
    /// Encoding of the components.
    pub encoding: Encoding,
    /// Bits of R, G, B and A of the colour a texel is made from (table 3.15's component
    /// choice: luminance and intensity come from R); 0 for components the base format drops.
    pub bits: [u32; 4],
}

/// The storage of colour internal format `internal` with base-format components `has`
/// (R, G, B, A of the colour it is made from).
pub fn of(internal: GLenum, has: [bool; 4]) -> Storage {
    use Encoding::*;
    let (encoding, color, alpha) = match internal {
        gl::GL_RGB10 => (Unorm, 10, 0),
        gl::GL_RGB10_A2 => (Unorm, 10, 2),
        gl::GL_RGB12 | gl::GL_RGBA12 | gl::GL_ALPHA12 | gl::GL_LUMINANCE12 | gl::GL_LUMINANCE12_ALPHA12 | gl::GL_INTENSITY12 => (Unorm, 12, 12),
        gl::GL_LUMINANCE12_ALPHA4 => (Unorm, 12, 4),
        gl::GL_R16 | gl::GL_RG16 | gl::GL_RGB16 | gl::GL_RGBA16 | gl::GL_ALPHA16 | gl::GL_LUMINANCE16 | gl::GL_LUMINANCE16_ALPHA16 | gl::GL_INTENSITY16 => (Unorm, 16, 16),
        gl::GL_R16_SNORM
        | gl::GL_RG16_SNORM
        | gl::GL_RGB16_SNORM
        | gl::GL_RGBA16_SNORM
        | gl::GL_ALPHA16_SNORM
        | gl::GL_LUMINANCE16_SNORM
        | gl::GL_LUMINANCE16_ALPHA16_SNORM
        | gl::GL_INTENSITY16_SNORM => (Snorm, 16, 16),
        gl::GL_RED_SNORM
        | gl::GL_RG_SNORM
        | gl::GL_RGB_SNORM
        | gl::GL_RGBA_SNORM
        | gl::GL_R8_SNORM
        | gl::GL_RG8_SNORM
        | gl::GL_RGB8_SNORM
        | gl::GL_RGBA8_SNORM
        | gl::GL_ALPHA_SNORM
        | gl::GL_LUMINANCE_SNORM
        | gl::GL_LUMINANCE_ALPHA_SNORM
        | gl::GL_INTENSITY_SNORM
        | gl::GL_ALPHA8_SNORM
        | gl::GL_LUMINANCE8_SNORM
        | gl::GL_LUMINANCE8_ALPHA8_SNORM
        | gl::GL_INTENSITY8_SNORM => (Snorm, 8, 8),
        gl::GL_R16F
        | gl::GL_RG16F
        | gl::GL_RGB16F
        | gl::GL_RGBA16F
        | gl::GL_ALPHA16F_ARB
        | gl::GL_LUMINANCE16F_ARB
        | gl::GL_LUMINANCE_ALPHA16F_ARB
        | gl::GL_INTENSITY16F_ARB => (Float, 16, 16),
        gl::GL_R32F
        | gl::GL_RG32F
        | gl::GL_RGB32F
        | gl::GL_RGBA32F
        | gl::GL_ALPHA32F_ARB
        | gl::GL_LUMINANCE32F_ARB
        | gl::GL_LUMINANCE_ALPHA32F_ARB
        | gl::GL_INTENSITY32F_ARB => (Float, 32, 32),
        gl::GL_SRGB
        | gl::GL_SRGB8
        | gl::GL_SRGB_ALPHA
        | gl::GL_SRGB8_ALPHA8
        | gl::GL_SLUMINANCE
        | gl::GL_SLUMINANCE8
        | gl::GL_SLUMINANCE_ALPHA
        | gl::GL_SLUMINANCE8_ALPHA8
        | gl::GL_COMPRESSED_SRGB
        | gl::GL_COMPRESSED_SRGB_ALPHA
        | gl::GL_COMPRESSED_SLUMINANCE
        | gl::GL_COMPRESSED_SLUMINANCE_ALPHA
        | gl::GL_COMPRESSED_SRGB_S3TC_DXT1_EXT
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT
        | gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT => (Srgb, 8, 8),
        gl::GL_RGBA8I
        | gl::GL_RGB8I
        | gl::GL_RG8I
        | gl::GL_R8I
        | gl::GL_ALPHA8I_EXT
        | gl::GL_INTENSITY8I_EXT
        | gl::GL_LUMINANCE8I_EXT
        | gl::GL_LUMINANCE_ALPHA8I_EXT => (Int, 8, 8),
        gl::GL_RGBA16I
        | gl::GL_RGB16I
        | gl::GL_RG16I
        | gl::GL_R16I
        | gl::GL_ALPHA16I_EXT
        | gl::GL_INTENSITY16I_EXT
        | gl::GL_LUMINANCE16I_EXT
        | gl::GL_LUMINANCE_ALPHA16I_EXT => (Int, 16, 16),
        gl::GL_RGBA32I
        | gl::GL_RGB32I
        | gl::GL_RG32I
        | gl::GL_R32I
        | gl::GL_ALPHA32I_EXT
        | gl::GL_INTENSITY32I_EXT
        | gl::GL_LUMINANCE32I_EXT
        | gl::GL_LUMINANCE_ALPHA32I_EXT => (Int, 32, 32),
        gl::GL_RGBA8UI
        | gl::GL_RGB8UI
        | gl::GL_RG8UI
        | gl::GL_R8UI
        | gl::GL_ALPHA8UI_EXT
        | gl::GL_INTENSITY8UI_EXT
        | gl::GL_LUMINANCE8UI_EXT
        | gl::GL_LUMINANCE_ALPHA8UI_EXT => (Uint, 8, 8),
        gl::GL_RGBA16UI
        | gl::GL_RGB16UI
        | gl::GL_RG16UI
        | gl::GL_R16UI
        | gl::GL_ALPHA16UI_EXT
        | gl::GL_INTENSITY16UI_EXT
        | gl::GL_LUMINANCE16UI_EXT
        | gl::GL_LUMINANCE_ALPHA16UI_EXT => (Uint, 16, 16),
        gl::GL_RGBA32UI
        | gl::GL_RGB32UI
        | gl::GL_RG32UI
        | gl::GL_R32UI
        | gl::GL_ALPHA32UI_EXT
        | gl::GL_INTENSITY32UI_EXT
        | gl::GL_LUMINANCE32UI_EXT
        | gl::GL_LUMINANCE_ALPHA32UI_EXT => (Uint, 32, 32),
        gl::GL_R11F_G11F_B10F => return Storage { encoding: PackedFloat, bits: [11, 11, 10, 0] },
        gl::GL_RGB9_E5 => return Storage { encoding: SharedExponent, bits: [9, 9, 9, 0] },
        _ => (Unorm, 8, 8),
    };
    // Components of fewer than 8 bits (the alpha of GL_RGB10_A2, GL_LUMINANCE12_ALPHA4) are
    // kept at 8: their values are exact in 8 bits (2^n − 1 divides 255 for n = 1, 2, 4).
    let bits = [color, color, color, alpha.max(8)];
    Storage { encoding, bits: std::array::from_fn(|i| if has[i] { bits[i] } else { 0 }) }
}

impl Storage {
    /// How a level of this storage is kept.
    pub fn precision(self) -> Precision {
        match self.encoding {
            Encoding::Srgb => Precision::Srgb8,
            Encoding::Int | Encoding::Uint => Precision::Integer,
            Encoding::Unorm if self.bits.iter().all(|&b| b <= 8) => Precision::Unorm8,
            _ => Precision::Float,
        }
    }

    /// Whether the components may leave [0, 1] (unpacking and packing then skip the clamp
    /// to [0, 1], section 3.7.5 of OpenGL 3.0).
    pub fn unclamped(self) -> bool {
        !matches!(self.encoding, Encoding::Unorm | Encoding::Srgb)
    }

    /// The `GL_TEXTURE_*_TYPE_ARB` of a component with bits (ARB_texture_float).
    pub fn component_type(self) -> GLenum {
        match self.encoding {
            Encoding::Unorm | Encoding::Srgb => gl::GL_UNSIGNED_NORMALIZED,
            Encoding::Snorm => gl::GL_SIGNED_NORMALIZED,
            Encoding::Float | Encoding::PackedFloat | Encoding::SharedExponent => gl::GL_FLOAT,
            Encoding::Int => gl::GL_INT,
            Encoding::Uint => gl::GL_UNSIGNED_INT,
        }
    }

    /// Whether the components are integers (EXT_texture_integer's table 3.16), which need
    /// the `*_INTEGER` pixel formats.
    pub fn is_integer(self) -> bool {
        matches!(self.encoding, Encoding::Int | Encoding::Uint)
    }

    /// An unpacked integer colour (R, G, B, A) clamped to the representable range of each
    /// component of an integer format (EXT_texture_integer section 3.8.1): [−2^(n−1),
    /// 2^(n−1) − 1] for signed, [0, 2^n − 1] for unsigned formats of n bits. Components the
    /// base format drops are left as they are.
    pub fn clamp_integers(self, c: [i64; 4]) -> [i64; 4] {
        std::array::from_fn(|i| match (self.encoding, self.bits[i]) {
            (_, 0) => c[i],
            (Encoding::Int, n) => c[i].clamp(-(1i64 << (n - 1)), (1i64 << (n - 1)) - 1),
            (_, n) => c[i].clamp(0, (1i64 << n) - 1),
        })
    }

    /// An unpacked colour (R, G, B, A before the base format's component choice) rounded to
    /// what this storage keeps: clamped to the encoding's range and rounded to its bits, with
    /// the conversions of the pixel types of as many bits, so that packing with the format's
    /// own type gives the unpacked bytes back.
    pub fn round(self, c: [f32; 4]) -> [f32; 4] {
        match self.encoding {
            Encoding::SharedExponent => {
                let (m, e) = small_float::to_rgb9e5([c[0], c[1], c[2]]);
                let [r, g, b] = small_float::from_rgb9e5(m, e);
                [r, g, b, c[3]]
            }
            _ => std::array::from_fn(|i| self.round_component(c[i], self.bits[i])),
        }
    }

    fn round_component(self, v: f32, bits: u32) -> f32 {
        match (self.encoding, bits) {
            (_, 0) => v,
            (Encoding::Float, 16) => small_float::from_f16(small_float::to_f16(v)),
            (Encoding::Float, _) => v,
            (Encoding::PackedFloat, b) => small_float::from_unsigned_float(small_float::to_unsigned_float(v, b - 5), b - 5),
            // Table 2.9's signed conversion (2c + 1) / (2^b − 1), inverted as packing does.
            (Encoding::Snorm, 8) => norm_i8(snorm_code(v, 8) as i8),
            (Encoding::Snorm, _) => norm_i16(snorm_code(v, 16) as i16),
            (Encoding::Unorm | Encoding::Srgb, b) => {
                let max = f64::from((1u32 << b) - 1);
                ((f64::from(v.clamp(0.0, 1.0)) * max).round() / max) as f32
            }
            (Encoding::SharedExponent | Encoding::Int | Encoding::Uint, _) => v,
        }
    }
}

/// The signed integer of `bits` bits whose table 2.9 value is closest to `v`.
fn snorm_code(v: f32, bits: u32) -> i64 {
    let max = f64::from((1u32 << bits) - 1);
    let half = 1i64 << (bits - 1);
    ((f64::from(v.clamp(-1.0, 1.0)) * max - 1.0) / 2.0).round().clamp(-(half as f64), (half - 1) as f64) as i64
}

#[cfg(test)]
mod tests {
    use super::*;

    const RGBA: [bool; 4] = [true; 4];

    #[test]
    fn rounding_keeps_the_formats_bits() {
        let r16 = of(gl::GL_RGBA16, RGBA);
        assert_eq!((r16.precision(), r16.bits), (Precision::Float, [16; 4]));
        assert_eq!(r16.round([1000.0 / 65535.0, 2.0, -1.0, 0.3])[..3], [1000.0 / 65535.0, 1.0, 0.0]);
        assert_eq!(of(gl::GL_RGBA4, RGBA).precision(), Precision::Unorm8);
        assert_eq!(of(gl::GL_SRGB8_ALPHA8, RGBA).precision(), Precision::Srgb8);
        let rgb10a2 = of(gl::GL_RGB10_A2, RGBA);
        assert_eq!(rgb10a2.round([0.5, 0.0, 0.0, 1.0 / 3.0]), [(512.0f64 / 1023.0) as f32, 0.0, 0.0, 85.0 / 255.0]);
        assert_eq!(rgb10a2.bits, [10, 10, 10, 8]);
        // Every signed byte survives: its value rounds to itself.
        let s8 = of(gl::GL_RGBA8_SNORM, RGBA);
        for c in -128i8..=127 {
            assert_eq!(s8.round([norm_i8(c); 4])[0], norm_i8(c), "{c}");
        }
        assert_eq!(s8.round([-5.0, 5.0, 0.0, 0.0])[..2], [-1.0, 1.0]);
        let f16 = of(gl::GL_RGBA16F, RGBA);
        assert_eq!(f16.round([1.0 / 3.0, -70000.0, 0.0, 0.0])[..2], [0.33325195, f32::NEG_INFINITY]);
        let packed = of(gl::GL_R11F_G11F_B10F, RGBA);
        assert_eq!((packed.bits, packed.round([-1.0, 1.02, 1.02, 0.5])), ([11, 11, 10, 0], [0.0, 1.015625, 1.03125, 0.5]));
        assert_eq!(of(gl::GL_LUMINANCE16_ALPHA16, [true, false, false, true]).bits, [16, 0, 0, 16]);
        assert_eq!(of(gl::GL_RGB32F, [true, true, true, false]).component_type(), gl::GL_FLOAT);
        assert!(!of(gl::GL_RGB16, RGBA).unclamped() && of(gl::GL_R8_SNORM, RGBA).unclamped());
    }

    #[test]
    fn integer_formats_clamp_to_their_range() {
        let i8s = of(gl::GL_RGBA8I_EXT, RGBA);
        assert_eq!((i8s.precision(), i8s.bits, i8s.component_type()), (Precision::Integer, [8; 4], gl::GL_INT));
        assert_eq!(i8s.clamp_integers([-1000, 1000, -128, 127]), [-128, 127, -128, 127]);
        let u16s = of(gl::GL_LUMINANCE_ALPHA16UI_EXT, [true, false, false, true]);
        assert_eq!((u16s.bits, u16s.component_type()), ([16, 0, 0, 16], gl::GL_UNSIGNED_INT));
        assert_eq!(u16s.clamp_integers([-5, 7, 9, 70000]), [0, 7, 9, 65535]);
        let u32s = of(gl::GL_RGBA32UI_EXT, RGBA);
        assert_eq!(u32s.clamp_integers([-1, 4294967295, 4294967296, 0]), [0, 4294967295, 4294967295, 0]);
        let i32s = of(gl::GL_ALPHA32I_EXT, [false, false, false, true]);
        assert_eq!(i32s.clamp_integers([0, 0, 0, -3_000_000_000]), [0, 0, 0, i64::from(i32::MIN)]);
        assert!(of(gl::GL_R16UI, RGBA).is_integer() && !of(gl::GL_RGBA16, RGBA).is_integer());
    }
}
