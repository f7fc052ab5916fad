//! The visual scene: walking nested nodes, accumulating transforms, and
//! dispatching each instance to the reader of its kind. The readers share
//! the scene under construction through [`super::builder`], not through
//! this module, so the dependency runs one way.

use super::builder::Builder;
use super::transform::{local_transform, up_axis_matrix, UpAxis};
use super::xml::{child, children, elements, Ctx, XNode};
use super::{cameras, geometry, lights};
use crate::desc::SceneDesc;
use crate::error::{ErrorKind, LoadError};
use glam::Mat4;

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

/// Reads the instanced visual scene into a [`SceneDesc`].
pub(crate) fn read_scene(ctx: &Ctx, root: XNode, up: UpAxis) -> Result<SceneDesc, LoadError> {
    for el in elements(root) {
        let name = el.tag_name().name();
        if !KNOWN_TOP_LEVEL.contains(&name) && elements(el).next().is_some() {
            ctx.warn(el, format!("<{name}> not supported; ignored"))?;
        }
    }
    let visual = visual_scene(ctx, root)?;
    let mut b = Builder::new(ctx);
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
