//! The visual scene: walking nested nodes, accumulating transforms, and
//! dispatching each instance to the reader of its kind.

use super::transform::{local_transform, up_axis_matrix, UpAxis};
use super::xml::{child, children, elements, Ctx, XNode};
use super::{cameras, geometry, lights, materials};
use crate::desc::{MaterialDesc, SceneDesc};
use crate::error::{ErrorKind, LoadError};
use glam::Mat4;
use roxmltree::NodeId;
use std::collections::HashMap;

/// Deepest node nesting accepted (also bounds `instance_node` cycles).
pub(crate) const MAX_NODE_DEPTH: usize = 256;

/// Top-level elements the loader reads or may skip silently.
const KNOWN_TOP_LEVEL: &[&str] = &[
    "asset",
    "library_geometries",
    "library_materials",
    "library_effects",
    "library_lights",
    "library_cameras",
    "library_images",
    "library_visual_scenes",
    "library_nodes",
    "scene",
    "extra",
];

/// The scene under construction, plus caches so shared materials are read once.
pub(crate) struct Builder {
    /// What has been read so far.
    pub scene: SceneDesc,
    materials: HashMap<NodeId, usize>,
    default_material: Option<usize>,
}

impl Builder {
    /// Index of the default grey material, added on first use.
    pub fn default_material(&mut self) -> usize {
        *self.default_material.get_or_insert_with(|| {
            self.scene.materials.push(MaterialDesc::default_grey());
            self.scene.materials.len() - 1
        })
    }

    /// Index of the `<material>` element's description, read on first use.
    pub fn material(&mut self, ctx: &Ctx, material: XNode) -> Result<usize, LoadError> {
        if let Some(&i) = self.materials.get(&material.id()) {
            return Ok(i);
        }
        let desc = materials::read_material(ctx, material)?;
        self.scene.materials.push(desc);
        let i = self.scene.materials.len() - 1;
        self.materials.insert(material.id(), i);
        Ok(i)
    }
}

/// Reads the instanced visual scene into a [`SceneDesc`].
pub(crate) fn read_scene(ctx: &Ctx, root: XNode, up: UpAxis) -> Result<SceneDesc, LoadError> {
    for el in elements(root) {
        let name = el.tag_name().name();
        if !KNOWN_TOP_LEVEL.contains(&name) && elements(el).next().is_some() {
            ctx.warn(el, format!("<{name}> not supported; ignored"))?;
        }
    }
    let visual = visual_scene(ctx, root)?;
    let mut b = Builder {
        scene: SceneDesc {
            source: ctx.file.to_path_buf(),
            ..SceneDesc::default()
        },
        materials: HashMap::new(),
        default_material: None,
    };
    let world = up_axis_matrix(up);
    for node in children(visual, "node") {
        walk(ctx, &mut b, node, world, 1)?;
    }
    Ok(b.scene)
}

/// The `<visual_scene>` named by `scene/instance_visual_scene`, else the first one.
fn visual_scene<'a, 'i>(
    ctx: &Ctx<'a, 'i>,
    root: XNode<'a, 'i>,
) -> Result<XNode<'a, 'i>, LoadError> {
    if let Some(inst) = child(root, "scene").and_then(|s| child(s, "instance_visual_scene")) {
        if let Some(v) = ctx.resolve(inst, "url", &["visual_scene"])? {
            return Ok(v);
        }
    }
    child(root, "library_visual_scenes")
        .and_then(|l| child(l, "visual_scene"))
        .ok_or_else(|| ctx.err(root, ErrorKind::MissingElement, "no <visual_scene> to load"))
}

/// Reads one node and its subtree; `parent` is the world-from-parent transform.
fn walk(
    ctx: &Ctx,
    b: &mut Builder,
    node: XNode,
    parent: Mat4,
    depth: usize,
) -> Result<(), LoadError> {
    if depth > MAX_NODE_DEPTH {
        return Err(ctx.err(
            node,
            ErrorKind::TooDeep,
            format!("nodes nested deeper than {MAX_NODE_DEPTH} levels"),
        ));
    }
    let m = parent * local_transform(ctx, node)?;
    for el in elements(node) {
        match el.tag_name().name() {
            "node" => walk(ctx, b, el, m, depth + 1)?,
            "instance_node" => {
                if let Some(target) = ctx.resolve(el, "url", &["node"])? {
                    walk(ctx, b, target, m, depth + 1)?;
                }
            }
            "instance_geometry" => geometry::instance(ctx, b, el, m)?,
            "instance_light" => lights::instance(ctx, b, el, m)?,
            "instance_camera" => cameras::instance(ctx, b, el, m)?,
            "matrix" | "translate" | "rotate" | "scale" | "lookat" | "skew" | "extra" | "asset" => {
            }
            other => ctx.warn(el, format!("<{other}> in a node not supported; ignored"))?,
        }
    }
    Ok(())
}
