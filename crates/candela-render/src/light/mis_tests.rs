//! The MIS density of a planar light must be the density its samples were
//! drawn with: a BSDF-sampled ray that hits the light is weighted with
//! `pdf_li(p, wi, hit point)`, so if that differed from what `sample_li`
//! used for the same direction, the two halves of the MIS estimator would
//! not add up and the image would be biased.

use super::solid_angle::SOLID_ANGLE_RANGE;
use super::*;
use crate::sampling::warp::Parallelogram;
use crate::shape::{intersect_triangle, triangle_surface_point, TriangleRay};
use glam::{Vec2, Vec3};

/// Where the ray from `p` along `wi` meets triangles `tris`, by the
/// renderer's own intersection and hit-point reconstruction (what the path
/// tracer hands to `pdf_li`).
fn traced_hit(p: Vec3, wi: Vec3, tris: &[[Vec3; 3]]) -> Option<Vec3> {
    let ray = TriangleRay::new(p, wi);
    tris.iter().find_map(|v| {
        let h = intersect_triangle(&ray, v, f32::INFINITY)?;
        Some(triangle_surface_point(v, h.b1, h.b2).p)
    })
}

/// Points from which `tris` (the light's geometry, emitting along `n`
/// around `centre`) is seen at every distance across the solid-angle rule's
/// range, head-on and at grazing angles.
fn viewpoints(centre: Vec3, n: Vec3, side: Vec3) -> Vec<Vec3> {
    let mut points = Vec::new();
    for k in 0..40 {
        let distance = 10f32.powf(-2.0 + 4.0 * k as f32 / 39.0);
        points.push(centre + distance * n);
        points.push(centre + distance * (0.05 * n + side));
    }
    points
}

fn assert_pdf_matches_samples(name: &str, light: &AreaLight, tris: &[[Vec3; 3]], points: &[Vec3]) {
    let wrapped = Light::Area(light.clone());
    let (mut checked, mut by_solid_angle, mut by_area) = (0, 0, 0);
    for &p in points {
        for i in 0..64 {
            let u = Vec2::new((i % 8) as f32 + 0.37, (i / 8) as f32 + 0.61) / 8.0;
            let Some(s) = wrapped.sample_li(p, u) else {
                continue;
            };
            let Some(q) = traced_hit(p, s.wi, tris) else {
                continue; // rounding at an edge
            };
            let pdf = wrapped.pdf_li(p, s.wi, q);
            assert!(
                (pdf - s.pdf).abs() <= 2e-3 * s.pdf,
                "{name} from {p}: sampled with {} but pdf_li says {pdf}",
                s.pdf
            );
            checked += 1;
        }
        // Which branch of the rule this point exercised.
        let n = tris[0];
        let solid_angle =
            crate::sampling::warp::SphericalTriangle::new(p, &n).map_or(0.0, |st| st.solid_angle());
        if SOLID_ANGLE_RANGE.contains(&solid_angle) {
            by_solid_angle += 1;
        } else {
            by_area += 1;
        }
    }
    assert!(checked > 40 * points.len(), "{name}: {checked} checked");
    assert!(
        by_solid_angle > 10 && by_area > 10,
        "{name}: {by_solid_angle} / {by_area}"
    );
}

#[test]
fn light_pdf_matches_its_samples_at_the_traced_hit() {
    let v = [
        Vec3::new(-0.5, 1.0, -0.3),
        Vec3::new(0.6, 1.0, -0.2),
        Vec3::new(0.1, 1.2, 0.7),
    ];
    let n = -(v[1] - v[0]).cross(v[2] - v[0]).normalize();
    let n = if n.y > 0.0 { -n } else { n };
    let triangle = AreaLight {
        shape: AreaShape::Triangle { v, normal: n },
        radiance: Vec3::ONE,
    };
    let centroid = (v[0] + v[1] + v[2]) / 3.0;
    let side = (v[1] - v[0]).normalize();
    assert_pdf_matches_samples("triangle", &triangle, &[v], &viewpoints(centroid, n, side));

    let shape = Parallelogram {
        origin: Vec3::new(-0.3, 1.0, -0.4),
        edge0: Vec3::new(0.6, 0.0, 0.0),
        edge1: Vec3::new(0.0, 0.0, 0.8),
    };
    let rect = AreaLight {
        shape: AreaShape::Rect {
            shape,
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
    };
    let (o, a, b) = (shape.origin, shape.edge0, shape.edge1);
    let halves = [[o, o + a, o + a + b], [o, o + a + b, o + b]];
    let centre = o + 0.5 * (a + b);
    assert_pdf_matches_samples(
        "rectangle",
        &rect,
        &halves,
        &viewpoints(centre, -Vec3::Y, Vec3::X),
    );
}
