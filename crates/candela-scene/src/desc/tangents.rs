//! Smooth per-vertex tangents generated from a mesh's UVs, for normal maps
//! on meshes whose file had none (glTF without `TANGENT`, OBJ, Mitsuba).
//!
//! Each triangle's dp/du and dp/dv (from its positions and UVs) are added
//! to its corners' normal vertices, weighted by the corner angle; each
//! vertex's sum of dp/du is then made orthogonal to its normal (Gram–
//! Schmidt) and normalised, and w is the side of N × T the summed dp/dv
//! lies on. This is MikkTSpace's construction in outline (Mikkelsen 2008,
//! "Simulation of Wrinkled Surfaces Revisited") but not bit for bit:
//! MikkTSpace also splits vertices where the UV winding flips or where
//! tangents would average across a UV seam, and normalises per-triangle
//! tangents before summing. Maps baked by MikkTSpace therefore match
//! exactly only where the UV layout is continuous; at mirrored seams a
//! shared normal vertex averages the two sides (the file should then carry
//! `TANGENT`).

use super::MeshDesc;
use glam::{Vec3, Vec4};

impl MeshDesc {
    /// Per-vertex tangents from the UVs, one per entry of `normals`
    /// (xyz unit, w = ±1), or `None` when the mesh lacks normals or UVs. A
    /// vertex no triangle gives a usable direction gets a zero tangent (the
    /// renderer then uses the triangle's own frame there).
    pub fn generated_tangents(&self) -> Option<Vec<Vec4>> {
        let has_all = |idx: &[[u32; 3]]| idx.len() == self.triangles.len();
        if self.normals.is_empty() || !has_all(&self.normal_indices) || !has_all(&self.uv_indices) {
            return None;
        }
        let mut sum_u = vec![Vec3::ZERO; self.normals.len()];
        let mut sum_v = vec![Vec3::ZERO; self.normals.len()];
        for (t, tri) in self.triangles.iter().enumerate() {
            let p = tri.map(|k| self.positions.get(k as usize).copied());
            let uv = self.uv_indices[t].map(|k| self.uvs.get(k as usize).copied());
            let ([Some(p0), Some(p1), Some(p2)], [Some(t0), Some(t1), Some(t2)]) = (p, uv) else {
                continue;
            };
            let (e1, e2) = (p1 - p0, p2 - p0);
            let (d1, d2) = (t1 - t0, t2 - t0);
            let det = d1.x * d2.y - d1.y * d2.x;
            if det.abs() < 1e-12 || !det.is_finite() {
                continue;
            }
            let dpdu = (d2.y * e1 - d1.y * e2) / det;
            let dpdv = (d1.x * e2 - d2.x * e1) / det;
            let corners = [p0, p1, p2];
            for (c, &k) in self.normal_indices[t].iter().enumerate() {
                let (a, b) = (
                    corners[(c + 1) % 3] - corners[c],
                    corners[(c + 2) % 3] - corners[c],
                );
                let angle = a.angle_between(b);
                let Some(slot) = sum_u.get_mut(k as usize) else {
                    continue;
                };
                if angle.is_finite() {
                    *slot += dpdu.normalize_or_zero() * angle;
                    sum_v[k as usize] += dpdv.normalize_or_zero() * angle;
                }
            }
        }
        Some(
            self.normals
                .iter()
                .zip(sum_u.iter().zip(&sum_v))
                .map(
                    |(&n, (&su, &sv))| match (su - n * n.dot(su)).try_normalize() {
                        Some(t) => t.extend(if n.cross(t).dot(sv) < 0.0 { -1.0 } else { 1.0 }),
                        None => Vec4::ZERO,
                    },
                )
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A quad in the z = 0 plane with u along `u_dir`, v along y.
    fn quad(u_sign: f32) -> MeshDesc {
        MeshDesc {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            normals: vec![Vec3::Z; 4],
            normal_indices: vec![[0, 1, 2], [0, 2, 3]],
            uvs: vec![
                Vec2::ZERO,
                Vec2::new(u_sign, 0.0),
                Vec2::new(u_sign, 1.0),
                Vec2::Y,
            ],
            uv_indices: vec![[0, 1, 2], [0, 2, 3]],
            ..MeshDesc::default()
        }
    }

    #[test]
    fn a_plane_gets_its_uv_axes_and_mirrored_uvs_flip_the_handedness() {
        let t = quad(1.0).generated_tangents().expect("tangents");
        assert!(t
            .iter()
            .all(|&t| (t - Vec4::new(1.0, 0.0, 0.0, 1.0)).length() < 1e-6));
        // u running along −x: T = −x, and N × T = −y against dp/dv = +y.
        let t = quad(-1.0).generated_tangents().expect("tangents");
        assert!(t
            .iter()
            .all(|&t| (t - Vec4::new(-1.0, 0.0, 0.0, -1.0)).length() < 1e-6));
        let mut bare = quad(1.0);
        bare.uv_indices.clear();
        assert_eq!(bare.generated_tangents(), None);
    }
}
