//! The one check every loader's scene passes before a renderer sees it:
//! all drawn geometry and every camera lie within [`MAX_COORDINATE`] of the
//! origin.
//!
//! Why a bound on finite numbers: loaders refuse NaN and infinity, but a
//! vertex at 1e38 is finite and still breaks single-precision ray tracing.
//! The watertight triangle test multiplies three coordinate differences
//! (relative to the ray origin), so coordinates beyond about 3e12 overflow
//! it, and the orbit camera framed around such bounds is infinite. Such a
//! value in a file is a corrupt number or a unit mistake, never a scene, so
//! it is refused at load time with its place in the file, instead of
//! failing later as a camera error without one.

use super::{SceneDesc, SourceLoc};
use crate::error::{located, ErrorKind, LoadError};
use glam::{Mat4, Vec3};

/// The largest absolute world coordinate of any vertex, sphere or camera
/// position (with margin: the triangle test's cubic terms overflow
/// `f32` for coordinate differences beyond about 7e12).
pub const MAX_COORDINATE: f32 = 1e12;

/// A point as `[x, y, z]`, huge values in exponent form (`-1e38`, not
/// 39 digits).
fn shown(p: Vec3) -> String {
    format!("[{:?}, {:?}, {:?}]", p.x, p.y, p.z)
}

/// Whether `p` is finite and within [`MAX_COORDINATE`] on every axis.
fn in_range(p: Vec3) -> bool {
    p.abs().max_element() <= MAX_COORDINATE
}

impl SceneDesc {
    /// Refuses a scene with drawn geometry or a camera beyond
    /// [`MAX_COORDINATE`] (after placement: an instance's transform can
    /// carry a reasonable mesh out of range), naming the element and the
    /// first vertex out of range.
    pub fn check_extent(&self) -> Result<(), LoadError> {
        for inst in &self.instances {
            let Some(mesh) = self.meshes.get(inst.mesh) else {
                continue;
            };
            let outside = mesh
                .positions
                .iter()
                .enumerate()
                .map(|(i, &p)| (i, inst.world_from_object.transform_point3(p)))
                .find(|&(_, w)| !in_range(w));
            if let Some((i, w)) = outside {
                let placed = if inst.world_from_object == Mat4::IDENTITY {
                    String::new()
                } else {
                    " once placed".to_string()
                };
                return Err(self.out_of_range(
                    inst.loc,
                    &format!("mesh \"{}\"", mesh.name),
                    format!("vertex {i} lies at {}{placed}", shown(w)),
                ));
            }
        }
        for s in &self.spheres {
            if !(in_range(s.center) && s.radius <= MAX_COORDINATE) {
                return Err(self.out_of_range(
                    s.loc,
                    &format!("sphere \"{}\"", s.name),
                    format!("centre {} with radius {:?}", shown(s.center), s.radius),
                ));
            }
        }
        for c in &self.cameras {
            let eye = c.world_from_camera.transform_point3(Vec3::ZERO);
            if !in_range(eye) {
                return Err(self.out_of_range(
                    c.loc,
                    &format!("camera \"{}\"", c.name),
                    format!("eye at {}", shown(eye)),
                ));
            }
        }
        Ok(())
    }

    fn out_of_range(&self, loc: SourceLoc, element: &str, what: String) -> LoadError {
        located(
            &self.source,
            loc,
            element,
            ErrorKind::BadValue,
            format!(
                "{what}: beyond ±{MAX_COORDINATE:e}, the largest coordinate single-precision \
                 ray tracing handles (a corrupt number or a unit mistake?)"
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::desc::{CameraDesc, InstanceDesc, MeshDesc, Projection, SphereDesc};

    fn scene_with_vertex(p: Vec3, placement: Mat4) -> SceneDesc {
        let mesh = MeshDesc {
            name: "m".into(),
            positions: vec![Vec3::ZERO, Vec3::X, p],
            triangles: vec![[0, 1, 2]],
            ..MeshDesc::default()
        };
        let loc = SourceLoc { line: 7, col: 3 };
        SceneDesc {
            source: "s.xml".into(),
            meshes: vec![mesh],
            instances: vec![InstanceDesc {
                world_from_object: placement,
                ..InstanceDesc::identity(0, loc)
            }],
            ..SceneDesc::default()
        }
    }

    #[test]
    fn a_vertex_beyond_the_bound_is_refused_with_its_place() {
        assert!(
            scene_with_vertex(Vec3::splat(MAX_COORDINATE), Mat4::IDENTITY)
                .check_extent()
                .is_ok()
        );
        let e = scene_with_vertex(Vec3::new(0.3, -1e38, 0.4), Mat4::IDENTITY)
            .check_extent()
            .unwrap_err();
        assert_eq!(e.kind, ErrorKind::BadValue);
        assert_eq!(e.loc, Some(SourceLoc { line: 7, col: 3 }));
        assert_eq!(e.element, "mesh \"m\"");
        assert!(e.message.starts_with("vertex 2 lies at"), "{}", e.message);
        assert_eq!(e.to_string().lines().count(), 1);
    }

    #[test]
    fn a_placement_that_carries_a_mesh_out_of_range_is_refused() {
        let far = Mat4::from_scale(Vec3::splat(1e13));
        let e = scene_with_vertex(Vec3::Y, far).check_extent().unwrap_err();
        // Vertex 0 stays at the origin; vertex 1 (X) is the first carried out.
        assert!(
            e.message.starts_with("vertex 1 lies at") && e.message.contains("once placed"),
            "{}",
            e.message
        );
        assert!(
            scene_with_vertex(Vec3::Y, Mat4::from_scale(Vec3::splat(1e11)))
                .check_extent()
                .is_ok()
        );
    }

    #[test]
    fn spheres_and_cameras_out_of_range_are_refused() {
        let loc = SourceLoc { line: 2, col: 1 };
        let sphere = |center: Vec3, radius: f32| SceneDesc {
            spheres: vec![SphereDesc {
                name: "s".into(),
                center,
                radius,
                material: 0,
                axes: SphereDesc::Y_POLE,
                inward: false,
                loc,
            }],
            ..SceneDesc::default()
        };
        assert!(sphere(Vec3::ONE, 2.0).check_extent().is_ok());
        assert!(sphere(Vec3::new(0.0, 2e12, 0.0), 2.0)
            .check_extent()
            .is_err());
        assert!(sphere(Vec3::ONE, 1e30).check_extent().is_err());
        assert!(sphere(Vec3::ONE, f32::NAN).check_extent().is_err());
        let camera = |eye: Vec3| SceneDesc {
            cameras: vec![CameraDesc {
                name: "c".into(),
                world_from_camera: Mat4::from_translation(eye),
                projection: Projection::Perspective {
                    xfov_deg: 60.0,
                    yfov_deg: 45.0,
                },
                znear: None,
                zfar: None,
                clip: None,
                loc,
            }],
            ..SceneDesc::default()
        };
        assert!(camera(Vec3::new(1.0, 2.0, 3.0)).check_extent().is_ok());
        let e = camera(Vec3::new(0.0, 0.0, -5e12))
            .check_extent()
            .unwrap_err();
        assert_eq!(e.element, "camera \"c\"");
    }
}
