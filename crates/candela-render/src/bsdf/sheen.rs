//! `KHR_materials_sheen`'s sheen on the glTF metallic-roughness BSDF
//! (`metallic_roughness/`, which layers it between the base and the
//! clear coat; see its module docs for the whole model).
//!
//! The sheen is the "Charlie" microfibre lobe of Estevez & Kulla 2017,
//! "Production Friendly Microfacet Sheen BRDF", as the extension defines
//! it: with sheen colour c (per channel in [0, 1]), α = sheenRoughness²
//! and h the half vector,
//!
//! - D(h) = (2 + 1/α) · sin(θh)^(1/α) / (2π), the fibres' normals
//!   (normalised: ∫ D cos θh dω = 1);
//! - V = 1 / ((1 + Λ(cos θo) + Λ(cos θi)) · 4 cos θo cos θi), the
//!   height-correlated Smith form with the paper's **fitted Λ**
//!   (Λ(μ) = exp(L(μ)) for μ < 0.5 and exp(2 L(0.5) − L(1 − μ)) above, L a
//!   five-coefficient curve interpolated in (1 − α)²), the extension's
//!   "Charlie" visibility. The extension also allows Ashikhmin's
//!   V = 1/(4 (μo + μi − μo μi)), which it notes is not energy conserving
//!   under the albedo scaling; the fit approximates this D's own Smith Λ
//!   (within 4% at α = 1), so the lobe is reciprocal and, with the two
//!   guards below, reflects less than it receives;
//! - f_sheen = c · D · V (no Fresnel: the extension's F = 1).
//!
//! The base under the sheen is scaled by
//! min(1 − max(c) E(cos θo), 1 − max(c) E(cos θi)), E the sheen's
//! directional albedo per unit colour (`sheen_albedo.rs`, our own
//! quadrature of this file's [`sheen_value`]): symmetric, so reciprocal,
//! and the base gets at most what the sheen leaves at `wo`.
//!
//! **Two guards keep the fit where it describes the lobe.** As α → 0 the
//! fibre normals lie flat and the exact Smith Λ grows without bound at
//! every angle; the fit does not (at α = 0.005 it is a third of the exact
//! Λ), so
//! for small α the lobe reflects more than it receives at grazing angles
//! (an albedo of 1.07 at α = 0.05, 2.0 at α = 0.005, θo ≈ 89°), and it
//! narrows to a rim of near-horizontal fibres that cosine sampling finds
//! poorly. So α is clamped to at least [`MIN_ALPHA`] (sheenRoughness
//! 0.28), where the fit is within 12% of the exact Λ and the albedo peaks
//! at 0.955. And the fitted μ Λ(μ) falls to 0 as μ → 0 (the exact one
//! tends to a constant), so the albedo would grow without bound at
//! μ ≲ 10⁻⁵; the cosines in V are read as at least [`MIN_COSINE`].
//!
//! Values here are for a pair already mirrored to the side where
//! `wo.z > 0` (`metallic_roughness::to_upper`): the sheen is two-sided, as
//! the opaque lobes are.

use std::f32::consts::FRAC_1_PI;

use glam::Vec3;

use super::sheen_albedo::sheen_albedo;

/// The smallest α = sheenRoughness² used (see the module docs): the
/// sheen's albedo then peaks at 0.955 (near the horizon), below 1 with
/// room for the table's interpolation.
pub(super) const MIN_ALPHA: f32 = 0.08;

/// The smallest cosine the visibility term reads (θ ≈ 89.4°): below it
/// V keeps its value at 0.01 (a kink in E, the table's worst spot for
/// interpolation, `sheen_tests.rs`).
pub(super) const MIN_COSINE: f32 = 1e-2;

/// A sheen: colour and perceptual roughness, each in [0, 1].
///
/// Both are kept as 16-bit fractions (steps of 1/65535, far finer than
/// any sheen a file or texture gives), 8 bytes in all: the glTF model then
/// stays within the 60 bytes that fit beside [`super::Bsdf`]'s tag (held
/// in a niche of the rough plastic's, the largest model). With the sheen
/// in four `f32` every `Bsdf` grows from 72 to 80 bytes, and the render
/// loop with it, sheen or not (0.15% more instructions on CS184's CBbunny;
/// `bsdf/mod.rs` checks the size).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Sheen {
    color: [u16; 3],
    roughness: u16,
}

/// The 16-bit fraction of one value in [0, 1].
const UNIT: f32 = u16::MAX as f32;

/// `v` in [0, 1] (NaN as 0) as a 16-bit fraction.
fn fraction(v: f32) -> u16 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    (v * UNIT).round() as u16
}

impl Sheen {
    /// No sheen (the extension's default colour, black).
    pub(super) const NONE: Self = Self {
        color: [0; 3],
        roughness: 0,
    };

    /// A sheen of colour `color` and perceptual `roughness`, each clamped to
    /// [0, 1] (NaN to 0, the extension's defaults) and rounded to 16-bit
    /// fractions.
    pub(super) fn new(color: Vec3, roughness: f32) -> Self {
        Self {
            color: color.to_array().map(fraction),
            roughness: fraction(roughness),
        }
    }

    /// The colour, per channel in [0, 1].
    fn color(&self) -> Vec3 {
        Vec3::from(self.color.map(f32::from)) / UNIT
    }

    /// The perceptual roughness.
    fn roughness(&self) -> f32 {
        f32::from(self.roughness) / UNIT
    }

    /// Colour and perceptual roughness.
    pub(super) fn parameters(&self) -> (Vec3, f32) {
        (self.color(), self.roughness())
    }

    /// Whether there is a sheen at all (the extension: a black sheen colour
    /// disables the layer); without one the BSDF skips every sheen term, so
    /// it is exactly the sheenless model.
    pub(super) fn is_on(&self) -> bool {
        self.color != [0; 3]
    }

    /// The lobe's α: roughness², at least [`MIN_ALPHA`].
    fn alpha(&self) -> f32 {
        let r = self.roughness();
        (r * r).max(MIN_ALPHA)
    }

    /// E(cos): the lobe's directional albedo per unit colour.
    pub(super) fn albedo(&self, cos: f32) -> f32 {
        sheen_albedo(cos, self.roughness())
    }

    /// What the sheen leaves to the base beneath it:
    /// min(1 − max(c) E(cos θo), 1 − max(c) E(cos θi)), symmetric in the
    /// two directions.
    pub(super) fn base_weight(&self, cos_o: f32, cos_i: f32) -> f32 {
        let e = self.albedo(cos_o).max(self.albedo(cos_i));
        (1.0 - self.color().max_element() * e).max(0.0)
    }

    /// The sheen lobe's value for an upper pair (0 below the surface).
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.color() * sheen_value(wo, wi, self.alpha())
    }
}

/// D(h) · V(wo, wi) for an upper pair at α: the sheen lobe per unit colour
/// (see the module docs).
pub(super) fn sheen_value(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
    let (o, i) = (Shadowing::at(wo.z, alpha), Shadowing::at(wi.z, alpha));
    sheen_value_from(wo, wi, alpha, o, i)
}

/// [`sheen_value`] with each direction's part of V given (the albedo
/// table's quadrature computes them once per direction, not per pair).
pub(super) fn sheen_value_from(wo: Vec3, wi: Vec3, alpha: f32, o: Shadowing, i: Shadowing) -> f32 {
    let h = (wo + wi).normalize();
    charlie_d(h.z, alpha) / ((1.0 + o.lambda + i.lambda) * 4.0 * o.cos * i.cos)
}

/// One direction's part of V: its cosine, at least [`MIN_COSINE`], and
/// the fitted Λ there.
#[derive(Clone, Copy, Debug)]
pub(super) struct Shadowing {
    cos: f32,
    lambda: f32,
}

impl Shadowing {
    /// At cosine `cos` and α `alpha`.
    pub(super) fn at(cos: f32, alpha: f32) -> Self {
        let cos = cos.max(MIN_COSINE);
        Self {
            cos,
            lambda: charlie_lambda(cos, alpha),
        }
    }
}

/// The Charlie distribution D(h) = (2 + 1/α) sin(θh)^(1/α) / (2π), of the
/// cosine of the half vector.
pub(super) fn charlie_d(cos_h: f32, alpha: f32) -> f32 {
    let sin2 = (1.0 - cos_h * cos_h).max(0.0);
    (2.0 + 1.0 / alpha) * sin2.powf(0.5 / alpha) * (0.5 * FRAC_1_PI)
}

/// Estevez & Kulla's fitted Smith Λ at cosine `cos` (their curve L is
/// fitted for μ ≤ 0.5 and continued to normal incidence by the symmetric
/// form above it).
pub(super) fn charlie_lambda(cos: f32, alpha: f32) -> f32 {
    if cos < 0.5 {
        charlie_l(cos, alpha).exp()
    } else {
        (2.0 * charlie_l(0.5, alpha) - charlie_l(1.0 - cos, alpha)).exp()
    }
}

/// The fit's L(x) = a / (1 + b x^c) + d x + e, each coefficient
/// interpolated between its value at α = 1 and at α = 0 by (1 − α)².
fn charlie_l(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let lerp = |at_one: f32, at_zero: f32| at_one + (at_zero - at_one) * t;
    let a = lerp(21.5473, 25.3245);
    let b = lerp(3.82987, 3.32435);
    let c = lerp(0.19823, 0.16801);
    let d = lerp(-1.97760, -1.27393);
    let e = lerp(-4.32054, -4.85967);
    a / (1.0 + b * x.powf(c)) + d * x + e
}
