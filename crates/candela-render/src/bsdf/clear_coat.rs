//! `KHR_materials_clearcoat`'s coat on the glTF metallic-roughness BSDF
//! (`metallic_roughness/`, which layers it over its other lobes; see its
//! module docs for the whole model).
//!
//! The coat is a clear dielectric of IOR 1.5 (F0 = 0.04) on GGX microfacets
//! with α = roughness², strength c in [0, 1]: a specular lobe
//! c · S(wo·h) · D(h) · G2(wo, wi) / (4 cos θo cos θi) (Schlick's S at the
//! half vector, height-correlated Smith G2, as the base's specular layer),
//! a delta mirror of reflectance c · S(cos θo) at roughness 0. What it
//! reflects at `wo` is its directional albedo c · E(cos θo), the base
//! specular layer's table with (F0, F90) = (0.04, 1) (`specular_albedo.rs`,
//! the same lobe), exactly c · S(cos θo) for the smooth coat; the layers
//! beneath get the rest, 1 − c · E(cos θo). The values here are for a pair
//! already mirrored to the side where `wo.z > 0`
//! (`metallic_roughness::to_upper`): the coat is two-sided, as the opaque
//! lobes are.

use glam::{Vec2, Vec3};

use super::distribution::MicrofacetDistribution;
use super::microfacet;
use super::specular_albedo::SpecularAlbedo;
use super::BsdfFlags;

/// The coat's Fresnel at normal incidence: ((1.5 − 1)/(1.5 + 1))².
const F0: f32 = 0.04;

/// A clear coat: strength and perceptual roughness, both in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ClearCoat {
    factor: f32,
    roughness: f32,
}

impl ClearCoat {
    /// No coat (the extension's default strength 0).
    pub(super) const NONE: Self = Self {
        factor: 0.0,
        roughness: 0.0,
    };

    /// A coat of strength `factor` and perceptual `roughness`, each clamped
    /// to [0, 1] (NaN to 0, the extension's defaults).
    pub(super) fn new(factor: f32, roughness: f32) -> Self {
        let unit = |v: f32| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        Self {
            factor: unit(factor),
            roughness: unit(roughness),
        }
    }

    /// Strength and perceptual roughness.
    pub(super) fn parameters(&self) -> (f32, f32) {
        (self.factor, self.roughness)
    }

    /// Whether there is a coat at all; without one the BSDF skips every
    /// coat term, so it is exactly the uncoated model.
    pub(super) fn is_on(&self) -> bool {
        self.factor > 0.0
    }

    /// Whether the coat is a delta mirror (roughness 0).
    pub(super) fn is_smooth(&self) -> bool {
        self.roughness == 0.0
    }

    /// The coat lobe's flag.
    pub(super) fn flag(&self) -> BsdfFlags {
        if self.is_smooth() {
            BsdfFlags::SPECULAR
        } else {
            BsdfFlags::GLOSSY
        }
    }

    /// GGX with α = roughness².
    pub(super) fn distribution(&self) -> MicrofacetDistribution {
        MicrofacetDistribution::ggx(self.roughness * self.roughness)
    }

    /// c · S(cos): the smooth coat's reflectance at `cos`.
    pub(super) fn reflected(&self, cos: f32) -> f32 {
        let m = (1.0 - cos).clamp(0.0, 1.0);
        let m2 = m * m;
        self.factor * (F0 + (1.0 - F0) * m2 * m2 * m)
    }

    /// c · E(cos): the share of the light arriving along `cos` that the
    /// coat reflects (its directional albedo; exactly
    /// [`ClearCoat::reflected`] for the smooth coat).
    pub(super) fn albedo(&self, cos: f32) -> f32 {
        if self.is_smooth() {
            return self.reflected(cos);
        }
        let alpha = self.roughness * self.roughness;
        let [a, b] = SpecularAlbedo::get().split(cos, alpha);
        self.factor * (F0 * a + b)
    }

    /// What the coat leaves to the layers beneath it seen from `cos_o`:
    /// 1 − c E(cos θo). Taken at the viewing direction only, as the
    /// extension's `fresnel_coat` and Blender Cycles' coat do, so a coat
    /// over a base of albedo a at `wo` reflects exactly c E + (1 − c E) a.
    pub(super) fn base_weight(&self, cos_o: f32) -> f32 {
        1.0 - self.albedo(cos_o)
    }

    /// The rough coat's value for an upper pair (0 for a smooth coat, whose
    /// delta lobe is only sampled, and below the surface).
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> f32 {
        if self.is_smooth() || wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize();
        let dist = self.distribution();
        self.reflected(wo.dot(h)) * dist.d(h) * dist.g2(wo, wi) / (4.0 * wo.z * wi.z)
    }

    /// The density of [`ClearCoat::sample`] (0 for a smooth coat).
    pub(super) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if self.is_smooth() {
            return 0.0;
        }
        microfacet::pdf(self.distribution(), wo, wi)
    }

    /// A direction reflected about a visible GGX normal (rough coat).
    pub(super) fn sample(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        microfacet::sample_reflection(self.distribution(), wo, u)
    }
}
