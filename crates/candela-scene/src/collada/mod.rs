//! The COLLADA 1.4 loader (with the CS184 course's `CGL` extensions).
//!
//! Stages: guard the input (size, DTD), parse XML with `roxmltree`, check the
//! root, read `asset/up_axis`, then walk the instanced visual scene, turning
//! each instance into plain [`crate::desc`] data in Y-up world space.
//! Dialect notes: `shared/scenes/README.md`.
//!
//! Module layout: `nodes` walks the node tree and hands each instance to its
//! reader (`cameras`, `geometry`, `lights`); all of them write to the scene
//! under construction in `builder`, which the readers depend on instead of
//! the walker. Each `<instance_geometry>` is baked into world-space meshes
//! (one per primitive element) placed by one identity instance each, so the
//! description holds exactly what the file draws.

mod builder;
mod cameras;
pub(crate) use cameras::xfov_from_yfov;
mod geometry;
mod lenient;
mod lights;
mod materials;
mod mesh;
mod nodes;
mod numbers;
mod primitives;
mod sources;
mod transform;
mod xml;

use crate::error::{ErrorKind, LoadError};
use crate::text_file::MAX_FILE_BYTES;
use crate::{LoadOptions, Loaded};
use std::path::Path;
use transform::UpAxis;
use xml::{child, text, Ctx};

/// Reads and loads a COLLADA file (the entry of [`crate::formats`]).
pub(crate) fn load_file(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let text = crate::text_file::read_text(path)?;
    load_str(&text, path, opts)
}

/// Loads COLLADA text; `source` names the file in messages and anchors
/// relative texture paths. The CS184 files' doubled lamp is merged unless
/// `opts.keep_duplicate_lamps` ([`crate::lamps`]).
pub(crate) fn load_str(
    text_in: &str,
    source: &Path,
    opts: &LoadOptions,
) -> Result<Loaded, LoadError> {
    let whole = |kind, msg: String| LoadError::whole_file(source.to_path_buf(), kind, msg);
    if text_in.len() as u64 > MAX_FILE_BYTES {
        return Err(whole(
            ErrorKind::TooLarge,
            format!(
                "{} bytes exceeds the limit of {MAX_FILE_BYTES}",
                text_in.len()
            ),
        ));
    }
    if let Some(byte) = text_in.find("<!DOCTYPE") {
        return Err(LoadError {
            loc: Some(xml::loc_in(text_in, byte)),
            element: "<!DOCTYPE>".into(),
            ..whole(
                ErrorKind::Dtd,
                "document type declarations (and entities) are not accepted".into(),
            )
        });
    }
    let doc = roxmltree::Document::parse(text_in).map_err(|e| {
        let pos = e.pos();
        LoadError {
            loc: Some(crate::desc::SourceLoc {
                line: pos.row,
                col: pos.col,
            }),
            ..whole(ErrorKind::NotXml, format!("not well-formed XML: {e}"))
        }
    })?;
    let ctx = Ctx::new(&doc, text_in, source, opts.strict);
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(ctx.err(root, ErrorKind::NotCollada, "root element is not <COLLADA>"));
    }
    let up = up_axis(&ctx, root)?;
    let mut scene = nodes::read_scene(&ctx, root, up)?;
    let mut report = ctx.into_report();
    if !opts.keep_duplicate_lamps {
        report
            .notes
            .extend(crate::lamps::merge_duplicate_lamps(&mut scene));
    }
    Ok(Loaded {
        scene,
        report,
        hints: crate::RenderHints::default(),
    })
}

/// Reads `asset/up_axis` (default `Y_UP`, as the COLLADA specification says).
fn up_axis(ctx: &Ctx, root: xml::XNode) -> Result<UpAxis, LoadError> {
    let Some(node) = child(root, "asset").and_then(|a| child(a, "up_axis")) else {
        return Ok(UpAxis::Y);
    };
    match text(node).trim() {
        "X_UP" => Ok(UpAxis::X),
        "Y_UP" => Ok(UpAxis::Y),
        "Z_UP" => Ok(UpAxis::Z),
        other => Err(ctx.err(
            node,
            ErrorKind::BadValue,
            format!("unknown up axis \"{other}\" (expected X_UP, Y_UP or Z_UP)"),
        )),
    }
}
