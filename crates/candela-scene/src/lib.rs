//! Scene descriptions for the Candela path tracer, and the loaders that make them.
//!
//! `load(path)` picks the loader by the file's extension (one table, in
//! `formats.rs`); every loader produces the same format-neutral
//! [`SceneDesc`] (see [`desc`]) and reports errors with the shared
//! [`ErrorKind`]s.
//!
//! Loading happens in stages (parse, describe, validate); every error carries
//! the file, `line:col` and the element, and everything a loader ignores is
//! named once in a [`Report`].
#![warn(missing_docs)]

mod collada;
pub mod desc;
mod error;
mod formats;
mod gltf;
mod hints;
mod lamps;
pub mod metals;
mod mitsuba;
mod obj;
mod ply;
mod referenced;
mod report;
mod text_file;

pub use desc::*;
pub use error::{ErrorKind, LoadError};
pub use hints::{FilterHint, RenderHints};
pub use referenced::referenced_files;
pub use report::{Report, Warning};

use std::path::{Path, PathBuf};

/// How strictly to load.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Turn every warning (an ignored element or feature) into an
    /// [`ErrorKind::Unsupported`] error, for users who want to know that what
    /// they render is exactly what the file says; and refuse, with the
    /// error it is, every defect the default mode repairs (a matrix missing
    /// its last row, a wrong `count`, an out-of-range colour, a `CMU462`
    /// profile, ...; README, "Lenient loading").
    pub strict: bool,
    /// Keep a CGL area light that duplicates an emissive mesh (the CS184
    /// Cornell-box lamp) instead of counting that lamp once. Only for tools
    /// that want the file exactly as written: rendering both doubles the light.
    /// (When the two radiances differ, the merged lamp takes the area light's.)
    pub keep_duplicate_lamps: bool,
    /// Parameter values given by the caller (`-D name=value`), replacing a
    /// file's own defaults: a Mitsuba file's `<default name=.. value=..>`
    /// only applies when the caller did not name the parameter. Formats
    /// without parameters ignore them.
    pub defines: Vec<(String, String)>,
}

/// A loaded scene and what the loader ignored on the way.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The scene, in Y-up world space.
    pub scene: SceneDesc,
    /// Ignored elements and features, each named once.
    pub report: Report,
    /// Render settings the scene suggests (below the user's own).
    pub hints: RenderHints,
}

/// Loads a scene file, choosing the loader by the file's extension
/// (case-insensitive; see [`supported_formats`]). An unknown extension is an
/// [`ErrorKind::UnknownFormat`] error naming it and the supported ones.
///
/// Files over 512 MiB are refused before they are read, so a wrong path to a
/// huge file fails fast.
///
/// Every format's scene then passes the same extent check
/// ([`SceneDesc::check_extent`]): geometry and cameras beyond
/// [`MAX_COORDINATE`] are refused with their place in the file.
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let loaded = (formats::format_of(path)?.load)(path, opts)?;
    loaded.scene.check_extent()?;
    Ok(loaded)
}

/// The extensions [`load`] accepts, with their formats, for messages and
/// help texts: e.g. `.dae (COLLADA)`.
pub fn supported_formats() -> String {
    formats::supported()
}

/// Loads COLLADA text. `source` names the file in messages and is the base
/// for relative texture paths.
pub fn load_str(text: &str, source: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let loaded = collada::load_str(text, source, opts)?;
    loaded.scene.check_extent()?;
    Ok(loaded)
}

/// The built-in demo scene (`scenes/demo.dae`: a Cornell box with a diffuse
/// and a mirror sphere), compiled into the library so the renderer always has
/// something to show.
pub fn demo_scene() -> Loaded {
    const DEMO: &str = include_str!("../../../scenes/demo.dae");
    let source = PathBuf::from("<built-in demo>");
    // The file is part of this crate and tested to load; should that ever
    // break, an empty scene with the error in its report is still returned
    // rather than a panic.
    let mut loaded = load_str(DEMO, &source, &LoadOptions::default()).unwrap_or_else(|e| Loaded {
        scene: SceneDesc {
            source: source.clone(),
            ..SceneDesc::default()
        },
        report: Report {
            source,
            warnings: vec![Warning {
                loc: e.loc.unwrap_or_default(),
                element: e.element,
                message: e.message,
                count: 1,
            }],
            notes: Vec::new(),
        },
        hints: RenderHints::default(),
    });
    // Its own camera frames the box; at this sample count and clamp the
    // first image a new user sees is clean and takes seconds.
    loaded.hints = RenderHints {
        spp: Some(DEMO_SPP),
        file_camera: true,
        clamp: Some(DEMO_CLAMP),
        ..RenderHints::default()
    };
    loaded
}

/// Samples per pixel of the demo unless the user says otherwise.
pub const DEMO_SPP: u32 = 16;
/// The demo's firefly clamp, a few times the walls' radiance: caustics off the mirror
/// sphere are single bright samples at this sample count.
pub const DEMO_CLAMP: f32 = 1.5;
