//! The scene under construction while the visual scene is walked: the
//! shared state that the node walker ([`super::nodes`]) hands to every
//! instance reader ([`super::cameras`], [`super::geometry`],
//! [`super::lights`]). It lives apart from the walker so the readers depend
//! on it and not on the walker (which depends on them).

use super::materials;
use super::xml::{Ctx, XNode};
use crate::desc::{MaterialDesc, MeshDesc, SceneDesc};
use crate::error::LoadError;
use roxmltree::NodeId;
use std::collections::HashMap;

/// The scene under construction, plus caches so shared materials are read once.
pub(crate) struct Builder {
    /// What has been read so far.
    pub scene: SceneDesc,
    materials: HashMap<NodeId, usize>,
    default_material: Option<usize>,
}

impl Builder {
    /// An empty scene read from `ctx`'s file.
    pub fn new(ctx: &Ctx) -> Self {
        Self {
            scene: SceneDesc {
                source: ctx.file.to_path_buf(),
                ..SceneDesc::default()
            },
            materials: HashMap::new(),
            default_material: None,
        }
    }

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

    /// Adds a mesh that is already in world space, placed once (COLLADA
    /// meshes are baked per `<instance_geometry>`; see the module docs of
    /// [`super`]).
    pub fn add_world_mesh(&mut self, mesh: MeshDesc) {
        self.scene.add_mesh(mesh);
    }
}
