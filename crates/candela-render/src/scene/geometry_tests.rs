//! The geometric normal a scene keeps per triangle for its hits.

use super::geometry::Geometry;
use crate::accel::Hit;
use crate::geometry::Ray;
use crate::shape::{triangle_surface_point, PrimRef};
use candela_scene::{InstanceDesc, MeshDesc, SceneDesc, SourceLoc};
use glam::{Mat4, Quat, Vec3};

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

/// 50 scattered triangles and a degenerate one, placed as stored and moved
/// (scaled with a mirror, turned, shifted).
fn two_placements() -> Geometry {
    let mut x = 0x2545_f491u32;
    let mut coordinate = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        x as f32 / u32::MAX as f32 * 8.0 - 4.0
    };
    let positions: Vec<Vec3> = (0..150)
        .map(|_| Vec3::new(coordinate(), coordinate(), coordinate()))
        .collect();
    let mut triangles: Vec<[u32; 3]> = (0..50).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    triangles.push([4, 4, 7]);
    let mesh = MeshDesc {
        positions,
        triangles,
        ..MeshDesc::default()
    };
    let moved = Mat4::from_scale_rotation_translation(
        Vec3::new(2.0, -0.5, 1.5),
        Quat::from_rotation_y(0.7),
        Vec3::new(3.0, 1.0, -2.0),
    );
    let desc = SceneDesc {
        meshes: vec![mesh],
        instances: vec![
            InstanceDesc::identity(0, SourceLoc::default()),
            InstanceDesc {
                world_from_object: moved,
                ..InstanceDesc::identity(0, SourceLoc::default())
            },
        ],
        ..SceneDesc::default()
    };
    Geometry::from_desc(&desc).expect("a valid scene")
}

#[test]
fn kept_normals_are_the_corners_normals_bit_for_bit() {
    let geometry = two_placements();
    let tris = &geometry.triangles;
    assert_eq!(tris.geometric_normals.len(), 102);
    assert_eq!(tris.geometric_normals.len(), tris.triangles.len());
    for (i, &kept) in tris.geometric_normals.iter().enumerate() {
        let computed = triangle_surface_point(&tris.corners(i), 0.25, 0.5).n;
        assert_eq!(bits(kept), bits(computed), "triangle {i}");
    }
    // The degenerate triangle has none; the moved copies have their own.
    assert_eq!(tris.geometric_normals[50], Vec3::ZERO);
    assert_eq!(tris.geometric_normals[101], Vec3::ZERO);
    assert_ne!(
        bits(tris.geometric_normals[0]),
        bits(tris.geometric_normals[51])
    );
}

#[test]
fn a_hit_takes_the_kept_normal_toward_the_viewer() {
    let geometry = two_placements();
    let tris = &geometry.triangles;
    for i in (0..tris.triangles.len()).filter(|&i| i % 51 != 50) {
        let v = tris.corners(i);
        let (b1, b2) = (0.3, 0.2);
        let point = triangle_surface_point(&v, b1, b2);
        let origin = point.p + Vec3::new(0.1, 5.0, 0.2);
        let ray = Ray::new(origin, (point.p - origin).normalize());
        let hit = Hit {
            t: (point.p - origin).length(),
            prim: PrimRef::triangle(i as u32),
            b1,
            b2,
        };
        let sh = geometry.surface_hit(&ray, &hit);
        let toward_viewer = if point.n.dot(sh.wo) < 0.0 {
            -point.n
        } else {
            point.n
        };
        assert_eq!(bits(sh.ng), bits(toward_viewer), "triangle {i}");
        assert_eq!(bits(sh.p), bits(point.p), "triangle {i}");
        assert_eq!(bits(sh.p_error), bits(point.p_error), "triangle {i}");
    }
}
