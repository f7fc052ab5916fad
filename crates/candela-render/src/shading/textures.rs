//! A material's texture slots at a hit: every parameter the description can
//! texture (colour, roughness, metalness, normal map, emission, opacity,
//! the glTF model's coat, transmission and specular layer) is
//! read at the hit (its `uv` and vertex colour, a [`TexturePoint`]) and
//! put into the BSDF it belongs to.
//!
//! What each slot drives, per BSDF:
//!
//! | slot | drives |
//! |---|---|
//! | colour | diffuse albedo; mirror reflectance; glass, refraction, thin and rough glass transmittance (the tint); smooth and rough plastic base; glTF and principled base colour; a smooth or rough conductor's normal-incidence reflectance F0 (η = 1, k = 2√(F0/(1−F0)), exact for F0) |
//! | roughness (R, or the slot's channel) | rough conductor and rough glass α; a smooth conductor becomes a Beckmann rough conductor of α = value (as Mitsuba's `roughconductor` default); smooth glass and refraction become Beckmann rough glass of α = value (CS184's convention); glTF and principled (perceptual) roughness |
//! | metalness (B by default, glTF's channel) | glTF and principled metalness |
//! | clear coat, clear coat roughness (R, or the slot's channel: glTF's are R and G) | the glTF model's coat strength and coat roughness (`metallic_roughness_slots.rs`, as the next three) |
//! | transmission (R, or the slot's channel) | the glTF model's transmitted fraction |
//! | specular strength (alpha, glTF's channel, or the slot's) | the glTF model's specular layer strength |
//! | specular colour | the glTF model's specular F0 tint (not clamped to 1: the model caps F0 itself, and glTF lets the factor exceed 1) |
//! | sheen colour (RGB), sheen roughness (R, or the slot's channel: glTF's is alpha) | the glTF model's sheen colour and sheen roughness |
//! | normal map, bump map | the shading normal (`normal_map.rs`) |
//! | emission | emitted radiance (`Material::emission_at`; area lights sample it at the sampled point) |
//! | opacity (alpha if the image has it, else R) | cut-outs (`opacity.rs`) |
//! | blend weight (luminance, clamped to [0, 1]) | a blend's weight (`Material::bsdf_at`, which mixes the parts, each with its own slots) |
//!
//! A colour slot's value is texel × tint × scale per channel, a one-value
//! slot's the channel × scale ([`SlotTexture`]). Colours are clamped to
//! [0, 1] (but the specular tint, above) and one-value parameters to their
//! ranges after scaling, so a texture never creates energy. A slot a BSDF
//! has no parameter for (roughness on a mirror, thin glass or smooth
//! plastic, metalness outside the glTF and principled models, the clear
//! coat's, sheen's, transmission's and specular layer's slots outside the glTF
//! model, colour or roughness on a blend (its parts have theirs), a blend
//! weight on anything but a blend, any of colour/roughness/metalness on a
//! pure emitter) is returned as unsupported, by name.

use super::metallic_roughness_slots::MetallicRoughnessSlots;
use crate::bsdf::{Bsdf, Masking, MicrofacetDistribution};
use crate::texture::{SlotTexture, TextureCache, TexturePoint};
use candela_scene::{PerturbationRules, TextureSlot, TextureSlots};
use glam::Vec3;

/// The channel one-value slots read when the description names none.
pub(super) const DEFAULT_CHANNEL: u8 = 0;
/// glTF and most packers keep metalness in blue.
const METALNESS_CHANNEL: u8 = 2;
/// Alpha: opacity's default when the image has it, and the specular
/// strength's (glTF's channel; 1 where the image has no alpha).
pub(super) const ALPHA_CHANNEL: u8 = 3;

/// The textures of one material, read once at scene build.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialTextures {
    /// Base colour.
    pub color: Option<SlotTexture>,
    /// Roughness (α, or glTF's perceptual roughness).
    pub roughness: Option<SlotTexture>,
    /// Metalness.
    pub metalness: Option<SlotTexture>,
    /// Tangent-space normal map.
    pub normal: Option<SlotTexture>,
    /// Bump (height) map.
    pub bump: Option<SlotTexture>,
    /// Emitted radiance.
    pub emission: Option<SlotTexture>,
    /// Opacity.
    pub opacity: Option<SlotTexture>,
    /// A blend's weight (read by [`crate::material::Material::bsdf_at`],
    /// which mixes the parts).
    pub weight: Option<SlotTexture>,
    /// The glTF model's clear coat, transmission and specular layer
    /// slots, boxed (see [`MetallicRoughnessSlots`]); `None` when all are
    /// empty.
    pub metallic_roughness: Option<Box<MetallicRoughnessSlots>>,
    /// `Some(c)`: opacity is a mask with cutoff c; `None`: a coverage
    /// fraction.
    pub opacity_cutoff: Option<f32>,
    /// The opacity where there is no opacity texture (glTF's constant
    /// alpha), read through `opacity_cutoff` like a texel.
    pub opacity_constant: Option<f32>,
    /// How the normal and bump maps become the shading frame.
    pub perturbation: PerturbationRules,
}

impl MaterialTextures {
    /// Reads every filled slot through `cache` and names the slots `bsdf`
    /// cannot use (the caller reports them).
    pub fn from_slots(
        slots: &TextureSlots,
        bsdf: Option<&Bsdf>,
        cache: &mut TextureCache,
    ) -> (Self, Vec<TextureSlot>) {
        let mut textures = Self {
            opacity_cutoff: slots.opacity_cutoff,
            opacity_constant: slots.opacity_constant,
            perturbation: slots.perturbation,
            ..Self::default()
        };
        let mut unusable = Vec::new();
        for (slot, t) in slots.iter() {
            if !drives(bsdf, slot) {
                unusable.push(slot);
                continue;
            }
            if let Some(loaded) = SlotTexture::load(t, cache) {
                *textures.slot_mut(slot) = Some(loaded);
            }
        }
        (textures, unusable)
    }

    /// The field of `slot` (a glTF extension's slot opens the box).
    fn slot_mut(&mut self, slot: TextureSlot) -> &mut Option<SlotTexture> {
        match slot {
            TextureSlot::Color => &mut self.color,
            TextureSlot::Roughness => &mut self.roughness,
            TextureSlot::Metalness => &mut self.metalness,
            TextureSlot::Normal => &mut self.normal,
            TextureSlot::Bump => &mut self.bump,
            TextureSlot::Emission => &mut self.emission,
            TextureSlot::Opacity => &mut self.opacity,
            TextureSlot::Weight => &mut self.weight,
            TextureSlot::Clearcoat => &mut self.layers().clearcoat,
            TextureSlot::ClearcoatRoughness => &mut self.layers().clearcoat_roughness,
            TextureSlot::SheenColor => &mut self.layers().sheen_color,
            TextureSlot::SheenRoughness => &mut self.layers().sheen_roughness,
            TextureSlot::Transmission => &mut self.layers().transmission,
            TextureSlot::Specular => &mut self.layers().specular,
            TextureSlot::SpecularColor => &mut self.layers().specular_color,
        }
    }

    /// The glTF model's extension slots, boxed on first use.
    fn layers(&mut self) -> &mut MetallicRoughnessSlots {
        self.metallic_roughness.get_or_insert_with(Box::default)
    }

    /// Whether any slot that changes the BSDF is filled. Asked per path
    /// vertex: four tests, whatever the glTF model's extensions add.
    #[inline]
    pub(crate) fn textures_bsdf(&self) -> bool {
        self.color.is_some()
            || self.roughness.is_some()
            || self.metalness.is_some()
            || self.metallic_roughness.is_some()
    }

    /// `bsdf` with its textured parameters read at `at`.
    pub fn apply(&self, bsdf: Bsdf, at: impl Into<TexturePoint>) -> Bsdf {
        if !self.textures_bsdf() {
            return bsdf;
        }
        let at: TexturePoint = at.into();
        let color = self
            .color
            .as_ref()
            .map(|t| t.color(at).clamp(Vec3::ZERO, Vec3::ONE));
        let roughness = self
            .roughness
            .as_ref()
            .map(|t| t.value(at, DEFAULT_CHANNEL).max(0.0));
        match bsdf {
            Bsdf::Diffuse { albedo } => Bsdf::Diffuse {
                albedo: color.unwrap_or(albedo),
            },
            Bsdf::Mirror { reflectance } => Bsdf::Mirror {
                reflectance: color.unwrap_or(reflectance),
            },
            Bsdf::Glass {
                reflectance,
                transmittance,
                ior,
            } => glass(reflectance, color.unwrap_or(transmittance), roughness, ior),
            Bsdf::Refraction { transmittance, ior } => match roughness {
                Some(_) => glass(Vec3::ZERO, color.unwrap_or(transmittance), roughness, ior),
                None => Bsdf::Refraction {
                    transmittance: color.unwrap_or(transmittance),
                    ior,
                },
            },
            Bsdf::ThinGlass {
                reflectance,
                transmittance,
                ior,
            } => Bsdf::ThinGlass {
                reflectance,
                transmittance: color.unwrap_or(transmittance),
                ior,
            },
            Bsdf::RoughGlass {
                distribution,
                masking,
                reflectance,
                transmittance,
                ior,
            } => Bsdf::RoughGlass {
                distribution: roughness.map_or(distribution, |a| with_alpha(distribution, a)),
                masking,
                reflectance,
                transmittance: color.unwrap_or(transmittance),
                ior,
            },
            Bsdf::Plastic(p) => Bsdf::Plastic(color.map_or(p, |c| p.with_diffuse(c))),
            // Roughness is not textured here: each α would need its own
            // coating table (`bsdf/coating.rs`); `drives` reports it.
            Bsdf::RoughPlastic(p) => Bsdf::RoughPlastic(color.map_or(p, |c| p.with_diffuse(c))),
            Bsdf::Conductor { eta, k } => {
                let (eta, k) = color.map_or((eta, k), conductor_of_reflectance);
                match roughness {
                    Some(a) => Bsdf::Microfacet {
                        distribution: MicrofacetDistribution::beckmann(a),
                        masking: Masking::HeightCorrelated,
                        eta,
                        k,
                    },
                    None => Bsdf::Conductor { eta, k },
                }
            }
            Bsdf::Microfacet {
                distribution,
                masking,
                eta,
                k,
            } => {
                let (eta, k) = color.map_or((eta, k), conductor_of_reflectance);
                Bsdf::Microfacet {
                    distribution: roughness.map_or(distribution, |a| with_alpha(distribution, a)),
                    masking,
                    eta,
                    k,
                }
            }
            Bsdf::MetallicRoughness(m) => {
                let (base, metallic, rough) = m.parameters();
                let metallic = self
                    .metalness
                    .as_ref()
                    .map_or(metallic, |t| t.value(at, METALNESS_CHANNEL));
                let m = m.with(color.unwrap_or(base), metallic, roughness.unwrap_or(rough));
                Bsdf::MetallicRoughness(match &self.metallic_roughness {
                    Some(layers) => layers.apply(m, at),
                    None => m,
                })
            }
            Bsdf::Principled(p) => {
                let q = p.parameters();
                let metallic = self
                    .metalness
                    .as_ref()
                    .map_or(q.metallic, |t| t.value(at, METALNESS_CHANNEL));
                Bsdf::Principled(p.with(
                    color.unwrap_or(q.base_color),
                    metallic,
                    roughness.unwrap_or(q.roughness),
                ))
            }
            // Models added later keep their constants until they get an arm.
            #[allow(unreachable_patterns)]
            other => other,
        }
    }

    /// The textured emission at `at`, if the emission slot is filled.
    pub fn emission(&self, at: impl Into<TexturePoint>) -> Option<Vec3> {
        let at = at.into();
        self.emission.as_ref().map(|t| t.color(at).max(Vec3::ZERO))
    }

    /// The opacity at `at` in [0, 1]: the texture's value, else the
    /// constant, else 1; with a cutoff, 1 where the value reaches it and 0
    /// below.
    pub fn opacity(&self, at: impl Into<TexturePoint>) -> f32 {
        let at: TexturePoint = at.into();
        let value = match (&self.opacity, self.opacity_constant) {
            (Some(t), _) => {
                let channel = if t.has_alpha() {
                    ALPHA_CHANNEL
                } else {
                    DEFAULT_CHANNEL
                };
                t.value(at, channel)
            }
            (None, Some(constant)) => constant,
            (None, None) => return 1.0,
        };
        match self.opacity_cutoff {
            Some(cutoff) => f32::from(u8::from(value >= cutoff)),
            None if value.is_nan() => 1.0,
            None => value.clamp(0.0, 1.0),
        }
    }

    /// Whether the material has cut-outs at all.
    pub fn has_opacity(&self) -> bool {
        self.opacity.is_some() || self.opacity_constant.is_some()
    }
}

/// Whether a texture in `slot` changes something on a material of `bsdf`
/// (see the table in the module docs).
fn drives(bsdf: Option<&Bsdf>, slot: TextureSlot) -> bool {
    match (slot, bsdf) {
        (TextureSlot::Emission | TextureSlot::Opacity, _) => true,
        (_, None) => false,
        (TextureSlot::Weight, Some(b)) => matches!(b, Bsdf::Blend(_)),
        // A blend's own colour and roughness: its parts have theirs.
        (TextureSlot::Color | TextureSlot::Roughness, Some(Bsdf::Blend(_))) => false,
        (TextureSlot::Color | TextureSlot::Normal | TextureSlot::Bump, Some(_)) => true,
        (
            TextureSlot::Clearcoat
            | TextureSlot::ClearcoatRoughness
            | TextureSlot::Transmission
            | TextureSlot::Specular
            | TextureSlot::SpecularColor
            | TextureSlot::SheenColor
            | TextureSlot::SheenRoughness,
            Some(b),
        ) => matches!(b, Bsdf::MetallicRoughness(_)),
        (TextureSlot::Metalness, Some(b)) => {
            matches!(b, Bsdf::MetallicRoughness(_) | Bsdf::Principled(_))
        }
        (TextureSlot::Roughness, Some(b)) => !matches!(
            b,
            Bsdf::Diffuse { .. }
                | Bsdf::Mirror { .. }
                | Bsdf::ThinGlass { .. }
                | Bsdf::Plastic(_)
                | Bsdf::RoughPlastic(_)
        ),
    }
}

/// Glass with an optional textured roughness: rough (Beckmann, α = the
/// value) when a roughness texture is given, else smooth.
fn glass(reflectance: Vec3, transmittance: Vec3, roughness: Option<f32>, ior: f32) -> Bsdf {
    match roughness {
        Some(alpha) => Bsdf::RoughGlass {
            distribution: MicrofacetDistribution::beckmann(alpha),
            masking: Masking::HeightCorrelated,
            reflectance,
            transmittance,
            ior,
        },
        None => Bsdf::Glass {
            reflectance,
            transmittance,
            ior,
        },
    }
}

/// The same distribution (kind) with isotropic roughness `alpha`.
fn with_alpha(d: MicrofacetDistribution, alpha: f32) -> MicrofacetDistribution {
    match d {
        MicrofacetDistribution::Beckmann { .. } => MicrofacetDistribution::beckmann(alpha),
        MicrofacetDistribution::Ggx { .. } => MicrofacetDistribution::ggx(alpha),
    }
}

/// A conductor whose normal-incidence reflectance is `f0`: η = 1 and
/// k = 2√(F0/(1−F0)), since ((η−1)² + k²)/((η+1)² + k²) = k²/(4 + k²) = F0.
fn conductor_of_reflectance(f0: Vec3) -> (Vec3, Vec3) {
    let f0 = f0.clamp(Vec3::ZERO, Vec3::splat(0.999));
    (Vec3::ONE, (f0 / (Vec3::ONE - f0)).map(f32::sqrt) * 2.0)
}
