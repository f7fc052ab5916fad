//! Names for what the render scene stores by index: materials, lights and
//! the primitives' meshes and spheres, as the description called them. The
//! integrators never read these; the path inspector and error messages do.

use crate::shape::{PrimKind, PrimRef};
use candela_scene::SceneDesc;

/// The description's names of the scene's materials, lights and shapes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SceneNames {
    /// By material index.
    pub materials: Vec<String>,
    /// By light index (the order of [`crate::light::LightSet`]).
    pub lights: Vec<String>,
    /// Mesh instances: the first triangle index of each and its mesh's
    /// name, in triangle order.
    instances: Vec<(u32, String)>,
    /// By sphere index.
    spheres: Vec<String>,
}

impl SceneNames {
    /// The material, mesh and sphere names of `desc`, in the order
    /// [`super::Geometry::from_desc`] flattens them; lights come later
    /// ([`SceneNames::lights`], filled in as the light set is built).
    pub(super) fn from_desc(desc: &SceneDesc) -> Self {
        let materials = desc.materials.iter().map(|m| m.name.clone()).collect();
        let mut first = 0u32;
        let mut instances = Vec::with_capacity(desc.instances.len());
        for inst in &desc.instances {
            let Some(mesh) = desc.meshes.get(inst.mesh) else {
                continue;
            };
            instances.push((first, mesh.name.clone()));
            first += mesh.triangles.len() as u32;
        }
        Self {
            materials,
            lights: Vec::new(),
            instances,
            spheres: desc.spheres.iter().map(|s| s.name.clone()).collect(),
        }
    }

    /// The shape `prim` belongs to: `mesh 'name' triangle i` (i counted
    /// within the instance) or `sphere 'name'`.
    pub fn shape(&self, prim: PrimRef) -> String {
        let i = prim.index();
        match prim.kind() {
            PrimKind::Triangle => {
                let k = self.instances.partition_point(|(first, _)| *first <= i);
                match k.checked_sub(1).and_then(|k| self.instances.get(k)) {
                    Some((first, name)) => format!("mesh '{name}' triangle {}", i - first),
                    None => format!("triangle {i}"),
                }
            }
            PrimKind::Sphere => match self.spheres.get(i as usize) {
                Some(name) => format!("sphere '{name}'"),
                None => format!("sphere {i}"),
            },
        }
    }

    /// The name of material `i` (`material i` if it has none).
    pub fn material(&self, i: u32) -> String {
        match self.materials.get(i as usize) {
            Some(name) if !name.is_empty() => name.clone(),
            _ => format!("material {i}"),
        }
    }

    /// The name of light `i` (`light i` if it has none).
    pub fn light(&self, i: u32) -> String {
        match self.lights.get(i as usize) {
            Some(name) if !name.is_empty() => name.clone(),
            _ => format!("light {i}"),
        }
    }
}
