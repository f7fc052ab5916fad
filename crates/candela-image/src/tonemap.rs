//! From linear radiance to 8-bit display values.
//!
//! The sRGB transfer functions are the exact piecewise formulas of
//! IEC 61966-2-1 (linear segment below 0.0031308 / 0.04045), not the 2.2
//! power approximation, so that reading a PNG back inverts writing it.
//!
//! Non-finite input never panics: NaN becomes 0, +inf saturates to white and
//! -inf to black. The renderer counts such samples itself; here we only make
//! sure a bad pixel cannot break the output file.

use crate::RgbImage;

/// Encodes a linear value in `[0, 1]` with the sRGB opto-electronic transfer
/// function (the curve a display expects). Inputs outside `[0, 1]` are
/// clamped first.
pub fn srgb_encode(linear: f32) -> f32 {
    // In f64 so that 1 encodes to exactly 1 and the round trip is tight.
    let l = clamp_unit(linear) as f64;
    let encoded = if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    encoded as f32
}

/// Decodes an sRGB-encoded value in `[0, 1]` to linear light; the exact
/// inverse of [`srgb_encode`]. Inputs outside `[0, 1]` are clamped first.
pub fn srgb_decode(encoded: f32) -> f32 {
    let v = clamp_unit(encoded) as f64;
    let linear = if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    };
    linear as f32
}

/// Clamps to `[0, 1]`, mapping NaN to 0 (`f32::clamp` would keep the NaN).
fn clamp_unit(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, 1.0)
    }
}

/// Quantises a display value in `[0, 1]` to 8 bits, rounding to nearest.
/// Out-of-range and NaN inputs are clamped as in [`srgb_encode`].
pub fn quantize_u8(display: f32) -> u8 {
    // After clamping, the product lies in [0, 255.5), so the cast is exact.
    (clamp_unit(display) * 255.0 + 0.5) as u8
}

/// The curve that maps exposed linear radiance to a display value in `[0, 1]`
/// (the `--tone` setting).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ToneCurve {
    /// Clamp to `[0, 1]`, then the exact sRGB encoding. Faithful for values
    /// that fit the display range; highlights clip.
    #[default]
    Srgb,
    /// What the CS184 PathTracer writes, so that images compare with the
    /// course's reference renders: multiply by √2, then the power `1/2.2`,
    /// then clamp to `[0, 1]`.
    Cs184,
    /// The ACES filmic fit of Krzysztof Narkowicz ("ACES Filmic Tone Mapping
    /// Curve", 2016): `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`, clamped to
    /// `[0, 1]`, then the sRGB encoding. Rolls highlights off smoothly instead
    /// of clipping; it darkens mid-tones slightly (0.18 maps to about 0.14),
    /// which `exposure` can compensate.
    Filmic,
}

/// How to turn linear radiance into display values: an exposure and a curve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToneMap {
    /// Exposure in stops: radiance is multiplied by `2^exposure` before the
    /// curve. 0 leaves it unchanged.
    pub exposure: f32,
    /// The curve applied after exposure.
    pub curve: ToneCurve,
}

impl ToneMap {
    /// Maps one linear channel value to a display value in `[0, 1]`.
    pub fn map_channel(&self, linear: f32) -> f32 {
        let x = linear * self.exposure.exp2();
        if x.is_nan() {
            return 0.0;
        }
        match self.curve {
            ToneCurve::Srgb => srgb_encode(x),
            ToneCurve::Cs184 => {
                let scaled = (x * std::f32::consts::SQRT_2).max(0.0);
                clamp_unit(scaled.powf(1.0 / 2.2))
            }
            ToneCurve::Filmic => srgb_encode(aces_fitted(x)),
        }
    }

    /// Maps an RGB pixel to display values in `[0, 1]`.
    pub fn map_pixel(&self, rgb: [f32; 3]) -> [f32; 3] {
        rgb.map(|c| self.map_channel(c))
    }

    /// Tone maps a whole image to interleaved 8-bit RGB, rows top to bottom:
    /// the byte layout a PNG encoder wants.
    pub fn to_rgb8(&self, image: &RgbImage) -> Vec<u8> {
        image
            .pixels()
            .iter()
            .flat_map(|&p| self.map_pixel(p).map(quantize_u8))
            .collect()
    }
}

/// Narkowicz's ACES fit, with the input limited so that `+inf` gives white
/// instead of `inf / inf`.
fn aces_fitted(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0e6);
    clamp_unit(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_segments_meet_at_the_standard_breakpoint() {
        // 12.92 * 0.0031308 = 0.040450; the power segment must agree there.
        let linear_side = 12.92 * 0.003_130_8_f32;
        let power_side = 1.055 * 0.003_130_8_f32.powf(1.0 / 2.4) - 0.055;
        assert!((linear_side - 0.040_45).abs() < 1e-6);
        assert!((power_side - 0.040_45).abs() < 1e-5);
        assert!((srgb_encode(0.003_130_8) - 0.040_45).abs() < 1e-6);
        assert!((srgb_decode(0.040_45) - 0.003_130_8).abs() < 1e-7);
    }

    #[test]
    fn srgb_known_values() {
        // 0.5 linear: 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357, * 255 = 187.5 -> 188.
        assert!((srgb_encode(0.5) - 0.735_357).abs() < 1e-5);
        assert_eq!(quantize_u8(srgb_encode(0.5)), 188);
        // 18% grey encodes to 0.461356 -> 118.
        assert_eq!(quantize_u8(srgb_encode(0.18)), 118);
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        // Below the breakpoint the curve is linear with slope 12.92.
        assert!((srgb_encode(0.001) - 0.01292).abs() < 1e-7);
        assert!((srgb_decode(0.01292) - 0.001).abs() < 1e-8);
    }

    #[test]
    fn srgb_decode_inverts_encode() {
        for i in 0..=1000 {
            let l = i as f32 / 1000.0;
            assert!((srgb_decode(srgb_encode(l)) - l).abs() < 2e-6, "at {l}");
        }
    }

    #[test]
    fn every_code_value_round_trips_through_linear() {
        for code in 0..=255u8 {
            let linear = srgb_decode(code as f32 / 255.0);
            assert_eq!(quantize_u8(srgb_encode(linear)), code);
        }
    }

    #[test]
    fn non_finite_values_do_not_panic() {
        for curve in [ToneCurve::Srgb, ToneCurve::Cs184, ToneCurve::Filmic] {
            let tm = ToneMap {
                exposure: 0.0,
                curve,
            };
            assert_eq!(tm.map_channel(f32::NAN), 0.0, "{curve:?}");
            assert_eq!(tm.map_channel(f32::INFINITY), 1.0, "{curve:?}");
            assert_eq!(tm.map_channel(f32::NEG_INFINITY), 0.0, "{curve:?}");
            assert_eq!(tm.map_channel(-3.0), 0.0, "{curve:?}");
        }
    }

    #[test]
    fn cs184_curve_matches_its_formula() {
        let tm = ToneMap {
            exposure: 0.0,
            curve: ToneCurve::Cs184,
        };
        // 0.25 * sqrt(2) = 0.353553; ^(1/2.2) = exp(ln(0.353553) / 2.2) = 0.623379.
        assert!((tm.map_channel(0.25) - 0.623_379).abs() < 1e-5);
        // 1/sqrt(2) maps exactly to 1; anything brighter clamps.
        assert!((tm.map_channel(std::f32::consts::FRAC_1_SQRT_2) - 1.0).abs() < 1e-6);
        assert_eq!(tm.map_channel(5.0), 1.0);
    }

    #[test]
    fn exposure_is_in_stops() {
        let plus_one = ToneMap {
            exposure: 1.0,
            curve: ToneCurve::Srgb,
        };
        assert_eq!(
            plus_one.map_channel(0.25),
            ToneMap::default().map_channel(0.5)
        );
    }

    #[test]
    fn filmic_is_monotonic_and_saturates() {
        let tm = ToneMap {
            exposure: 0.0,
            curve: ToneCurve::Filmic,
        };
        let mut previous = 0.0;
        for i in 1..2000 {
            let v = tm.map_channel(i as f32 * 0.01);
            assert!(v >= previous, "not monotonic at {}", i as f32 * 0.01);
            previous = v;
        }
        // The published fit at 0.18: 0.18(0.4818+0.03)/(0.18(0.4374+0.59)+0.14).
        let expected = srgb_encode(0.18 * 0.481_8 / (0.18 * 1.027_4 + 0.14));
        assert!((tm.map_channel(0.18) - expected).abs() < 1e-6);
        assert_eq!(tm.map_channel(1.0e5), 1.0);
    }
}
