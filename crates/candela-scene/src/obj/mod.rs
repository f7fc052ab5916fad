//! The Wavefront OBJ loader, with MTL material libraries.
//!
//! Stages: read the file (size guard, UTF-8), check every statement with its
//! place and write a plain copy (`scan`), read the material libraries it
//! names (`mtl`), let `tobj` assemble the meshes (objects, groups, `usemtl`
//! runs; n-gons fan-triangulated; separate position, normal and UV indices),
//! and turn them into [`crate::desc`] meshes (`meshes`). OBJ is Y-up by
//! convention, so positions are taken as they are; a mesh without vertex
//! normals is flat-shaded. Vertex colours (the common extension
//! `v x y z r g b`) are read as given, linear; a mesh without a material
//! shows them (the default grey coloured by them), a material of the
//! `.mtl` is kept as it is (MTL has no way to name them). Colours on only
//! some vertices are dropped and reported (`scan`). A missing `.mtl` or texture file, or an unknown
//! `usemtl` name, is a warning (the default material is used) and an
//! [`ErrorKind::MissingReference`] error in strict mode.

mod meshes;
mod mtl;
mod scan;
mod statements;

use crate::desc::{MaterialDesc, MeshDesc, SceneDesc, SourceLoc, TextureRef, TextureSlot};
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use crate::{LoadOptions, Loaded};
use std::collections::HashMap;
use std::path::Path;

/// Reads and loads an OBJ file (the entry of [`crate::formats`]).
pub(crate) fn load_file(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let mut warnings = Collector::new(path.to_path_buf(), opts.strict);
    let text = read(path)?;
    let scan = scan::scan(&text, path, &mut warnings)?;
    let mut materials: Vec<MaterialDesc> = Vec::new();
    let mut libraries: HashMap<String, Vec<String>> = HashMap::new();
    let base = path.parent().unwrap_or(Path::new(""));
    for (library, loc) in &scan.mtllibs {
        let before = materials.len();
        for file in library_files(base, library) {
            if !file.is_file() {
                missing(
                    path,
                    *loc,
                    "mtllib",
                    format!("material library {} not found", file.display()),
                    opts.strict,
                    &mut warnings,
                )?;
                continue;
            }
            let mtl_text = read(&file)?;
            let mut mtl_warnings = Collector::new(file.clone(), opts.strict);
            materials.extend(mtl::read_mtl(
                &mtl_text,
                &file,
                opts.strict,
                &mut mtl_warnings,
            )?);
            // The library's warnings join the OBJ's, naming the library.
            for w in mtl_warnings.finish().warnings {
                let element = format!("{}: {}", file.display(), w.element);
                for _ in 0..w.count {
                    warnings.warn(element.clone(), w.message.clone(), || w.loc)?;
                }
            }
        }
        let names = materials[before..].iter().map(|m| m.name.clone()).collect();
        libraries.insert(library.clone(), names);
    }
    for (name, loc) in &scan.usemtls {
        if !materials.iter().any(|m| &m.name == name) {
            missing(
                path,
                *loc,
                "usemtl",
                format!("material \"{name}\" is not defined; default material used"),
                opts.strict,
                &mut warnings,
            )?;
        }
    }
    let models = meshes::assemble(&scan.clean, path, |library| {
        libraries.get(library).cloned().unwrap_or_default()
    })?;
    let mut scene = SceneDesc {
        source: path.to_path_buf(),
        materials,
        ..SceneDesc::default()
    };
    // The default material, plain and on vertex colours.
    let mut default_material = [None, None];
    for (i, model) in models.into_iter().enumerate() {
        let colored = !model.mesh.colors.is_empty();
        let material = match model.material {
            Some(m) => m,
            None => *default_material[usize::from(colored)].get_or_insert_with(|| {
                let mut grey = MaterialDesc::default_grey();
                if colored {
                    grey.textures
                        .set(TextureSlot::Color, TextureRef::vertex_color());
                }
                scene.materials.push(grey);
                scene.materials.len() - 1
            }),
        };
        scene.add_mesh(MeshDesc {
            material,
            loc: scan.mesh_locs.get(i).copied().unwrap_or_default(),
            ..model.mesh
        });
    }
    Ok(Loaded {
        scene,
        report: warnings.finish(),
        hints: crate::RenderHints::default(),
    })
}

/// Reads the OBJ file `path` as one mesh, ignoring its materials: for
/// formats (Mitsuba) that reference mesh files and give materials
/// themselves. Warnings go to `warnings`.
pub(crate) fn read_obj_mesh(path: &Path, warnings: &mut Collector) -> Result<MeshDesc, LoadError> {
    let text = read(path)?;
    let scan = scan::scan(&text, path, warnings)?;
    let models = meshes::assemble(&scan.clean, path, |_| Vec::new())?;
    let mut merged = MeshDesc {
        name: path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
        loc: scan.mesh_locs.first().copied().unwrap_or_default(),
        ..MeshDesc::default()
    };
    for model in models {
        meshes::append(&mut merged, model.mesh);
    }
    Ok(merged)
}

fn read(path: &Path) -> Result<String, LoadError> {
    crate::text_file::utf8(
        crate::text_file::read_bytes(path)?,
        path,
        ErrorKind::NotText,
    )
}

/// The files an `mtllib` statement names: the whole argument if it is a
/// file (names may hold spaces), else each word.
fn library_files(base: &Path, library: &str) -> Vec<std::path::PathBuf> {
    let whole = base.join(library);
    if whole.is_file() || !library.contains(char::is_whitespace) {
        return vec![whole];
    }
    library.split_whitespace().map(|f| base.join(f)).collect()
}

/// A referenced file or name that is not there: a warning, or an error in
/// strict mode.
fn missing(
    file: &Path,
    loc: SourceLoc,
    element: &str,
    message: String,
    strict: bool,
    warnings: &mut Collector,
) -> Result<(), LoadError> {
    if strict {
        return Err(statements::error(
            file,
            loc,
            element,
            ErrorKind::MissingReference,
            message,
        ));
    }
    warnings.warn(element.into(), message, || loc)
}
