//! Texture references. [`crate::TextureRef`] names an image file, so an
//! image stored inside the glTF (a `data:` URI or a `.glb` buffer view) is
//! written once to a content-addressed file in the system's temporary
//! directory (`candela-gltf-images/<hash>.<ext>`) and referenced from there;
//! external images are referenced beside the scene as they are. The
//! texture's image is its `EXT_texture_webp` source when it has one
//! (`use_webp_sources` in `mod.rs`). The
//! texture's sampler gives its wrap mode per axis (`wrapS`, `wrapT`) and,
//! by `magFilter`, whether texels are interpolated: `NEAREST` keeps texels
//! sharp (pixel art, masks), anything else is bilinear. `minFilter` asks for
//! mipmaps, which the renderer does not build, so it is not read.

use super::accessors::Buffers;
use super::buffers::{file_path, read_uri};
use super::Ctx;
use crate::desc::{ColorSpace, TextureFilter, TextureRef, TextureWrap, WrapMode};
use crate::error::{ErrorKind, LoadError};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// The file of texture `tex`, read in `space`; `None` (after a warning) for
/// one the loader cannot reference.
pub(super) fn texture_ref(
    ctx: &Ctx,
    buffers: &Buffers,
    tex: &gltf::Texture,
    tex_coord: u32,
    space: ColorSpace,
) -> Result<Option<TextureRef>, LoadError> {
    if tex_coord != 0 {
        ctx.warn("TEXCOORD_1+", "only TEXCOORD_0 is read")?;
    }
    let image = tex.source();
    let at = format!("/images/{}", image.index());
    let path = match image.source() {
        gltf::image::Source::Uri { uri, mime_type } if uri.starts_with("data:") => {
            let bytes = read_uri(ctx, &at, uri)?;
            let mime = mime_type.or_else(|| uri[5..].split(';').next());
            cache_file(ctx, &at, &bytes, mime)?
        }
        gltf::image::Source::Uri { uri, .. } => file_path(ctx, uri),
        gltf::image::Source::View { view, mime_type } => {
            let buffer = &buffers[view.buffer().index()];
            let bytes = view
                .offset()
                .checked_add(view.length())
                .and_then(|end| buffer.get(view.offset()..end))
                .ok_or_else(|| {
                    ctx.err(
                        format!("/bufferViews/{}", view.index()),
                        ErrorKind::IndexOutOfRange,
                        format!(
                            "image bytes run past the end of buffer {}",
                            view.buffer().index()
                        ),
                    )
                })?;
            cache_file(ctx, &at, bytes, Some(mime_type))?
        }
    };
    let mut t = TextureRef::new(path, space);
    let sampler = tex.sampler();
    t.wrap = TextureWrap {
        u: wrap_mode(sampler.wrap_s()),
        v: wrap_mode(sampler.wrap_t()),
    };
    if sampler.mag_filter() == Some(gltf::texture::MagFilter::Nearest) {
        t.filter = TextureFilter::Nearest;
    }
    Ok(Some(t))
}

/// A sampler's `wrapS` or `wrapT`. glTF's v runs down the image and
/// Candela's up, but every mode is symmetric under that flip (texel `j`
/// from the top is `n − 1 − j` from the bottom, and the modes fold both
/// alike), so the axis keeps its mode.
fn wrap_mode(mode: gltf::texture::WrappingMode) -> WrapMode {
    match mode {
        gltf::texture::WrappingMode::Repeat => WrapMode::Repeat,
        gltf::texture::WrappingMode::MirroredRepeat => WrapMode::Mirror,
        gltf::texture::WrappingMode::ClampToEdge => WrapMode::Clamp,
    }
}

/// Writes embedded image bytes to the temporary cache (unless a file of
/// that content is there already) and returns its path.
fn cache_file(ctx: &Ctx, at: &str, bytes: &[u8], mime: Option<&str>) -> Result<PathBuf, LoadError> {
    let ext = match mime {
        Some("image/png") => "png",
        Some("image/jpeg") => "jpg",
        Some("image/webp") => "webp",
        Some(other) => {
            ctx.warn(
                "image type",
                &format!("embedded {other} images cannot be read by the renderer"),
            )?;
            "bin"
        }
        None => "png",
    };
    let dir = extracted_images_dir();
    let path = dir.join(format!("{:016x}-{}.{ext}", fnv1a(bytes), bytes.len()));
    let same = std::fs::metadata(&path).is_ok_and(|m| m.len() == bytes.len() as u64);
    if !same {
        let io = |e: std::io::Error| {
            ctx.err(
                at.to_string(),
                ErrorKind::Io,
                format!("cannot write the embedded image to {}: {e}", path.display()),
            )
        };
        std::fs::create_dir_all(&dir).map_err(io)?;
        // Write beside and rename, so a concurrent load never sees half a
        // file. The temporary name is unique to this write (process and a
        // per-process count): two loads of one image in the same process
        // (threads, the studio, tests) must not share it, or one renames
        // the file away from under the other.
        static WRITES: AtomicU64 = AtomicU64::new(0);
        let tmp = dir.join(format!(
            "{:016x}.{}.{}.part",
            fnv1a(bytes),
            std::process::id(),
            WRITES.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::write(&tmp, bytes).map_err(io)?;
        std::fs::rename(&tmp, &path).map_err(io)?;
    }
    Ok(path)
}

/// Where images embedded in a glTF file are written for the renderer to
/// read (shared by every load, named by content).
pub(crate) fn extracted_images_dir() -> std::path::PathBuf {
    std::env::temp_dir().join("candela-gltf-images")
}

/// 64-bit FNV-1a: names cache files by content.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}
