//! `KHR_materials_clearcoat`: a clear GGX coat over the metallic-roughness
//! material (`clearcoatFactor`, `clearcoatRoughnessFactor`, 0 by default,
//! each multiplying its texture: the coat's strength in red, its roughness
//! in green).
//!
//! The `gltf` crate does not type this extension, so its object is read
//! from the material's extension map. Its texture references are typed
//! through the parser's own `Info` (so `KHR_texture_transform` on them is
//! read as on any other texture); a reference the parser cannot read or
//! whose index names no texture is reported and not used.
//! `clearcoatNormalTexture` is reported by name: the coat follows the
//! material's shading normal.

use super::materials::{khr_texture_transform, TexInfo};
use super::Ctx;
use crate::desc::UvTransform;
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
        texture: texture(ctx, doc, ext.get("clearcoatTexture"))?,
        roughness_texture: texture(ctx, doc, ext.get("clearcoatRoughnessTexture"))?,
    }))
}

/// A texture reference of the extension as the loader's [`TexInfo`]:
/// texture, UV set (`KHR_texture_transform`'s `texCoord` overriding the
/// reference's) and uv transform.
fn texture<'a>(
    ctx: &Ctx,
    doc: &'a gltf::Document,
    value: Option<&Value>,
) -> Result<Option<TexInfo<'a>>, LoadError> {
    let Some(value) = value else {
        return Ok(None);
    };
    type Info = gltf::json::texture::Info;
    let info = match gltf::json::deserialize::from_value::<Info>(value.clone()) {
        Ok(info) => info,
        Err(e) => {
            ctx.warn(
                NAME,
                &format!("a texture reference is malformed ({e}); not used"),
            )?;
            return Ok(None);
        }
    };
    let Some(tex) = doc.textures().nth(info.index.value()) else {
        ctx.warn(NAME, "a texture reference names no texture; not used")?;
        return Ok(None);
    };
    let transform = info.extensions.and_then(|e| e.texture_transform);
    let coord = transform
        .as_ref()
        .and_then(|t| t.tex_coord)
        .unwrap_or(info.tex_coord);
    let uv = transform.map_or(UvTransform::IDENTITY, |t| {
        khr_texture_transform(t.offset.0, t.rotation.0, t.scale.0)
    });
    Ok(Some((tex, coord, uv)))
}
