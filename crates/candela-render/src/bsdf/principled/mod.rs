//! The principled BSDF (Burley 2012, "Physically Based Shading at Disney",
//! and 2015, "Extending the Disney BRDF to a BSDF with Integrated
//! Subsurface Scattering"), as Mitsuba 3's `principled` defines it, so that
//! its scenes render as there.
//!
//! With c the base colour, m `metallic`, s `spec_trans`, the diffuse weight
//! w_d = (1 − m)(1 − s) and the transmission weight w_t = (1 − m) s, and
//! on the outside (both cosines positive, h the half vector):
//!
//! - **main specular**: F · D(h) · G(wo, wi) / (4 cos θo cos θi), GGX with
//!   α = roughness² (anisotropic: α_x = α/a, α_y = α·a, a = √(1 − 0.9
//!   `anisotropic`); both at least [`MIN_ALPHA`](super::MIN_ALPHA)), the
//!   *separable* Smith G1·G1 as in Mitsuba, and F the blend of
//!   `fresnel.rs`: (1 − m)(1 − spec_tint) times the exact dielectric
//!   Fresnel of IOR `eta`, plus m times Schlick's with F0 = c, plus
//!   (1 − m) spec_tint times Schlick's with F0 = r0(η) c/lum(c). Mitsuba
//!   switches the whole lobe off where the dielectric Fresnel is 0 (η = 1,
//!   i.e. `specular` 0 on an opaque material), metallic part included; so
//!   do we;
//! - **diffuse**: w_d · c/π · Burley's retro-reflective shape, blended
//!   toward the "fake subsurface" shape by `flatness` (`base.rs`);
//! - **sheen**: `sheen`·(1 − m)·(1 − cos θd)⁵, tinted by `sheen_tint`
//!   (Mitsuba's scalar variants drop it where w_d = 0, i.e. at spec_trans
//!   1, because their code evaluates it inside the diffuse branch; the
//!   lobe's own condition, which the vectorised variants follow, is
//!   1 − m > 0, and so is ours);
//! - **clearcoat**: GTR1, Schlick F0 = 0.04 (`clearcoat.rs`, which notes
//!   Mitsuba's missing cosines);
//! - **specular transmission**: w_t √c times the rough dielectric's
//!   refraction lobe (`rough_dielectric.rs`, same GGX, IOR `eta`, separable
//!   G), with its 1/η² radiance scaling.
//!
//! Inside (wo.z < 0) only the dielectric remains: the rough dielectric of
//! reflectance w_t and transmittance w_t √c. A material that does not
//! transmit (w_t = 0) is opaque and two-sided like every opaque BSDF here
//! (the pair is mirrored to the outside); Mitsuba's is black from behind
//! unless wrapped in `twosided`, which its loader expresses as the
//! material's sides (`Material::facing`), not here.
//!
//! **Frame.** Mitsuba evaluates it in the shading frame (`si.sh_frame`), as
//! every BSDF; so do we. Anisotropy is along the frame's x axis, which
//! follows the surface's ∂p/∂u when `anisotropic` > 0, as Mitsuba's
//! ([`Principled::is_anisotropic`], `shading::shading_frame`).
//!
//! **Sampling** (Mitsuba's weights, sampling rates 1): on the outside, the
//! diffuse lobe (cosine) with probability ∝ w_d, the clearcoat (GTR1
//! normals) ∝ clearcoat/4, the main lobe ∝ 1; the main lobe draws a visible
//! GGX normal and reflects, except with probability w_t where it samples
//! the rough dielectric (reflect with probability F, else refract), which
//! is Mitsuba's "reflect with probability 1 − w_t(1 − F)". Inside, the rough
//! dielectric. `pdf` is the mixture.
//!
//! **Energy.** Burley's diffuse is not energy conserving: its
//! retro-reflection exceeds Lambert at grazing angles for rough surfaces,
//! and the specular lobe (and the clearcoat) is added on top of it rather
//! than taken from it. Mitsuba's model, and ours, keep it so. Energy
//! albedo of white materials (`principled_white_furnace` in `tests.rs`,
//! 40k samples, ±0.005; θo = 0°, 60°, 85°; glass seen from outside,
//! refraction counted as energy):
//!
//! | roughness | metal          | metal, anisotropic 0.8 | glass (spec_trans 1) | half-metal glass | opaque dielectric | + clearcoat 1  |
//! |-----------|----------------|------------------------|----------------------|------------------|-------------------|----------------|
//! | 0.1       | 1.00 1.00 0.99 | 1.00 1.00 0.97         | 1.00 1.00 0.99       | 1.00 1.00 0.99   | 1.02 1.06 1.33    | 1.05 1.07 1.34 |
//! | 0.5       | 0.92 0.86 0.86 | 0.83 0.80 0.86         | 0.99 0.96 0.87       | 0.95 0.91 0.87   | 1.04 1.07 1.18    | 1.07 1.09 1.19 |
//! | 1.0       | 0.31 0.41 0.56 | 0.22 0.30 0.46         | 0.89 0.67 0.39       | 0.60 0.54 0.48   | 1.05 1.08 1.44    | 1.08 1.09 1.45 |
//!
//! The first four are single-scattering microfacet lobes (GGX's 1 − ln 2
//! = 0.31 for the metal at α = 1, normal incidence) and stay below 1; the
//! opaque dielectric reflects up to 1.45 of what it receives at grazing
//! angles (the specular lobe's Fresnel rises toward 1 there while the
//! diffuse keeps its weight).

mod base;
mod clearcoat;
mod fresnel;
#[cfg(test)]
mod tests;

use glam::{Vec2, Vec3};

use super::distribution::{Masking, MicrofacetDistribution};
use super::fresnel::fresnel_dielectric;
use super::microfacet;
use super::rough_dielectric::RoughDielectric;
use super::{BsdfFlags, BsdfSample};
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};

/// The parameters, as the scene description defines them (Mitsuba's
/// names and defaults).
pub use candela_scene::PrincipledParameters;

/// The principled BSDF with parameters in their ranges (see
/// [`Principled::new`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principled {
    p: PrincipledParameters,
}

/// Lobe probabilities on the outside.
struct LobeChoice {
    diffuse: f32,
    clearcoat: f32,
    main: f32,
}

impl Principled {
    /// Whether its specular lobes' roughness differs along the shading
    /// frame's x and y (`anisotropic` > 0), so the frame must follow dp/du.
    pub fn is_anisotropic(&self) -> bool {
        self.p.anisotropic > 0.0
    }

    /// The BSDF of `p`, every parameter but `eta` clamped to [0, 1] (NaN to
    /// its default); `eta` must be positive and finite (else 1.5).
    pub fn new(p: PrincipledParameters) -> Self {
        let d = PrincipledParameters::default();
        let unit = |v: f32, default: f32| {
            if v.is_nan() {
                default
            } else {
                v.clamp(0.0, 1.0)
            }
        };
        let color = |c: Vec3| Vec3::new(unit(c.x, 0.5), unit(c.y, 0.5), unit(c.z, 0.5));
        Self {
            p: PrincipledParameters {
                base_color: color(p.base_color),
                roughness: unit(p.roughness, d.roughness),
                anisotropic: unit(p.anisotropic, 0.0),
                metallic: unit(p.metallic, 0.0),
                spec_trans: unit(p.spec_trans, 0.0),
                eta: if p.eta.is_finite() && p.eta > 0.0 {
                    p.eta
                } else {
                    d.eta
                },
                spec_tint: unit(p.spec_tint, 0.0),
                sheen: unit(p.sheen, 0.0),
                sheen_tint: unit(p.sheen_tint, 0.0),
                flatness: unit(p.flatness, 0.0),
                clearcoat: unit(p.clearcoat, 0.0),
                clearcoat_gloss: unit(p.clearcoat_gloss, 0.0),
            },
        }
    }

    /// The parameters.
    pub fn parameters(&self) -> PrincipledParameters {
        self.p
    }

    /// The same material with another base colour, metalness and roughness
    /// (the textured ones), clamped as in [`Principled::new`].
    pub fn with(&self, base_color: Vec3, metallic: f32, roughness: f32) -> Self {
        Self::new(PrincipledParameters {
            base_color,
            metallic,
            roughness,
            ..self.p
        })
    }

    /// Index of refraction of the inside relative to the outside.
    pub fn ior(&self) -> f32 {
        self.p.eta
    }

    /// The weight of the diffuse base, (1 − metallic)(1 − spec_trans).
    fn diffuse_weight(&self) -> f32 {
        (1.0 - self.p.metallic) * (1.0 - self.p.spec_trans)
    }

    /// The weight of the transmission, (1 − metallic) spec_trans.
    fn transmission_weight(&self) -> f32 {
        (1.0 - self.p.metallic) * self.p.spec_trans
    }

    /// GGX of α = roughness², stretched by the anisotropy.
    fn distribution(&self) -> MicrofacetDistribution {
        let alpha = self.p.roughness * self.p.roughness;
        let aspect = (1.0 - 0.9 * self.p.anisotropic).sqrt();
        MicrofacetDistribution::Ggx {
            alpha_x: alpha / aspect,
            alpha_y: alpha * aspect,
        }
    }

    /// The dielectric share: what remains inside, and the refraction lobe.
    fn dielectric(&self) -> RoughDielectric {
        let w = self.transmission_weight();
        RoughDielectric {
            dist: self.distribution(),
            reflectance: Vec3::splat(w),
            transmittance: w * self.p.base_color.map(f32::sqrt),
            ior: self.p.eta,
            masking: Masking::Separable,
        }
    }

    /// The pair as evaluated: mirrored to the outside when the material is
    /// opaque (two-sided), as given when it transmits.
    fn orient(&self, wo: Vec3, wi: Vec3) -> (Vec3, Vec3) {
        if wo.z < 0.0 && self.transmission_weight() <= 0.0 {
            (mirror(wo), mirror(wi))
        } else {
            (wo, wi)
        }
    }

    /// The union of the flags of the lobes that have weight.
    pub(super) fn flags(&self) -> BsdfFlags {
        let mut flags = BsdfFlags::REFLECTION | BsdfFlags::GLOSSY;
        if self.diffuse_weight() > 0.0 {
            flags = flags | BsdfFlags::DIFFUSE;
        }
        if self.transmission_weight() > 0.0 {
            flags = flags | BsdfFlags::TRANSMISSION;
        }
        flags
    }

    /// The BSDF value (cosine excluded).
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let (wo, wi) = self.orient(wo, wi);
        if wo.z == 0.0 || wi.z == 0.0 {
            return Vec3::ZERO;
        }
        if wo.z > 0.0 && wi.z > 0.0 {
            return self.reflection_outside(wo, wi);
        }
        if self.transmission_weight() > 0.0 {
            self.dielectric().f(wo, wi)
        } else {
            Vec3::ZERO
        }
    }

    /// Every lobe but the transmission, both directions outside.
    fn reflection_outside(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let p = &self.p;
        let h = (wo + wi).normalize();
        let cos_oh = wo.dot(h);
        let cos_d = wi.dot(h);
        let mut f = Vec3::ZERO;
        let dielectric = fresnel_dielectric(cos_oh, p.eta);
        if dielectric > 0.0 {
            let dist = self.distribution();
            let specular =
                dist.d(h) * dist.masking(Masking::Separable, wo, wi) / (4.0 * wo.z * wi.z);
            let fresnel = fresnel::main_reflection(
                dielectric,
                cos_oh,
                p.eta,
                p.base_color,
                p.metallic,
                p.spec_tint,
            );
            f += fresnel * specular;
        }
        if p.clearcoat > 0.0 {
            f += Vec3::splat(clearcoat::f(
                p.clearcoat,
                p.clearcoat_gloss,
                p.eta,
                wo,
                wi,
                h,
            ));
        }
        let w = self.diffuse_weight();
        if w > 0.0 {
            let shape = base::diffuse_shape(wo.z, wi.z, cos_d, p.roughness, p.flatness);
            f += base::diffuse(w, p.base_color, shape);
        }
        if p.sheen > 0.0 && p.metallic < 1.0 {
            f += base::sheen(p.sheen, p.sheen_tint, p.metallic, p.base_color, cos_d);
        }
        f
    }

    /// The lobe probabilities on the outside.
    fn choice(&self) -> LobeChoice {
        let diffuse = self.diffuse_weight();
        let clearcoat = 0.25 * self.p.clearcoat;
        let total = 1.0 + diffuse + clearcoat;
        LobeChoice {
            diffuse: diffuse / total,
            clearcoat: clearcoat / total,
            main: 1.0 / total,
        }
    }

    /// The density of [`Principled::sample`] per unit solid angle.
    pub(super) fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (wo, wi) = self.orient(wo, wi);
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let transmitted = self.transmission_weight();
        if wo.z < 0.0 {
            return self.dielectric().pdf(wo, wi);
        }
        let c = self.choice();
        let mut pdf = 0.0;
        if transmitted > 0.0 {
            pdf += c.main * transmitted * self.dielectric().pdf(wo, wi);
        }
        if wi.z < 0.0 {
            return pdf;
        }
        pdf += c.main * (1.0 - transmitted) * microfacet::pdf(self.distribution(), wo, wi);
        pdf += c.diffuse * cosine_hemisphere_pdf(wi);
        if c.clearcoat > 0.0 {
            let h = (wo + wi).normalize();
            pdf += c.clearcoat * clearcoat::pdf(self.p.clearcoat_gloss, wi, h);
        }
        pdf
    }

    /// Picks a lobe with `u1` (the main lobe reuses the rest of it to
    /// choose between reflection and the dielectric), samples it with `u2`,
    /// and returns the mixture's value and density.
    pub(super) fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let flip = wo.z < 0.0 && self.transmission_weight() <= 0.0;
        let (wi, lobe) = self.sample_direction(if flip { mirror(wo) } else { wo }, u1, u2)?;
        let wi = if flip { mirror(wi) } else { wi };
        BsdfSample::of_mixture(wo, wi, lobe, self.pdf(wo, wi), || self.f(wo, wi))
    }

    /// A direction from the lobe `u1` picks (`wo` as evaluated: outside
    /// unless the material transmits), and the lobe's kind.
    fn sample_direction(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<(Vec3, BsdfFlags)> {
        let transmitted = self.transmission_weight();
        if wo.z < 0.0 {
            let s = self.dielectric().sample(wo, u1, u2)?;
            return Some((s.wi, BsdfFlags::GLOSSY));
        }
        let c = self.choice();
        if u1 < c.diffuse {
            return Some((square_to_cosine_hemisphere(u2), BsdfFlags::DIFFUSE));
        }
        if u1 < c.diffuse + c.clearcoat {
            let wi = clearcoat::sample(self.p.clearcoat_gloss, wo, u2)?;
            return Some((wi, BsdfFlags::GLOSSY));
        }
        let u = ((u1 - c.diffuse - c.clearcoat) / c.main).clamp(0.0, 1.0 - f32::EPSILON);
        let wi = if u < transmitted {
            let u = (u / transmitted).clamp(0.0, 1.0 - f32::EPSILON);
            self.dielectric().sample(wo, u, u2)?.wi
        } else {
            microfacet::sample_reflection(self.distribution(), wo, u2)?
        };
        Some((wi, BsdfFlags::GLOSSY))
    }

    /// A representative colour: the base colour.
    pub(super) fn albedo(&self) -> Vec3 {
        self.p.base_color
    }
}

/// The direction mirrored through the tangent plane.
fn mirror(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}
