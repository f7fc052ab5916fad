//! The glTF 2.0 loader: `.gltf` (JSON with external or `data:` buffers) and
//! `.glb` (binary container).
//!
//! Stages: read the file (size guard), split a `.glb` into its chunks
//! (`glb`, lengths checked, nothing copied), parse and validate the JSON
//! with the `gltf` crate (its validation refuses dangling indices and
//! `extensionsRequired` it does not support, once the extensions this loader
//! reads itself are taken off that list), name every unsupported
//! extension and feature once, load the buffers (`buffers`), then walk the
//! default scene (`nodes`) into meshes (`meshes`, reading accessors through
//! the bounds-checked `accessors`), materials (`materials`, `textures`),
//! cameras (`cameras`) and lights (`lights`).
//!
//! JSON has no useful line for most problems, so errors are located by
//! their JSON pointer (`/nodes/3/mesh`) in the element position of the
//! one-line message; JSON syntax errors carry `line:col`.

mod accessors;
mod buffers;
mod cameras;
mod clearcoat;
mod extension_textures;
mod glb;
mod lights;
mod materials;
mod meshes;
mod nodes;
mod sheen;
mod textures;

pub(crate) use textures::extracted_images_dir;

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use crate::text_file::MAX_FILE_BYTES;
use crate::{LoadOptions, Loaded, RenderHints};
use std::cell::RefCell;
use std::path::Path;

/// Extensions the loader reads; a file may require any of them (any other
/// required extension is refused).
const READ_EXTENSIONS: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_materials_clearcoat",
    "KHR_materials_emissive_strength",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_volume",
    "KHR_texture_transform",
    "EXT_texture_webp",
];

/// The file being loaded and the warnings so far.
pub(crate) struct Ctx<'a> {
    /// The scene file, for messages and relative URIs.
    pub file: &'a Path,
    warnings: RefCell<Collector>,
}

impl Ctx<'_> {
    /// An error at JSON pointer (or chunk name) `at`.
    pub fn err(&self, at: String, kind: ErrorKind, message: String) -> LoadError {
        LoadError {
            file: self.file.to_path_buf(),
            loc: None,
            element: at,
            kind,
            message,
        }
    }

    /// Reports ignored feature `name` (once, with a count).
    pub fn warn(&self, name: &str, message: &str) -> Result<(), LoadError> {
        self.warnings
            .borrow_mut()
            .warn(name.to_string(), message.to_string(), SourceLoc::default)
    }
}

/// Reads and loads a `.gltf` or `.glb` file (the entry of [`crate::formats`]).
pub(crate) fn load_file(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let whole = |kind, msg| LoadError::whole_file(path.to_path_buf(), kind, msg);
    let len = std::fs::metadata(path)
        .map_err(|e| whole(ErrorKind::Io, e.to_string()))?
        .len();
    if len > MAX_FILE_BYTES {
        return Err(whole(
            ErrorKind::TooLarge,
            format!("{len} bytes exceeds the limit of {MAX_FILE_BYTES}"),
        ));
    }
    crate::referenced::note_read(path);
    let bytes = std::fs::read(path).map_err(|e| whole(ErrorKind::Io, e.to_string()))?;
    load_bytes(&bytes, path, opts)
}

/// Loads glTF from the file's bytes; `source` names it in messages and
/// anchors relative URIs.
pub(crate) fn load_bytes(
    bytes: &[u8],
    source: &Path,
    opts: &LoadOptions,
) -> Result<Loaded, LoadError> {
    let ctx = Ctx {
        file: source,
        warnings: RefCell::new(Collector::new(source.to_path_buf(), opts.strict)),
    };
    let is_glb_name = source
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    let (json, bin) = if glb::is_glb(bytes) || is_glb_name {
        let g = glb::split(&ctx, bytes)?;
        (g.json, g.bin)
    } else {
        (bytes, None)
    };
    let mut root: gltf::json::Root =
        gltf::json::deserialize::from_slice(json).map_err(|e| LoadError {
            loc: (e.line() > 0).then(|| SourceLoc {
                line: e.line() as u32,
                col: e.column() as u32,
            }),
            ..ctx.err(
                String::new(),
                ErrorKind::BadValue,
                format!("not a glTF JSON document: {e}"),
            )
        })?;
    check_position_indices(&ctx, &root)?;
    check_image_sources(&ctx, &root)?;
    use_webp_sources(&ctx, &mut root)?;
    accept_read_requirements(&mut root);
    let doc = gltf::Document::from_json(root).map_err(|e| validation_error(&ctx, e))?;
    report_unsupported(&ctx, &doc)?;
    let buffers = buffers::read_all(&ctx, &doc, bin)?;
    let scene = nodes::read_scene(&ctx, &doc, &buffers)?;
    let hints = RenderHints {
        file_camera: !scene.cameras.is_empty(),
        ..RenderHints::default()
    };
    Ok(Loaded {
        scene,
        report: ctx.warnings.into_inner().finish(),
        hints,
    })
}

/// Refuses a `POSITION` index past the accessors before the `gltf` crate's
/// validation, which indexes the accessors with it unchecked (and panics).
fn check_position_indices(ctx: &Ctx, root: &gltf::json::Root) -> Result<(), LoadError> {
    use gltf::json::validation::Checked;
    for (i, mesh) in root.meshes.iter().enumerate() {
        for (j, prim) in mesh.primitives.iter().enumerate() {
            let pos = prim
                .attributes
                .get(&Checked::Valid(gltf::Semantic::Positions));
            if let Some(index) = pos.filter(|a| a.value() >= root.accessors.len()) {
                return Err(ctx.err(
                    format!("/meshes/{i}/primitives/{j}/attributes/POSITION"),
                    ErrorKind::IndexOutOfRange,
                    format!(
                        "accessor {} does not exist ({} accessors)",
                        index.value(),
                        root.accessors.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Drops from `extensionsRequired` the extensions this loader reads, for
/// the `gltf` crate's validation refuses every required extension outside
/// its own list, which misses some the loader reads (`KHR_mesh_quantization`,
/// whose reading is the accessor reader's work, `accessors`). Whatever is
/// left is refused there.
fn accept_read_requirements(root: &mut gltf::json::Root) {
    root.extensions_required
        .retain(|ext| !READ_EXTENSIONS.contains(&ext.as_str()));
}

/// Points every texture with an `EXT_texture_webp` source at that image:
/// the renderer reads WebP, and the extension's image is the one the file's
/// author meant (the core `source`, if any, is a fallback for readers
/// without WebP, and may be absent when the extension is required). An
/// extension source that names no image is refused here, by its pointer.
fn use_webp_sources(ctx: &Ctx, root: &mut gltf::json::Root) -> Result<(), LoadError> {
    let images = root.images.len();
    for (i, texture) in root.textures.iter_mut().enumerate() {
        let Some(webp) = texture
            .extensions
            .as_ref()
            .and_then(|e| e.others.get("EXT_texture_webp"))
        else {
            continue;
        };
        let at = format!("/textures/{i}/extensions/EXT_texture_webp/source");
        let index = webp.get("source").ok_or_else(|| {
            ctx.err(
                at.clone(),
                ErrorKind::MissingElement,
                "the extension needs a source image".into(),
            )
        })?;
        match index.as_u64().filter(|&n| n < images as u64) {
            Some(n) => texture.source = gltf::json::Index::new(n as u32),
            None => {
                return Err(ctx.err(
                    at,
                    ErrorKind::IndexOutOfRange,
                    format!("{index} is not an image index ({images} images)"),
                ))
            }
        }
    }
    Ok(())
}

/// Refuses an image without a source before the `gltf` crate reads it:
/// its `Image::source` unwraps the `uri` of an image without a
/// `bufferView`, and the `mimeType` of one with (the specification
/// requires both; its validation checks neither).
fn check_image_sources(ctx: &Ctx, root: &gltf::json::Root) -> Result<(), LoadError> {
    for (i, image) in root.images.iter().enumerate() {
        let missing = match (&image.buffer_view, &image.uri, &image.mime_type) {
            (Some(_), _, None) => "an image in a bufferView needs a mimeType",
            (None, None, _) => "an image needs a uri or a bufferView",
            _ => continue,
        };
        return Err(ctx.err(
            format!("/images/{i}"),
            ErrorKind::MissingElement,
            missing.to_string(),
        ));
    }
    Ok(())
}

/// Names every extension and feature the loader does not draw, once.
fn report_unsupported(ctx: &Ctx, doc: &gltf::Document) -> Result<(), LoadError> {
    for ext in doc.extensions_used() {
        if !READ_EXTENSIONS.contains(&ext) {
            ctx.warn(ext, "extension not supported; ignored")?;
        }
    }
    if doc.animations().next().is_some() {
        ctx.warn("animations", "not supported; the rest pose is drawn")?;
    }
    Ok(())
}

/// The first problem the `gltf` crate's validation found, as a located error.
fn validation_error(ctx: &Ctx, e: gltf::Error) -> LoadError {
    use gltf::json::validation::Error as V;
    let gltf::Error::Validation(errors) = e else {
        return ctx.err(String::new(), ErrorKind::BadValue, e.to_string());
    };
    let Some((path, error)) = errors.into_iter().next() else {
        return ctx.err(String::new(), ErrorKind::BadValue, "invalid glTF".into());
    };
    let (kind, what) = match error {
        V::IndexOutOfBounds => (ErrorKind::IndexOutOfRange, "index out of range"),
        V::Invalid => (ErrorKind::BadValue, "invalid value"),
        V::Missing => (ErrorKind::MissingElement, "required field missing"),
        V::Oversize => (ErrorKind::TooLarge, "size beyond the system's limits"),
        V::Unsupported => (ErrorKind::Unsupported, "required extension not supported"),
    };
    let path = path.to_string();
    let (pointer, value) = match path.split_once(" = ") {
        Some((p, v)) => (p.to_string(), format!(" ({v})")),
        None => (path, String::new()),
    };
    ctx.err(json_pointer(&pointer), kind, format!("{what}{value}"))
}

/// `nodes[3].mesh` (the `gltf` crate's paths) as the JSON pointer `/nodes/3/mesh`.
fn json_pointer(path: &str) -> String {
    let mut out = String::from("/");
    out.push_str(&path.replace('[', "/").replace(']', "").replace('.', "/"));
    out.replace("//", "/")
}

#[cfg(test)]
mod tests {
    use super::json_pointer;

    #[test]
    fn crate_paths_become_json_pointers() {
        assert_eq!(json_pointer("nodes[3].mesh"), "/nodes/3/mesh");
        assert_eq!(
            json_pointer("extensionsRequired[0]"),
            "/extensionsRequired/0"
        );
    }
}
