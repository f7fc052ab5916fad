//! Mitsuba's built-in shapes as triangle meshes in their own space:
//! `rectangle` ([-1, 1]² in the z = 0 plane, normal +Z), `cube` ([-1, 1]³,
//! normals outward), `disk` (unit disk in z = 0, normal +Z) and `cylinder`
//! (radius 1 around +Z from z = 0 to 1, open, normals outward). Triangles
//! wind counter-clockwise seen from the side their normal points to.
//!
//! Each carries Mitsuba's own uv (v as Mitsuba reads it, from an image's
//! top row; the loader turns it into Candela's rows), since textures, the
//! tangent of anisotropic BSDFs (dp/du) and normal and bump maps all follow
//! it. Read from Mitsuba 3 by ray queries (`si.uv`, `si.dp_du`): the
//! rectangle's uv is ((x + 1) / 2, (y + 1) / 2); the disk's is polar, (r,
//! φ / 2π) with φ from +X toward +Y; the cube's faces each have their own
//! orientation ([`CUBE_FACES`]); the cylinder's is (φ / 2π, z).

use crate::desc::{MeshDesc, SourceLoc};
use glam::{Vec2, Vec3};

/// Segments of a tessellated disk: the polygon's area is within 0.2 % of
/// the disk's.
pub(super) const DISK_SEGMENTS: u32 = 64;

/// Rings of a tessellated disk. Its polar uv is exact at the vertices and
/// linear between them: u = r within the chords' sag (0.12 %), v nearly
/// exact except inside the innermost ring, a fan around the centre (where
/// φ has no value), where it strays by up to half a segment. v is constant
/// along a spoke, so each triangle's dp/du runs along one of its two
/// spokes: the radius (Mitsuba's dp/du) within one segment.
pub(super) const DISK_RINGS: u32 = 16;

/// Segments around a tessellated cylinder. The mesh carries the exact
/// radial normals, so shading matches the round surface; the polygon's
/// area is within 0.05 % of the cylinder's and its silhouette within
/// 0.03 % of the radius.
pub(super) const CYLINDER_SEGMENTS: u32 = 128;

/// Mitsuba's cube face by face: (outward normal, the direction u grows
/// along, the direction v grows along), each over [0, 1] across the face
/// (Mitsuba's cube is a mesh of its own with these texture coordinates).
/// On every face u × v points inward: a left-handed (u, v) in Mitsuba's
/// rows, right-handed once v is flipped into Candela's.
const CUBE_FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Y, Vec3::NEG_Z),
    (Vec3::NEG_X, Vec3::Y, Vec3::Z),
    (Vec3::Y, Vec3::NEG_X, Vec3::NEG_Z),
    (Vec3::NEG_Y, Vec3::Z, Vec3::X),
    (Vec3::Z, Vec3::Y, Vec3::X),
    (Vec3::NEG_Z, Vec3::NEG_Y, Vec3::X),
];

/// The square of side 2 around `center` spanned by `u` and `v` (uv (0, 0)
/// at center − u − v, (1, 1) at center + u + v), facing `n`.
fn quad(mesh: &mut MeshDesc, center: Vec3, u: Vec3, v: Vec3, n: Vec3) {
    let base = mesh.positions.len() as u32;
    for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        mesh.positions.push(center + su * u + sv * v);
        mesh.normals.push(n);
        mesh.uvs.push(Vec2::new(0.5 * (su + 1.0), 0.5 * (sv + 1.0)));
    }
    // The corners go around counter-clockwise about u × v.
    let tris = if u.cross(v).dot(n) > 0.0 {
        [[0, 1, 2], [0, 2, 3]]
    } else {
        [[0, 2, 1], [0, 3, 2]]
    };
    for t in tris {
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
    quad(&mut m, Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    m
}

/// Mitsuba's `cube`.
pub(super) fn cube(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    for (n, u, v) in CUBE_FACES {
        quad(&mut m, n, u, v, n);
    }
    m
}

/// Mitsuba's `disk` with its polar uv: [`DISK_RINGS`] rings of
/// [`DISK_SEGMENTS`] segments, the innermost a fan whose centre vertex has,
/// per segment, v at the segment's middle angle. The seam at φ = 0 has
/// its own vertices for u = 1.
pub(super) fn disk(name: String, loc: SourceLoc) -> MeshDesc {
    let mut m = MeshDesc {
        name,
        loc,
        ..MeshDesc::default()
    };
    m.normals.push(Vec3::Z);
    let (rings, segments) = (DISK_RINGS, DISK_SEGMENTS);
    // Ring j (1..=rings) at radius j / rings, columns 0..=segments.
    let at = |j: u32, i: u32| segments + (j - 1) * (segments + 1) + i;
    for i in 0..segments {
        m.positions.push(Vec3::ZERO);
        m.uvs
            .push(Vec2::new(0.0, (i as f32 + 0.5) / segments as f32));
    }
    for j in 1..=rings {
        let r = j as f32 / rings as f32;
        for i in 0..=segments {
            let v = i as f32 / segments as f32;
            let (s, c) = (std::f32::consts::TAU * v).sin_cos();
            m.positions.push(Vec3::new(r * c, r * s, 0.0));
            m.uvs.push(Vec2::new(r, v));
        }
    }
    let mut push = |tri: [u32; 3]| {
        m.triangles.push(tri);
        m.normal_indices.push([0, 0, 0]);
        m.uv_indices.push(tri);
    };
    for i in 0..segments {
        push([i, at(1, i), at(1, i + 1)]);
        for j in 1..rings {
            let (a, b) = (at(j, i), at(j, i + 1));
            let (c, d) = (at(j + 1, i + 1), at(j + 1, i));
            push([a, d, c]);
            push([a, c, b]);
        }
    }
    m
}

/// Turns the mesh inside out: reversed winding, negated normals.
pub(super) fn flip(mesh: &mut MeshDesc) {
    mesh.reverse_winding();
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
