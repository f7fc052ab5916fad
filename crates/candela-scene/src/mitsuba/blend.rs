//! Mitsuba's `blendbsdf`: the mixture (1 − w)·f₀ + w·f₁ of its two inner
//! BSDFs, as a [`BsdfDesc::Blend`].
//!
//! The weight is a float, a colour (read as the mean of its channels, as
//! Mitsuba reads a constant colour as one value) or a texture (the blend
//! weight slot); a constant outside [0, 1] is clamped, as Mitsuba clamps
//! it, and reported. Each part keeps its own textures and sides (a
//! one-sided part is black from behind even where the other is not). A
//! part's normal, bump or opacity map is reported and dropped: Candela
//! shades a hit in one frame, where Mitsuba perturbs each part's own.

use super::bsdfs::set;
use super::doc::{elements, Doc, XNode};
use super::Builder;
use crate::desc::{BlendDesc, BsdfDesc, MaterialDesc, Sides, TextureSlot, TextureSlots};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

impl Builder {
    /// A `blendbsdf` element as a material.
    pub(super) fn blend(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: String,
    ) -> Result<MaterialDesc, LoadError> {
        let mut parts = Vec::new();
        for c in elements(node) {
            let part = match c.tag_name().name() {
                "bsdf" => self.bsdf(doc, c)?,
                "ref" => {
                    let id = doc.required(c, "id")?;
                    if self.textures.contains_key(&id) {
                        continue; // the weight, given by reference
                    }
                    self.named_bsdf(doc, c, &id)?
                }
                _ => continue,
            };
            parts.push(part);
        }
        let Ok(mut parts) = <[MaterialDesc; 2]>::try_from(parts) else {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                "blendbsdf needs exactly two inner BSDFs",
            ));
        };
        for (i, part) in parts.iter_mut().enumerate() {
            self.keep_scattering_only(doc, node, i, part)?;
        }
        let mut textures = TextureSlots::default();
        let weight = self.blend_weight(doc, node, &mut textures)?;
        Ok(MaterialDesc {
            name,
            bsdf: BsdfDesc::Blend(Box::new(BlendDesc { weight, parts })),
            emission: None,
            textures,
            // Each part decides for itself what it does behind.
            sides: Sides::Both,
            loc: doc.loc(node),
        })
    }

    /// `weight`: required; a texture fills the blend weight slot.
    fn blend_weight(
        &mut self,
        doc: &Doc,
        node: XNode,
        textures: &mut TextureSlots,
    ) -> Result<f32, LoadError> {
        let Some(p) = doc.prop(node, "weight")? else {
            return Err(doc.err(
                node,
                ErrorKind::MissingElement,
                "blendbsdf has no \"weight\"",
            ));
        };
        let (value, texture) = self.color(doc, node, "weight", Vec3::splat(0.5))?;
        set(textures, TextureSlot::Weight, texture);
        // Finite: the value parser refuses NaN and infinities.
        let w = value.element_sum() / 3.0;
        if !(0.0..=1.0).contains(&w) {
            self.warn(
                doc,
                p,
                format!("blendbsdf weight {w} is outside [0, 1] (clamped)"),
            )?;
        }
        Ok(w.clamp(0.0, 1.0))
    }

    /// Drops (and reports) what a blend's part `i` has besides scattering:
    /// maps that move the shading frame or cut the surface out, which
    /// Candela applies per material, not per part.
    fn keep_scattering_only(
        &mut self,
        doc: &Doc,
        node: XNode,
        i: usize,
        part: &mut MaterialDesc,
    ) -> Result<(), LoadError> {
        let which = ["first", "second"][i];
        let t = &mut part.textures;
        for (slot, present) in [
            (TextureSlot::Normal, t.normal.take().is_some()),
            (TextureSlot::Bump, t.bump.take().is_some()),
            (
                TextureSlot::Opacity,
                t.opacity.take().is_some() | t.opacity_constant.take().is_some(),
            ),
        ] {
            if present {
                self.warn(
                    doc,
                    node,
                    format!(
                        "blendbsdf: the {} of its {which} BSDF is not supported inside a blend (ignored)",
                        slot.name()
                    ),
                )?;
            }
        }
        Ok(())
    }
}

/// Makes every part of a blend that scatters on its front only scatter on
/// both sides, through nested blends: what `twosided` around a blend does
/// (Mitsuba turns the frame over before the blend sees it, so every part
/// sees the viewer in front).
pub(super) fn blend_parts_two_sided(m: &mut MaterialDesc) {
    if let BsdfDesc::Blend(blend) = &mut m.bsdf {
        for part in &mut blend.parts {
            if part.sides == Sides::Front {
                part.sides = Sides::Both;
            }
            blend_parts_two_sided(part);
        }
    }
}

/// Whether a material's BSDF transmits somewhere: a dielectric, or a blend
/// with a part that does (Mitsuba's `twosided` refuses both).
pub(super) fn transmits(m: &MaterialDesc) -> bool {
    match &m.bsdf {
        BsdfDesc::Glass { .. }
        | BsdfDesc::ThinDielectric { .. }
        | BsdfDesc::RoughDielectric { .. }
        | BsdfDesc::Refraction { .. } => true,
        BsdfDesc::Blend(b) => b.parts.iter().any(transmits),
        _ => false,
    }
}
