//! Rays starting microns above large triangles (a ground quad under a
//! model): they must hit, with `t` agreeing with f64, through both the
//! scalar test and the 4-lane packet.

use super::tests::{triangle_f64, Rng};
use super::triangle::t_error_bound_of;
use super::*;
use glam::{Mat3, Vec3};

/// A square of side `size` centred at `c` in the plane spanned by the
/// columns `x`, `z` of `frame`, as two triangles.
fn quad(frame: Mat3, c: Vec3, size: f32) -> [[Vec3; 3]; 2] {
    let h = 0.5 * size;
    let corner = |a: f32, b: f32| c + frame * Vec3::new(a * h, 0.0, b * h);
    let (p00, p10, p11, p01) = (
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
    );
    [[p00, p10, p11], [p00, p11, p01]]
}

/// The f64 hit of the quad, if the ray meets a triangle's interior (margin
/// `m` in barycentrics) at t > 0: which triangle, and `t`; `None` also
/// when it is near an edge.
fn quad_f64(o: Vec3, d: Vec3, tris: &[[Vec3; 3]; 2]) -> Option<(usize, f64)> {
    let m = 1e-4;
    tris.iter().enumerate().find_map(|(i, v)| {
        let (t, b1, b2) = triangle_f64(o, d, v)?;
        (b1 > m && b2 > m && 1.0 - b1 - b2 > m && t > 0.0).then_some((i, t))
    })
}

#[test]
fn rays_microns_above_large_quads_hit() {
    let mut rng = Rng(31);
    let tilted = Mat3::from_axis_angle(Vec3::new(1.0, 0.3, -0.5).normalize(), 0.7);
    // Lift above the quad, as powers of ten. On a 6-unit quad, 1-10
    // microns (the reported defect). On a 1000-unit quad the vertices' f32
    // spacing is ~3e-5, so a micron is below what f32 can place, and a t
    // that rounds to <= 0 is rejected before the error bound is computed
    // (that early exit keeps shadow rays fast): there the lift is 0.1-1 mm,
    // still far inside the old bound (~1e-2).
    for (size, frame, lift) in [
        (6.0, Mat3::IDENTITY, (-6.0, -5.0)),
        (1000.0, Mat3::IDENTITY, (-4.0, -3.0)),
        (6.0, tilted, (-6.0, -5.0)),
        (1000.0, tilted, (-4.0, -3.0)),
    ] {
        let c = Vec3::ZERO;
        let tris = quad(frame, c, size);
        let n = frame.y_axis;
        let mut checked = 0;
        for _ in 0..20_000 {
            // A point on the quad within a unit of its centre, lifted along
            // the normal.
            let q = c + frame * Vec3::new(rng.f32() * 2.0 - 1.0, 0.0, rng.f32() * 2.0 - 1.0);
            let o = q + n * rng.log(lift.0, lift.1);
            // Down at any angle, from straight down to 1 degree above grazing.
            let cos = 0.017 + 0.983 * rng.f32();
            let phi = std::f32::consts::TAU * rng.f32();
            let s = (1.0 - cos * cos).sqrt();
            let d = frame * Vec3::new(s * phi.cos(), -cos, s * phi.sin());
            let Some((hit, want)) = quad_f64(o, d, &tris) else {
                continue;
            };
            let tr = TriangleRay::new(o, d);
            let scalar = tris
                .iter()
                .filter_map(|v| intersect_triangle(&tr, v, f32::INFINITY))
                .map(|h| h.t)
                .reduce(f32::min);
            let packet = TrianglePacket::new(&tris);
            let lanes = intersect_triangle4(&TriangleRay4::new(&tr), &packet, 0b11, f32::INFINITY);
            let t = scalar.unwrap_or_else(|| panic!("missed: size {size}, o {o}, d {d}, t {want}"));
            assert_eq!(lanes.map(|h| h.1.t), Some(t), "packet disagrees");
            assert!(occluded_triangle4(
                &TriangleRay4::new(&tr),
                &packet,
                0b11,
                f32::INFINITY
            ));
            // Within its own error bound when the f32 t was trusted, and to
            // f32 precision when it was recomputed in f64 (|t| <= bound).
            let bound = t_error_bound_of(&tr, &tris[hit]) as f64;
            let err = (t as f64 - want).abs();
            let tol = if t as f64 > bound {
                bound
            } else {
                4.0 * f32::EPSILON as f64 * want
            };
            assert!(
                err <= tol,
                "t {t} vs f64 {want}, bound {bound}: size {size}, o {o}, d {d}"
            );
            checked += 1;
        }
        assert!(checked > 15_000, "{checked}");
    }
}
