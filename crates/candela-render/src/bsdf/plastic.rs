//! Smooth plastic: a diffuse base under a smooth dielectric coating, with
//! Mitsuba's `plastic` semantics (Weidlich & Wilkie 2007, "Arbitrarily
//! Layered Micro-Facet Surfaces", in its smooth-coating limit).
//!
//! Light either reflects specularly off the coating (Fresnel F(cos θo)), or
//! enters it, scatters diffusely off the base of albedo ρ, and leaves:
//!
//! f_diffuse(wo, wi) = (1 − F(cos θo)) (1 − F(cos θi)) ρ / (π η² (1 − ρ F_dr)),
//!
//! η the coating's IOR. The 1/η² is the radiance change on leaving the
//! denser coating. The *internal-scattering renormalisation* 1 / (1 − ρ F_dr)
//! sums the light the coating reflects back onto the base from inside,
//! again and again: F_dr = ∫ F_inside(μ) 2μ dμ is the coating's internal
//! reflectance of diffuse light (about 0.596 for η = 1.5, mostly total
//! internal reflection), and each round trip keeps ρ·F_dr of it:
//! Σₖ (ρ F_dr)ᵏ = 1 / (1 − ρ F_dr). With ρ = 1 the albedo is then exactly
//! F(cos θo) + (1 − F(cos θo)) = 1, because η² (1 − F_dr) equals the
//! outside diffuse transmittance ∫ (1 − F(μ)) 2μ dμ.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_dielectric;
use super::specular::{delta_sample, reflect_local, MIRROR_FLAGS};
use super::{diffuse, same_hemisphere, BsdfFlags, BsdfSample};
use crate::sampling::warp::square_to_cosine_hemisphere;

/// The lobes' flags: a diffuse and a delta reflection.
pub(super) const FLAGS: BsdfFlags = diffuse::FLAGS.union(MIRROR_FLAGS);

/// A smooth plastic's parameters, with the coating's internal diffuse
/// reflectance computed once from its IOR.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    diffuse: Vec3,
    specular: Vec3,
    ior: f32,
    internal_reflectance: f32,
    specular_weight: f32,
    linear: bool,
}

impl Plastic {
    /// A base of albedo `diffuse` (clamped to [0, 1]) under a coating of
    /// IOR `ior` (relative to the outside) whose specular reflection is
    /// tinted by `specular`.
    pub fn new(diffuse: Vec3, specular: Vec3, ior: f32) -> Self {
        let diffuse = diffuse.clamp(Vec3::ZERO, Vec3::ONE);
        let (d, s) = (diffuse.element_sum(), specular.element_sum());
        Self {
            diffuse,
            specular,
            ior,
            internal_reflectance: diffuse_fresnel_reflectance(1.0 / ior),
            // Mitsuba's choice: share samples between the lobes by their
            // mean tints (then by Fresnel, per direction).
            specular_weight: if d + s > 0.0 { s / (d + s) } else { 0.5 },
            linear: false,
        }
    }

    /// Mitsuba's `nonlinear` switch: `true` (what [`Self::new`] makes) keeps
    /// the physical renormalisation ρ/(1 − ρ F_dr); `false`, Mitsuba's
    /// default, uses ρ/(1 − F_dr), linear in ρ so that textures keep their
    /// colours, equal at ρ = 1 and brighter below (still at most 1, being
    /// linear in ρ).
    pub fn with_nonlinear(self, nonlinear: bool) -> Self {
        Self {
            linear: !nonlinear,
            ..self
        }
    }

    /// The base's albedo (what one mostly sees).
    pub fn diffuse(&self) -> Vec3 {
        self.diffuse
    }

    /// The same coating over another base (a colour texture).
    pub fn with_diffuse(&self, diffuse: Vec3) -> Self {
        Self {
            linear: self.linear,
            ..Self::new(diffuse, self.specular, self.ior)
        }
    }

    /// The probability of sampling the specular lobe from `wo`.
    fn specular_probability(&self, cos_o: f32) -> f32 {
        let fresnel = fresnel_dielectric(cos_o.abs(), self.ior);
        let specular = fresnel * self.specular_weight;
        let diffuse = (1.0 - fresnel) * (1.0 - self.specular_weight);
        if specular + diffuse > 0.0 {
            specular / (specular + diffuse)
        } else {
            0.0
        }
    }

    /// The diffuse lobe (cosine excluded); the specular one is a delta.
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if !same_hemisphere(wo, wi) {
            return Vec3::ZERO;
        }
        let transmitted = (1.0 - fresnel_dielectric(wo.z.abs(), self.ior))
            * (1.0 - fresnel_dielectric(wi.z.abs(), self.ior));
        let kept = if self.linear { Vec3::ONE } else { self.diffuse };
        let renormalised = self.diffuse / (Vec3::ONE - self.internal_reflectance * kept);
        renormalised * (transmitted * FRAC_1_PI / (self.ior * self.ior))
    }

    /// The density of the diffuse samples.
    pub(super) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !same_hemisphere(wo, wi) {
            return 0.0;
        }
        (1.0 - self.specular_probability(wo.z)) * wi.z.abs() * FRAC_1_PI
    }

    /// Specular reflection with probability `specular_probability` (chosen
    /// by `u1`), else a cosine-distributed direction on the side of `wo`.
    pub(super) fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let p_specular = self.specular_probability(wo.z);
        if u1 < p_specular {
            let fresnel = fresnel_dielectric(wo.z.abs(), self.ior);
            let weight = self.specular * (fresnel / p_specular);
            return delta_sample(reflect_local(wo), weight, p_specular, MIRROR_FLAGS);
        }
        let mut wi = square_to_cosine_hemisphere(u2);
        if wo.z < 0.0 {
            wi.z = -wi.z;
        }
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            flags: diffuse::FLAGS,
        })
    }
}

/// ∫₀¹ F(μ) 2μ dμ: the reflectance of an interface of relative IOR `eta`
/// (far side over near side) for diffuse light from the near side. Total
/// internal reflection (F = 1 below μc = √(1 − η²) when η < 1) is
/// integrated exactly, the smooth rest by Simpson's rule.
pub(crate) fn diffuse_fresnel_reflectance(eta: f32) -> f32 {
    let critical = if eta < 1.0 {
        f64::from((1.0 - eta * eta).sqrt())
    } else {
        0.0
    };
    let g = |mu: f64| f64::from(fresnel_dielectric(mu as f32, eta)) * 2.0 * mu;
    let n = 512;
    let h = (1.0 - critical) / n as f64;
    let simpson: f64 = (0..n)
        .map(|i| {
            let a = critical + i as f64 * h;
            h / 6.0 * (g(a) + 4.0 * g(a + h / 2.0) + g(a + h))
        })
        .sum();
    (critical * critical + simpson) as f32
}
