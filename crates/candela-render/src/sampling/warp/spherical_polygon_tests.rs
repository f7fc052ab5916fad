//! The spherical triangle and rectangle warps: analytic solid angles,
//! chi-square fits against 1 / solid angle, and every direction landing on
//! the polygon.

use glam::{DVec3, Vec2, Vec3};

use super::*;
use crate::sampling::chi2::Chi2Test;

/// Where the ray from the origin along `w` meets the plane of triangle `v`,
/// as barycentric weights (computed in f64, independently of the warp).
fn ray_triangle_weights(v: [Vec3; 3], w: Vec3) -> Option<[f64; 3]> {
    let [a, b, c] = v.map(|x| x.as_dvec3());
    let w = w.as_dvec3();
    let n = (b - a).cross(c - a);
    let denom = w.dot(n);
    if denom == 0.0 {
        return None;
    }
    let t = a.dot(n) / denom;
    if t <= 0.0 {
        return None;
    }
    let q = t * w;
    let total = n.length_squared();
    let area = |x: DVec3, y: DVec3, z: DVec3| (y - x).cross(z - x).dot(n) / total;
    Some([area(q, b, c), area(a, q, c), area(a, b, q)])
}

/// Whether the ray from the origin along `w` hits triangle `v` (`slack`:
/// how far outside, in barycentric weight, still counts).
fn hits_triangle(v: [Vec3; 3], w: Vec3, slack: f64) -> bool {
    ray_triangle_weights(v, w).is_some_and(|b| b.iter().all(|&x| x >= -slack))
}

fn rectangle_corners(corner: Vec3, e0: Vec3, e1: Vec3) -> [[Vec3; 3]; 2] {
    let far = corner + e0 + e1;
    [[corner, corner + e0, far], [corner, far, corner + e1]]
}

fn hits_rectangle(corner: Vec3, e0: Vec3, e1: Vec3, w: Vec3, slack: f64) -> bool {
    rectangle_corners(corner, e0, e1)
        .iter()
        .any(|&t| hits_triangle(t, w, slack))
}

#[test]
fn solid_angles_match_closed_forms() {
    // An octant: π/2, whatever the corners' distances.
    let octant = triangle_solid_angle(Vec3::X, 2.0 * Vec3::Y, 0.5 * Vec3::Z);
    assert!(
        (octant - std::f32::consts::FRAC_PI_2).abs() < 1e-6,
        "{octant}"
    );
    // A 2a × 2b rectangle centred at distance d: 4 asin(ab / √((a²+d²)(b²+d²))).
    for (a, b, d) in [(0.5f64, 0.3f64, 1.0f64), (2.0, 3.0, 0.1), (1e-3, 2e-3, 5.0)] {
        let exact = 4.0 * (a * b / ((a * a + d * d) * (b * b + d * d)).sqrt()).asin();
        let corner = Vec3::new(-a as f32, -b as f32, d as f32);
        let (e0, e1) = (Vec3::X * 2.0 * a as f32, Vec3::Y * 2.0 * b as f32);
        let omega = f64::from(rectangle_solid_angle(corner, e0, e1));
        assert!(
            (omega - exact).abs() <= 1e-5 * exact,
            "{a} {b} {d}: {omega} vs {exact}"
        );
    }
    // Beyond a hemisphere's half (Ω > π): a large triangle just above its centre.
    let big = triangle_solid_angle(
        Vec3::new(-100.0, -100.0, 0.01),
        Vec3::new(100.0, -100.0, 0.01),
        Vec3::new(0.0, 100.0, 0.01),
    );
    assert!(big > 6.0 && big < 2.0 * std::f32::consts::PI, "{big}");
}

/// Triangles (corners relative to the viewpoint) covering the cases the
/// warp must survive.
fn triangle_cases() -> Vec<(&'static str, [Vec3; 3])> {
    vec![
        (
            "near",
            [
                Vec3::new(-1.0, -0.8, 0.3),
                Vec3::new(1.2, -0.5, 0.3),
                Vec3::new(0.1, 1.0, 0.3),
            ],
        ),
        (
            "far",
            [
                Vec3::new(-0.2, 0.1, 3.0),
                Vec3::new(0.3, 0.0, 3.1),
                Vec3::new(0.0, 0.4, 2.9),
            ],
        ),
        (
            "grazing",
            [
                Vec3::new(1.0, -1.0, -0.05),
                Vec3::new(3.0, -1.0, 0.0),
                Vec3::new(2.0, 1.5, 0.02),
            ],
        ),
        (
            "thin",
            [
                Vec3::new(-1.5, 0.0, 2.0),
                Vec3::new(1.5, 0.05, 2.0),
                Vec3::new(1.4, 0.08, 2.1),
            ],
        ),
        (
            "obtuse, behind-facing order",
            [
                Vec3::new(0.3, 0.2, -1.0),
                Vec3::new(-1.2, 0.0, -0.8),
                Vec3::new(1.2, 0.1, -0.9),
            ],
        ),
    ]
}

/// Chi-square of a warp of directions toward the polygon with `corners`
/// against `pdf`, on the gnomonic projection of the directions onto the
/// plane at unit distance along the corners' mean direction (density per
/// unit area `pdf · cos³θ`), over the polygon's bounding box plus a margin:
/// a zoomed grid that resolves small, far and thin polygons, which fall in
/// a cell or two of the sphere's (where the quadrature also misses their
/// slivers). A sample outside the polygon lands in a cell that expects
/// none and fails the test. Polygons too wide to project (a corner more
/// than 78° off the axis) are tested over the whole sphere instead.
fn check_polygon_warp(
    name: &str,
    corners: &[Vec3],
    warp: impl Fn(Vec2) -> Option<Vec3> + Copy,
    pdf: impl Fn(Vec3) -> f32 + Copy,
) {
    let axis = corners
        .iter()
        .map(|c| c.normalize())
        .sum::<Vec3>()
        .normalize();
    if corners.iter().any(|c| c.normalize().dot(axis) < 0.2) {
        // Too wide to project: the sphere's grid resolves it.
        let outcome = Chi2Test::sphere(name).with_quadrature_panels(16).run(
            |u| {
                let w = warp(Vec2::new(u[0], u[1]))?;
                Some((w, pdf(w)))
            },
            pdf,
        );
        outcome.assert_ok();
        assert_eq!(outcome.failure_fraction, 0.0, "{name}");
        return;
    }
    let frame = crate::geometry::Frame::from_normal(axis);
    let project = |w: Vec3| {
        let l = frame.to_local(w);
        Vec3::new(l.x / l.z, l.y / l.z, 0.0)
    };
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for &c in corners {
        let q = project(c).truncate();
        (lo, hi) = (lo.min(q), hi.max(q));
    }
    let margin = 0.05 * (hi - lo);
    let plane_pdf = move |q: Vec3| {
        let w = frame.to_world(Vec3::new(q.x, q.y, 1.0)).normalize();
        let cos = frame.to_local(w).z;
        pdf(w) * cos * cos * cos
    };
    let outcome = Chi2Test::plane(&format!("{name}, zoomed"), lo - margin, hi + margin)
        .with_quadrature_panels(16)
        .run(
            |u| {
                let q = project(warp(Vec2::new(u[0], u[1]))?);
                Some((q, plane_pdf(q)))
            },
            plane_pdf,
        );
    outcome.assert_ok();
    assert_eq!(outcome.failure_fraction, 0.0, "{name}");
}

#[test]
fn spherical_triangle_warp_passes_chi_square() {
    for (name, v) in triangle_cases() {
        let omega = triangle_solid_angle(v[0], v[1], v[2]);
        check_polygon_warp(
            &format!("spherical triangle, {name} (Ω = {omega})"),
            &v,
            |u| square_to_spherical_triangle(v, u),
            // A sample on an edge may round to just outside it.
            move |w| {
                if hits_triangle(v, w, 1e-6) {
                    1.0 / omega
                } else {
                    0.0
                }
            },
        );
    }
}

#[test]
fn spherical_rectangle_warp_passes_chi_square() {
    let cases = [
        (
            "centred, near",
            Vec3::new(-1.0, -0.7, 0.4),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 1.4, 0.0),
        ),
        (
            "seen from a corner",
            Vec3::new(0.0, 0.0, 0.5),
            Vec3::new(1.5, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ),
        (
            "far, tilted",
            Vec3::new(1.0, 0.5, 2.5),
            Vec3::new(0.3, 0.0, 0.3),
            Vec3::new(-0.2, 0.3, 0.2),
        ),
        (
            "grazing",
            Vec3::new(0.5, -1.0, -0.05),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.08),
        ),
        (
            "long and thin",
            Vec3::new(-2.0, 0.3, -0.6),
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(0.0, 0.05, 0.0),
        ),
    ];
    for (name, corner, e0, e1) in cases {
        let omega = rectangle_solid_angle(corner, e0, e1);
        check_polygon_warp(
            &format!("spherical rectangle, {name} (Ω = {omega})"),
            &[corner, corner + e0, corner + e0 + e1, corner + e1],
            |u| Some(square_to_spherical_rectangle(corner, e0, e1, u)?.normalize()),
            move |w| {
                if hits_rectangle(corner, e0, e1, w, 1e-6) {
                    1.0 / omega
                } else {
                    0.0
                }
            },
        );
    }
}

/// A grid of samples including the edges of the square, where the warps
/// reach the polygon's corners and sides.
fn edge_grid() -> impl Iterator<Item = Vec2> {
    let steps = [0.0, 1e-7, 1e-3, 0.25, 0.5, 0.75, 0.999, 1.0 - 1e-7, 1.0];
    steps
        .into_iter()
        .flat_map(move |x| steps.into_iter().map(move |y| Vec2::new(x, y)))
}

#[test]
fn sampled_directions_hit_the_polygon() {
    // Tiny (1e-6 sr, far below the lights' fallback) to wide.
    let mut triangles = triangle_cases();
    triangles.push((
        "tiny",
        [
            Vec3::new(0.0, 0.0, 10.0),
            Vec3::new(0.01, 0.0, 10.0),
            Vec3::new(0.0, 0.01, 10.0),
        ],
    ));
    for (name, v) in triangles {
        for u in edge_grid() {
            let w = square_to_spherical_triangle(v, u).expect(name);
            assert!((w.length() - 1.0).abs() < 1e-5, "{name} {u:?}: {w:?}");
            assert!(hits_triangle(v, w, 1e-4), "{name} {u:?}: {w:?} misses");
        }
    }
    let (corner, e0, e1) = (
        Vec3::new(0.0, 0.0, 0.5),
        Vec3::new(1.5, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    );
    for scale in [1.0f32, 1e-3] {
        let (c, a, b) = (
            corner * Vec3::new(1.0, 1.0, 1.0 / scale),
            e0 * scale,
            e1 * scale,
        );
        for u in edge_grid() {
            let q = square_to_spherical_rectangle(c, a, b, u).expect("rectangle");
            // The point lies on the rectangle itself.
            let local = q - c;
            let (s, t) = (
                local.dot(a) / a.length_squared(),
                local.dot(b) / b.length_squared(),
            );
            assert!((-1e-5..=1.0 + 1e-5).contains(&s), "{scale} {u:?}: s = {s}");
            assert!((-1e-5..=1.0 + 1e-5).contains(&t), "{scale} {u:?}: t = {t}");
            assert!(
                local.dot(a.cross(b)).abs() < 1e-4 * q.length(),
                "{q:?} off the plane"
            );
        }
    }
    // The viewpoint in the plane: nothing to sample.
    assert!(square_to_spherical_rectangle(
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::X,
        Vec3::Y,
        Vec2::splat(0.5)
    )
    .is_none());
}

#[test]
fn spherical_warps_reject_a_wrong_solid_angle() {
    // The triangle sampled right but claimed 3% larger: the normalisation
    // (pdf integrates to 0.97) and the histogram both notice.
    let (_, v) = triangle_cases()[0];
    let omega = 1.03 * triangle_solid_angle(v[0], v[1], v[2]);
    let outcome = Chi2Test::sphere("triangle, wrong Ω")
        .with_quadrature_panels(16)
        .run(
            |u| {
                Some((
                    square_to_spherical_triangle(v, Vec2::new(u[0], u[1]))?,
                    1.0 / omega,
                ))
            },
            |w| {
                if hits_triangle(v, w, 0.0) {
                    1.0 / omega
                } else {
                    0.0
                }
            },
        );
    assert!(!outcome.passed(), "{outcome:#?}");
}
