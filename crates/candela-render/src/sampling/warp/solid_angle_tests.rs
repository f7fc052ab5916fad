//! Chi-square fits and round trips of the solid-angle samplers of
//! triangles and rectangles, from far, near and grazing points.

use glam::{Vec2, Vec3};

use super::*;
use crate::sampling::chi2::Chi2Test;

/// A triangle and the points it is seen from: a moderate view, one so near
/// that it fills most of the hemisphere, one almost in its plane (a thin
/// sliver), and a distant one (a small solid angle).
fn triangle_cases() -> ([Vec3; 3], [(&'static str, Vec3); 4]) {
    let v = [
        Vec3::new(-0.5, 1.0, -0.3),
        Vec3::new(0.6, 1.0, -0.2),
        Vec3::new(0.1, 1.2, 0.7),
    ];
    let centroid = (v[0] + v[1] + v[2]) / 3.0;
    let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    (
        v,
        [
            ("moderate", Vec3::ZERO),
            ("near", centroid - 0.02 * n),
            ("grazing", centroid + Vec3::new(2.0, 0.0, 0.0) - 0.01 * n),
            ("distant", Vec3::new(0.3, -30.0, 0.2)),
        ],
    )
}

/// The parallelogram `corner + s e0 + t e1` hit from `p` along `w`: the
/// parameters `(s, t)` by plain ray-plane intersection (independent of the
/// samplers), if in front of `p`.
fn plane_params(p: Vec3, corner: Vec3, e0: Vec3, e1: Vec3, w: Vec3) -> Option<Vec2> {
    let n = e0.cross(e1);
    let t = (corner - p).dot(n) / w.dot(n);
    if t.is_nan() || t <= 0.0 {
        return None;
    }
    let m = n.length_squared();
    let d = p + t * w - corner;
    Some(Vec2::new(d.dot(e1.cross(n)), d.dot(n.cross(e0))) / m)
}

/// Chi-square fits of a solid-angle sampler of the parallelogram `corner +
/// s e0 + t e1` (or of its half `s + t <= 1`, a triangle), in two domains:
/// - directions on the sphere, density `1 / Ω` where `inside(w)`;
/// - the light's own parameters `(s, t)`, density `|cos θ_l| |e0 × e1| /
///   (d² Ω)`: a light seen at a grazing angle is a thin sliver of the sphere
///   that the sphere's grid cannot resolve, but fills this domain.
///
/// `sample` returns a direction, `solid_angle` is the sampler's `Ω`.
fn check_solid_angle_sampler(
    name: &str,
    p: Vec3,
    (corner, e0, e1, triangle): (Vec3, Vec3, Vec3, bool),
    solid_angle: f32,
    sample: impl Fn(Vec2) -> Vec3,
    inside: impl Fn(Vec3) -> bool,
) {
    let pdf = 1.0 / solid_angle;
    eprintln!("{name}: solid angle {solid_angle}");
    if solid_angle > 0.05 {
        Chi2Test::sphere(&format!("{name}, directions"))
            .with_quadrature_panels(16)
            .run(
                |u| Some((sample(Vec2::new(u[1], u[2])), pdf)),
                |w| if inside(w) { pdf } else { 0.0 },
            )
            .assert_ok();
    }
    let n = e0.cross(e1);
    let on_light = |st: Vec2| {
        // A margin of rounding at the edges the samples lie on.
        let lo = -1e-5;
        st.x >= lo
            && st.y >= lo
            && if triangle {
                st.x + st.y <= 1.0 - lo
            } else {
                st.max_element() <= 1.0 - lo
            }
    };
    let param_pdf = |st: Vec2| {
        if !on_light(st) {
            return 0.0;
        }
        let d = corner + st.x * e0 + st.y * e1 - p;
        pdf * n.dot(d).abs() / d.length_squared().powf(1.5)
    };
    Chi2Test::plane(&format!("{name}, on the light"), Vec2::ZERO, Vec2::ONE)
        .with_quadrature_panels(8)
        .run(
            |u| {
                let st = plane_params(p, corner, e0, e1, sample(Vec2::new(u[1], u[2])))?;
                Some((st.extend(0.0), param_pdf(st)))
            },
            |q| param_pdf(q.truncate()),
        )
        .assert_ok();
}

#[test]
fn spherical_triangle_sampling_matches_its_pdf() {
    let (v, cases) = triangle_cases();
    for (name, p) in cases {
        let st = SphericalTriangle::new(p, &v).expect("p is not a vertex");
        check_solid_angle_sampler(
            &format!("spherical triangle, {name}"),
            p,
            (v[0], v[1] - v[0], v[2] - v[0], true),
            st.solid_angle(),
            |u| st.sample(u),
            |w| st.contains(w),
        );
    }
}

#[test]
fn spherical_triangle_area_is_girards() {
    // The octant triangle: three right angles, area 4π/8.
    let st = SphericalTriangle::new(Vec3::ZERO, &[Vec3::X, Vec3::Y, Vec3::Z]).unwrap();
    assert!((st.solid_angle() - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert!(st.contains(Vec3::ONE.normalize()) && !st.contains(-Vec3::ONE.normalize()));
}

#[test]
fn spherical_triangle_round_trips_through_its_inverse() {
    let (v, cases) = triangle_cases();
    for (name, p) in cases {
        let st = SphericalTriangle::new(p, &v).unwrap();
        for i in 1..40 {
            for j in 1..40 {
                let u = Vec2::new(i as f32, j as f32) / 40.0;
                let w = st.sample(u);
                assert!(st.contains(w), "{name}: {u} gave a direction outside");
                let back = st.to_square(w);
                assert!(
                    (back - u).abs().max_element() < 2e-3,
                    "{name}: {u} -> {w} -> {back}"
                );
            }
        }
    }
}

#[test]
fn spherical_rectangle_sampling_matches_its_pdf() {
    let (corner, e0, e1) = (
        Vec3::new(-0.3, 1.0, -0.4),
        Vec3::new(0.6, 0.0, 0.0),
        Vec3::new(0.0, 0.3, 0.8),
    );
    let n = e0.cross(e1).normalize();
    let centre = corner + 0.5 * (e0 + e1);
    for (name, p) in [
        ("moderate", Vec3::ZERO),
        ("near", centre + 0.02 * n),
        ("behind", centre - 0.5 * n + 0.3 * e0),
        ("grazing", centre + 2.0 * e1 + 0.01 * n),
        ("distant", centre + 30.0 * n + Vec3::X),
    ] {
        let sr = SphericalRectangle::new(p, corner, e0, e1).expect("p is off the plane");
        let inside = |w: Vec3| {
            plane_params(p, corner, e0, e1, w)
                .is_some_and(|st| st.cmpge(Vec2::ZERO).all() && st.cmple(Vec2::ONE).all())
        };
        check_solid_angle_sampler(
            &format!("spherical rectangle, {name}"),
            p,
            (corner, e0, e1, false),
            sr.solid_angle(),
            |u| {
                let (w, distance) = sr.sample(u);
                // The distance lands on the rectangle's plane.
                let q = p + distance * w - corner;
                assert!(
                    q.dot(n).abs() < 1e-4 * (1.0 + distance),
                    "{name}: off the plane"
                );
                w
            },
            inside,
        );
    }
}
