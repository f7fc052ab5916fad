//! The one dispatch point from a file to its loader: a table of formats,
//! each with the extensions it claims. Adding a format is one row here plus
//! its own folder (like `collada/`) that turns the file into a
//! [`crate::SceneDesc`], reporting problems with the shared
//! [`crate::LoadError`] kinds.

use crate::error::{ErrorKind, LoadError};
use crate::{LoadOptions, Loaded};
use std::path::Path;

/// A scene file format this crate reads.
pub(crate) struct Format {
    /// The format's name in messages.
    pub name: &'static str,
    /// Lower-case file extensions, without the dot.
    pub extensions: &'static [&'static str],
    /// Reads a file of this format.
    pub load: fn(&Path, &LoadOptions) -> Result<Loaded, LoadError>,
}

/// Every format, in the order they are listed in messages.
pub(crate) const FORMATS: &[Format] = &[
    Format {
        name: "COLLADA",
        extensions: &["dae"],
        load: crate::collada::load_file,
    },
    Format {
        name: "Wavefront OBJ",
        extensions: &["obj"],
        load: crate::obj::load_file,
    },
    Format {
        name: "PLY",
        extensions: &["ply"],
        load: crate::ply::load_file,
    },
    Format {
        name: "glTF",
        extensions: &["gltf", "glb"],
        load: crate::gltf::load_file,
    },
    Format {
        name: "Mitsuba 3 XML",
        extensions: &["xml"],
        load: crate::mitsuba::load_file,
    },
];

/// The format whose extensions include `path`'s (case-insensitive), or an
/// [`ErrorKind::UnknownFormat`] error naming it and the supported ones.
pub(crate) fn format_of(path: &Path) -> Result<&'static Format, LoadError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if let Some(format) = ext
        .as_deref()
        .and_then(|e| FORMATS.iter().find(|f| f.extensions.contains(&e)))
    {
        return Ok(format);
    }
    let named = match path.extension() {
        Some(e) => format!("unknown scene file extension \".{}\"", e.to_string_lossy()),
        None => "scene file has no extension".to_string(),
    };
    Err(LoadError::whole_file(
        path.to_path_buf(),
        ErrorKind::UnknownFormat,
        format!("{named}; supported: {}", supported()),
    ))
}

/// The supported extensions with their formats, e.g. `.dae (COLLADA)`.
pub(crate) fn supported() -> String {
    FORMATS
        .iter()
        .flat_map(|f| {
            f.extensions
                .iter()
                .map(move |e| format!(".{e} ({})", f.name))
        })
        .collect::<Vec<_>>()
        .join(", ")
}
