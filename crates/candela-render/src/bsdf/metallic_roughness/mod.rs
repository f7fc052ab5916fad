//! The glTF 2.0 metallic-roughness BSDF (glTF 2.0 specification,
//! appendix B "BRDF Implementation"), with `KHR_materials_transmission`,
//! `KHR_materials_ior`, `KHR_materials_specular`, `KHR_materials_sheen`
//! and `KHR_materials_clearcoat`: the coat over the sheen over the base,
//! as the extensions order them.
//!
//! With base colour c, metalness m, transmission t, α = roughness² on GGX
//! (Trowbridge-Reitz) microfacets, h the half vector and
//! S(F0) = F0 + (1 − F0)(1 − |wo·h|)⁵ Schlick's Fresnel:
//!
//! - specular = D(h) · G2(wo, wi) / (4 |cos θo| |cos θi|) (height-correlated
//!   Smith G2, as the spec's V term);
//! - metal = S(c) · specular;
//! - opaque dielectric = S(F0d) · specular + Lambert · c / π, with
//!   F0d = ((ior − 1)/(ior + 1))² (0.04 at the default ior 1.5): a Lambert
//!   base under a specular layer;
//! - `KHR_materials_specular`: with strength s (`specularFactor`, 1 by
//!   default) and tint k (`specularColorFactor`, white by default) the
//!   layer's Fresnel is S(F0d, F90) = F0d + (F90 − F0d)(1 − |wo·h|)⁵ with
//!   F0d = min(((ior − 1)/(ior + 1))² k, 1) · s and F90 = s, per channel.
//!   At s = 0 the layer is gone and the dielectric is exactly Lambert c/π
//!   (the base's weight below is then exactly 1): the way a glTF file says
//!   "pure Lambertian";
//! - f_base = m · metal + (1 − m)(1 − t) · opaque dielectric + (1 − m) t · glass;
//! - a rough metal also returns what its single-scattering lobe loses, as
//!   a cosine-like lobe of the colour of multiply scattered light (Kulla and
//!   Conty 2017; `MetallicRoughness::metal_multiple_scattering`), so that a
//!   white metal reflects all the light, as Blender Cycles' does. The
//!   dielectric's specular layer is not compensated: what it loses goes to
//!   the Lambert base (see "Lambert's weight");
//! - `KHR_materials_sheen`, with sheen colour k_s and perceptual roughness
//!   r_s (`sheen.rs`: Estevez & Kulla's "Charlie" fibre lobe, α = r_s²,
//!   its directional albedo E tabulated in `sheen_albedo.rs`):
//!   f_under = f_sheen + min(1 − max(k_s) E(|cos θo|), 1 − max(k_s) E(|cos θi|)) · f_base,
//!   the extension's albedo scaling, symmetric as written. At k_s = 0
//!   every sheen term is skipped: exactly the sheenless model;
//! - `KHR_materials_clearcoat`, with strength c and a coat of perceptual
//!   roughness r_c (`clear_coat.rs`: GGX with α = r_c², F0 = 0.04):
//!   f = (1 − c E_c(|cos θo|)) · f_under +
//!   c S(0.04, wo·h) · D_c(h) G2_c(wo, wi) / (4 cos θo cos θi), with E_c
//!   the coat lobe's directional albedo.
//!   At c = 0 every coat term is skipped: exactly the uncoated model.
//!
//! **Lambert's weight.** The spec's `fresnel_mix` weights the base by
//! 1 − S(F0d) at the half vector, which is reciprocal but not energy
//! conserving: for a white base it reflects up to 1.026 of the incident
//! energy (rough 0.2, 60°; measured with this file's furnace test). The
//! spec calls its BRDF an approximation that implementations may improve;
//! here the base is weighted by
//! (1 − E(cos θo)) (1 − E(cos θi)) / (1 − Ē), where E(μ) is the specular
//! layer's own directional albedo at μ (the rough GGX lobe with its
//! Schlick Fresnel, tabulated in `specular_albedo.rs`; for a smooth layer
//! exactly S(F0d, μ)) and Ē = 2∫E(μ) μ dμ its average (the weight is 0
//! when Ē = 1: nothing enters the base): still reciprocal (symmetric in wo
//! and wi), and the base then reflects exactly c (1 − E(cos θo)), what the
//! specular layer leaves, so a white dielectric reflects all the light at
//! every angle and roughness (Shirley et al. 1997, "A Practitioners'
//! Assessment of Light Reflection Models", use the same per-direction
//! transmission factors; Kelemen and Szirmay-Kalos 2001 the albedo of the
//! rough layer in them). Weighting by Schlick's S at cos θ itself instead,
//! as this model did before, over-dims a rough layer's base at grazing
//! views, where the microfacets see the light at far less grazing angles:
//! against Blender Cycles' energy-conserving Principled BSDF on the same
//! glTF plane, roughness 1 seen at 20° elevation was 9% darker with S and
//! is within 1% with E (BENCHMARKS.md, "glTF against Blender Cycles").
//!
//! **The coat's weights.** The extension layers the coat as
//! mix(base, coat, c · S(0.04, N·V)): the base is dimmed by
//! 1 − c S(cos θo) and the coat's specular lobe is scaled by
//! c S(cos θo), both at the viewing direction only. Here the coat's
//! Fresnel is taken at the half vector, as the base's specular layer does
//! (for a smooth coat h is the normal, so it is exactly the spec's
//! c S(cos θo)), and the base is dimmed by what the coat reflects at the
//! viewing direction, its directional albedo c E_c(cos θo) (`clear_coat.rs`;
//! exactly c S(cos θo) for a smooth coat, less for a rough one at grazing
//! angles, where masking keeps its lobe far below S): the spec's look, and
//! Blender Cycles' coat, which attenuates the layers beneath by the coat's
//! albedo at the view alone. Energy is conserved at every `wo` (the coat
//! reflects c E_c, the base at most its own albedo times the 1 − c E_c the
//! coat leaves), and a white dielectric under any coat reflects all the
//! light. The weight is not reciprocal (it reads `wo` only); light
//! subpaths use the adjoint, f evaluated with the two directions swapped
//! (`transport.rs`). Dimming the base once per crossing of the coat instead,
//! (1 − c S(cos θo))(1 − c S(cos θi)), as this model did before, lost what
//! the light bouncing between coat and base would return: a coated sphere
//! lit by an area lamp was 11% darker than Cycles' (BENCHMARKS.md, "glTF
//! against Blender Cycles"). The coat follows the shading normal (the
//! extension's own coat normal map is reported by the loader), and it dims
//! neither emission nor the transmitted light's colour beyond this weight.
//!
//! **The sheen between them.** "The base" of the coat's weights is then
//! everything beneath the coat, sheen included. The sheen's own scaling
//! is the extension's min form, which is already symmetric; it also dims
//! the transmitted lobe (at |cos θi| on the far side), as the coat does at
//! the viewing side, and the sheen lobe is two-sided like the opaque lobes. A smooth
//! specular layer under a sheen stays a delta lobe, dimmed by
//! 1 − max(k_s) E(cos θo) (the mirror direction has the same cosine).
//!
//! The transmitted fraction ("glass-like transmission") is the rough
//! dielectric of `rough_dielectric.rs` (Walter et al. 2007) with the same
//! α, IOR `ior` and transmittance c: it refracts, scales radiance by 1/η²,
//! and reflects with the exact dielectric Fresnel term, so a fully
//! transmissive material is exactly the rough glass (the spec's thin-walled
//! default would not bend the rays; glass spheres and blocks in glTF files
//! are meant to). The opaque lobes are two-sided (mirrored when `wo.z < 0`),
//! the glass reads the side of `wo`.
//!
//! **Roughness 0** makes the opaque specular lobe (metal and dielectric
//! layer) a delta lobe, a perfect mirror of reflectance S(F0, cos θo): it
//! leaves `f` and `pdf` (which keep the diffuse lobe) and is sampled with
//! its discrete probability, as the smooth plastic's coating is. Metallic
//! 1, roughness 0, white base is then exactly [`Bsdf::Mirror`](super::Bsdf::Mirror)
//! of reflectance 1 (Schlick's S(1) = 1). The transmitted lobe is then the
//! smooth dielectric (the exact Fresnel F reflects, 1 − F refracts with
//! transmittance c/η²; with full transmission exactly [`Bsdf::Glass`](super::Bsdf::Glass)),
//! also sampled only: a delta light is not seen through or in it, as in
//! Blender Cycles and Mitsuba, where a rough dielectric of α clamped to
//! [`MIN_ALPHA`](super::MIN_ALPHA), as this model had before, drew the
//! tiny, very bright reflections and refractions of punctual lights that no
//! other renderer draws (a glass sphere under a sun and a point light was
//! 5% brighter than Cycles' from those alone; BENCHMARKS.md, "glTF against
//! Blender Cycles"), and noisily. A smooth glass's reflection shares the
//! mirror direction with the specular layer and a smooth coat: a sample
//! there carries all three.
//!
//! Sampling (`sampling.rs`) picks a lobe with probabilities that depend on `wo` only
//! (the lobes' approximate albedos: c E_c(cos θo) for the coat, the
//! rest shared by the sheen, luminance(k_s) E(cos θo), and the base's
//! lobes dimmed by 1 − max(k_s) E(cos θo), as their weights say; Schlick at cos θo
//! for the specular lobe, the rest of the dielectric's weight times the base's luminance for
//! the diffuse lobe, t(1 − m) for the glass), samples it (visible GGX
//! normals, cosine hemisphere for the diffuse lobe and for the sheen, or
//! the rough dielectric), and returns the
//! whole mixture's `f` and `pdf`. A smooth coat over a smooth specular
//! layer puts two delta lobes in one direction; a delta sample then
//! carries both (their reflectances over their summed probabilities). Single scattering: energy is lost at
//! high roughness as for every microfacet model (see the furnace curve in
//! `metallic_roughness_tests.rs`).

use std::f32::consts::FRAC_1_PI;

use glam::Vec3;

mod sampling;

use super::clear_coat::ClearCoat;
use super::distribution::{Masking, MicrofacetDistribution};
use super::rough_dielectric::RoughDielectric;
use super::sheen::Sheen;
use super::specular_albedo::SpecularAlbedo;
use super::BsdfFlags;

/// The model's parameters, each in its range (see [`MetallicRoughness::new`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicRoughness {
    base_color: Vec3,
    metallic: f32,
    roughness: f32,
    transmission: f32,
    ior: f32,
    specular: f32,
    specular_color: Vec3,
    sheen: Sheen,
    coat: ClearCoat,
}

impl MetallicRoughness {
    /// A glTF material: base colour, metalness, perceptual roughness and
    /// transmission clamped to [0, 1] (NaN to 0), IOR to at least 1 (1.5
    /// when not finite).
    pub fn new(
        base_color: Vec3,
        metallic: f32,
        roughness: f32,
        transmission: f32,
        ior: f32,
    ) -> Self {
        Self {
            base_color: base_color.to_array().map(unit).into(),
            metallic: unit(metallic),
            roughness: unit(roughness),
            transmission: unit(transmission),
            ior: if ior.is_finite() { ior.max(1.0) } else { 1.5 },
            specular: 1.0,
            specular_color: Vec3::ONE,
            sheen: Sheen::NONE,
            coat: ClearCoat::NONE,
        }
    }

    /// The same material with `KHR_materials_specular`'s strength
    /// (`specularFactor`, clamped to [0, 1]) and tint (`specularColorFactor`,
    /// at least 0); NaN becomes the default (1, white).
    pub fn with_specular(self, factor: f32, color: Vec3) -> Self {
        let color = color
            .to_array()
            .map(|v| if v.is_nan() { 1.0 } else { v.max(0.0) });
        Self {
            specular: if factor.is_nan() {
                1.0
            } else {
                factor.clamp(0.0, 1.0)
            },
            specular_color: color.into(),
            ..self
        }
    }

    /// The same material with `KHR_materials_clearcoat`'s strength
    /// (`clearcoatFactor`) and the coat's perceptual roughness
    /// (`clearcoatRoughnessFactor`), each clamped to [0, 1] (NaN to 0).
    pub fn with_clearcoat(self, factor: f32, roughness: f32) -> Self {
        Self {
            coat: ClearCoat::new(factor, roughness),
            ..self
        }
    }

    /// The same material with another transmitted fraction (a texture),
    /// clamped as in [`MetallicRoughness::new`].
    pub fn with_transmission(self, transmission: f32) -> Self {
        Self {
            transmission: unit(transmission),
            ..self
        }
    }

    /// The transmitted fraction of the dielectric part.
    pub fn transmission(&self) -> f32 {
        self.transmission
    }

    /// The dielectric specular layer's strength and F0 tint.
    pub fn specular(&self) -> (f32, Vec3) {
        (self.specular, self.specular_color)
    }

    /// The clear coat's strength and perceptual roughness.
    pub fn clearcoat(&self) -> (f32, f32) {
        self.coat.parameters()
    }

    /// Whether f(wo, wi) = f(wi, wo) up to refraction's η² (generalised
    /// reciprocity): true but with a coat, whose weight reads `wo` alone
    /// (see the module docs), so that light subpaths must evaluate the
    /// model with the two directions swapped.
    pub fn is_reciprocal(&self) -> bool {
        !self.coat.is_on()
    }

    /// The same material with `KHR_materials_sheen`'s colour
    /// (`sheenColorFactor`) and perceptual roughness
    /// (`sheenRoughnessFactor`), each clamped to [0, 1] (NaN to 0).
    pub fn with_sheen(self, color: Vec3, roughness: f32) -> Self {
        Self {
            sheen: Sheen::new(color, roughness),
            ..self
        }
    }

    /// The sheen's colour and perceptual roughness.
    pub fn sheen(&self) -> (Vec3, f32) {
        self.sheen.parameters()
    }

    /// Base colour.
    pub fn base_color(&self) -> Vec3 {
        self.base_color
    }

    /// The same material with other base colour, metalness or roughness
    /// (textures), clamped as in [`MetallicRoughness::new`]; the sheen and
    /// the coat are kept.
    pub fn with(&self, base_color: Vec3, metallic: f32, roughness: f32) -> Self {
        Self {
            sheen: self.sheen,
            coat: self.coat,
            ..Self::new(base_color, metallic, roughness, self.transmission, self.ior)
                .with_specular(self.specular, self.specular_color)
        }
    }

    /// Base colour, metalness, perceptual roughness.
    pub fn parameters(&self) -> (Vec3, f32, f32) {
        (self.base_color, self.metallic, self.roughness)
    }

    /// Index of refraction of the inside relative to the outside.
    pub fn ior(&self) -> f32 {
        self.ior
    }

    /// The union of the flags of the lobes that have weight: a metal or
    /// dielectric layer at roughness 0 is a delta lobe, so a smooth metal
    /// is purely specular (no light sampling).
    pub(super) fn flags(&self) -> BsdfFlags {
        let mut flags = BsdfFlags::REFLECTION;
        let dielectric = self.opaque_dielectric_weight();
        if self.has_specular_layer() {
            flags = flags.union(self.specular_lobe_flag());
        }
        if dielectric > 0.0 || (self.metallic > 0.0 && !self.is_smooth()) {
            // The Lambert base, or the rough metal's multiple scattering.
            flags = flags.union(BsdfFlags::DIFFUSE);
        }
        if self.glass_weight() > 0.0 {
            flags = flags
                .union(BsdfFlags::TRANSMISSION)
                .union(self.specular_lobe_flag());
        }
        if self.sheen.is_on() {
            flags = flags.union(BsdfFlags::GLOSSY);
        }
        if self.coat.is_on() {
            flags = flags.union(self.coat.flag());
        }
        flags
    }

    /// Whether the opaque specular lobe (metal or dielectric layer) has
    /// weight.
    fn has_specular_layer(&self) -> bool {
        self.metallic > 0.0 || (self.opaque_dielectric_weight() > 0.0 && self.specular > 0.0)
    }

    /// Whether the opaque specular lobe is a delta (roughness 0).
    fn is_smooth(&self) -> bool {
        self.roughness == 0.0
    }

    fn specular_lobe_flag(&self) -> BsdfFlags {
        if self.is_smooth() {
            BsdfFlags::SPECULAR
        } else {
            BsdfFlags::GLOSSY
        }
    }

    /// GGX with α = roughness².
    fn distribution(&self) -> MicrofacetDistribution {
        MicrofacetDistribution::ggx(self.roughness * self.roughness)
    }

    fn glass(&self) -> RoughDielectric {
        RoughDielectric {
            dist: self.distribution(),
            reflectance: Vec3::ONE,
            transmittance: self.base_color,
            ior: self.ior,
            masking: Masking::HeightCorrelated,
        }
    }

    /// The dielectric layer's Schlick Fresnel (F0, F90), per channel:
    /// F0 from the IOR, tinted, clamped to 1 and scaled by the strength;
    /// F90 the strength.
    fn dielectric_fresnel(&self) -> (Vec3, f32) {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        let f0 = (r * r * self.specular_color).min(Vec3::ONE) * self.specular;
        (f0, self.specular)
    }

    /// The dielectric layer's Fresnel at `cos` (Schlick's weight `s5`).
    fn dielectric_schlick(&self, s5: f32) -> Vec3 {
        let (f0, f90) = self.dielectric_fresnel();
        f0 + (Vec3::splat(f90) - f0) * s5
    }

    /// The metal's Fresnel, Schlick with F0 = base colour.
    fn metal_schlick(&self, s5: f32) -> Vec3 {
        self.base_color + (Vec3::ONE - self.base_color) * s5
    }

    /// The weight of the Lambert base (see the module docs); exactly 1
    /// when the specular layer is off.
    fn lambert_weight(&self, cos_o: f32, cos_i: f32) -> Vec3 {
        let (f0, f90) = self.dielectric_fresnel();
        let alpha = self.roughness * self.roughness;
        let (transmitted, pass_o, pass_i) = if alpha == 0.0 {
            // The delta layer reflects exactly Schlick's S at cos θ.
            (
                Vec3::ONE - (f0 + (Vec3::splat(f90) - f0) / 21.0),
                Vec3::ONE - self.dielectric_schlick(schlick_weight(cos_o)),
                Vec3::ONE - self.dielectric_schlick(schlick_weight(cos_i)),
            )
        } else {
            let table = SpecularAlbedo::get();
            (
                Vec3::ONE - table.average_albedo(alpha, f0, f90),
                Vec3::ONE - table.albedo(cos_o, alpha, f0, f90),
                Vec3::ONE - table.albedo(cos_i, alpha, f0, f90),
            )
        };
        let w = pass_o * pass_i / transmitted;
        Vec3::select(transmitted.cmpgt(Vec3::ZERO), w, Vec3::ZERO)
    }

    fn glass_weight(&self) -> f32 {
        (1.0 - self.metallic) * self.transmission
    }

    fn opaque_dielectric_weight(&self) -> f32 {
        (1.0 - self.metallic) * (1.0 - self.transmission)
    }

    /// The BSDF value (cosine excluded): the base's, under the sheen and
    /// the coat where there are.
    pub(super) fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let mut base = self.base_f(wo, wi);
        if self.sheen.is_on() {
            base = self.under_sheen(base, wo, wi);
        }
        if !self.coat.is_on() {
            return base;
        }
        let (up_o, up_i) = to_upper(wo, wi);
        base * self.coat.base_weight(up_o.z) + Vec3::splat(self.coat.f(up_o, up_i))
    }

    /// `base`'s value under the sheen: dimmed by it, plus the sheen's own
    /// lobe. Out of line, so that the sheenless model's value (inlined into
    /// the render loop's BSDF calls) is as small as before the sheen.
    #[inline(never)]
    fn under_sheen(&self, base: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        let (up_o, up_i) = to_upper(wo, wi);
        base * self.sheen.base_weight(up_o.z, up_i.z.abs()) + self.sheen.f(up_o, up_i)
    }

    /// The uncoated model's value.
    fn base_f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        // A smooth glass is a delta lobe: sampled only.
        let glass = if self.glass_weight() > 0.0 && !self.is_smooth() {
            self.glass().f(wo, wi) * self.glass_weight()
        } else {
            Vec3::ZERO
        };
        let (wo, wi) = to_upper(wo, wi);
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return glass;
        }
        let w = self.opaque_dielectric_weight();
        let lambert = self.lambert_weight(wo.z, wi.z) * self.base_color * FRAC_1_PI;
        if self.is_smooth() || !self.has_specular_layer() {
            // No glossy reflection: a delta layer (sampled only) or none.
            return glass + w * lambert;
        }
        let h = (wo + wi).normalize();
        let s5 = schlick_weight(wo.dot(h));
        let dist = self.distribution();
        let specular = dist.d(h) * dist.g2(wo, wi) / (4.0 * wo.z * wi.z);
        let dielectric = self.dielectric_schlick(s5) * specular + lambert;
        let mut metal = self.metal_schlick(s5) * specular;
        if self.metallic > 0.0 {
            let ms = self.metal_multiple_scattering(wo.z);
            let lost_i = self.metal_single_scattering_loss(wi.z);
            metal += ms.color * (ms.lost * lost_i * ms.normalisation * FRAC_1_PI);
        }
        glass + self.metallic * metal + w * dielectric
    }

    /// The metal's multiple scattering (Kulla and Conty 2017, "Revisiting
    /// Physically Based Shading at Imageworks"): the light a rough GGX lobe
    /// loses to its single-scattering truncation comes back as the lobe
    /// F_ms (1 − E(cos θo)) (1 − E(cos θi)) / (π (1 − Ē)), with E the lobe's
    /// albedo under a white Fresnel (`specular_albedo.rs`: A + B), Ē its
    /// cosine average, and F_ms = F̄² Ē / (1 − F̄ (1 − Ē)) the colour of
    /// light that bounced among the microfacets (F̄ Schlick's hemispherical
    /// average, F0 + (1 − F0)/21), at one direction's cosine. Symmetric,
    /// so reciprocal, and a white metal reflects all the light at every
    /// angle and roughness. Blender Cycles compensates its metals too (by
    /// scaling the lobe at the view).
    fn metal_multiple_scattering(&self, cos: f32) -> MultipleScattering {
        let [a_avg, b_avg] = SpecularAlbedo::get().average(self.roughness * self.roughness);
        let e_avg = a_avg + b_avg;
        if e_avg >= 1.0 {
            return MultipleScattering {
                color: Vec3::ZERO,
                lost: 0.0,
                normalisation: 0.0,
            };
        }
        let f_avg = self.base_color + (Vec3::ONE - self.base_color) / 21.0;
        MultipleScattering {
            color: f_avg * f_avg * e_avg / (Vec3::ONE - f_avg * (1.0 - e_avg)),
            lost: self.metal_single_scattering_loss(cos),
            normalisation: 1.0 / (1.0 - e_avg),
        }
    }

    /// 1 − E(cos): what the metal's single-scattering lobe loses at `cos`
    /// under a white Fresnel (the table's A + B).
    fn metal_single_scattering_loss(&self, cos: f32) -> f32 {
        let [a, b] = SpecularAlbedo::get().split(cos, self.roughness * self.roughness);
        (1.0 - a - b).max(0.0)
    }

    /// The factor that turns a delta sample's radiance value into its
    /// adjoint's beyond refraction's η² (`transport.rs`): the coat's weight
    /// at `wi` over its weight at `wo`, which differ only for a refraction
    /// (a mirror keeps the angle); 1 without a coat.
    pub(in crate::bsdf) fn delta_adjoint_scale(&self, wo: Vec3, wi: Vec3) -> f32 {
        if !self.coat.is_on() {
            return 1.0;
        }
        let at_o = self.coat.base_weight(wo.z.abs());
        if at_o > 0.0 {
            self.coat.base_weight(wi.z.abs()) / at_o
        } else {
            0.0
        }
    }

    /// The delta layer's reflectance at `wo` (roughness 0): the metal's
    /// and the dielectric layer's Fresnel at cos θo.
    fn smooth_reflectance(&self, cos_o: f32) -> Vec3 {
        let s5 = schlick_weight(cos_o);
        self.metallic * self.metal_schlick(s5)
            + self.opaque_dielectric_weight() * self.dielectric_schlick(s5)
    }

    /// A representative colour: the base colour.
    pub(super) fn albedo(&self) -> Vec3 {
        self.base_color
    }
}

/// The parts of the metal's multiple-scattering lobe at one direction
/// (`MetallicRoughness::metal_multiple_scattering`): its value is
/// `color · lost(o) · lost(i) · normalisation / π`, its albedo at `wo`
/// `color · lost(o)`.
struct MultipleScattering {
    /// F_ms, the colour of light scattered more than once.
    color: Vec3,
    /// 1 − E(cos θ): what the single-scattering lobe loses at this
    /// direction.
    lost: f32,
    /// 1 / (1 − Ē).
    normalisation: f32,
}

/// (1 − cos)⁵, Schlick's Fresnel weight.
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Rec. 709 luminance, for lobe selection only.
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722)).max(0.0)
}

/// Mirrors the pair to the side where `wo.z > 0` (two-sided opaque lobes).
fn to_upper(wo: Vec3, wi: Vec3) -> (Vec3, Vec3) {
    if wo.z < 0.0 {
        (Vec3::new(wo.x, wo.y, -wo.z), Vec3::new(wi.x, wi.y, -wi.z))
    } else {
        (wo, wi)
    }
}

/// `v` clamped to [0, 1], NaN to 0: the range of the model's fractions.
fn unit(v: f32) -> f32 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, 1.0)
    }
}
