//! Rough dielectrics: reflection and refraction through a microfacet
//! interface (Walter, Marschner, Li & Torrance 2007, "Microfacet Models for
//! Refraction through Rough Surfaces").
//!
//! With η the relative IOR (far side over the side of `wo`: `ior` when `wo`
//! is outside, `1/ior` when inside) and m the microfacet normal (m.z > 0):
//! - reflection (`wi` on the side of `wo`): m ∝ wo + wi and
//!   f_r = R · F(wo·m) · D(m) · G2 / (4 |cos θo| |cos θi|);
//! - transmission: the generalised half vector m ∝ wo + η wi and
//!   f_t = T · (1 − F) · D(m) · G2 · |wo·m| |wi·m| / (|cos θo| |cos θi| (wo·m + η wi·m)²).
//!
//! F is the exact dielectric Fresnel term at the microfacet. f_t carries
//! the 1/η² radiance scaling of the module docs (Walter's η_o² numerator with
//! the light arriving along `wi`): radiance transport, the path traced from
//! the camera. It obeys the generalised reciprocity f_t(wo, wi)·η_wi² =
//! f_t(wi, wo)·η_wo², with η_w the absolute IOR on the side of w; an
//! adjoint (importance) transport would drop the 1/η². G2 = 1 / (1 + Λ(wo) +
//! Λ(wi)) is used for transmission too (as pbrt-v4 does): it is reciprocal
//! and at most G1, though Heitz 2014 derives a slightly different
//! height-correlated form for the two sides of the surface. The principled
//! BSDF asks for the separable G1(wo)·G1(wi) instead (`masking`), as
//! Mitsuba does.
//!
//! Sampling draws a normal visible from `wo` (viewed from `wo`'s side: the
//! distributions are point-symmetric, so `−wo` from above sees the same
//! statistics), reflects with probability F(wo·m) and refracts otherwise;
//! under total internal reflection at the microfacet F = 1 and it always
//! reflects. Samples whose direction lands on the wrong side of the macro
//! surface are rejected, and `pdf` accounts for that loss.

use glam::{Vec2, Vec3};

use super::distribution::{Masking, MicrofacetDistribution};
use super::fresnel::{fresnel_dielectric, refract};
use super::{BsdfFlags, BsdfSample};

/// The flags of both lobes.
pub(super) const FLAGS: BsdfFlags = BsdfFlags::REFLECTION
    .union(BsdfFlags::TRANSMISSION)
    .union(BsdfFlags::GLOSSY);

/// A rough dielectric interface, as [`super::Bsdf::RoughGlass`] describes it.
#[derive(Clone, Copy, Debug)]
pub(super) struct RoughDielectric {
    pub dist: MicrofacetDistribution,
    pub reflectance: Vec3,
    pub transmittance: Vec3,
    /// IOR of the inside (−Z) over the outside.
    pub ior: f32,
    /// How G2 combines the masking of the two directions.
    pub masking: Masking,
}

/// The microfacet normal that scatters `wo` into `wi`.
struct Configuration {
    /// The normal, on the outside (m.z > 0).
    m: Vec3,
    /// Whether `wi` is on the side of `wo`.
    reflect: bool,
    /// The relative IOR, far side over the side of `wo` (1 for reflection).
    eta: f32,
}

impl RoughDielectric {
    /// The relative IOR seen from `wo`'s side.
    fn eta_from(&self, wo: Vec3) -> f32 {
        if wo.z > 0.0 {
            self.ior
        } else {
            1.0 / self.ior
        }
    }

    /// The microfacet normal for the pair, or `None` when no microfacet
    /// facing both directions from their sides scatters one into the other.
    fn configuration(&self, wo: Vec3, wi: Vec3) -> Option<Configuration> {
        if wo.z == 0.0 || wi.z == 0.0 {
            return None;
        }
        let reflect = wo.z * wi.z > 0.0;
        let eta = if reflect { 1.0 } else { self.eta_from(wo) };
        let m = wo + eta * wi;
        if m.length_squared() <= 1e-12 {
            return None;
        }
        let m = m.normalize();
        let m = if m.z < 0.0 { -m } else { m };
        // Each direction must see the microfacet from its own side.
        if wo.dot(m) * wo.z <= 0.0 || wi.dot(m) * wi.z <= 0.0 {
            return None;
        }
        Some(Configuration { m, reflect, eta })
    }

    /// The BSDF value (cosine excluded).
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let Some(Configuration { m, reflect, eta }) = self.configuration(wo, wi) else {
            return Vec3::ZERO;
        };
        let (cos_om, cos_im) = (wo.dot(m), wi.dot(m));
        let fresnel = fresnel_dielectric(cos_om, self.ior);
        let dg = self.dist.d(m) * self.dist.masking(self.masking, wo, wi);
        let cosines = (wo.z * wi.z).abs();
        if reflect {
            self.reflectance * (fresnel * dg / (4.0 * cosines))
        } else {
            let denom = cos_om + eta * cos_im;
            let jacobian_terms = (cos_om * cos_im).abs() / (cosines * denom * denom);
            self.transmittance * ((1.0 - fresnel) * dg * jacobian_terms)
        }
    }

    /// The density of [`Self::sample`] per unit solid angle of `wi`.
    pub(super) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(Configuration { m, reflect, eta }) = self.configuration(wo, wi) else {
            return 0.0;
        };
        let view = wo * wo.z.signum();
        let normal_pdf = self.dist.visible_pdf(view, m);
        let (cos_om, cos_im) = (wo.dot(m), wi.dot(m));
        let fresnel = fresnel_dielectric(cos_om, self.ior);
        if reflect {
            fresnel * normal_pdf / (4.0 * cos_om.abs())
        } else {
            // dωm/dωi of the generalised half vector (Walter eq. 17).
            let denom = cos_om + eta * cos_im;
            (1.0 - fresnel) * normal_pdf * eta * eta * cos_im.abs() / (denom * denom)
        }
    }

    /// Samples a visible microfacet normal with `u2`, then reflection
    /// (`u1 < F`) or refraction through it.
    pub(super) fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let side = wo.z.signum();
        let m = self.dist.sample_visible_normal(wo * side, u2);
        let cos_om = wo.dot(m);
        if cos_om * side <= 0.0 {
            return None;
        }
        let fresnel = fresnel_dielectric(cos_om, self.ior);
        let wi = if u1 < fresnel {
            let wi = (2.0 * cos_om * m - wo).normalize();
            (wi.z * side > 0.0).then_some(wi)?
        } else {
            let wi = refract(wo, m * side, self.eta_from(wo))?;
            (wi.z * side < 0.0).then_some(wi)?
        };
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            flags: if wi.z * side > 0.0 {
                BsdfFlags::REFLECTION.union(BsdfFlags::GLOSSY)
            } else {
                BsdfFlags::TRANSMISSION.union(BsdfFlags::GLOSSY)
            },
        })
    }
}
