//! Materials as parameters: a scattering model with constant parameters,
//! plus one texture slot per parameter a material can vary over a surface.
//!
//! A texture in a slot replaces the constant of that parameter (times its
//! `scale`); an empty slot leaves the constant. The constants live in the
//! [`BsdfDesc`] (colour, roughness) and in [`MaterialDesc::emission`]; the
//! parameters no model has a constant for yet take the neutral value noted
//! on their [`TextureSlot`] (metalness 0, opacity 1, the geometry's own
//! shading normal).

use super::{ColorSpace, PerturbationRules, SourceLoc, TextureRef};
use glam::Vec3;

/// A material: one BSDF, optionally emissive, optionally textured.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    /// Material id/name from the file.
    pub name: String,
    /// The scattering model and its constant parameters.
    pub bsdf: BsdfDesc,
    /// Emitted radiance (one-sided, on the side of the geometric normal), if any.
    pub emission: Option<Vec3>,
    /// Textures that replace constant parameters, one slot per parameter.
    pub textures: TextureSlots,
    /// Which sides of the surface scatter light, and with what.
    pub sides: Sides,
    /// Where the material was described.
    pub loc: SourceLoc,
}

/// Which sides of a surface scatter light. The front is the side the
/// surface's shading normal points to (its authored normals, else its
/// winding); a path tracer that reads COLLADA, OBJ, PLY or glTF shades both
/// sides alike, while Mitsuba 3's non-dielectric BSDFs are black from
/// behind unless wrapped in `twosided`.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Sides {
    /// The BSDF scatters on both sides, as if the surface were turned to
    /// face the viewer (a dielectric reads the side to tell entering from
    /// leaving).
    #[default]
    Both,
    /// Only the front scatters; seen from behind the surface is black
    /// (Mitsuba's one-sided BSDFs).
    Front,
    /// The material's BSDF on the front, this one's on the back (turned to
    /// face the viewer): Mitsuba's `twosided` with two BSDFs. Only the
    /// back material's BSDF and textures are used (emission stays the
    /// front's).
    Back(Box<MaterialDesc>),
}

impl MaterialDesc {
    /// The loader's default when a file names no material: diffuse 0.5 grey.
    pub fn default_grey() -> Self {
        Self {
            name: "default".into(),
            bsdf: BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            emission: None,
            textures: TextureSlots::default(),
            sides: Sides::Both,
            loc: SourceLoc::default(),
        }
    }
}

/// The parameters a texture can drive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextureSlot {
    /// Base colour: the BSDF's albedo, reflectance or transmittance.
    Color,
    /// Roughness (a dielectric's `roughness`, a conductor's `alpha`, the
    /// metallic-roughness model's perceptual roughness).
    Roughness,
    /// Metalness in [0, 1]; 0 when no texture says otherwise.
    Metalness,
    /// Tangent-space normal map; the geometry's shading normal otherwise.
    Normal,
    /// Bump (height) map: the shading normal of the surface displaced by
    /// the value (times the scale) along its normal, the value read as
    /// scene units per unit of UV (OBJ `bump`/`map_Bump`, Mitsuba
    /// `bumpmap` with its `scale`).
    Bump,
    /// Emitted radiance, replacing [`MaterialDesc::emission`].
    Emission,
    /// Opacity in [0, 1] (cut-outs); 1 when no texture says otherwise.
    Opacity,
    /// The weight of a [`BsdfDesc::Blend`]'s second part, in [0, 1] (the
    /// luminance of a colour texture, as Mitsuba reads one value).
    Weight,
    /// The strength of the metallic-roughness model's clear coat in [0, 1]
    /// (`KHR_materials_clearcoat`'s `clearcoatTexture`, red by default).
    Clearcoat,
    /// The clear coat's perceptual roughness in [0, 1]
    /// (`clearcoatRoughnessTexture`, green in glTF files).
    ClearcoatRoughness,
    /// The transmitted fraction of the metallic-roughness model's
    /// dielectric part in [0, 1] (`KHR_materials_transmission`'s
    /// `transmissionTexture`, red).
    Transmission,
    /// The strength of the metallic-roughness model's dielectric specular
    /// layer in [0, 1] (`KHR_materials_specular`'s `specularTexture`,
    /// alpha in glTF files).
    Specular,
    /// The tint of that layer's F0, a colour (`specularColorTexture`, sRGB).
    SpecularColor,
    /// The colour of the metallic-roughness model's sheen, per channel in
    /// [0, 1] (`KHR_materials_sheen`'s `sheenColorTexture`, sRGB).
    SheenColor,
    /// The sheen's perceptual roughness in [0, 1]
    /// (`sheenRoughnessTexture`, alpha in glTF files).
    SheenRoughness,
}

impl TextureSlot {
    /// Every slot, in declaration order.
    pub const ALL: [TextureSlot; 15] = [
        TextureSlot::Color,
        TextureSlot::Roughness,
        TextureSlot::Metalness,
        TextureSlot::Normal,
        TextureSlot::Bump,
        TextureSlot::Emission,
        TextureSlot::Opacity,
        TextureSlot::Weight,
        TextureSlot::Clearcoat,
        TextureSlot::ClearcoatRoughness,
        TextureSlot::Transmission,
        TextureSlot::Specular,
        TextureSlot::SpecularColor,
        TextureSlot::SheenColor,
        TextureSlot::SheenRoughness,
    ];

    /// The slot's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            TextureSlot::Color => "colour",
            TextureSlot::Roughness => "roughness",
            TextureSlot::Metalness => "metalness",
            TextureSlot::Normal => "normal map",
            TextureSlot::Bump => "bump map",
            TextureSlot::Emission => "emission",
            TextureSlot::Opacity => "opacity",
            TextureSlot::Weight => "blend weight",
            TextureSlot::Clearcoat => "clear coat",
            TextureSlot::ClearcoatRoughness => "clear coat roughness",
            TextureSlot::Transmission => "transmission",
            TextureSlot::Specular => "specular strength",
            TextureSlot::SpecularColor => "specular colour",
            TextureSlot::SheenColor => "sheen colour",
            TextureSlot::SheenRoughness => "sheen roughness",
        }
    }

    /// The colour space a loader should assume when its file does not say:
    /// sRGB for colours, linear for data.
    pub fn default_color_space(self) -> ColorSpace {
        match self {
            TextureSlot::Color
            | TextureSlot::Emission
            | TextureSlot::SpecularColor
            | TextureSlot::SheenColor => ColorSpace::Srgb,
            _ => ColorSpace::Linear,
        }
    }
}

/// One optional texture per [`TextureSlot`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TextureSlots {
    /// Base colour.
    pub color: Option<TextureRef>,
    /// Roughness.
    pub roughness: Option<TextureRef>,
    /// Metalness.
    pub metalness: Option<TextureRef>,
    /// Tangent-space normal map.
    pub normal: Option<TextureRef>,
    /// Bump (height) map.
    pub bump: Option<TextureRef>,
    /// Emitted radiance.
    pub emission: Option<TextureRef>,
    /// Opacity.
    pub opacity: Option<TextureRef>,
    /// A blend's weight.
    pub weight: Option<TextureRef>,
    /// The glTF clear coat's strength.
    pub clearcoat: Option<TextureRef>,
    /// The glTF clear coat's roughness.
    pub clearcoat_roughness: Option<TextureRef>,
    /// The glTF model's transmitted fraction.
    pub transmission: Option<TextureRef>,
    /// The glTF model's specular strength.
    pub specular: Option<TextureRef>,
    /// The glTF model's specular tint.
    pub specular_color: Option<TextureRef>,
    /// The glTF sheen's colour.
    pub sheen_color: Option<TextureRef>,
    /// The glTF sheen's roughness.
    pub sheen_roughness: Option<TextureRef>,
    /// How the opacity slot's value is read: `None` as a coverage fraction
    /// (a point of opacity a is kept with probability a, glTF `BLEND`),
    /// `Some(c)` as a mask (opaque where the value is at least c, cut out
    /// below: glTF `MASK` with its `alphaCutoff`).
    pub opacity_cutoff: Option<f32>,
    /// A constant opacity in [0, 1] for a material whose opacity slot has
    /// no texture (glTF `BLEND`/`MASK` with only a base colour factor's
    /// alpha); read like the texture's value, `opacity_cutoff` included.
    /// Ignored when the slot has a texture.
    pub opacity_constant: Option<f32>,
    /// How the normal and bump maps become the shading frame (the
    /// format's conventions).
    pub perturbation: PerturbationRules,
}

impl TextureSlots {
    /// The texture in `slot`, if any.
    pub fn get(&self, slot: TextureSlot) -> Option<&TextureRef> {
        self.slot(slot).as_ref()
    }

    /// Puts `texture` in `slot` (replacing what was there).
    pub fn set(&mut self, slot: TextureSlot, texture: TextureRef) {
        *self.slot_mut(slot) = Some(texture);
    }

    /// The filled slots, in [`TextureSlot::ALL`] order.
    pub fn iter(&self) -> impl Iterator<Item = (TextureSlot, &TextureRef)> {
        TextureSlot::ALL
            .into_iter()
            .filter_map(|s| self.get(s).map(|t| (s, t)))
    }

    fn slot(&self, slot: TextureSlot) -> &Option<TextureRef> {
        match slot {
            TextureSlot::Color => &self.color,
            TextureSlot::Roughness => &self.roughness,
            TextureSlot::Metalness => &self.metalness,
            TextureSlot::Normal => &self.normal,
            TextureSlot::Bump => &self.bump,
            TextureSlot::Emission => &self.emission,
            TextureSlot::Opacity => &self.opacity,
            TextureSlot::Weight => &self.weight,
            TextureSlot::Clearcoat => &self.clearcoat,
            TextureSlot::ClearcoatRoughness => &self.clearcoat_roughness,
            TextureSlot::Transmission => &self.transmission,
            TextureSlot::Specular => &self.specular,
            TextureSlot::SpecularColor => &self.specular_color,
            TextureSlot::SheenColor => &self.sheen_color,
            TextureSlot::SheenRoughness => &self.sheen_roughness,
        }
    }

    fn slot_mut(&mut self, slot: TextureSlot) -> &mut Option<TextureRef> {
        match slot {
            TextureSlot::Color => &mut self.color,
            TextureSlot::Roughness => &mut self.roughness,
            TextureSlot::Metalness => &mut self.metalness,
            TextureSlot::Normal => &mut self.normal,
            TextureSlot::Bump => &mut self.bump,
            TextureSlot::Emission => &mut self.emission,
            TextureSlot::Opacity => &mut self.opacity,
            TextureSlot::Weight => &mut self.weight,
            TextureSlot::Clearcoat => &mut self.clearcoat,
            TextureSlot::ClearcoatRoughness => &mut self.clearcoat_roughness,
            TextureSlot::Transmission => &mut self.transmission,
            TextureSlot::Specular => &mut self.specular,
            TextureSlot::SpecularColor => &mut self.specular_color,
            TextureSlot::SheenColor => &mut self.sheen_color,
            TextureSlot::SheenRoughness => &mut self.sheen_roughness,
        }
    }
}

/// Scattering models, as parameters. The renderer turns these into BSDFs.
#[derive(Clone, Debug, PartialEq)]
pub enum BsdfDesc {
    /// Lambertian reflection.
    Diffuse {
        /// Reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
    /// Perfect specular reflection.
    Mirror {
        /// Reflectance per channel.
        reflectance: Vec3,
    },
    /// Dielectric interface with reflection and refraction.
    Glass {
        /// Reflectance scale per channel.
        reflectance: Vec3,
        /// Transmittance scale per channel.
        transmittance: Vec3,
        /// Roughness (0 = smooth).
        roughness: f32,
        /// Index of refraction of the inside.
        ior: f32,
    },
    /// Dielectric interface that only refracts.
    Refraction {
        /// Transmittance scale per channel.
        transmittance: Vec3,
        /// Roughness (0 = smooth).
        roughness: f32,
        /// Index of refraction of the inside.
        ior: f32,
    },
    /// Rough conductor with a Beckmann microfacet distribution.
    Microfacet {
        /// Beckmann roughness alpha.
        alpha: f32,
        /// Real part of the complex index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
    },
    /// Rough dielectric interface (reflection and refraction through
    /// microfacets), with a choice of distribution.
    RoughDielectric {
        /// The microfacet distribution.
        distribution: MicrofacetModel,
        /// How its masking combines.
        masking: Masking,
        /// Roughness along u and v (> 0).
        alpha: Alpha,
        /// Index of refraction of the inside relative to the outside.
        ior: f32,
        /// Reflectance scale per channel.
        reflectance: Vec3,
        /// Transmittance scale per channel.
        transmittance: Vec3,
    },
    /// A dielectric pane of zero thickness (light passes straight through).
    ThinDielectric {
        /// Index of refraction of the pane relative to its surroundings.
        ior: f32,
        /// Reflectance scale per channel.
        reflectance: Vec3,
        /// Transmittance scale per channel.
        transmittance: Vec3,
    },
    /// A diffuse base under a dielectric coating (smooth when `alpha` is 0).
    Plastic {
        /// Albedo of the base.
        diffuse: Vec3,
        /// Tint of the coating's specular reflection.
        specular: Vec3,
        /// Index of refraction of the coating relative to the outside.
        ior: f32,
        /// Roughness alpha of the coating (0 = smooth).
        alpha: f32,
        /// The coating's microfacet distribution when rough.
        distribution: MicrofacetModel,
        /// How the rough coating's masking combines.
        masking: Masking,
        /// How the rough coating's albedo for diffuse light from inside is
        /// averaged over directions.
        internal_reflectance: InternalReflectance,
        /// Whether the base's colour is renormalised by the physical sum of
        /// internal reflections, ρ/(1 − ρ F_int), which saturates colours
        /// (Mitsuba's `nonlinear`), instead of ρ/(1 − F_int) (the default).
        nonlinear: bool,
    },
    /// A conductor with a complex index of refraction, smooth when `alpha`
    /// is 0, else rough with the given distribution.
    Conductor {
        /// The microfacet distribution.
        distribution: MicrofacetModel,
        /// How its masking combines when rough.
        masking: Masking,
        /// Roughness along u and v (0 = smooth).
        alpha: Alpha,
        /// Real part of the complex index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
    },
    /// Black: absorbs everything (the BSDF of a pure emitter).
    Black,
    /// Invisible (Mitsuba's `null`, which bounds a medium or carries an
    /// emitter): every ray, shadow rays too, passes straight through. The
    /// material's emission is still seen, on its front side.
    Null,
    /// The glTF 2.0 metallic-roughness model (Lambert base, GGX specular
    /// with Schlick Fresnel, mixed by metalness) with
    /// `KHR_materials_transmission`, `KHR_materials_ior` and
    /// `KHR_materials_specular`, `KHR_materials_sheen` and
    /// `KHR_materials_clearcoat` (the coat over the sheen over the rest).
    MetallicRoughness {
        /// Base colour (linear), per channel in [0, 1].
        base_color: Vec3,
        /// Metalness in [0, 1].
        metallic: f32,
        /// Perceptual roughness in [0, 1] (α = roughness²).
        roughness: f32,
        /// Fraction of the dielectric part that is transmitted, in [0, 1].
        transmission: f32,
        /// Index of refraction (1.5 by default).
        ior: f32,
        /// Strength of the dielectric specular layer (`specularFactor`, 1 by
        /// default; 0 leaves a pure Lambert base).
        specular: f32,
        /// Tint of the dielectric layer's F0 (`specularColorFactor`, white
        /// by default).
        specular_color: Vec3,
        /// Strength of the clear coat in [0, 1] (`KHR_materials_clearcoat`'s
        /// `clearcoatFactor`, 0 by default: no coat).
        clearcoat: f32,
        /// The clear coat's perceptual roughness in [0, 1]
        /// (`clearcoatRoughnessFactor`, 0 by default: a mirror-smooth coat).
        clearcoat_roughness: f32,
        /// Colour of the sheen, per channel in [0, 1] (`KHR_materials_sheen`'s
        /// `sheenColorFactor`, black by default: no sheen).
        sheen_color: Vec3,
        /// The sheen's perceptual roughness in [0, 1]
        /// (`sheenRoughnessFactor`, 0 by default).
        sheen_roughness: f32,
    },
    /// The principled BSDF (Burley 2012/2015) as Mitsuba 3's `principled`
    /// defines it.
    Principled(PrincipledParameters),
    /// A mixture of two BSDFs (Mitsuba's `blendbsdf`):
    /// f = (1 − w)·f₀ + w·f₁, with w the [`TextureSlot::Weight`] texture
    /// where the material has one, else `weight`.
    Blend(Box<BlendDesc>),
}

/// The two parts of a [`BsdfDesc::Blend`] and their weight. Each part is a
/// whole material description so that it keeps its own textures (a
/// textured diffuse blended with a conductor) and its own sides (a
/// one-sided part is black from behind, whatever the other does); their
/// emission, normal, bump and opacity maps are not used (the loader
/// reports them).
#[derive(Clone, Debug, PartialEq)]
pub struct BlendDesc {
    /// The weight of the second part, in [0, 1].
    pub weight: f32,
    /// The first part (weight 1 − w) and the second (weight w).
    pub parts: [MaterialDesc; 2],
}

/// The principled BSDF's parameters, Mitsuba's names and defaults; every
/// one but `eta` in [0, 1] (the renderer clamps them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledParameters {
    /// Base colour (linear), per channel. Default 0.5.
    pub base_color: Vec3,
    /// Roughness (α = roughness²). Default 0.5.
    pub roughness: f32,
    /// Anisotropy (0 isotropic).
    pub anisotropic: f32,
    /// Metalness.
    pub metallic: f32,
    /// Fraction of the dielectric part that is transmitted.
    pub spec_trans: f32,
    /// Index of refraction of the inside relative to the outside. Default
    /// 1.5 (`specular` 0.5).
    pub eta: f32,
    /// Fraction of the dielectric reflection tinted by the base colour.
    pub spec_tint: f32,
    /// Strength of the sheen lobe.
    pub sheen: f32,
    /// Fraction of the sheen tinted by the base colour.
    pub sheen_tint: f32,
    /// Blend of the diffuse toward the flattened "subsurface" shape.
    pub flatness: f32,
    /// Strength of the clearcoat lobe.
    pub clearcoat: f32,
    /// Gloss of the clearcoat (0: α = 0.1, 1: α = 0.001).
    pub clearcoat_gloss: f32,
}

impl Default for PrincipledParameters {
    fn default() -> Self {
        Self {
            base_color: Vec3::splat(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            metallic: 0.0,
            spec_trans: 0.0,
            eta: 1.5,
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            clearcoat: 0.0,
            clearcoat_gloss: 0.0,
        }
    }
}

/// The roughness α of a microfacet distribution along the two tangent
/// directions of the surface: `u` along dp/du of its texture
/// parameterisation (projected onto the tangent plane of the shading
/// normal), `v` across it. Equal: isotropic, and the axes do not matter.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Alpha {
    /// Roughness along dp/du.
    pub u: f32,
    /// Roughness across dp/du (along the shading frame's second tangent).
    pub v: f32,
}

impl Alpha {
    /// The same roughness in every direction.
    pub const fn isotropic(alpha: f32) -> Self {
        Self { u: alpha, v: alpha }
    }

    /// Whether the roughness differs between the two directions.
    pub fn is_anisotropic(&self) -> bool {
        self.u != self.v
    }

    /// Whether the surface is rough at all (both α positive); 0 means a
    /// smooth (delta) model.
    pub fn is_rough(&self) -> bool {
        self.u > 0.0 && self.v > 0.0
    }
}

/// How a microfacet BSDF combines the masking of its two directions into
/// G2: a convention of the renderer a file was written for, so the loader
/// chooses it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Masking {
    /// G2 = 1 / (1 + Λ(wo) + Λ(wi)) (Heitz 2014): masking and shadowing by
    /// the same heights counted once, as pbrt-v4. The default.
    #[default]
    HeightCorrelated,
    /// G2 = G1(wo)·G1(wi), as if the two were independent: at most the
    /// height-correlated form, so it loses a little more energy at grazing
    /// angles. Burley 2012 and Mitsuba 3 (every microfacet BSDF) use it.
    Separable,
}

/// How a rough plastic averages its coating's albedo E(μ) for light from
/// inside over the cosines μ into F_int, the albedo for diffuse light: the
/// base's lobe scales by 1 / (1 − F_int), so a small change in F_int (about
/// 0.6) shows about 2.5 times as large in the base's brightness. A
/// convention of the renderer a file was written for, so the loader
/// chooses it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum InternalReflectance {
    /// F_int = 2 ∫₀¹ E(μ) μ dμ, integrated to convergence. The default.
    #[default]
    Integral,
    /// The plain mean of 2 E(μ) μ at 64 evenly spaced μ in [0, 1], both ends
    /// included, as Mitsuba 3's `roughplastic` computes it: that is
    /// (63/64) F_int + E(1)/64, about 1.5% below the integral, which makes
    /// the base about 2% darker.
    EvenSampleMean,
}

/// Microfacet normal distributions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum MicrofacetModel {
    /// Beckmann (Gaussian slopes).
    #[default]
    Beckmann,
    /// GGX / Trowbridge-Reitz (longer tails).
    Ggx,
}
