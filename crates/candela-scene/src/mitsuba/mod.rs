//! The Mitsuba 3 XML loader: the subset of Mitsuba's scene format that
//! research scenes use, read into the format-neutral [`crate::SceneDesc`].
//!
//! - `<scene version="2.x|3.x">`; `<default name value>` and `$name`
//!   substitution (the caller's [`crate::LoadOptions::defines`] win over a
//!   file's defaults); `<include filename>` relative to the including file
//!   (cycles are an error); `<ref id>` to named BSDFs, textures and shape
//!   groups.
//! - Shapes, BSDFs, textures: see `shapes.rs`, `bsdfs.rs` (its table lists
//!   every BSDF: the smooth and rough models, `principled` in
//!   `principled.rs`, `blendbsdf` in `blend.rs`) and `textures.rs`; emitters
//!   `emitters.rs`; the sensor, film, sampler and integrator `sensor.rs`
//!   (they become [`crate::RenderHints`]); participating media
//!   `media.rs` (homogeneous ones, traced only when the file's integrator
//!   is a volumetric one, as in Mitsuba).
//! - Coordinates are kept as they are: Mitsuba's world has no up axis of its
//!   own and its environment maps are +Y up, as Candela's.
//!
//! Plugin types Mitsuba has but Candela lacks are rendered as the closest
//! supported one (or skipped) and reported once by name; a type Mitsuba does
//! not have is an error.

mod blend;
mod bsdfs;
mod cie_tables;
mod doc;
mod emitters;
mod media;
mod principled;
mod sensor;
mod serialized;
mod shapes;
mod spectrum;
mod tables;
mod tessellate;
mod textures;
mod transform;
mod values;

use crate::desc::{MaterialDesc, SceneDesc};
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use crate::{LoadOptions, Loaded, RenderHints};
use doc::{describe, elements, Doc, XNode};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Includes nested deeper than this are refused.
const MAX_INCLUDE_DEPTH: usize = 32;

/// Reads and loads a Mitsuba scene (the entry of [`crate::formats`]).
pub(crate) fn load_file(path: &Path, opts: &LoadOptions) -> Result<Loaded, LoadError> {
    let defines = RefCell::new(opts.defines.iter().cloned().collect());
    let mut b = Builder {
        scene: SceneDesc {
            source: path.to_path_buf(),
            ..SceneDesc::default()
        },
        hints: RenderHints::default(),
        warnings: Collector::new(path.to_path_buf(), opts.strict),
        including: Vec::new(),
        bsdfs: HashMap::new(),
        bsdf_materials: HashMap::new(),
        textures: HashMap::new(),
        groups: HashMap::new(),
        default_material: None,
        media_by_id: HashMap::new(),
        phases: HashMap::new(),
        volumes: HashMap::new(),
        integrator: None,
    };
    b.read_file(path, &defines, None)?;
    b.drop_media_the_integrator_ignores();
    Ok(Loaded {
        scene: b.scene,
        report: b.warnings.finish(),
        hints: b.hints,
    })
}

/// The loader's state across the scene's files.
struct Builder {
    scene: SceneDesc,
    hints: RenderHints,
    warnings: Collector,
    /// Canonical paths of the files being read (the include chain).
    including: Vec<PathBuf>,
    /// Named BSDFs (`<bsdf id>`), as materials without emission.
    bsdfs: HashMap<String, MaterialDesc>,
    /// The material index already made for a named BSDF.
    bsdf_materials: HashMap<String, usize>,
    /// Named textures (`<texture id>`).
    textures: HashMap<String, textures::Texture>,
    /// Shape groups (`<shape type="shapegroup" id>`).
    groups: HashMap<String, Vec<shapes::GroupItem>>,
    /// Index of the grey material of shapes that name none.
    default_material: Option<usize>,
    /// Named media (`<medium id>`): the index in `scene.media`, `None` for
    /// one Candela lacks (reported where it is defined).
    media_by_id: HashMap<String, Option<usize>>,
    /// Named phase functions (`<phase id>`) as Henyey–Greenstein g.
    phases: HashMap<String, Option<f32>>,
    /// Named constant volumes (`<volume id>`).
    volumes: HashMap<String, Option<glam::Vec3>>,
    /// The `<integrator>` read, if any (Mitsuba's default is `path`).
    integrator: Option<media::IntegratorSeen>,
}

impl Builder {
    /// Reads one file (the scene, or one it includes from `include`).
    fn read_file(
        &mut self,
        path: &Path,
        defines: &RefCell<HashMap<String, String>>,
        include: Option<(&Doc, XNode)>,
    ) -> Result<(), LoadError> {
        let canonical = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
        if let Some((doc, node)) = include {
            if self.including.contains(&canonical) {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("cyclic include: {} is already being read", path.display()),
                ));
            }
            if self.including.len() >= MAX_INCLUDE_DEPTH {
                return Err(doc.err(
                    node,
                    ErrorKind::TooDeep,
                    format!("includes nested deeper than {MAX_INCLUDE_DEPTH}"),
                ));
            }
        }
        let text = crate::text_file::read_text(path)?;
        let xml = roxmltree::Document::parse(&text).map_err(|e| {
            let pos = e.pos();
            LoadError {
                loc: Some(crate::desc::SourceLoc {
                    line: pos.row,
                    col: pos.col,
                }),
                ..LoadError::whole_file(
                    path.to_path_buf(),
                    ErrorKind::NotXml,
                    format!("not well-formed XML: {e}"),
                )
            }
        })?;
        let doc = Doc {
            text: &text,
            file: path,
            defines,
            lines: Default::default(),
        };
        let root = xml.root_element();
        if root.tag_name().name() != "scene" {
            return Err(doc.err(
                root,
                ErrorKind::BadValue,
                "root element is not <scene> (not a Mitsuba scene)",
            ));
        }
        check_version(&doc, root)?;
        self.including.push(canonical);
        for node in elements(root) {
            self.scene_child(&doc, node)?;
        }
        self.including.pop();
        Ok(())
    }

    /// One element directly under `<scene>`.
    fn scene_child(&mut self, doc: &Doc, node: XNode) -> Result<(), LoadError> {
        match node.tag_name().name() {
            "default" => {
                let name = doc.required(node, "name")?;
                let value = doc.required(node, "value")?;
                doc.defines.borrow_mut().entry(name).or_insert(value);
            }
            "include" => {
                let file = doc.required(node, "filename")?;
                let path = doc.path(&file);
                if !path.is_file() {
                    return Err(doc.err(
                        node,
                        ErrorKind::MissingReference,
                        format!("included file {} not found", path.display()),
                    ));
                }
                self.read_file(&path, doc.defines, Some((doc, node)))?;
            }
            "integrator" => sensor::integrator(self, doc, node)?,
            "sensor" => sensor::sensor(self, doc, node)?,
            "shape" => self.shape(doc, node, None)?,
            "emitter" => emitters::emitter(self, doc, node)?,
            "bsdf" => {
                let material = self.bsdf(doc, node)?;
                match doc.attr(node, "id")? {
                    Some(id) => {
                        self.bsdfs.insert(id, material);
                    }
                    None => {
                        self.warn(doc, node, "a top-level <bsdf> without an id is never used")?
                    }
                }
            }
            "texture" => {
                let texture = self.texture(doc, node)?;
                match doc.attr(node, "id")? {
                    Some(id) => {
                        self.textures.insert(id, texture);
                    }
                    None => self.warn(
                        doc,
                        node,
                        "a top-level <texture> without an id is never used",
                    )?,
                }
            }
            "medium" | "phase" | "volume" => self.named_medium_part(doc, node)?,
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown element <{other}> in <scene>"),
                ))
            }
        }
        Ok(())
    }

    /// Records that `node` was ignored or approximated (an error in strict mode).
    fn warn(
        &mut self,
        doc: &Doc,
        node: XNode,
        message: impl Into<String>,
    ) -> Result<(), LoadError> {
        let mut message = message.into();
        if doc.file != self.scene.source {
            message = format!("{} (in {})", message, doc.file.display());
        }
        self.warnings
            .warn(describe(node), message, || doc.loc(node))
    }

    /// A file a property names (`<string name="filename">`), which must exist.
    fn existing_file(&self, doc: &Doc, node: XNode) -> Result<PathBuf, LoadError> {
        let Some(p) = doc.prop(node, "filename")? else {
            return Err(doc.err(
                node,
                ErrorKind::MissingElement,
                "missing <string name=\"filename\">",
            ));
        };
        let name = doc.required(p, "value")?;
        let path = doc.path(&name);
        if !path.is_file() {
            return Err(doc.err(
                p,
                ErrorKind::MissingReference,
                format!("file {} not found", path.display()),
            ));
        }
        Ok(path)
    }
}

/// Accepts Mitsuba 2 and 3 files (`version="2.x.y"` or `"3.x.y"`): older
/// ones name their parameters differently.
fn check_version(doc: &Doc, root: XNode) -> Result<(), LoadError> {
    let version = doc.required(root, "version")?;
    let major = version.split('.').next().unwrap_or("").trim();
    match major.parse::<u32>() {
        Ok(2 | 3) => Ok(()),
        Ok(_) => Err(doc.err(
            root,
            ErrorKind::BadValue,
            format!("scene version {version} is not supported (only 2.x and 3.x)"),
        )),
        Err(_) => Err(doc.err(
            root,
            ErrorKind::BadNumber,
            format!("\"{version}\" is not a version number"),
        )),
    }
}
