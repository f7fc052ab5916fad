//! Rough plastic: a diffuse base under a rough dielectric coating, with
//! Mitsuba 3's `roughplastic` semantics (Weidlich & Wilkie 2007,
//! "Arbitrarily Layered Micro-Facet Surfaces"; the smooth limit is
//! `plastic.rs`).
//!
//! f = f_coat + f_base, cosine excluded, both directions on one side:
//! - f_coat(wo, wi) = s · F(wo·h) D(h) G2(wo, wi) / (4 cos θo cos θi): the
//!   coating's microfacet reflection (h the half vector, F the exact
//!   dielectric Fresnel term, G2 the Smith masking-shadowing, combined as
//!   the description's `Masking` says: height-correlated by default,
//!   separable G1·G1 for Mitsuba's scenes, a difference of a few percent at
//!   grazing angles; the coating's table follows the same choice);
//! - f_base(wo, wi) = ρ' T(cos θo) T(cos θi) / (π η²): light that the
//!   coating lets in (T the energy of the rough dielectric's refraction
//!   lobe, see `coating.rs`), scattered by the base, let out again; 1/η² is
//!   the radiance change on leaving the denser coating;
//! - ρ' = ρ / (1 − ρ F_int) (`nonlinear`) or ρ / (1 − F_int) (Mitsuba's
//!   default): the sum of the round trips between base and coating, F_int
//!   the coating's internal albedo for diffuse light. The nonlinear form is
//!   the physical one (each round trip keeps ρ F_int); the default keeps f
//!   linear in ρ, so textures keep their colours, and reflects more than
//!   the physical sum for 0 < ρ < 1 (1 − F_int ≤ 1 − ρ F_int). The two agree
//!   at ρ = 1, where the albedo is bounded as below, and the default is
//!   linear in ρ, so its albedo stays ≤ 1 too. F_int is the integral by
//!   default, or Mitsuba's coarser mean (`InternalReflectance`), which is
//!   about 1.5% lower and so makes the base about 2% darker.
//!
//! # Energy
//! At ρ = 1 the directional albedo is
//! E(μo) + T(μo) · T̄ / (η² (1 − F_int)), with T̄ = 2∫T(μ)μ dμ the
//! coating's transmittance for diffuse light from outside. For a smooth
//! coating T = 1 − F and the fraction is exactly 1 (reciprocity: the diffuse
//! transmittances of the two sides differ by η²), so the white plastic
//! reflects everything. A rough coating loses energy to single-scattering
//! masking on the way in, on the way out, and in its internal reflections
//! (which lowers F_int): the albedo is below 1, by a few percent at α = 0.1
//! and by up to half at α = 1 (`rough_plastic_tests.rs` prints the curve).
//! This is Mitsuba 3's model and its loss; we keep it, rather than forcing
//! F_int = 1 − T̄/η² (which would make the white plastic white), so that
//! scenes render as in Mitsuba. The model is reciprocal: both terms are
//! symmetric in (wo, wi).
//!
//! # Sampling
//! The coating's lobe by visible normals with probability
//! p = (1 − T(μo)) s̄ / ((1 − T(μo)) s̄ + T(μo)(1 − s̄)), s̄ = mean(s) /
//! (mean(s) + mean(ρ)) (Mitsuba's weights), the base's by the cosine
//! otherwise; `pdf` is the mixture. Two-sided like every opaque BSDF here.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::coating::{coating_table, CoatingTable, InternalReflectance};
use super::distribution::{Masking, MicrofacetDistribution};
use super::fresnel::fresnel_dielectric;
use super::microfacet::to_upper;
use super::{diffuse, BsdfFlags, BsdfSample};
use crate::sampling::warp::square_to_cosine_hemisphere;

/// The coating's glossy lobe.
const COATING_FLAGS: BsdfFlags = BsdfFlags::REFLECTION.union(BsdfFlags::GLOSSY);
/// Both lobes.
pub(super) const FLAGS: BsdfFlags = COATING_FLAGS.union(diffuse::FLAGS);

/// A rough plastic's parameters, with its coating's table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughPlastic {
    dist: MicrofacetDistribution,
    masking: Masking,
    internal: InternalReflectance,
    diffuse: Vec3,
    specular: Vec3,
    ior: f32,
    /// ρ' / (π η²): the base lobe without its two transmittances.
    base_scale: Vec3,
    specular_weight: f32,
    nonlinear: bool,
    coating: &'static CoatingTable,
}

impl RoughPlastic {
    /// A base of albedo `diffuse` (clamped to [0, 1]) under a rough coating
    /// of distribution `dist` and IOR `ior` (relative to the outside, > 0),
    /// its reflection tinted by `specular`; `nonlinear` as in the module
    /// docs. The coating's table is computed on the first use of (dist, ior).
    pub fn new(
        dist: MicrofacetDistribution,
        diffuse: Vec3,
        specular: Vec3,
        ior: f32,
        nonlinear: bool,
    ) -> Self {
        Self::with_conventions(
            dist,
            Masking::HeightCorrelated,
            InternalReflectance::Integral,
            diffuse,
            specular,
            ior,
            nonlinear,
        )
    }

    /// [`RoughPlastic::new`] with the coating's masking combined as
    /// `masking` says (in its lobe and its table) and F_int averaged as
    /// `internal` says.
    pub fn with_conventions(
        dist: MicrofacetDistribution,
        masking: Masking,
        internal: InternalReflectance,
        diffuse: Vec3,
        specular: Vec3,
        ior: f32,
        nonlinear: bool,
    ) -> Self {
        let diffuse = diffuse.clamp(Vec3::ZERO, Vec3::ONE);
        let coating = coating_table(dist, masking, internal, ior);
        let f_int = coating.internal_reflectance();
        let round_trips = if nonlinear {
            Vec3::ONE - f_int * diffuse
        } else {
            Vec3::splat(1.0 - f_int)
        };
        let base_scale = diffuse / round_trips.max(Vec3::splat(1e-6)) * (FRAC_1_PI / (ior * ior));
        let (d, s) = (diffuse.element_sum(), specular.element_sum());
        Self {
            dist,
            masking,
            internal,
            diffuse,
            specular,
            ior,
            base_scale,
            specular_weight: if d + s > 0.0 { s / (d + s) } else { 0.5 },
            nonlinear,
            coating,
        }
    }

    /// The same coating, conventions included, over another base (a colour
    /// texture).
    pub fn with_diffuse(&self, diffuse: Vec3) -> Self {
        Self::with_conventions(
            self.dist,
            self.masking,
            self.internal,
            diffuse,
            self.specular,
            self.ior,
            self.nonlinear,
        )
    }

    /// The base's albedo (what one mostly sees).
    pub fn diffuse(&self) -> Vec3 {
        self.diffuse
    }

    /// The probability of sampling the coating's lobe from `wo` (upper side).
    fn coating_probability(&self, cos_o: f32) -> f32 {
        let t = self.coating.transmittance(cos_o);
        let coat = (1.0 - t) * self.specular_weight;
        let base = t * (1.0 - self.specular_weight);
        if coat + base > 0.0 {
            coat / (coat + base)
        } else {
            0.0
        }
    }

    /// f (cosine excluded).
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let (wo, wi, _) = to_upper(wo, wi);
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        let h = (wo + wi).normalize();
        let coat = fresnel_dielectric(wo.dot(h), self.ior)
            * self.dist.d(h)
            * self.dist.masking(self.masking, wo, wi)
            / (4.0 * wo.z * wi.z);
        let base = self.coating.transmittance(wo.z) * self.coating.transmittance(wi.z);
        self.specular * coat + self.base_scale * base
    }

    /// The density of [`Self::sample`].
    pub(super) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (wo, wi, _) = to_upper(wo, wi);
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let p = self.coating_probability(wo.z);
        let h = (wo + wi).normalize();
        let coat = self.dist.d(h) * self.dist.g1(wo) / (4.0 * wo.z);
        p * coat + (1.0 - p) * wi.z * FRAC_1_PI
    }

    /// The coating's lobe (`u1 < p`) or the base's.
    pub(super) fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let (up, _, sign) = to_upper(wo, Vec3::Z);
        if up.z <= 0.0 {
            return None;
        }
        let p = self.coating_probability(up.z);
        let (wi_up, flags) = if u1 < p {
            let m = self.dist.sample_visible_normal(up, u2);
            let cos_om = up.dot(m);
            if cos_om <= 0.0 {
                return None;
            }
            ((2.0 * cos_om * m - up).normalize(), COATING_FLAGS)
        } else {
            (square_to_cosine_hemisphere(u2), diffuse::FLAGS)
        };
        if wi_up.z <= 0.0 {
            return None;
        }
        let wi = Vec3::new(wi_up.x, wi_up.y, sign * wi_up.z);
        let pdf = self.pdf(wo, wi);
        (pdf > 0.0 && pdf.is_finite()).then(|| BsdfSample {
            wi,
            f: self.f(wo, wi),
            pdf,
            flags,
        })
    }
}
