//! Mitsuba's built-in shapes as triangle meshes in their own space:
//! `rectangle` ([-1, 1]² in the z = 0 plane, normal +Z), `cube` ([-1, 1]³,
//! normals outward) and `disk` (unit disk in z = 0, normal +Z). Triangles
//! wind counter-clockwise seen from the side their normal points to.

use crate::desc::{MeshDesc, SourceLoc};
use glam::{Vec2, Vec3};

/// Segments of a tessellated disk: the polygon's area is within 0.2 % of
/// the disk's.
pub(super) const DISK_SEGMENTS: u32 = 64;

/// The square of side 2 around `center` spanned by `u` and `v`, facing u × v.
fn quad(mesh: &mut MeshDesc, center: Vec3, u: Vec3, v: Vec3) {
    let base = mesh.positions.len() as u32;
    let n = u.cross(v);
    for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        mesh.positions.push(center + su * u + sv * v);
        mesh.normals.push(n);
        mesh.uvs.push(Vec2::new(0.5 * (su + 1.0), 0.5 * (sv + 1.0)));
    }
    for t in [[0, 1, 2], [0, 2, 3]] {
        let tri = t.map(|i| base + i);
        mesh.triangles.push(tri);
        mesh.normal_indices.push(tri);
        mesh.uv_indices.push(tri);
    }
}

/// Mitsuba's `rectangle`.
pub(super) fn rectangle(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    quad(&mut m, Vec3::ZERO, Vec3::X, Vec3::Y);
    m
}

/// Mitsuba's `cube`.
pub(super) fn cube(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    let axes = [Vec3::X, Vec3::Y, Vec3::Z];
    for a in 0..3 {
        let (n, u, v) = (axes[a], axes[(a + 1) % 3], axes[(a + 2) % 3]);
        quad(&mut m, n, u, v); // u × v = +n
        quad(&mut m, -n, v, u); // v × u = −n
    }
    m
}

/// Mitsuba's `disk`, as a fan of [`DISK_SEGMENTS`] triangles.
pub(super) fn disk(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    m.positions.push(Vec3::ZERO);
    m.uvs.push(Vec2::splat(0.5));
    for i in 0..DISK_SEGMENTS {
        let phi = std::f32::consts::TAU * i as f32 / DISK_SEGMENTS as f32;
        let (s, c) = phi.sin_cos();
        m.positions.push(Vec3::new(c, s, 0.0));
        m.uvs.push(Vec2::new(0.5 + 0.5 * c, 0.5 + 0.5 * s));
    }
    m.normals.push(Vec3::Z);
    for i in 0..DISK_SEGMENTS {
        let tri = [0, 1 + i, 1 + (i + 1) % DISK_SEGMENTS];
        m.triangles.push(tri);
        m.normal_indices.push([0, 0, 0]);
        m.uv_indices.push(tri);
    }
    m
}

/// Turns the mesh inside out: reversed winding, negated normals.
pub(super) fn flip(mesh: &mut MeshDesc) {
    for t in mesh
        .triangles
        .iter_mut()
        .chain(mesh.normal_indices.iter_mut())
        .chain(mesh.uv_indices.iter_mut())
    {
        t.swap(1, 2);
    }
    for n in &mut mesh.normals {
        *n = -*n;
    }
}
