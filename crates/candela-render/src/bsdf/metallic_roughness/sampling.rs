//! Sampling the glTF metallic-roughness BSDF (`mod.rs` has the model and,
//! in its module docs, how a lobe is chosen): the lobe probabilities at
//! `wo`, the exact mixture density, and the sample with the whole
//! mixture's value.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::super::fresnel::fresnel_dielectric;
use super::super::microfacet;
use super::super::specular::{
    delta_sample, reflect_local, refract_local, MIRROR_FLAGS, REFRACTION_FLAGS,
};
use super::super::{BsdfFlags, BsdfSample};
use super::{luminance, schlick_weight, to_upper, MetallicRoughness};
use crate::sampling::warp::square_to_cosine_hemisphere;

/// Lobe selection probabilities of the base at one `wo`, and their
/// approximate albedo before normalisation (to weigh the sheen and the
/// coat against).
struct LobeChoice {
    specular: f32,
    diffuse: f32,
    glass: f32,
    total: f32,
}

/// What lies under the coat at one `wo`: the base's lobe choice (`None`
/// when the base scatters nothing), the probability of the sheen lobe
/// against it, and their approximate albedo (to weigh the coat against).
struct UnderCoat {
    base: Option<LobeChoice>,
    sheen: f32,
    total: f32,
}

impl MetallicRoughness {
    /// The lobe probabilities at `wo`; `None` when nothing scatters.
    fn choice(&self, wo: Vec3) -> Option<LobeChoice> {
        let s5 = schlick_weight(wo.z.abs());
        let fd = self.dielectric_schlick(s5);
        let w = self.opaque_dielectric_weight();
        let specular = self.metallic * luminance(self.metal_schlick(s5)) + w * luminance(fd);
        let mut diffuse = w * luminance((Vec3::ONE - fd) * self.base_color);
        if self.metallic > 0.0 && !self.is_smooth() {
            // The metal's multiple scattering, sampled with the Lambert
            // base (both cosine-weighted): its albedo F_ms (1 − E(cos θo)).
            let ms = self.metal_multiple_scattering(wo.z.abs());
            diffuse += self.metallic * luminance(ms.color) * ms.lost;
        }
        let glass = self.glass_weight();
        let total = specular + diffuse + glass;
        (total > 0.0 && total.is_finite()).then(|| LobeChoice {
            specular: specular / total,
            diffuse: diffuse / total,
            glass: glass / total,
            total,
        })
    }

    /// The layers under the coat at `wo`: the base's lobe choice and, with
    /// a sheen, the sheen's probability against the base, whose weight the
    /// sheen dims to 1 − max(c) E(cos θo) (see `sheen.rs`). Without a sheen
    /// it is the base alone.
    fn under_coat(&self, wo: Vec3) -> UnderCoat {
        let base = self.choice(wo);
        let base_total = base.as_ref().map_or(0.0, |c| c.total);
        let (sheen, total) = if self.sheen.is_on() {
            self.sheen_share(wo.z.abs(), base_total)
        } else {
            (0.0, base_total)
        };
        UnderCoat { base, sheen, total }
    }

    /// The sheen's probability against the base's lobes (their approximate
    /// albedo `base_total`) at cosine `cos`, and the two's approximate
    /// albedo. Out of line, as `under_sheen` (`mod.rs`).
    #[inline(never)]
    fn sheen_share(&self, cos: f32, base_total: f32) -> (f32, f32) {
        let sheen = luminance(self.sheen.parameters().0) * self.sheen.albedo(cos);
        let total = sheen + self.sheen.base_weight(cos, cos) * base_total;
        (if total > 0.0 { sheen / total } else { 0.0 }, total)
    }

    /// The probability of sampling the coat at `wo`: its albedo c E(cos θo)
    /// against what it leaves to the layers beneath (their approximate
    /// albedo `under.total`); 0 without a coat.
    fn coat_probability(&self, wo: Vec3, under: &UnderCoat) -> f32 {
        if !self.coat.is_on() {
            return 0.0;
        }
        let coat = self.coat.albedo(wo.z.abs());
        let rest = (1.0 - coat) * under.total;
        coat / (coat + rest)
    }

    /// The density of [`MetallicRoughness::sample`] per unit solid angle.
    pub(in crate::bsdf) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let under = self.under_coat(wo);
        let coat = self.coat_probability(wo, &under);
        let base = under
            .base
            .as_ref()
            .map_or(0.0, |c| self.base_pdf(c, wo, wi));
        if coat == 0.0 && under.sheen == 0.0 {
            return base;
        }
        let (up_o, up_i) = to_upper(wo, wi);
        let below = if under.sheen > 0.0 {
            (1.0 - under.sheen) * base + under.sheen * up_i.z.max(0.0) * FRAC_1_PI
        } else {
            base
        };
        if coat == 0.0 {
            return below;
        }
        (1.0 - coat) * below + coat * self.coat.pdf(up_o, up_i)
    }

    /// The base lobes' density, chosen as `c` says.
    fn base_pdf(&self, c: &LobeChoice, wo: Vec3, wi: Vec3) -> f32 {
        let glass = if c.glass > 0.0 && !self.is_smooth() {
            c.glass * self.glass().pdf(wo, wi)
        } else {
            0.0
        };
        let (up_o, up_i) = to_upper(wo, wi);
        if up_o.z <= 0.0 || up_i.z <= 0.0 {
            return glass;
        }
        let diffuse = glass + c.diffuse * up_i.z * FRAC_1_PI;
        if self.is_smooth() || c.specular <= 0.0 {
            return diffuse;
        }
        diffuse + c.specular * microfacet::pdf(self.distribution(), wo, wi)
    }

    /// Picks a lobe with `u1`, samples it with `u2` (the glass reuses the
    /// rest of `u1`), and returns the mixture's value and density.
    /// The coat, when there is one, is picked first (its probability
    /// from [`MetallicRoughness::coat_probability`]), then the sheen (a
    /// cosine-weighted direction, its probability from
    /// [`MetallicRoughness::under_coat`]), and the rest of `u1` picks among
    /// the base's lobes.
    pub(in crate::bsdf) fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let under = self.under_coat(wo);
        let coat = self.coat_probability(wo, &under);
        let up_o = Vec3::new(wo.x, wo.y, wo.z.abs());
        let sign = if wo.z < 0.0 { -1.0 } else { 1.0 };
        if u1 < coat {
            if self.coat.is_smooth() {
                return self.mirror_sample(wo, coat, &under);
            }
            let wi = self.coat.sample(wo, u2)?;
            return BsdfSample::of_mixture(wo, wi, BsdfFlags::GLOSSY, self.pdf(wo, wi), || {
                self.f(wo, wi)
            });
        }
        // Exactly `u1` without a coat (coat = 0), and again without a sheen.
        let u1 = (u1 - coat) / (1.0 - coat);
        if u1 < under.sheen {
            let w = square_to_cosine_hemisphere(u2);
            let wi = Vec3::new(w.x, w.y, sign * w.z);
            return BsdfSample::of_mixture(wo, wi, BsdfFlags::GLOSSY, self.pdf(wo, wi), || {
                self.f(wo, wi)
            });
        }
        let c = under.base.as_ref()?;
        let u1 = (u1 - under.sheen) / (1.0 - under.sheen);
        if self.is_smooth() && c.glass > 0.0 && (u1 < c.specular || u1 >= c.specular + c.diffuse) {
            return self.smooth_sample(wo, u1, coat, &under, c);
        }
        if u1 < c.specular && self.is_smooth() {
            if coat > 0.0 || under.sheen > 0.0 {
                return self.mirror_sample(wo, coat, &under);
            }
            let weight = self.smooth_reflectance(up_o.z) / c.specular;
            return delta_sample(reflect_local(wo), weight, c.specular, MIRROR_FLAGS);
        }
        let (wi, lobe) = if u1 < c.specular {
            let wi = microfacet::sample_reflection(self.distribution(), wo, u2)?;
            (wi, BsdfFlags::GLOSSY)
        } else if u1 < c.specular + c.diffuse || c.glass <= 0.0 {
            let w = square_to_cosine_hemisphere(u2);
            (Vec3::new(w.x, w.y, sign * w.z), BsdfFlags::DIFFUSE)
        } else {
            let u = ((u1 - c.specular - c.diffuse) / c.glass).clamp(0.0, 1.0 - f32::EPSILON);
            (self.glass().sample(wo, u, u2)?.wi, BsdfFlags::GLOSSY)
        };
        BsdfSample::of_mixture(wo, wi, lobe, self.pdf(wo, wi), || self.f(wo, wi))
    }

    /// A delta lobe of the smooth base picked by `u1` (already past the
    /// coat and the sheen): the specular layer (`u1 < c.specular`) or the
    /// smooth glass (past the specular and diffuse shares), which
    /// reflects with the exact dielectric Fresnel F at cos θo (1 under
    /// total internal reflection) and refracts otherwise. Reflections go
    /// to [`MetallicRoughness::mirror_sample`], which sums every delta lobe
    /// in the mirror direction; a refraction carries the glass's
    /// transmittance (the base colour) over η², dimmed by the sheen and the
    /// coat.
    fn smooth_sample(
        &self,
        wo: Vec3,
        u1: f32,
        coat: f32,
        under: &UnderCoat,
        c: &LobeChoice,
    ) -> Option<BsdfSample> {
        if u1 < c.specular {
            return self.mirror_sample(wo, coat, under);
        }
        let fresnel = fresnel_dielectric(wo.z, self.ior);
        let u = ((u1 - c.specular - c.diffuse) / c.glass).clamp(0.0, 1.0);
        if u < fresnel {
            return self.mirror_sample(wo, coat, under);
        }
        let (wi, eta) = refract_local(wo, self.ior)?;
        let mut weight = self.base_color * (self.glass_weight() * (1.0 - fresnel) / (eta * eta));
        weight *= self.coat.base_weight(wo.z.abs());
        if self.sheen.is_on() {
            weight *= self.sheen.base_weight(wo.z.abs(), wi.z.abs());
        }
        let probability = (1.0 - coat) * (1.0 - under.sheen) * c.glass * (1.0 - fresnel);
        delta_sample(wi, weight / probability, probability, REFRACTION_FLAGS)
    }

    /// The delta lobes at the mirror direction of `wo` (coat probability
    /// `coat`, the layers beneath `under`): a smooth coat, the base's
    /// smooth specular layer and its smooth glass's reflection, dimmed by
    /// the sheen and the coat, each with its probability.
    fn mirror_sample(&self, wo: Vec3, coat: f32, under: &UnderCoat) -> Option<BsdfSample> {
        let cos = wo.z.abs();
        let (mut reflectance, mut probability) = (Vec3::ZERO, 0.0);
        if self.coat.is_on() && self.coat.is_smooth() {
            reflectance += Vec3::splat(self.coat.reflected(cos));
            probability += coat;
        }
        if let (Some(c), true) = (&under.base, self.is_smooth()) {
            let fresnel = if c.glass > 0.0 {
                fresnel_dielectric(wo.z, self.ior)
            } else {
                0.0
            };
            let mut base =
                self.smooth_reflectance(cos) + Vec3::splat(self.glass_weight() * fresnel);
            base *= self.coat.base_weight(cos);
            if self.sheen.is_on() {
                base *= self.sheen.base_weight(cos, cos);
            }
            reflectance += base;
            probability += (1.0 - coat) * (1.0 - under.sheen) * (c.specular + c.glass * fresnel);
        }
        delta_sample(
            reflect_local(wo),
            reflectance / probability,
            probability,
            MIRROR_FLAGS,
        )
    }
}
