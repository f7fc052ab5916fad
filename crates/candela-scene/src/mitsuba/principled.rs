//! Mitsuba's `principled` BSDF: its parameters, with the loader's rules
//! for `eta` and `specular` (Mitsuba's `principled.cpp` constructor).
//!
//! `base_color`, `roughness` and `metallic` may be textures (the colour,
//! roughness and metalness slots); the others are constants here, and a
//! texture on one is reported by name and replaced by its default. The
//! sampling rates change only how Mitsuba picks lobes, not the image
//! Candela converges to, and are reported as unused.

use super::doc::{Doc, XNode};
use super::values::float_of;
use super::Builder;
use crate::desc::{BsdfDesc, PrincipledParameters, TextureSlot, TextureSlots};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// Properties that only steer Mitsuba's lobe sampling.
const SAMPLING_RATES: [&str; 3] = [
    "main_specular_sampling_rate",
    "clearcoat_sampling_rate",
    "diffuse_reflectance_sampling_rate",
];

impl Builder {
    /// A `principled` BSDF; textures go into `textures`.
    pub(super) fn principled(
        &mut self,
        doc: &Doc,
        node: XNode,
        textures: &mut TextureSlots,
    ) -> Result<BsdfDesc, LoadError> {
        let mut textured = |b: &mut Self, name: &str, slot: TextureSlot, default: f32| {
            let (value, tex) = b.color(doc, node, name, Vec3::splat(default))?;
            super::bsdfs::set(textures, slot, tex);
            Ok::<Vec3, LoadError>(value)
        };
        let base_color = textured(self, "base_color", TextureSlot::Color, 0.5)?;
        let roughness = textured(self, "roughness", TextureSlot::Roughness, 0.5)?.x;
        let metallic = textured(self, "metallic", TextureSlot::Metalness, 0.0)?.x;
        let scalar = |b: &mut Self, name: &str| {
            Ok::<f32, LoadError>(b.constant(doc, node, name, Vec3::ZERO)?.x)
        };
        let spec_trans = scalar(self, "spec_trans")?;
        let desc = BsdfDesc::Principled(PrincipledParameters {
            base_color,
            roughness,
            anisotropic: scalar(self, "anisotropic")?,
            metallic,
            spec_trans,
            eta: principled_eta(doc, node, spec_trans != 0.0)?,
            spec_tint: scalar(self, "spec_tint")?,
            sheen: scalar(self, "sheen")?,
            sheen_tint: scalar(self, "sheen_tint")?,
            flatness: scalar(self, "flatness")?,
            clearcoat: scalar(self, "clearcoat")?,
            clearcoat_gloss: scalar(self, "clearcoat_gloss")?,
        });
        for name in SAMPLING_RATES {
            if let Some(p) = doc.prop(node, name)? {
                self.warn(
                    doc,
                    p,
                    format!("\"{name}\" is not used (it changes Mitsuba's noise, not the image)"),
                )?;
            }
        }
        Ok(desc)
    }
}

/// The relative IOR from `eta` or `specular` (not both): specular s maps
/// to η = 2 / (1 − √(0.08 s)) − 1 (s = 0.5 is η = 1.5). A transmitting
/// material (`transmits`) never gets η = 1: `eta` 1 becomes 1.001 and
/// `specular` 0 becomes 0.001, as in Mitsuba.
fn principled_eta(doc: &Doc, node: XNode, transmits: bool) -> Result<f32, LoadError> {
    let eta_prop = doc.prop(node, "eta")?;
    let specular_prop = doc.prop(node, "specular")?;
    let (eta, at) = match (eta_prop, specular_prop) {
        (Some(_), Some(s)) => {
            return Err(doc.err(
                s,
                ErrorKind::BadValue,
                "principled: give either \"eta\" or \"specular\", not both",
            ))
        }
        (Some(p), None) => {
            let eta = float_of(doc, p)?;
            (if transmits && eta == 1.0 { 1.001 } else { eta }, p)
        }
        (None, Some(p)) => {
            let s = float_of(doc, p)?;
            let s = if transmits && s == 0.0 { 1e-3 } else { s };
            (2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0, p)
        }
        (None, None) => return Ok(1.5),
    };
    if eta.is_finite() && eta > 0.0 {
        Ok(eta)
    } else {
        Err(doc.err(
            at,
            ErrorKind::BadValue,
            format!("principled: relative IOR {eta} is not positive and finite"),
        ))
    }
}
