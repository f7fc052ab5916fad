//! Spectra to linear sRGB, as Mitsuba 3's RGB variants convert the
//! `wavelength:value` lists of its files, so that a scene written with
//! spectra (its classic Cornell box) renders in the colours it renders in
//! there.
//!
//! The spectrum, linear between its samples and zero outside them, is
//! integrated against the CIE 1931 observer by the midpoint-free rule
//! Mitsuba uses (1000 evenly spaced wavelengths from 360 to 830 nm, ends
//! included), the XYZ scaled by the inverse of ȳ's integral and taken to
//! linear sRGB. How the spectrum is read depends on where it stands:
//! - inside an `<emitter>` it is light: equal-energy white stays equal
//!   energy (a flat 1 becomes RGB (1.205, 0.948, 0.909), sRGB's white being
//!   D65), and only negative channels are clamped;
//! - elsewhere it is a reflectance seen under D65 (a flat spectrum stays
//!   flat) and is clamped to [0, 1], except a conductor's `eta` and `k`
//!   and the `value` of a `<volume>` (a medium's constant `sigma_t` or
//!   `albedo`), which may exceed 1. A medium's `sigma_t` given directly as
//!   a `<spectrum>` is clamped as a reflectance, as in Mitsuba (which
//!   warns; so does the medium reader).
//!
//! Checked against Mitsuba 3.9's own `spectrum_list_to_srgb` and its XML
//! parser (emitter radiance, diffuse reflectance, conductor `k`): see the
//! tests.

use super::cie_tables::{FIRST_NM, LAST_NM, XYZ_D65};
use super::doc::{Doc, XNode};
use crate::error::LoadError;
use glam::{DMat3, DVec3, Vec3};

/// Mitsuba's 1/∫ȳ(λ) dλ over the tables.
const CIE_Y_NORMALIZATION: f64 = 0.009_367_658_735_689_113;

/// Wavelengths the integral is evaluated at.
const STEPS: usize = 1000;

/// CIE XYZ to linear sRGB (D65 white), rows as Mitsuba writes them.
const XYZ_TO_SRGB: DMat3 = DMat3::from_cols_array(&[
    3.240_479, -0.969_256, 0.055_648, //
    -1.537_150, 1.875_991, -0.204_043, //
    -0.498_535, 0.041_556, 1.057_311,
]);

/// How a spectrum in a file is read (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct SpectrumReading {
    /// Light (inside an `<emitter>`): no illuminant, no upper clamp.
    emitted: bool,
    /// May exceed 1 (light, or a conductor's `eta`/`k`).
    unbounded: bool,
}

impl SpectrumReading {
    /// The reading of the `<spectrum>` element `node`, from where it stands.
    pub(super) fn of(doc: &Doc, node: XNode) -> Result<Self, LoadError> {
        let emitted = node
            .ancestors()
            .any(|a| a.is_element() && a.tag_name().name() == "emitter");
        let name = doc.attr(node, "name")?;
        let optical_constant = matches!(name.as_deref(), Some("eta" | "k"));
        let in_volume = node
            .ancestors()
            .any(|a| a.is_element() && a.tag_name().name() == "volume");
        Ok(Self {
            emitted,
            unbounded: emitted || optical_constant || in_volume,
        })
    }

    /// This reading without its upper clamp (to tell whether it clamped).
    pub(super) fn unclamped(self) -> Self {
        Self {
            unbounded: true,
            ..self
        }
    }

    /// A flat spectrum of `value` (a `<spectrum value="v">`): Mitsuba
    /// keeps the number for a reflectance and makes light of it the
    /// equal-energy white of that power.
    pub(super) fn flat(self, value: f32) -> Vec3 {
        if self.emitted {
            (XYZ_TO_SRGB * DVec3::ONE * value as f64).as_vec3()
        } else {
            Vec3::splat(value)
        }
    }

    /// Linear sRGB of the spectrum `samples` (wavelength in nm, value),
    /// wavelengths increasing.
    pub(super) fn rgb(self, samples: &[(f32, f32)]) -> Vec3 {
        let (first, last) = (samples[0].0 as f64, samples[samples.len() - 1].0 as f64);
        let span = (LAST_NM - FIRST_NM) as f64;
        let mut xyz = DVec3::ZERO;
        for i in 0..STEPS {
            let l = FIRST_NM as f64 + i as f64 / (STEPS - 1) as f64 * span;
            if l < first || l > last {
                continue;
            }
            let row = table_at(l);
            let weight = if self.emitted { 1.0 } else { row[3] };
            xyz += DVec3::new(row[0], row[1], row[2]) * weight * sample_at(samples, l);
        }
        xyz *= span / STEPS as f64 * CIE_Y_NORMALIZATION;
        let rgb = (XYZ_TO_SRGB * xyz).max(DVec3::ZERO);
        let rgb = if self.unbounded {
            rgb
        } else {
            rgb.min(DVec3::ONE)
        };
        rgb.as_vec3()
    }
}

/// The piecewise-linear spectrum at `l`, within its samples.
fn sample_at(samples: &[(f32, f32)], l: f64) -> f64 {
    let i = samples.partition_point(|&(w, _)| (w as f64) < l);
    if i == 0 {
        return samples[0].1 as f64;
    }
    if i == samples.len() {
        return samples[i - 1].1 as f64;
    }
    let ((l0, v0), (l1, v1)) = (samples[i - 1], samples[i]);
    let (l0, v0, l1, v1) = (l0 as f64, v0 as f64, l1 as f64, v1 as f64);
    v0 + (v1 - v0) * (l - l0) / (l1 - l0)
}

/// x̄, ȳ, z̄ and D65 at `l` nm (within the tables), linear between whole
/// nanometres.
fn table_at(l: f64) -> [f64; 4] {
    let x = l - FIRST_NM as f64;
    let i = (x.floor() as usize).min(XYZ_D65.len() - 2);
    let f = x - i as f64;
    let (a, b) = (XYZ_D65[i], XYZ_D65[i + 1]);
    std::array::from_fn(|k| a[k] as f64 * (1.0 - f) + b[k] as f64 * f)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIGHT: SpectrumReading = SpectrumReading {
        emitted: true,
        unbounded: true,
    };
    const REFLECTANCE: SpectrumReading = SpectrumReading {
        emitted: false,
        unbounded: false,
    };
    const OPTICAL_CONSTANT: SpectrumReading = SpectrumReading {
        emitted: false,
        unbounded: true,
    };

    /// Within 2e-5 of Mitsuba's figure (relative, and absolute near 0):
    /// both integrate the same tables by the same rule, so what is left is
    /// float rounding and the 6 digits Mitsuba printed.
    fn assert_mitsuba(got: Vec3, mitsuba: [f32; 3]) {
        let want = Vec3::from(mitsuba);
        let err = (got - want).abs() / want.abs().max(Vec3::splat(1.0));
        assert!(err.max_element() < 2e-5, "{got} vs Mitsuba {want}");
    }

    // Figures from Mitsuba 3.9.1 (scalar_rgb): its XML parser's reading of
    // each spectrum (an area emitter's `eval`, a diffuse BSDF's `eval`
    // times π, a rough conductor's `k`) and `spectrum_list_to_srgb`.

    #[test]
    fn light_is_read_without_an_illuminant_and_equal_energy_is_not_rgb_white() {
        let lamp = [(400.0, 0.0), (500.0, 8.0), (600.0, 15.6), (700.0, 18.4)];
        assert_mitsuba(LIGHT.rgb(&lamp), [20.7108, 10.8546, 2.77115]);
        assert_mitsuba(
            LIGHT.rgb(&[(400.0, 2.0), (700.0, 2.0)]),
            [2.39939, 1.89904, 1.80688],
        );
        assert_mitsuba(LIGHT.flat(2.0), [2.40959, 1.89658, 1.81783]);
        // Negative channels clamp to 0, nothing else.
        let dip = [(400.0, -0.5), (500.0, 0.2), (700.0, 0.9)];
        assert_mitsuba(LIGHT.rgb(&dip), [0.796571, 0.348678, 0.0]);
    }

    #[test]
    fn a_reflectance_is_read_under_d65_and_clamped_to_one() {
        let ramp = [(400.0, 0.1), (500.0, 0.3), (600.0, 0.6), (700.0, 0.7)];
        assert_mitsuba(REFLECTANCE.rgb(&ramp), [0.684633, 0.42812, 0.174425]);
        // Flat stays flat, less what 360-400 and 700-830 nm would add.
        let flat = [(400.0, 0.5), (700.0, 0.5)];
        assert_mitsuba(REFLECTANCE.rgb(&flat), [0.497671, 0.499878, 0.497455]);
        assert_eq!(REFLECTANCE.flat(0.5), Vec3::splat(0.5));
        let bright = [(400.0, 1.5), (700.0, 1.5)];
        assert_eq!(REFLECTANCE.rgb(&bright), Vec3::ONE);
        let dip = [(400.0, -0.5), (500.0, 0.2), (700.0, 0.9)];
        assert_mitsuba(REFLECTANCE.rgb(&dip), [0.685103, 0.363804, 0.0]);
    }

    #[test]
    fn a_conductors_k_is_read_under_d65_without_the_clamp() {
        let k = [(400.0, 3.0), (700.0, 4.0)];
        assert_mitsuba(OPTICAL_CONSTANT.rgb(&k), [3.79017, 3.47572, 3.12077]);
    }

    #[test]
    fn the_rule_integrates_the_tables_to_mitsubas_normalisation() {
        // Mitsuba's constant is one over the rule's own ∫ȳ dλ: light of a
        // flat 1 over the whole range has luminance Y = 1 (to the tables' 7
        // digits; X and Z differ from it by the CMFs' own integrals).
        let flat = LIGHT.rgb(&[(FIRST_NM, 1.0), (LAST_NM, 1.0)]).as_dvec3();
        let y = (XYZ_TO_SRGB.inverse() * flat).y;
        assert!((y - 1.0).abs() < 1e-5, "Y {y}");
        // Under D65 the same rule gives Mitsuba's 0.999, not exactly 1.
        let white = REFLECTANCE.rgb(&[(FIRST_NM, 1.0), (LAST_NM, 1.0)]);
        assert_mitsuba(white, [0.998983, 0.998872, 0.998802]);
    }
}
