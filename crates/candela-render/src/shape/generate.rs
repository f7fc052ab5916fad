//! Closed meshes generated in code, for tests, benchmarks and synthetic
//! scenes.

use glam::Vec3;
use std::collections::HashMap;

/// An icosphere of radius `r` around `c`, subdivided `levels` times, wound
/// so that its geometric normals point outward. Vertices are shared
/// (indexed), as in a real closed mesh: for watertightness tests, furnaces
/// and synthetic scenes.
pub fn icosphere(levels: u32, c: Vec3, r: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let g = (1.0 + 5f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, g, 0.0),
        (1.0, g, 0.0),
        (-1.0, -g, 0.0),
        (1.0, -g, 0.0),
        (0.0, -1.0, g),
        (0.0, 1.0, g),
        (0.0, -1.0, -g),
        (0.0, 1.0, -g),
        (g, 0.0, -1.0),
        (g, 0.0, 1.0),
        (-g, 0.0, -1.0),
        (-g, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = HashMap::new();
        let mut m = |a: u32, b: u32, v: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push((v[a as usize] + v[b as usize]).normalize());
                v.len() as u32 - 1
            })
        };
        f = f
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (m(a, b, &mut v), m(b, c, &mut v), m(c, a, &mut v));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    (v.iter().map(|&p| c + r * p).collect(), f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn icosphere_is_closed_and_wound_outward() {
        let c = Vec3::new(1.0, -2.0, 0.5);
        let (v, f) = icosphere(2, c, 3.0);
        assert_eq!(f.len(), 20 * 4 * 4);
        // Euler: V - E + F = 2 for a closed genus-0 mesh (E = 3F/2).
        assert_eq!(v.len() as i64 - 3 * f.len() as i64 / 2 + f.len() as i64, 2);
        for [a, b, d] in f {
            let (a, b, d) = (v[a as usize], v[b as usize], v[d as usize]);
            let n = (b - a).cross(d - a);
            assert!(n.dot((a + b + d) / 3.0 - c) > 0.0, "inward face");
            assert!(((a - c).length() - 3.0).abs() < 1e-5);
        }
    }
}
