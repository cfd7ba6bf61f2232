//! The seed's log quantisation of the compressed part of the matrix (seed 004, §4.2): values
//! divided by the largest of them, log-scaled, shifted onto the positive half axis and scaled
//! to codes. Code 0 stands for 0 (and for values below `max · e^−shift`); a positive value `x`
//! gets `1 + round((ln(x / max) + shift) / shift · 254)`, so code `q ≥ 1` stands for
//! `max · e^((q − 1) · shift / 254 − shift)`: a step of `e^(shift / 254)`.
//!
//! The seed shifts by [`LOG_SHIFT`] = 25 whatever the values (a step of e^0.098: 5 % error
//! at most), which spends most codes on values that are not there: a k-bounce matrix spans a few
//! decades. [`fitted_shift`] shifts by the span of the values present instead, so the same 255
//! codes (and BC1's 32 levels of its end points) cover only it.

/// The seed's shift: values down to `e^−25` of the maximum keep a code.
pub const LOG_SHIFT: f32 = 25.0;
/// The smallest shift [`fitted_shift`] gives (values within a factor e of each other).
const MIN_SHIFT: f32 = 1.0;

/// The shift that spans `values` (≥ 0) exactly: `ln(max / smallest positive)`, within
/// `MIN_SHIFT..=LOG_SHIFT`.
pub fn fitted_shift(values: impl Iterator<Item = f32>) -> f32 {
    let (min, max) = values.filter(|&x| x > 0.0).fold((f32::INFINITY, 0.0f32), |(lo, hi), x| (lo.min(x), hi.max(x)));
    if max > 0.0 { (max / min).ln().clamp(MIN_SHIFT, LOG_SHIFT) } else { LOG_SHIFT }
}

/// The code of `x` (≥ 0) for a part whose largest value is `max` (> 0), shifted by `shift`.
pub fn encode(x: f32, max: f32, shift: f32) -> u8 {
    if !(x > 0.0 && max > 0.0) {
        return 0;
    }
    let scaled = ((x / max).ln() + shift) / shift * 254.0;
    if scaled < -0.5 { 0 } else { 1 + scaled.round().min(254.0) as u8 }
}

/// The value code `q` stands for (see the module doc).
pub fn decode(q: u8, max: f32, shift: f32) -> f32 {
    if q == 0 { 0.0 } else { max * (f32::from(q - 1) * shift / 254.0 - shift).exp() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_codes_keep_five_percent_over_eleven_decades() {
        assert_eq!((encode(0.0, 2.0, LOG_SHIFT), encode(2.0, 2.0, LOG_SHIFT), encode(-1.0, 2.0, LOG_SHIFT)), (0, 255, 0));
        assert_eq!(decode(255, 2.0, LOG_SHIFT), 2.0);
        assert_eq!(decode(0, 2.0, LOG_SHIFT), 0.0);
        for k in 0..100 {
            let x = 2.0 * (-(k as f32) * 0.24).exp();
            let back = decode(encode(x, 2.0, LOG_SHIFT), 2.0, LOG_SHIFT);
            assert!((back - x).abs() <= 0.051 * x, "{x} -> {back}");
        }
        assert_eq!(encode(2.0e-13, 2.0, LOG_SHIFT), 0);
    }

    #[test]
    fn a_fitted_shift_spends_every_code_on_the_values_present() {
        let values = [0.0, 1.0e-3, 0.01, 0.1];
        let shift = fitted_shift(values.into_iter());
        assert!((shift - 100f32.ln()).abs() < 1e-5);
        assert_eq!(encode(1.0e-3, 0.1, shift), 1);
        assert_eq!(encode(0.1, 0.1, shift), 255);
        // A step of 100^(1/254): 0.9 % at most.
        for k in 0..50 {
            let x = 0.1 * (-(k as f32) * 0.09).exp();
            let back = decode(encode(x, 0.1, shift), 0.1, shift);
            assert!((back - x).abs() <= 0.01 * x, "{x} -> {back}");
        }
        assert_eq!(fitted_shift([0.0, 0.0].into_iter()), LOG_SHIFT);
        assert_eq!(fitted_shift([1.0, 1.0].into_iter()), MIN_SHIFT);
    }
}
