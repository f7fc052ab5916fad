//! Shape tests against independent f64 computations, and re-intersection of
//! spawned rays (a ray leaving a surface never hits that surface at t ~ 0).

use super::*;
use crate::geometry::Ray;
use glam::{DVec3, Vec3};

/// The seeded generator every shape test uses.
pub(super) use candela_testkit::SplitMix64 as Rng;

/// Möller–Trumbore in f64: (t, b1, b2) of the plane hit, no range checks.
pub(super) fn triangle_f64(o: Vec3, d: Vec3, v: &[Vec3; 3]) -> Option<(f64, f64, f64)> {
    let (o, d) = (o.as_dvec3(), d.as_dvec3());
    let [v0, v1, v2]: [DVec3; 3] = v.map(|x| x.as_dvec3());
    let (e1, e2) = (v1 - v0, v2 - v0);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = o - v0;
    let q = s.cross(e1);
    Some((e2.dot(q) / det, s.dot(p) / det, d.dot(q) / det))
}

#[test]
fn triangle_matches_f64_away_from_edges() {
    let mut rng = Rng(11);
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..200_000 {
        let c = rng.vec(-10.0, 10.0);
        let s = rng.log(-2.0, 2.0);
        let v = [
            c + s * rng.vec(-1.0, 1.0),
            c + s * rng.vec(-1.0, 1.0),
            c + s * rng.vec(-1.0, 1.0),
        ];
        let o = c + s * 3.0 * rng.dir();
        let target = c + s * rng.vec(-1.0, 1.0);
        let d = (target - o).normalize();
        let t_max = if rng.f32() < 0.2 {
            s * rng.f32() * 4.0
        } else {
            f32::INFINITY
        };
        let got = intersect_triangle(&TriangleRay::new(o, d), &v, t_max);
        let Some((t, b1, b2)) = triangle_f64(o, d, &v) else {
            continue;
        };
        let m = 1e-4;
        let inside = b1 > m && b2 > m && 1.0 - b1 - b2 > m;
        let outside = b1 < -m || b2 < -m || 1.0 - b1 - b2 < -m;
        let t_in = t > m * s as f64 && t < t_max as f64 * (1.0 - m);
        let t_out = t < -m * s as f64 || t > t_max as f64 * (1.0 + m);
        if inside && t_in {
            let h = got.expect("f64 says hit");
            assert!(((h.t as f64 - t) / t).abs() < 1e-3, "t {} vs {t}", h.t);
            assert!((h.b1 as f64 - b1).abs() < 1e-3 && (h.b2 as f64 - b2).abs() < 1e-3);
            hits += 1;
        } else if outside || t_out {
            assert!(
                got.is_none(),
                "f64 says miss: {b1} {b2} t={t} t_max={t_max}"
            );
            misses += 1;
        }
    }
    assert!(
        hits > 10_000 && misses > 10_000,
        "{hits} hits, {misses} misses"
    );
}

#[test]
fn triangle_parallel_and_degenerate_rays_miss() {
    let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
    // In the plane, parallel above it, degenerate triangle.
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(-1.0, 0.2, 0.0), Vec3::X),
        &v,
        f32::INFINITY
    )
    .is_none());
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(-1.0, 0.2, 1.0), Vec3::X),
        &v,
        f32::INFINITY
    )
    .is_none());
    let flat = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z),
        &flat,
        f32::INFINITY
    )
    .is_none());
    // Both faces hit (no culling); behind the origin is a miss.
    let up = intersect_triangle(
        &TriangleRay::new(Vec3::new(0.25, 0.25, -2.0), Vec3::Z),
        &v,
        f32::INFINITY,
    );
    let down = intersect_triangle(
        &TriangleRay::new(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z),
        &v,
        f32::INFINITY,
    );
    assert_eq!(up.map(|h| h.t), Some(2.0));
    assert_eq!(down.map(|h| (h.b1, h.b2)), Some((0.25, 0.25)));
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(0.25, 0.25, 2.0), Vec3::Z),
        &v,
        f32::INFINITY
    )
    .is_none());
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z),
        &v,
        2.0
    )
    .is_none());
    // Exactly on a vertex and an edge: inclusive.
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(1.0, 0.0, 1.0), -Vec3::Z),
        &v,
        f32::INFINITY
    )
    .is_some());
    assert!(intersect_triangle(
        &TriangleRay::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z),
        &v,
        f32::INFINITY
    )
    .is_some());
}

/// Roots of the sphere quadratic in f64.
fn sphere_f64(o: Vec3, d: Vec3, c: Vec3, r: f32) -> Option<(f64, f64)> {
    let (f, d) = (o.as_dvec3() - c.as_dvec3(), d.as_dvec3());
    let (a, b, cc) = (d.dot(d), 2.0 * f.dot(d), f.dot(f) - (r as f64).powi(2));
    let disc = b * b - 4.0 * a * cc;
    (disc >= 0.0).then(|| {
        (
            (-b - disc.sqrt()) / (2.0 * a),
            (-b + disc.sqrt()) / (2.0 * a),
        )
    })
}

#[test]
fn sphere_matches_f64() {
    let mut rng = Rng(12);
    let mut checked = 0;
    for i in 0..100_000 {
        let c = rng.vec(-100.0, 100.0);
        let r = rng.log(-2.0, 2.0);
        // Outside, inside, and far away.
        let o = match i % 3 {
            0 => c + r * rng.log(0.1, 1.0) * rng.dir(),
            1 => c + r * 0.9 * rng.f32() * rng.dir(),
            _ => c + r * 1000.0 * rng.dir(),
        };
        let d = if rng.f32() < 0.7 {
            (c + r * rng.vec(-1.0, 1.0) - o).normalize()
        } else {
            rng.dir()
        };
        let got = intersect_sphere(o, d, c, r, f32::INFINITY);
        let want =
            sphere_f64(o, d, c, r).and_then(|(t0, t1)| [t0, t1].into_iter().find(|&t| t > 0.0));
        let tol = 1e-4 * (r as f64);
        match (got, want) {
            (Some(g), Some(w)) => {
                assert!((g as f64 - w).abs() < tol + 1e-5 * w, "t {g} vs {w}");
                checked += 1;
            }
            (None, None) => {}
            (g, w) => {
                // Allowed only when f64 itself is within rounding of tangent or of the origin.
                let (t0, t1) = sphere_f64(o, d, c, r).unwrap_or((0.0, 0.0));
                assert!(
                    (t1 - t0).abs() < 1e-3 * r as f64 || t0.abs().min(t1.abs()) < tol,
                    "{g:?} vs {w:?}"
                );
            }
        }
    }
    assert!(checked > 50_000);
}

/// Scalar and packet tests alike; about a third of these rays fall within
/// the f32 `t` error bound of zero and are decided in f64.
#[test]
fn spawned_rays_never_rehit_their_triangle() {
    let mut rng = Rng(13);
    for _ in 0..200_000 {
        let c = rng.dir() * rng.log(-1.0, 5.0);
        let s = rng.log(-3.0, 3.0);
        let v = [
            c + s * rng.vec(-1.0, 1.0),
            c + s * rng.vec(-1.0, 1.0),
            c + s * rng.vec(-1.0, 1.0),
        ];
        let o = c + s * 2.0 * rng.dir();
        let target = v[0] + (v[1] - v[0]) * rng.f32() * 0.5 + (v[2] - v[0]) * rng.f32() * 0.5;
        let d = (target - o).normalize();
        let Some(h) = intersect_triangle(&TriangleRay::new(o, d), &v, f32::INFINITY) else {
            continue;
        };
        let sp = triangle_surface_point(&v, h.b1, h.b2);
        // Reflected (toward the incoming side) and transmitted directions.
        for w in [rng.dir(), -d, d] {
            let ray = spawn_ray(&sp, w);
            let tr = TriangleRay::new(ray.origin, ray.dir);
            let again = intersect_triangle(&tr, &v, f32::INFINITY);
            let packet = TrianglePacket::new(&[v]);
            assert!(!occluded_triangle4(
                &TriangleRay4::new(&tr),
                &packet,
                1,
                f32::INFINITY
            ));
            assert!(
                again.is_none(),
                "re-hit at t={:?}, scale {s}, at {c}",
                again.map(|h| h.t)
            );
        }
    }
}

#[test]
fn spawned_rays_never_rehit_their_sphere() {
    let mut rng = Rng(14);
    for _ in 0..200_000 {
        let c = rng.dir() * rng.log(-1.0, 4.0);
        let r = rng.log(-2.0, 3.0);
        let o = c + r * rng.log(0.05, 2.0) * rng.dir();
        let d = (c + 0.9 * r * rng.vec(-1.0, 1.0) - o).normalize();
        let Some(t) = intersect_sphere(o, d, c, r, f32::INFINITY) else {
            continue;
        };
        let sp = sphere_surface_point(c, r, &Ray::new(o, d), t);
        let w = rng.dir();
        let ray = spawn_ray(&sp, w);
        let again = intersect_sphere(ray.origin, ray.dir, c, r, f32::INFINITY);
        let cos = w.dot(sp.n);
        if cos > 0.0 {
            assert!(
                again.is_none(),
                "outward ray re-hit at {again:?}, r {r}, at {c}"
            );
        } else if cos < -0.1 && sp.p_error.max_element() < 1e-4 * r {
            // The far side, not the spawning point (the chord's accuracy is
            // limited by f32 positions far from the origin, checked above).
            let chord = 2.0 * r * -cos;
            let t = again.expect("inward ray must hit the far side");
            assert!(
                t > 0.5 * chord && t < 1.5 * chord,
                "inward t {t}, chord {chord}, r {r}, c {c}"
            );
        }
    }
}

#[test]
fn sphere_uv_in_the_default_axes_is_the_accelerators_uv_and_follows_rotated_axes() {
    use candela_scene::SphereDesc;
    let c = Vec3::new(0.3, -1.0, 2.0);
    let dirs = [
        Vec3::new(0.3, 0.5, -0.8),
        Vec3::new(-0.9, 0.1, 0.2),
        Vec3::new(0.0, -1.0, 0.4),
        Vec3::new(0.6, 0.2, 0.7),
    ];
    // Rotated 90° about x, as Mitsuba's `rotate x=1 angle=90`: its pole
    // (local +z) is world −y, its local +y world +z.
    let rotated = glam::Mat3::from_cols(Vec3::X, Vec3::Z, -Vec3::Y);
    for d in dirs {
        let p = c + 1.7 * d.normalize();
        assert_eq!(
            sphere_uv_in(SphereDesc::Y_POLE, c, p),
            sphere_uv(c, p),
            "{d}"
        );
        // In the rotated axes the local point is (x, z, −y) of the offset.
        let q = d.normalize();
        let (u, v) = sphere_uv_in(rotated, c, p);
        let phi = q.z.atan2(q.x).rem_euclid(std::f32::consts::TAU);
        assert!((u - phi / std::f32::consts::TAU).abs() < 1e-5, "{d}: u {u}");
        assert!(
            (v - (-q.y).acos() / std::f32::consts::PI).abs() < 1e-5,
            "{d}: v {v}"
        );
    }
}
