//! The node hierarchy: a depth-first walk of the default scene (or of every
//! root node when the file has no scene), composing each node's matrix with
//! its parent's. A glTF mesh used by several nodes is read once (one
//! [`crate::MeshDesc`] per primitive) and placed by one
//! [`crate::InstanceDesc`] per node; cameras and lights take their node's
//! world transform. A node whose transform mirrors (negative determinant)
//! turns its triangles' front faces round, as the glTF specification says:
//! it is placed with a copy of the mesh wound the other way, so that the
//! face normal still points out of the object (which side is glass or
//! medium, and which side a lamp lights, follows the face normal). glTF is
//! Y-up, right-handed, in metres, like Candela's world: no axis change.

use super::accessors::Buffers;
use super::{cameras, lights, materials, meshes, Ctx};
use crate::desc::{CameraDesc, InstanceDesc, MaterialDesc, MediumInterface, SceneDesc};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4};
use std::collections::HashMap;

/// Deepest node nesting accepted.
const MAX_DEPTH: usize = 256;

/// What the walk has built so far.
struct Walk<'d> {
    scene: SceneDesc,
    /// Scene mesh index per (glTF mesh, primitive, mirrored); `None` for a
    /// primitive that draws nothing.
    meshes: HashMap<(usize, usize, bool), Option<usize>>,
    /// Scene material index per glTF material (`None`: the default
    /// grey) and whether it is drawn on vertex colours.
    materials: HashMap<(Option<usize>, bool), usize>,
    cameras: Vec<(usize, CameraDesc)>,
    buffers: &'d Buffers<'d>,
    /// The document, for texture references inside untyped extensions.
    doc: &'d gltf::Document,
}

/// Walks the document's scene into a [`SceneDesc`]; cameras are kept in the
/// document order of their nodes.
pub(super) fn read_scene(
    ctx: &Ctx,
    doc: &gltf::Document,
    buffers: &Buffers,
) -> Result<SceneDesc, LoadError> {
    let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => {
            if doc.scenes().len() > 1 {
                ctx.warn("scenes", "only the default scene is drawn")?;
            }
            scene.nodes().collect()
        }
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for n in doc.nodes() {
                for c in n.children() {
                    is_child[c.index()] = true;
                }
            }
            doc.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    };
    let mut walk = Walk {
        scene: SceneDesc {
            source: ctx.file.to_path_buf(),
            ..SceneDesc::default()
        },
        meshes: HashMap::new(),
        materials: HashMap::new(),
        cameras: Vec::new(),
        buffers,
        doc,
    };
    let mut visited = vec![false; doc.nodes().len()];
    let mut stack: Vec<(gltf::Node, Mat4, usize)> = roots
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY, 0))
        .collect();
    while let Some((node, parent, depth)) = stack.pop() {
        let i = node.index();
        if std::mem::replace(&mut visited[i], true) {
            return Err(ctx.err(
                format!("/nodes/{i}"),
                ErrorKind::TooDeep,
                "node is reached twice: the hierarchy has a cycle or a node with two parents"
                    .into(),
            ));
        }
        if depth > MAX_DEPTH {
            return Err(ctx.err(
                format!("/nodes/{i}"),
                ErrorKind::TooDeep,
                format!("nodes nested deeper than {MAX_DEPTH}"),
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        if !local.is_finite() {
            return Err(ctx.err(
                format!("/nodes/{i}"),
                ErrorKind::NonFinite,
                "transform (matrix or translation/rotation/scale) is not finite".into(),
            ));
        }
        let m = parent * local;
        visit(ctx, &mut walk, &node, m)?;
        let children: Vec<gltf::Node> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, m, depth + 1)));
    }
    walk.cameras.sort_by_key(|(node, _)| *node);
    walk.scene.cameras = walk.cameras.into_iter().map(|(_, c)| c).collect();
    Ok(walk.scene)
}

/// Adds what node `node` carries (mesh instances, camera, light) at `m`.
fn visit(ctx: &Ctx, walk: &mut Walk, node: &gltf::Node, m: Mat4) -> Result<(), LoadError> {
    if node.skin().is_some() {
        ctx.warn("skins", "not supported; the bind pose is drawn")?;
    }
    if let Some(mesh) = node.mesh() {
        let det = Mat3::from_mat4(m).determinant();
        if det.abs() <= 1e-20 || det.is_nan() {
            ctx.warn(
                "zero scale",
                "a node with a singular transform is not drawn",
            )?;
        } else {
            for prim in mesh.primitives() {
                let Some(index) = mesh_of(ctx, walk, &mesh, &prim, det < 0.0)? else {
                    continue;
                };
                walk.scene.instances.push(InstanceDesc {
                    mesh: index,
                    world_from_object: m,
                    material: None,
                    loc: Default::default(),
                });
            }
        }
    }
    if let Some(cam) = node.camera() {
        let desc = cameras::read_camera(ctx, node, &cam, m)?;
        walk.cameras.push((node.index(), desc));
    }
    if let Some(light) = node.light() {
        let desc = lights::read_light(ctx, node, &light, m)?;
        walk.scene.lights.push(desc);
    }
    Ok(())
}

/// The scene mesh of primitive `prim`, read on its first use; for a
/// `mirrored` node, a copy of it wound the other way, made on its first use.
fn mesh_of(
    ctx: &Ctx,
    walk: &mut Walk,
    mesh: &gltf::Mesh,
    prim: &gltf::Primitive,
    mirrored: bool,
) -> Result<Option<usize>, LoadError> {
    let key = (mesh.index(), prim.index(), mirrored);
    if let Some(&known) = walk.meshes.get(&key) {
        return Ok(known);
    }
    let index = if mirrored {
        mesh_of(ctx, walk, mesh, prim, false)?.map(|plain| {
            let mut desc = walk.scene.meshes[plain].clone();
            desc.reverse_winding();
            walk.scene.meshes.push(desc);
            walk.scene.meshes.len() - 1
        })
    } else {
        match meshes::read_primitive(ctx, walk.buffers, mesh, prim)? {
            Some(mut desc) => {
                desc.material = material_of(ctx, walk, &prim.material(), !desc.colors.is_empty())?;
                walk.scene.meshes.push(desc);
                Some(walk.scene.meshes.len() - 1)
            }
            None => None,
        }
    };
    walk.meshes.insert(key, index);
    Ok(index)
}

/// The scene material of `m`, read on its first use; a primitive without a
/// material gets the loader-wide default grey. A primitive with vertex
/// colours (`vertex_colored`) gets its own copy whose base colour they
/// multiply (`materials::times_vertex_colors`), so the primitives without
/// them that share the material keep the plain one.
fn material_of(
    ctx: &Ctx,
    walk: &mut Walk,
    m: &gltf::Material,
    vertex_colored: bool,
) -> Result<usize, LoadError> {
    let key = (m.index(), vertex_colored);
    if let Some(&known) = walk.materials.get(&key) {
        return Ok(known);
    }
    let mut desc = match m.index() {
        Some(_) => materials::read_material(ctx, walk.doc, walk.buffers, m)?,
        None => MaterialDesc::default_grey(),
    };
    if vertex_colored {
        materials::times_vertex_colors(&mut desc);
    }
    let scene = &mut walk.scene;
    scene.materials.push(desc);
    let index = scene.materials.len() - 1;
    if let Some(medium) = materials::volume_medium(m) {
        scene.media.push(medium);
        let interface = MediumInterface {
            interior: Some(scene.media.len() - 1),
            exterior: None,
        };
        scene.medium_interfaces.push((index, interface));
    }
    walk.materials.insert(key, index);
    Ok(index)
}
