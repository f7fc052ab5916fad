//! Texture references inside material extensions the `gltf` crate does not
//! type (`KHR_materials_clearcoat`, `KHR_materials_sheen`): each is typed
//! through the parser's own `Info`, so `KHR_texture_transform` on it is read
//! as on any other texture reference. Shared by the extensions' readers
//! (`clearcoat.rs`, `sheen.rs`).

use super::materials::{khr_texture_transform, TexInfo};
use super::Ctx;
use crate::desc::UvTransform;
use crate::error::LoadError;
use gltf::json::Value;

/// The texture reference `value` of extension `extension` as the loader's
/// [`TexInfo`]: texture, UV set (`KHR_texture_transform`'s `texCoord`
/// overriding the reference's) and uv transform. A reference the parser
/// cannot read, or whose index names no texture, is reported under the
/// extension's name and not used.
pub(super) fn extension_texture<'a>(
    ctx: &Ctx,
    doc: &'a gltf::Document,
    extension: &str,
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
                extension,
                &format!("a texture reference is malformed ({e}); not used"),
            )?;
            return Ok(None);
        }
    };
    let Some(tex) = doc.textures().nth(info.index.value()) else {
        ctx.warn(extension, "a texture reference names no texture; not used")?;
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
