//! `KHR_materials_clearcoat`: a clear GGX coat over the metallic-roughness
//! material (`clearcoatFactor`, `clearcoatRoughnessFactor`, 0 by default,
//! each multiplying its texture: the coat's strength in red, its roughness
//! in green).
//!
//! The `gltf` crate does not type this extension, so its object is read
//! from the material's extension map, its texture references through
//! `extension_textures.rs` (a reference the parser cannot read or whose
//! index names no texture is reported and not used).
//! `clearcoatNormalTexture` is reported by name: the coat follows the
//! material's shading normal.

use super::extension_textures::extension_texture;
use super::materials::TexInfo;
use super::Ctx;
use crate::error::LoadError;
use gltf::json::Value;

/// The extension's name in files.
const NAME: &str = "KHR_materials_clearcoat";

/// A material's clear coat: its factors and textures.
pub(super) struct Clearcoat<'a> {
    /// `clearcoatFactor`.
    pub factor: f32,
    /// `clearcoatRoughnessFactor`.
    pub roughness: f32,
    /// `clearcoatTexture` (red channel).
    pub texture: Option<TexInfo<'a>>,
    /// `clearcoatRoughnessTexture` (green channel).
    pub roughness_texture: Option<TexInfo<'a>>,
}

/// The clear coat of material `m`, if it has the extension.
pub(super) fn read_clearcoat<'a>(
    ctx: &Ctx,
    doc: &'a gltf::Document,
    m: &gltf::Material,
) -> Result<Option<Clearcoat<'a>>, LoadError> {
    let Some(ext) = m.extensions().and_then(|e| e.get(NAME)) else {
        return Ok(None);
    };
    let number = |key: &str| ext.get(key).and_then(Value::as_f64).map(|v| v as f32);
    if ext.get("clearcoatNormalTexture").is_some() {
        ctx.warn(
            "clearcoatNormalTexture",
            "the clear coat's own normal map is not read; the coat follows the material's normal",
        )?;
    }
    Ok(Some(Clearcoat {
        factor: number("clearcoatFactor").unwrap_or(0.0),
        roughness: number("clearcoatRoughnessFactor").unwrap_or(0.0),
        texture: extension_texture(ctx, doc, NAME, ext.get("clearcoatTexture"))?,
        roughness_texture: extension_texture(ctx, doc, NAME, ext.get("clearcoatRoughnessTexture"))?,
    }))
}
