//! Rough conductors: the Cook-Torrance microfacet model on a Beckmann or
//! GGX distribution (see `distribution.rs`).
//!
//! f(wo, wi) = D(h) · G2(wo, wi) · F(wo·h) / (4 cos θo cos θi), with D the
//! distribution of normals, G2 the Smith masking-shadowing (height-correlated,
//! or separable G1·G1 where the scene's renderer uses it: `Masking`), and F
//! the exact conductor Fresnel term per channel.
//!
//! Sampling draws a normal visible from `wo` and reflects `wo` about it,
//! giving the density G1(wo)·D(h) / (4 cos θo). Reflections that go below
//! the surface are rejected (`None`); `pdf` accounts for that loss, so the
//! density integrates to less than 1 at grazing angles.

use glam::{Vec2, Vec3};

use super::distribution::{Masking, MicrofacetDistribution};
use super::fresnel::fresnel_conductor;
use super::{BsdfFlags, BsdfSample};

/// The lobe's flags.
pub(super) const FLAGS: BsdfFlags = BsdfFlags::REFLECTION.union(BsdfFlags::GLOSSY);

/// Mirrors the pair to the side where `wo.z > 0` (two-sided shading);
/// returns the flipped pair and the sign to restore.
pub(super) fn to_upper(wo: Vec3, wi: Vec3) -> (Vec3, Vec3, f32) {
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
pub(super) fn f(
    dist: MicrofacetDistribution,
    masking: Masking,
    eta: Vec3,
    k: Vec3,
    wo: Vec3,
    wi: Vec3,
) -> Vec3 {
    let (wo, wi, _) = to_upper(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (wo + wi).normalize();
    let scalar = dist.d(h) * dist.masking(masking, wo, wi) / (4.0 * wo.z * wi.z);
    fresnel_conductor(wo.dot(h), eta, k) * scalar
}

/// The density of [`sample`] per unit solid angle of `wi`: the visible
/// normal density times the reflection Jacobian 1 / (4 wo·h).
pub(super) fn pdf(dist: MicrofacetDistribution, wo: Vec3, wi: Vec3) -> f32 {
    let (wo, wi, _) = to_upper(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let h = (wo + wi).normalize();
    dist.d(h) * dist.g1(wo) / (4.0 * wo.z)
}

/// Samples a visible normal and reflects `wo` about it.
pub(super) fn sample(
    dist: MicrofacetDistribution,
    masking: Masking,
    eta: Vec3,
    k: Vec3,
    wo: Vec3,
    u: Vec2,
) -> Option<BsdfSample> {
    let wi = sample_reflection(dist, wo, u)?;
    let pdf = pdf(dist, wo, wi);
    (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
        wi,
        f: f(dist, masking, eta, k, wo, wi),
        pdf,
        flags: FLAGS,
    })
}

/// A direction reflected about a normal visible from `wo` (either side, the
/// result on the side of `wo`), with density [`pdf`]; `None` when the
/// reflection goes below the surface (the density accounts for that loss).
pub(super) fn sample_reflection(dist: MicrofacetDistribution, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let (up, _, sign) = to_upper(wo, Vec3::Z);
    if up.z <= 0.0 {
        return None;
    }
    let h = dist.sample_visible_normal(up, u);
    let cos_oh = up.dot(h);
    if cos_oh <= 0.0 {
        return None;
    }
    let wi_up = (2.0 * cos_oh * h - up).normalize();
    (wi_up.z > 0.0).then(|| Vec3::new(wi_up.x, wi_up.y, sign * wi_up.z))
}
