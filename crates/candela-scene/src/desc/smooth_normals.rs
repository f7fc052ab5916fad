//! Vertex normals for a mesh that has none, for formats whose renderers
//! shade such meshes smoothly (Mitsuba's `obj`, `ply` and `serialized`
//! without `face_normals`).

use super::MeshDesc;
use glam::Vec3;

impl MeshDesc {
    /// Gives every vertex the mean of its triangles' normals weighted by the
    /// angle each triangle makes at the vertex (Thürmer and Wüthrich 1998,
    /// "Computing Vertex Normals from Polygonal Facets", the rule Mitsuba
    /// uses): unlike area or plain averages, the result does not change when
    /// a polygon around the vertex is triangulated differently. A vertex
    /// whose triangles are all degenerate gets +Z (Mitsuba picks an
    /// arbitrary axis too). Does nothing if the mesh already has normals.
    pub fn set_angle_weighted_normals(&mut self) {
        if !self.normals.is_empty() {
            return;
        }
        let mut sums = vec![Vec3::ZERO; self.positions.len()];
        for tri in &self.triangles {
            let p = tri.map(|i| self.positions[i as usize]);
            let Some(n) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else {
                continue;
            };
            for k in 0..3 {
                let a = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
                let b = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
                let angle = a.dot(b).clamp(-1.0, 1.0).acos();
                sums[tri[k] as usize] += n * angle;
            }
        }
        self.normals = sums
            .into_iter()
            .map(|s| s.try_normalize().unwrap_or(Vec3::Z))
            .collect();
        self.normal_indices = self.triangles.clone();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube's corner: three faces meet at right angles, so the
    /// angle-weighted normal is the diagonal whatever the triangulation.
    #[test]
    fn a_cube_corner_gets_the_diagonal_for_any_triangulation() {
        let positions = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ];
        // Faces z = 0, x = 0, y = 0 around the corner at the origin, each
        // seen from outside (normals −Z, −X, −Y); z = 0 split into two
        // triangles meeting at the origin, the others into one there.
        let split = vec![
            [0, 2, 4],
            [0, 4, 1],
            [0, 3, 5],
            [0, 5, 2],
            [0, 1, 6],
            [0, 6, 3],
        ];
        let other = vec![
            [0, 2, 1],
            [2, 4, 1],
            [0, 3, 5],
            [0, 5, 2],
            [0, 1, 6],
            [0, 6, 3],
        ];
        for triangles in [split, other] {
            let mut m = MeshDesc {
                positions: positions.clone(),
                triangles,
                ..MeshDesc::default()
            };
            m.set_angle_weighted_normals();
            let n = m.normals[0];
            assert!((n - Vec3::splat(-1.0).normalize()).length() < 1e-6, "{n}");
            assert_eq!(m.normal_indices, m.triangles);
        }
    }

    #[test]
    fn existing_normals_are_kept_and_degenerate_vertices_get_plus_z() {
        let mut m = MeshDesc {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            triangles: vec![[0, 1, 2]],
            ..MeshDesc::default()
        };
        m.set_angle_weighted_normals();
        assert_eq!(m.normals, vec![Vec3::Z; 3]);
        m.normals = vec![Vec3::X; 3];
        m.set_angle_weighted_normals();
        assert_eq!(m.normals, vec![Vec3::X; 3]);
    }
}
