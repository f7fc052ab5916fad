//! `KHR_materials_sheen`: a sheen (the back-scattering rim of velvet and
//! other fabrics) over the metallic-roughness material: `sheenColorFactor`
//! (linear RGB, black by default: no sheen) times `sheenColorTexture` (its
//! RGB, sRGB-encoded), and `sheenRoughnessFactor` (0 by default) times
//! `sheenRoughnessTexture` (its alpha channel, linear).
//!
//! The `gltf` crate does not type this extension, so its object is read
//! from the material's extension map, its texture references through
//! `extension_textures.rs` (a reference the parser cannot read or whose
//! index names no texture is reported and not used), as for the clear coat.
//! A `sheenColorFactor` that is not three numbers is reported and read as
//! black.

use super::extension_textures::extension_texture;
use super::materials::TexInfo;
use super::Ctx;
use crate::error::LoadError;
use glam::Vec3;
use gltf::json::Value;

/// The extension's name in files.
const NAME: &str = "KHR_materials_sheen";

/// A material's sheen: its factors and textures.
pub(super) struct Sheen<'a> {
    /// `sheenColorFactor`.
    pub color: Vec3,
    /// `sheenRoughnessFactor`.
    pub roughness: f32,
    /// `sheenColorTexture` (RGB, sRGB).
    pub color_texture: Option<TexInfo<'a>>,
    /// `sheenRoughnessTexture` (alpha channel).
    pub roughness_texture: Option<TexInfo<'a>>,
}

/// The sheen of material `m`, if it has the extension.
pub(super) fn read_sheen<'a>(
    ctx: &Ctx,
    doc: &'a gltf::Document,
    m: &gltf::Material,
) -> Result<Option<Sheen<'a>>, LoadError> {
    let Some(ext) = m.extensions().and_then(|e| e.get(NAME)) else {
        return Ok(None);
    };
    let color = match ext.get("sheenColorFactor").map(color) {
        None => Vec3::ZERO,
        Some(Some(c)) => c,
        Some(None) => {
            ctx.warn(
                "sheenColorFactor",
                "the sheen colour is not three numbers; no sheen",
            )?;
            Vec3::ZERO
        }
    };
    let roughness = ext
        .get("sheenRoughnessFactor")
        .and_then(Value::as_f64)
        .map_or(0.0, |v| v as f32);
    Ok(Some(Sheen {
        color,
        roughness,
        color_texture: extension_texture(ctx, doc, NAME, ext.get("sheenColorTexture"))?,
        roughness_texture: extension_texture(ctx, doc, NAME, ext.get("sheenRoughnessTexture"))?,
    }))
}

/// An array of exactly three numbers as a colour.
fn color(value: &Value) -> Option<Vec3> {
    let items = value.as_array()?;
    let [r, g, b] = items.as_slice() else {
        return None;
    };
    Some(Vec3::new(
        r.as_f64()? as f32,
        g.as_f64()? as f32,
        b.as_f64()? as f32,
    ))
}
