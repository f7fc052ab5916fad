//! The CS184 Cornell boxes describe their lamp twice: an emissive mesh just
//! under the ceiling and a CGL area light of the same size, radiance and
//! height. Rendering both would double the light, so an area light that
//! coincides with an emissive mesh is dropped in favour of the mesh (which
//! the camera can also see), and the report says so.
//!
//! Some files in the wild give the two different radiances. The CS184
//! program light-samples the area light and only sees the mesh by chance
//! hits, so its users see the scene lit at the area light's radiance: the
//! lamp is still counted once, as the mesh, but emitting the area light's
//! radiance, and the note names both values.

use crate::desc::{LightKind, SceneDesc};
use crate::report::Warning;
use glam::{Mat3, Vec3};

/// Relative tolerance on area and radiance, and on the centre distance
/// measured in units of the lamp's size: loose enough for the files'
/// rounding (their lamp mesh sits 0.004 below the light, a 0.6% offset),
/// tight enough that two distinct lamps never match.
const TOLERANCE: f32 = 0.05;

/// An emissive mesh summarised as one flat lamp.
struct Lamp {
    /// Index into [`SceneDesc::instances`].
    instance: usize,
    name: String,
    area: f32,
    centroid: Vec3,
    /// Area-weighted normal of the emitting side.
    normal: Vec3,
    radiance: Vec3,
}

/// Removes area lights that duplicate an emissive mesh (same area, place
/// and facing; the mesh takes the light's radiance if they differ) and
/// returns one note per removal.
pub(crate) fn merge_duplicate_lamps(scene: &mut SceneDesc) -> Vec<Warning> {
    let lamps: Vec<Lamp> = scene
        .instances
        .iter()
        .enumerate()
        .filter_map(|(instance, inst)| {
            let mesh = scene.meshes.get(inst.mesh)?;
            let material = inst.material.unwrap_or(mesh.material);
            let radiance = scene.materials.get(material)?.emission?;
            let m = inst.world_from_object;
            let normal_m = Mat3::from_mat4(m).inverse().transpose();
            let (mut area, mut centroid, mut normal) = (0.0, Vec3::ZERO, Vec3::ZERO);
            for (i, t) in mesh.triangles.iter().enumerate() {
                let [a, b, c] = t.map(|k| m.transform_point3(mesh.positions[k as usize]));
                let cross = (b - a).cross(c - a);
                let tri_area = 0.5 * cross.length();
                let mut n = cross.normalize_or_zero();
                if let Some(ni) = mesh.normal_indices.get(i) {
                    let authored: Vec3 = ni
                        .iter()
                        .map(|&k| normal_m * mesh.normals[k as usize])
                        .sum();
                    if authored.dot(n) < 0.0 {
                        n = -n;
                    }
                }
                area += tri_area;
                centroid += tri_area * (a + b + c) / 3.0;
                normal += tri_area * n;
            }
            (area > 0.0).then(|| Lamp {
                instance,
                name: mesh.name.clone(),
                area,
                centroid: centroid / area,
                normal: normal.normalize_or_zero(),
                radiance,
            })
        })
        .collect();
    let mut notes = Vec::new();
    let mut reradiate = Vec::new();
    scene.lights.retain(|light| {
        let LightKind::Area {
            center,
            edge_x,
            edge_y,
            normal,
            radiance,
        } = light.kind
        else {
            return true;
        };
        let area = edge_x.cross(edge_y).length();
        let size = area.sqrt();
        let twin = lamps.iter().find(|lamp| {
            close(lamp.area, area)
                && (lamp.centroid - center).length() <= TOLERANCE * size
                && lamp.normal.dot(normal.normalize_or_zero()) > 1.0 - TOLERANCE
        });
        let Some(lamp) = twin else {
            return true;
        };
        let same = close(lamp.radiance.max_element(), radiance.max_element())
            && (lamp.radiance - radiance).abs().max_element() <= TOLERANCE * radiance.max_element();
        let message = if same {
            format!(
                "area light '{}' describes the emissive mesh '{}' (same area, place and radiance): its light is counted once, as the mesh",
                light.name, lamp.name
            )
        } else {
            reradiate.push((lamp.instance, radiance));
            let (l, m) = (radiance, lamp.radiance);
            format!(
                "area light '{}' sits on the emissive mesh '{}' with radiance ({}, {}, {}) against the mesh's ({}, {}, {}): counted once, as the mesh at the area light's radiance (what the CS184 program renders)",
                light.name, lamp.name, l.x, l.y, l.z, m.x, m.y, m.z
            )
        };
        notes.push(Warning {
            loc: light.loc,
            element: "<area>".into(),
            message,
            count: 1,
        });
        false
    });
    for (instance, radiance) in reradiate {
        emit_from(scene, instance, radiance);
    }
    notes
}

/// Gives one instance its own copy of its material, emitting `radiance`
/// (other meshes sharing the material keep theirs).
fn emit_from(scene: &mut SceneDesc, instance: usize, radiance: Vec3) {
    let inst = &scene.instances[instance];
    let current = inst.material.unwrap_or(scene.meshes[inst.mesh].material);
    let mut material = scene.materials[current].clone();
    material.emission = Some(radiance);
    scene.materials.push(material);
    scene.instances[instance].material = Some(scene.materials.len() - 1);
}

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= TOLERANCE * a.abs().max(b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::desc::{BsdfDesc, LightDesc, MaterialDesc, MeshDesc, SourceLoc};
    use crate::{load_str, LoadOptions};

    /// A 0.8 x 0.6 lamp at height 1.49 facing down, and an area light.
    fn scene_with(light_center: Vec3, light_radiance: f32) -> SceneDesc {
        let p = |x: f32, z: f32| Vec3::new(x, 1.49, z);
        let mesh = MeshDesc {
            name: "light".into(),
            positions: vec![p(0.4, -0.3), p(0.4, 0.3), p(-0.4, 0.3), p(-0.4, -0.3)],
            // Wound so the geometric normal points down.
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            material: 0,
            ..Default::default()
        };
        let mut emitter = MaterialDesc::default_grey();
        emitter.bsdf = BsdfDesc::Black;
        emitter.emission = Some(Vec3::splat(10.0));
        let mut scene = SceneDesc {
            materials: vec![emitter],
            lights: vec![LightDesc {
                name: "Light".into(),
                kind: LightKind::Area {
                    center: light_center,
                    // Rotated by 90 degrees relative to the mesh.
                    edge_x: Vec3::new(0.0, 0.0, 0.8),
                    edge_y: Vec3::new(0.6, 0.0, 0.0),
                    normal: -Vec3::Y,
                    radiance: Vec3::splat(light_radiance),
                },
                loc: SourceLoc { line: 14, col: 5 },
            }],
            ..Default::default()
        };
        scene.add_mesh(mesh);
        scene
    }

    #[test]
    fn the_cornell_lamp_is_counted_once() {
        let mut scene = scene_with(Vec3::new(0.0, 1.486, 0.0), 10.0);
        let notes = merge_duplicate_lamps(&mut scene);
        assert!(scene.lights.is_empty());
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].message.contains("counted once"),
            "{}",
            notes[0].message
        );
    }

    #[test]
    fn a_lamp_elsewhere_is_kept() {
        let mut scene = scene_with(Vec3::new(0.5, 1.49, 0.0), 10.0);
        assert!(merge_duplicate_lamps(&mut scene).is_empty());
        assert_eq!(scene.lights.len(), 1);
    }

    #[test]
    fn a_dimmer_light_on_the_lamp_sets_its_radiance() {
        let mut scene = scene_with(Vec3::new(0.0, 1.49, 0.0), 3.0);
        let notes = merge_duplicate_lamps(&mut scene);
        assert!(scene.lights.is_empty());
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].message.contains("(3, 3, 3)"),
            "{}",
            notes[0].message
        );
        assert!(
            notes[0].message.contains("(10, 10, 10)"),
            "{}",
            notes[0].message
        );
        let inst = &scene.instances[0];
        let material = inst.material.unwrap_or(scene.meshes[inst.mesh].material);
        assert_eq!(scene.materials[material].emission, Some(Vec3::splat(3.0)));
        // The shared material itself is untouched.
        assert_eq!(scene.materials[0].emission, Some(Vec3::splat(10.0)));
    }

    #[test]
    fn the_demo_scene_has_one_lamp() {
        let loaded = crate::demo_scene();
        assert!(
            loaded.report.notes.is_empty(),
            "the demo describes its lamp once"
        );
        assert!(loaded.scene.lights.is_empty());
        let _ = (load_str, LoadOptions::default());
    }
}
