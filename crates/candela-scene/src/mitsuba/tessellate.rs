//! Mitsuba's built-in shapes as triangle meshes in their own space:
//! `rectangle` ([-1, 1]² in the z = 0 plane, normal +Z), `cube` ([-1, 1]³,
//! normals outward), `disk` (unit disk in z = 0, normal +Z) and `cylinder`
//! (radius 1 around +Z from z = 0 to 1, open, normals outward). Triangles
//! wind counter-clockwise seen from the side their normal points to.

use crate::desc::{MeshDesc, SourceLoc};
use glam::{Vec2, Vec3};

/// Segments of a tessellated disk: the polygon's area is within 0.2 % of
/// the disk's.
pub(super) const DISK_SEGMENTS: u32 = 64;

/// Segments around a tessellated cylinder. The mesh carries the exact
/// radial normals, so shading matches the round surface; the polygon's
/// area is within 0.05 % of the cylinder's and its silhouette within
/// 0.03 % of the radius.
pub(super) const CYLINDER_SEGMENTS: u32 = 128;

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

/// Mitsuba's `cylinder` in its own space: radius 1 around +Z from z = 0 to
/// z = 1, without caps, as [`CYLINDER_SEGMENTS`] quads with radial normals.
/// Its uv is Mitsuba's: u = φ / 2π with φ = atan2(y, x) in [0, 2π), v = z.
pub(super) fn cylinder(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    // One column more than segments: the seam at u = 0 and u = 1 has its
    // own uvs; positions and normals repeat there.
    for i in 0..=CYLINDER_SEGMENTS {
        let u = i as f32 / CYLINDER_SEGMENTS as f32;
        let (sin, cos) = (std::f32::consts::TAU * u).sin_cos();
        let radial = Vec3::new(cos, sin, 0.0);
        for z in [0.0, 1.0] {
            m.positions.push(radial + Vec3::new(0.0, 0.0, z));
            m.normals.push(radial);
            m.uvs.push(Vec2::new(u, z));
        }
    }
    for i in 0..CYLINDER_SEGMENTS {
        let (bottom, top) = (2 * i, 2 * i + 1);
        let (next_bottom, next_top) = (bottom + 2, top + 2);
        // Counter-clockwise seen from outside: φ grows to the right when
        // looking at the cylinder with +Z up.
        for tri in [[bottom, next_bottom, next_top], [bottom, next_top, top]] {
            m.triangles.push(tri);
            m.normal_indices.push(tri);
            m.uv_indices.push(tri);
        }
    }
    m
}
