//! The seed's log quantisation of the compressed part of the matrix (seed 004, §4.2): values
//! divided by the largest of them, log-scaled, shifted by [`LOG_SHIFT`] onto the positive half
//! axis and scaled to 0..=255. Code `q > 0` stands for `max · e^(q · LOG_SHIFT / 255 − LOG_SHIFT)`
//! (a step of e^(25/255) ≈ 1.10, so at most ~5 % relative error); code 0 for 0 and for every
//! value below `max · e^−LOG_SHIFT` (≈ 1.4 · 10⁻¹¹ · max).

/// The shift added to `ln(x / max)`: values down to `e^−25` of the maximum keep a code.
pub const LOG_SHIFT: f32 = 25.0;

/// The code of `x` (≥ 0) for a part whose largest value is `max` (> 0).
pub fn encode(x: f32, max: f32) -> u8 {
    if !(x > 0.0 && max > 0.0) {
        return 0;
    }
    let scaled = ((x / max).ln() + LOG_SHIFT) / LOG_SHIFT * 255.0;
    scaled.round().clamp(0.0, 255.0) as u8
}

/// The value code `q` stands for (see the module doc).
pub fn decode(q: u8, max: f32) -> f32 {
    if q == 0 { 0.0 } else { max * (f32::from(q) * LOG_SHIFT / 255.0 - LOG_SHIFT).exp() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_keep_five_percent_over_eleven_decades() {
        assert_eq!((encode(0.0, 2.0), encode(2.0, 2.0), encode(-1.0, 2.0)), (0, 255, 0));
        assert_eq!(decode(255, 2.0), 2.0);
        assert_eq!(decode(0, 2.0), 0.0);
        for k in 0..100 {
            let x = 2.0 * (-(k as f32) * 0.24).exp();
            let back = decode(encode(x, 2.0), 2.0);
            assert!((back - x).abs() <= 0.05 * x, "{x} -> {back}");
        }
        assert_eq!(encode(2.0e-13, 2.0), 0);
    }
}
