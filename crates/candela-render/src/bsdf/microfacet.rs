//! Rough conductors: the Beckmann microfacet model.
//!
//! f(wo, wi) = D(h) · G2(wo, wi) · F(wo·h) / (4 cos θo cos θi), with
//! - D the Beckmann distribution of normals, slope variance α²/2;
//! - G2 the *height-correlated* Smith masking-shadowing term
//!   1 / (1 + Λ(wo) + Λ(wi)) (Heitz 2014, "Understanding the
//!   Masking-Shadowing Function"), which, unlike the separable product
//!   G1·G1, does not double-count shadowing by the same heights;
//! - F the exact conductor Fresnel term per channel.
//!
//! Sampling draws a normal from the distribution of normals visible from
//! `wo` (Heitz & d'Eon 2014, see `visible_normals.rs`) and reflects `wo`
//! about it, giving the density G1(wo)·D(h) / (4 cos θo). Reflections that
//! go below the surface are rejected (`None`); `pdf` accounts for that
//! loss, so the density integrates to less than 1 at grazing angles.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_conductor;
use super::special::erfc;
use super::visible_normals::sample_visible_normal;
use super::{BsdfFlags, BsdfSample};

/// The lobe's flags.
pub(super) const FLAGS: BsdfFlags = BsdfFlags::REFLECTION.union(BsdfFlags::GLOSSY);

/// Roughness below this is clamped: a smaller α makes D overflow `f32`
/// and the lobe is indistinguishable from a mirror anyway.
pub(crate) const MIN_ALPHA: f32 = 1e-3;

/// The Beckmann distribution of microfacet normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Beckmann {
    alpha: f32,
}

impl Beckmann {
    /// The distribution of roughness α, whose RMS microfacet slope is α
    /// (α/√2 per axis); clamped to [`MIN_ALPHA`].
    pub(crate) fn new(alpha: f32) -> Self {
        Self {
            alpha: alpha.max(MIN_ALPHA),
        }
    }

    /// D(h): microfacet area per unit solid angle of normals, per unit
    /// macro-surface area; ∫ D(h) cos θh dωh = 1.
    pub(crate) fn d(&self, h: Vec3) -> f32 {
        let cos2 = h.z * h.z;
        if h.z <= 0.0 || cos2 == 0.0 {
            return 0.0;
        }
        let tan2 = (1.0 - cos2).max(0.0) / cos2;
        let a2 = self.alpha * self.alpha;
        let exponent = tan2 / a2;
        // Beyond e^-80 the density is zero in f32 anyway, and cos⁴ may
        // have underflowed, which would turn 0/0 into NaN.
        if exponent > 80.0 {
            return 0.0;
        }
        (-exponent).exp() / (PI * a2 * cos2 * cos2)
    }

    /// Smith's Λ(w) for Beckmann: with a = 1 / (α tan θ),
    /// Λ = (exp(−a²) / (a√π) − erfc(a)) / 2, written with erfc so that it
    /// stays accurate as both terms vanish for steep slopes.
    pub(crate) fn lambda(&self, w: Vec3) -> f32 {
        let cos = f64::from(w.z.abs());
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        if sin == 0.0 {
            return 0.0;
        }
        if cos == 0.0 {
            return f32::INFINITY;
        }
        let a = cos / (f64::from(self.alpha) * sin);
        if a > 30.0 {
            return 0.0;
        }
        let value = ((-a * a).exp() / (a * std::f64::consts::PI.sqrt()) - erfc(a)) / 2.0;
        value.max(0.0) as f32
    }

    /// Height-correlated masking-shadowing G2(wo, wi).
    pub(crate) fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }
}

/// Mirrors the pair to the side where `wo.z > 0` (two-sided shading);
/// returns the flipped pair and the sign to restore.
fn to_upper(wo: Vec3, wi: Vec3) -> (Vec3, Vec3, f32) {
    if wo.z < 0.0 {
        (
            Vec3::new(wo.x, wo.y, -wo.z),
            Vec3::new(wi.x, wi.y, -wi.z),
            -1.0,
        )
    } else {
        (wo, wi, 1.0)
    }
}

/// The rough conductor BSDF value (cosine excluded).
pub(super) fn f(alpha: f32, eta: Vec3, k: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    let (wo, wi, _) = to_upper(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (wo + wi).normalize();
    let dist = Beckmann::new(alpha);
    let scalar = dist.d(h) * dist.g2(wo, wi) / (4.0 * wo.z * wi.z);
    fresnel_conductor(wo.dot(h), eta, k) * scalar
}

/// The density of [`sample`] per unit solid angle of `wi`.
pub(super) fn pdf(alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    let (wo, wi, _) = to_upper(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let h = (wo + wi).normalize();
    let dist = Beckmann::new(alpha);
    dist.d(h) / ((1.0 + dist.lambda(wo)) * 4.0 * wo.z)
}

/// Samples a visible normal and reflects `wo` about it.
pub(super) fn sample(alpha: f32, eta: Vec3, k: Vec3, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
    let (up, _, sign) = to_upper(wo, Vec3::Z);
    if up.z <= 0.0 {
        return None;
    }
    let h = sample_visible_normal(Beckmann::new(alpha).alpha, up, u);
    let cos_oh = up.dot(h);
    if cos_oh <= 0.0 {
        return None;
    }
    let wi_up = (2.0 * cos_oh * h - up).normalize();
    if wi_up.z <= 0.0 {
        return None;
    }
    let wi = Vec3::new(wi_up.x, wi_up.y, sign * wi_up.z);
    let pdf = pdf(alpha, wo, wi);
    (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
        wi,
        f: f(alpha, eta, k, wo, wi),
        pdf,
        flags: FLAGS,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::integrate_2d;

    #[test]
    fn beckmann_projected_area_is_one() {
        for alpha in [0.05f32, 0.3, 1.0] {
            let dist = Beckmann::new(alpha);
            let area = integrate_2d(
                |theta, phi| {
                    let (s, c) = (theta.sin(), theta.cos());
                    let h = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32);
                    f64::from(dist.d(h)) * c * s
                },
                (0.0, std::f64::consts::FRAC_PI_2),
                (0.0, 2.0 * std::f64::consts::PI),
            );
            assert!((area - 1.0).abs() < 1e-3, "α = {alpha}: {area}");
        }
    }

    #[test]
    fn smith_lambda_satisfies_the_masking_identity() {
        // Projected visible microfacet area equals the projected macro area:
        // ∫ G1(w) max(0, w·h) D(h) dωh = cos θ, with G1 = 1 / (1 + Λ).
        for alpha in [0.1f32, 0.5, 1.0] {
            let dist = Beckmann::new(alpha);
            for theta_o in [0.0f32, 0.7, 1.3, 1.5] {
                let w = Vec3::new(theta_o.sin(), 0.0, theta_o.cos());
                let visible = integrate_2d(
                    |theta, phi| {
                        let (s, c) = (theta.sin(), theta.cos());
                        let h = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32);
                        f64::from(dist.d(h) * w.dot(h).max(0.0)) * s
                    },
                    (0.0, std::f64::consts::FRAC_PI_2),
                    (0.0, 2.0 * std::f64::consts::PI),
                );
                let g1 = 1.0 / (1.0 + f64::from(dist.lambda(w)));
                let lhs = g1 * visible;
                assert!(
                    (lhs - f64::from(w.z)).abs() < 2e-3,
                    "α = {alpha}, θ = {theta_o}: {lhs} vs {}",
                    w.z
                );
            }
        }
    }
}
