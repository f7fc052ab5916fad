//! The principled BSDF's clearcoat: a second, untinted specular lobe on
//! Burley's GTR1 ("generalized Trowbridge-Reitz", γ = 1) distribution,
//! D(m) = (α² − 1) / (π ln(α²) (1 + (α² − 1) cos²θm)), whose long tail
//! gives a coat's haze; α = lerp(0.1, 0.001, clearcoat_gloss); Schlick's
//! Fresnel with F0 = 0.04; separable Smith GGX masking of fixed α = 0.25.
//!
//! As in Mitsuba's `principled`, the value is 0.25 · clearcoat · F D G
//! *without* the 1/(4 cos θo cos θi) of a microfacet BRDF (Burley's
//! `smithG_GGX` carries those cosines; Mitsuba's G1 does not, and its code
//! does not add them): the lobe is dimmer than Burley's, by 4 cos θo cos θi.
//! We keep Mitsuba's definition, so its scenes render as there.
//!
//! Sampling draws m with density D(m) cos θm (no visible-normal sampling:
//! GTR1 has none in closed form, and the lobe is weak) and reflects.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::super::distribution::MicrofacetDistribution;
use super::fresnel::schlick;
use crate::sampling::warp::sin_cos_turns;

/// The α of the coat's masking term.
const MASKING_ALPHA: f32 = 0.25;
/// The coat's normal-incidence reflectance (IOR 1.5).
const F0: f32 = 0.04;

/// The GTR1 distribution of the coat's normals.
#[derive(Clone, Copy, Debug)]
pub(super) struct Gtr1 {
    alpha: f32,
}

impl Gtr1 {
    /// The coat of the given gloss in [0, 1]: α from 0.1 down to 0.001.
    pub(super) fn of_gloss(gloss: f32) -> Self {
        Self {
            alpha: 0.1 + gloss * (0.001 - 0.1),
        }
    }

    /// D(m); zero below the horizon.
    pub(super) fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z))
    }

    /// A normal with density D(m) cos θm.
    pub(super) fn sample(&self, u: Vec2) -> Vec3 {
        let a2 = self.alpha * self.alpha;
        let cos2 = ((1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2)).clamp(0.0, 1.0);
        let (sin_phi, cos_phi) = sin_cos_turns(u.x);
        let sin = (1.0 - cos2).sqrt();
        Vec3::new(cos_phi * sin, sin_phi * sin, cos2.sqrt())
    }

    /// The density of [`Gtr1::sample`].
    pub(super) fn pdf(&self, m: Vec3) -> f32 {
        self.d(m) * m.z.max(0.0)
    }
}

/// The coat's value (cosine excluded) for the pair (both above, `h` their
/// half vector), of strength `clearcoat`, on an interface of relative IOR
/// `eta` (for Schlick's rule below 1).
pub(super) fn f(clearcoat: f32, gloss: f32, eta: f32, wo: Vec3, wi: Vec3, h: Vec3) -> f32 {
    let fresnel = schlick(Vec3::splat(F0), wo.dot(h), eta).x;
    let masking = MicrofacetDistribution::ggx(MASKING_ALPHA);
    let g = masking.g1(wo) * masking.g1(wi);
    0.25 * clearcoat * fresnel * Gtr1::of_gloss(gloss).d(h) * g
}

/// The density of sampling `wi` by reflecting `wo` about a GTR1 normal.
pub(super) fn pdf(gloss: f32, wi: Vec3, h: Vec3) -> f32 {
    Gtr1::of_gloss(gloss).pdf(h) / (4.0 * wi.dot(h).abs())
}

/// `wo` reflected about a sampled coat normal; `None` below the surface.
pub(super) fn sample(gloss: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let m = Gtr1::of_gloss(gloss).sample(u);
    let cos = wo.dot(m);
    if cos <= 0.0 {
        return None;
    }
    let wi = (2.0 * cos * m - wo).normalize();
    (wi.z > 0.0).then_some(wi)
}
