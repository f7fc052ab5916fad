//! The PLY loader (Stanford polygon files, ASCII and binary of either byte
//! order), written here rather than taken from a crate so that no header
//! count is ever trusted: each element's count is bounded by the bytes left
//! in the file before anything is read or allocated.
//!
//! Read: the `vertex` element's `x y z`, optional `nx ny nz` and `u v`
//! (also `s t` and `texture_u texture_v`); the `face` element's
//! `vertex_indices` (or `vertex_index`) list, fan-triangulated; the
//! vertices' `red green blue` (also `r g b`) colours: floats linear as
//! given, integers scaled to [0, 1] and decoded from sRGB (`mesh.rs`,
//! `ColorEncoding`). Other properties and elements are skipped and
//! reported once by name. A PLY file carries no materials: the mesh gets
//! the default grey one, which shades both sides, coloured by the vertex
//! colours when the file has them.

mod body;
mod header;
mod mesh;

use crate::desc::{MaterialDesc, MeshDesc, SceneDesc, TextureRef, TextureSlot};
use crate::error::LoadError;
use crate::report::Collector;
use crate::{LoadOptions, Loaded};
use std::path::Path;

/// Reads and loads a PLY file (the entry of [`crate::formats`]).
pub(crate) fn load_file(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let mut warnings = Collector::new(path.to_path_buf(), opts.strict);
    let mesh = read_ply_mesh(path, &mut warnings)?;
    let mut material = MaterialDesc::default_grey();
    if !mesh.colors.is_empty() {
        material
            .textures
            .set(TextureSlot::Color, TextureRef::vertex_color());
    }
    let mut scene = SceneDesc {
        source: path.to_path_buf(),
        materials: vec![material],
        ..SceneDesc::default()
    };
    scene.add_mesh(mesh);
    Ok(Loaded {
        scene,
        report: warnings.finish(),
        hints: crate::RenderHints::default(),
    })
}

/// Reads the PLY file `path` into one mesh (material 0): the entry for
/// formats that reference mesh files (Mitsuba). Warnings go to `warnings`.
pub(crate) fn read_ply_mesh(path: &Path, warnings: &mut Collector) -> Result<MeshDesc, LoadError> {
    let bytes = crate::text_file::read_bytes(path)?;
    read_ply_bytes(&bytes, path, warnings)
}

/// Reads PLY data `bytes`; `path` names it in messages.
pub(crate) fn read_ply_bytes(
    bytes: &[u8],
    path: &Path,
    warnings: &mut Collector,
) -> Result<MeshDesc, LoadError> {
    let header = header::parse(bytes, path)?;
    let mut mesh = mesh::read(bytes, &header, path, warnings)?;
    mesh.name = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    Ok(mesh)
}

pub(crate) use crate::error::located;
