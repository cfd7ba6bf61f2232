//! Floating-point numbers of fewer than 32 bits: the 16-bit half float (ARB_half_float_pixel,
//! ARB_texture_float's 16-bit formats), the unsigned 11- and 10-bit floats of
//! EXT_packed_float, and the shared-exponent RGB9_E5 of EXT_texture_shared_exponent. Each
//! encodes an `f32` to its bits (rounding to nearest) and decodes bits back; every format has
//! a 5-bit exponent with bias 15.

/// Exponent bias of every format here.
const BIAS: i32 = 15;
/// Smallest exponent of a normal number.
const MIN_EXP: i32 = 1 - BIAS;

/// Encodes a finite `a` ≥ 0 with a 5-bit exponent and `man` mantissa bits, rounding to
/// nearest; values beyond the largest finite number give infinity.
fn encode_magnitude(a: f32, man: u32) -> u32 {
    let inf = 0x1f << man;
    if a == 0.0 {
        return 0;
    }
    if a.is_infinite() {
        return inf;
    }
    let a = f64::from(a);
    let exp = ((a.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let mut e = exp.max(MIN_EXP);
    let mut m = (a / 2f64.powi(e - man as i32)).round() as u64;
    if m >= 1 << (man + 1) {
        e += 1;
        m >>= 1;
    }
    if m < 1 << man {
        // Denormal (or rounded to zero): exponent field 0.
        return m as u32;
    }
    let field = e + BIAS;
    if field >= 31 {
        return inf;
    }
    ((field as u32) << man) | (m as u32 & ((1 << man) - 1))
}

/// Decodes a 5-bit exponent and `man`-bit mantissa.
fn decode_magnitude(bits: u32, man: u32) -> f32 {
    let field = (bits >> man) & 0x1f;
    let m = bits & ((1 << man) - 1);
    match field {
        0 => (f64::from(m) * 2f64.powi(MIN_EXP - man as i32)) as f32,
        31 if m == 0 => f32::INFINITY,
        31 => f32::NAN,
        _ => (f64::from(m | 1 << man) * 2f64.powi(field as i32 - BIAS - man as i32)) as f32,
    }
}

/// An `f32` as a half float.
pub fn to_f16(v: f32) -> u16 {
    let sign = if v.is_sign_negative() { 0x8000 } else { 0 };
    if v.is_nan() {
        return 0x7e00;
    }
    sign | encode_magnitude(v.abs(), 10) as u16
}

/// A half float as an `f32`.
pub fn from_f16(h: u16) -> f32 {
    let m = decode_magnitude(u32::from(h & 0x7fff), 10);
    if h & 0x8000 != 0 { -m } else { m }
}

/// An `f32` as an unsigned float of `man` mantissa bits (6 for the 11-bit, 5 for the 10-bit
/// float): negative values and NaN become 0 (EXT_packed_float section 2.1.A says negative
/// values convert to zero, and leaves NaN to the implementation).
pub fn to_unsigned_float(v: f32, man: u32) -> u32 {
    if v.is_nan() || v <= 0.0 { 0 } else { encode_magnitude(v, man) }
}

/// An unsigned float of `man` mantissa bits as an `f32`.
pub fn from_unsigned_float(bits: u32, man: u32) -> f32 {
    decode_magnitude(bits, man)
}

/// Mantissa bits of RGB9_E5.
const E5_MANTISSA: i32 = 9;

/// An RGB colour as RGB9_E5 (EXT_texture_shared_exponent section 3.8.1): the three 9-bit
/// mantissas and the shared exponent, each clamped to [0, largest representable].
pub fn to_rgb9e5(rgb: [f32; 3]) -> ([u32; 3], u32) {
    let max = f64::from((1 << E5_MANTISSA) - 1) / f64::from(1 << E5_MANTISSA) * 2f64.powi(31 - BIAS);
    let c = rgb.map(|v| if v.is_nan() { 0.0 } else { f64::from(v).clamp(0.0, max) });
    let largest = c[0].max(c[1]).max(c[2]);
    let floor_log2 = if largest > 0.0 { ((largest.to_bits() >> 52) & 0x7ff) as i32 - 1023 } else { -BIAS - 1 };
    let mut exp = floor_log2.max(-BIAS - 1) + 1 + BIAS;
    let max_s = (largest / 2f64.powi(exp - BIAS - E5_MANTISSA) + 0.5).floor();
    if max_s >= f64::from(1 << E5_MANTISSA) {
        exp += 1;
    }
    let scale = 2f64.powi(exp - BIAS - E5_MANTISSA);
    (c.map(|v| ((v / scale + 0.5).floor() as u32).min((1 << E5_MANTISSA) - 1)), exp as u32)
}

/// RGB9_E5 mantissas and exponent as an RGB colour.
pub fn from_rgb9e5(mantissas: [u32; 3], exp: u32) -> [f32; 3] {
    let scale = 2f64.powi(exp as i32 - BIAS - E5_MANTISSA);
    mantissas.map(|m| (f64::from(m) * scale) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_floats_round_trip_and_round() {
        for (v, bits) in [(1.0f32, 0x3c00u16), (-2.0, 0xc000), (65504.0, 0x7bff), (0.5, 0x3800), (6.1035156e-5, 0x0400), (5.9604645e-8, 0x0001)] {
            assert_eq!(to_f16(v), bits, "{v}");
            assert_eq!(from_f16(bits), v, "{bits:#x}");
        }
        assert_eq!(to_f16(1e6), 0x7c00);
        assert_eq!(from_f16(0x7c00), f32::INFINITY);
        // 1 + 2^-11 lies halfway between 1 and 1 + 2^-10 and rounds away.
        assert_eq!(to_f16(1.0 + 1.0 / 4096.0), 0x3c00);
        assert_eq!(to_f16(1.0 + 3.0 / 4096.0), 0x3c01);
        for h in (0..0x7c00u16).step_by(7) {
            assert_eq!(to_f16(from_f16(h)), h);
        }
    }

    #[test]
    fn packed_floats_are_unsigned() {
        assert_eq!(to_unsigned_float(1.0, 6), 15 << 6);
        assert_eq!(to_unsigned_float(-1.0, 6), 0);
        assert_eq!(from_unsigned_float(15 << 5 | 16, 5), 1.5);
        assert_eq!(from_unsigned_float(0x7bf, 6), 65024.0);
        for b in 0..0x7c0u32 {
            assert_eq!(to_unsigned_float(from_unsigned_float(b, 6), 6), b);
        }
    }

    #[test]
    fn shared_exponent_follows_the_extension() {
        // 1.0: exponent 16 (2^1 range), mantissa 256.
        let (m, e) = to_rgb9e5([1.0, 0.5, 0.0]);
        assert_eq!((m, e), ([256, 128, 0], 16));
        assert_eq!(from_rgb9e5(m, e), [1.0, 0.5, 0.0]);
        let (m, e) = to_rgb9e5([-3.0, f32::NAN, 1e9]);
        assert_eq!(from_rgb9e5(m, e), [0.0, 0.0, 65408.0]);
        // Mantissa rounding that overflows bumps the exponent.
        let (m, e) = to_rgb9e5([0.9995, 0.0, 0.0]);
        assert_eq!((m[0], e), (256, 16));
    }
}
