//! Sine and cosine for the warps' angles, by polynomial.
//!
//! Every diffuse bounce turns two sample values into a direction through an
//! angle (the concentric disk's φ), and the C library's `sincosf` took 5%
//! of a Lambertian Cornell box's render time (perf, CBspheres_lambertian):
//! it reduces any argument, while the warps' angles are already confined.
//! The polynomial made that render 3% faster (BENCHMARKS.md, 2026-12-02).
//! On |x| ≤ π/4 the Taylor series to x⁹ (sine) and x¹⁰ (cosine) is exact to
//! 2·10⁻⁹ before rounding, so these agree with `f64::sin_cos` within a few
//! float ulps (tested), and the warps stay what their pdfs say.

use std::f32::consts::{FRAC_PI_4, TAU};

/// `(x.sin(), x.cos())` for |x| ≤ π/4 (beyond it the error grows with
/// |x|¹¹; callers reduce their angle first).
#[inline(always)]
pub fn sin_cos_within_quarter_pi(x: f32) -> (f32, f32) {
    debug_assert!(x.abs() <= FRAC_PI_4 * 1.0001, "{x} is outside [-π/4, π/4]");
    let x2 = x * x;
    // Horner forms of the series; the coefficients are ±1/n!.
    let sin_poly = 1.0
        + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0))));
    let cos_poly = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 + x2 * (-1.0 / 3_628_800.0)))));
    (x * sin_poly, cos_poly)
}

/// `(sin 2πu, cos 2πu)` for a sample value `u` in [0, 1): the nearest
/// quarter turn is taken out exactly (`u − k/4` rounds nothing for u in
/// [0, 1)) and the rest, within ±π/4, goes to the polynomial.
#[inline(always)]
pub fn sin_cos_turns(u: f32) -> (f32, f32) {
    let k = (4.0 * u).round();
    let (s, c) = sin_cos_within_quarter_pi(TAU * (u - 0.25 * k));
    // A quarter turn maps (sin, cos) to (cos, −sin).
    match (k as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A float ulp at 1 is 1.19e-7; the polynomial's own error is 2e-9, the
    /// evaluation's rounding a few ulps of values at most 1.
    const BOUND: f64 = 3.0e-7;

    #[test]
    fn the_quarter_pi_polynomial_is_sine_and_cosine_to_a_few_ulps() {
        let n = 200_000;
        let mut worst = 0.0f64;
        for i in 0..=n {
            let x = (-1.0 + 2.0 * i as f64 / n as f64) * std::f64::consts::FRAC_PI_4;
            let (s, c) = sin_cos_within_quarter_pi(x as f32);
            let xf = f64::from(x as f32);
            worst = worst
                .max((f64::from(s) - xf.sin()).abs())
                .max((f64::from(c) - xf.cos()).abs());
        }
        assert!(worst < BOUND, "largest error {worst:e} over [-π/4, π/4]");
        assert_eq!(sin_cos_within_quarter_pi(0.0), (0.0, 1.0));
    }

    #[test]
    fn turns_are_sine_and_cosine_of_the_whole_circle() {
        let n = 400_000;
        let mut worst = 0.0f64;
        for i in 0..n {
            let u = i as f32 / n as f32;
            let (s, c) = sin_cos_turns(u);
            let phi = std::f64::consts::TAU * f64::from(u);
            worst = worst
                .max((f64::from(s) - phi.sin()).abs())
                .max((f64::from(c) - phi.cos()).abs());
        }
        // One more rounding (2π times the reduced value) than above.
        assert!(
            worst < BOUND + 2.0e-7,
            "largest error {worst:e} over [0, 1)"
        );
        // The largest sample value below 1, and the quarter-turn boundaries.
        for u in [1.0 - f32::EPSILON / 2.0, 0.125, 0.375, 0.625, 0.875] {
            let (s, c) = sin_cos_turns(u);
            let phi = std::f64::consts::TAU * f64::from(u);
            assert!((f64::from(s) - phi.sin()).abs() < 5.0e-7, "sin at {u}");
            assert!((f64::from(c) - phi.cos()).abs() < 5.0e-7, "cos at {u}");
        }
    }
}
