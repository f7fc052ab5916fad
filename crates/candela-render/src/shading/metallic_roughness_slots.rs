//! The texture slots only the glTF metallic-roughness model reads: its
//! extensions' clear coat (`KHR_materials_clearcoat`), sheen
//! (`KHR_materials_sheen`), transmitted fraction
//! (`KHR_materials_transmission`) and specular layer
//! (`KHR_materials_specular`).
//!
//! Kept apart from [`MaterialTextures`](super::MaterialTextures)' common
//! slots and boxed, so that the render loop's per-vertex question "does a
//! texture change this BSDF?" (`MaterialTextures::textures_bsdf`) asks one
//! pointer about all of them, however many there are: asked one by one,
//! three more slots cost the untextured CS184 render 0.1% more
//! instructions (`benches/callgrind_render.sh`).

use super::textures::{ALPHA_CHANNEL, DEFAULT_CHANNEL};
use crate::bsdf::MetallicRoughness;
use crate::texture::{SlotTexture, TexturePoint};

/// The glTF model's extension slots of one material.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MetallicRoughnessSlots {
    /// The clear coat's strength.
    pub clearcoat: Option<SlotTexture>,
    /// The clear coat's perceptual roughness.
    pub clearcoat_roughness: Option<SlotTexture>,
    /// The sheen's colour (texel × tint × scale).
    pub sheen_color: Option<SlotTexture>,
    /// The sheen's perceptual roughness (R unless the slot names a channel;
    /// glTF's loader names alpha).
    pub sheen_roughness: Option<SlotTexture>,
    /// The dielectric part's transmitted fraction.
    pub transmission: Option<SlotTexture>,
    /// The dielectric specular layer's strength (alpha by default, glTF's
    /// channel).
    pub specular: Option<SlotTexture>,
    /// The specular layer's F0 tint, a colour (texel × tint × scale),
    /// passed unclamped: the model caps F0 itself, and glTF lets the
    /// factor exceed 1.
    pub specular_color: Option<SlotTexture>,
}

impl MetallicRoughnessSlots {
    /// `m` with the textured layers read at `at`; an empty slot keeps the
    /// model's constant.
    pub fn apply(&self, m: MetallicRoughness, at: TexturePoint) -> MetallicRoughness {
        let value = |t: &Option<SlotTexture>, constant: f32, channel: u8| {
            t.as_ref().map_or(constant, |t| t.value(at, channel))
        };
        let (coat, coat_roughness) = m.clearcoat();
        let (sheen, sheen_roughness) = m.sheen();
        let sheen = self.sheen_color.as_ref().map_or(sheen, |t| t.color(at));
        let (specular, specular_color) = m.specular();
        let specular_color = self
            .specular_color
            .as_ref()
            .map_or(specular_color, |t| t.color(at));
        let transmission = value(&self.transmission, m.transmission(), DEFAULT_CHANNEL);
        m.with_transmission(transmission)
            .with_specular(
                value(&self.specular, specular, ALPHA_CHANNEL),
                specular_color,
            )
            .with_sheen(
                sheen,
                value(&self.sheen_roughness, sheen_roughness, DEFAULT_CHANNEL),
            )
            .with_clearcoat(
                value(&self.clearcoat, coat, DEFAULT_CHANNEL),
                value(&self.clearcoat_roughness, coat_roughness, DEFAULT_CHANNEL),
            )
    }
}

#[cfg(test)]
#[path = "metallic_roughness_slots_tests.rs"]
mod tests;
