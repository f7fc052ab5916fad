//! Watertightness where it is hardest: rays aimed exactly at the shared
//! vertex of a fan and at shared vertices and edges of a fine height-field
//! grid. Every direction used sees each triangle from the same side (the
//! surfaces are graphs and `d` is steeper than every triangle), so in exact
//! arithmetic every such ray crosses the surface: at least one triangle
//! must report a hit.

use super::tests::Rng;
use super::*;
use glam::Vec3;

/// Whether `d` sees every triangle of `tris` from the same (upper) side, by
/// a clear margin, so the surface covers the target as seen along `d`.
fn steep_enough(d: Vec3, v: &[Vec3], tris: &[[u32; 3]]) -> bool {
    tris.iter().all(|t| {
        let [a, b, c] = t.map(|i| v[i as usize].as_dvec3());
        let n = (b - a).cross(c - a);
        n.dot(d.as_dvec3()) <= -0.2 * n.length() * d.as_dvec3().length()
    })
}

/// Whether the ray from `o` toward `target` misses every triangle.
fn escapes(o: Vec3, target: Vec3, v: &[Vec3], tris: &[[u32; 3]]) -> bool {
    let d = (target - o).normalize();
    let ray = TriangleRay::new(o, d);
    !tris
        .iter()
        .any(|t| intersect_triangle(&ray, &t.map(|i| v[i as usize]), f32::INFINITY).is_some())
}

/// A point above `p` from which the surface is seen steeply.
fn origin_above(rng: &mut Rng, p: Vec3, s: f32) -> Vec3 {
    let a = rng.vec(-0.6, 0.6);
    p + s * rng.log(-1.0, 1.5) * Vec3::new(a.x, 1.0, a.z)
}

/// Rays cast at a surface's shared vertices and edges, and those that
/// missed every triangle.
#[derive(Default)]
struct Tally {
    rays: u32,
    escaped: u32,
}

impl Tally {
    /// Casts `tries` rays at `target` from origins above it (scale `s`),
    /// counting those steep enough to be sure of a hit.
    fn cast(
        &mut self,
        rng: &mut Rng,
        target: Vec3,
        s: f32,
        tries: usize,
        v: &[Vec3],
        tris: &[[u32; 3]],
    ) {
        for _ in 0..tries {
            let o = origin_above(rng, target, s);
            if !steep_enough((target - o).normalize(), v, tris) {
                continue;
            }
            self.rays += 1;
            self.escaped += escapes(o, target, v, tris) as u32;
        }
    }
}

#[test]
fn rays_through_fan_vertices_hit() {
    let mut rng = Rng(51);
    let mut tally = Tally::default();
    for _ in 0..3000 {
        let c = rng.vec(-100.0, 100.0);
        let s = rng.log(-2.0, 2.0);
        let k = 3 + (rng.f32() * 6.0) as u32;
        let mut v = vec![c];
        let phase = rng.f32();
        for i in 0..k {
            let phi = std::f32::consts::TAU * (i as f32 + phase + 0.3 * rng.f32()) / k as f32;
            let r = rng.range(0.5, 1.5);
            v.push(c + s * Vec3::new(r * phi.cos(), rng.range(-0.2, 0.2), -r * phi.sin()));
        }
        let tris: Vec<[u32; 3]> = (1..=k).map(|i| [0, i, i % k + 1]).collect();
        tally.cast(&mut rng, c, s, 20, &v, &tris);
    }
    let Tally { rays, escaped } = tally;
    assert!(rays > 20_000, "{rays}");
    assert_eq!(
        escaped, 0,
        "{escaped} of {rays} rays through a fan's vertex escaped"
    );
}

#[test]
fn rays_through_grid_vertices_and_edges_hit() {
    let mut rng = Rng(52);
    let n = 24;
    let mut tally = Tally::default();
    for (c, s) in [(Vec3::ZERO, 1.0), (Vec3::new(700.0, -30.0, 2e3), 5.0)] {
        let h: Vec<f32> = (0..(n + 1) * (n + 1))
            .map(|_| rng.range(-0.1, 0.1))
            .collect();
        let v: Vec<Vec3> = (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let (x, z) = (i as f32 / n as f32, j as f32 / n as f32);
                c + s * Vec3::new(x, h[i * (n + 1) + j] / n as f32, z)
            })
            .collect();
        let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let tris: Vec<[u32; 3]> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .flat_map(|(i, j)| {
                let (a, b, cc, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                [[a, cc, b], [a, d, cc]]
            })
            .collect();
        // Interior vertices (six triangles each) and points on interior edges.
        let mut targets = Vec::new();
        for i in 1..n {
            for j in 1..n {
                let p = v[id(i, j) as usize];
                targets.push(p);
                for q in [id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)] {
                    let q = v[q as usize];
                    targets.push(p + (q - p) * 0.5);
                    targets.push(p + (q - p) * rng.f32());
                }
            }
        }
        for &p in &targets {
            tally.cast(&mut rng, p, s, 3, &v, &tris);
        }
    }
    let Tally { rays, escaped } = tally;
    assert!(rays > 10_000, "{rays}");
    assert_eq!(
        escaped, 0,
        "{escaped} of {rays} rays through shared vertices and edges escaped"
    );
}

#[test]
fn fan_check_rejects_shallow_directions() {
    // The premise of the tests above: a direction flatter than a triangle
    // is refused.
    let v = [Vec3::ZERO, Vec3::X, Vec3::Z];
    let tris = [[0, 2, 1]];
    assert!(steep_enough(-Vec3::Y, &v, &tris));
    assert!(!steep_enough(Vec3::Y, &v, &tris));
    assert!(!steep_enough(Vec3::X, &v, &tris));
}
