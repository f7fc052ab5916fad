//! Watertightness: every ray from inside a closed mesh hits it, including
//! rays aimed exactly at vertices and at points on shared edges.

use super::tests::Rng;
use super::*;
use crate::shape::icosphere;
use glam::Vec3;

/// A cube `[-1, 1]^3` scaled by `s` around `c`, two triangles per face.
fn cube(c: Vec3, s: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let v = (0..8)
        .map(|i| {
            c + s * Vec3::new(
                [-1.0, 1.0][i & 1],
                [-1.0, 1.0][(i >> 1) & 1],
                [-1.0, 1.0][i >> 2],
            )
        })
        .collect();
    let faces = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    let f = faces
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    (v, f)
}

fn hits_mesh(o: Vec3, d: Vec3, v: &[Vec3], f: &[[u32; 3]]) -> bool {
    f.iter().any(|t| {
        intersect_triangle(
            &TriangleRay::new(o, d),
            &t.map(|i| v[i as usize]),
            f32::INFINITY,
        )
        .is_some()
    })
}

/// Targets on the surface: every vertex, points on every edge (the edge's
/// own floating-point interpolation), and random directions.
fn assert_closed(v: &[Vec3], f: &[[u32; 3]], origins: &[Vec3], rng: &mut Rng) {
    let mut targets: Vec<Vec3> = v.to_vec();
    for t in f {
        for k in 0..3 {
            let (a, b) = (v[t[k] as usize], v[t[(k + 1) % 3] as usize]);
            targets.push(a + (b - a) * 0.5);
            targets.push(a + (b - a) * rng.f32());
        }
    }
    let mut rays = 0;
    for &o in origins {
        for &p in &targets {
            let d = (p - o).normalize();
            assert!(hits_mesh(o, d, v, f), "ray from {o} toward {p} escaped");
            rays += 1;
        }
        for _ in 0..2000 {
            let d = rng.dir();
            assert!(hits_mesh(o, d, v, f), "ray from {o} along {d} escaped");
        }
    }
    assert_eq!(rays, origins.len() * targets.len());
}

#[test]
fn icosphere_is_watertight() {
    let mut rng = Rng(21);
    for (c, r) in [
        (Vec3::ZERO, 1.0),
        (Vec3::new(1e3, -2e3, 5e2), 7.0),
        (Vec3::splat(0.3), 1e-3),
    ] {
        let (v, f) = icosphere(3, c, r);
        let origins: Vec<Vec3> = std::iter::once(c)
            .chain((0..4).map(|_| c + r * 0.8 * rng.f32() * rng.dir()))
            .collect();
        assert_closed(&v, &f, &origins, &mut rng);
    }
}

#[test]
fn cube_is_watertight_at_edges_and_corners() {
    let mut rng = Rng(22);
    for (c, s) in [(Vec3::ZERO, 1.0), (Vec3::new(-300.0, 40.0, 1e4), 3.0)] {
        let (v, f) = cube(c, s);
        // The centre sees edges and corners along exact diagonals.
        let origins = [
            c,
            c + s * Vec3::new(0.5, 0.0, 0.0),
            c + s * Vec3::new(0.25, -0.5, 0.75),
        ];
        assert_closed(&v, &f, &origins, &mut rng);
    }
}
