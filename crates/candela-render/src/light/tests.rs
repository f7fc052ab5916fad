//! Chi-square tests of every non-delta light's sampling against its
//! `pdf_li`, seen from several points, and consistency of the delta lights.

use super::*;
use crate::sampling::chi2::Chi2Test;
use crate::sampling::warp::Parallelogram;
use glam::{Vec2, Vec3};

/// Where a ray from `p` along `wi` meets the light's surface, if it does
/// (an independent intersection, so the test does not trust the sampler's
/// own distance).
fn hit_point(light: &AreaLight, p: Vec3, wi: Vec3) -> Option<Vec3> {
    let plane_hit = |origin: Vec3, normal: Vec3| {
        let denom = wi.dot(normal);
        if denom.abs() < 1e-12 {
            return None;
        }
        let t = (origin - p).dot(normal) / denom;
        (t > 0.0).then(|| p + t * wi)
    };
    match &light.shape {
        AreaShape::Triangle { v, normal } => {
            let q = plane_hit(v[0], *normal)?;
            let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).dot(*normal);
            let total = area(v[0], v[1], v[2]);
            let inside = [
                area(q, v[1], v[2]),
                area(v[0], q, v[2]),
                area(v[0], v[1], q),
            ]
            .iter()
            .all(|&a| a / total >= 0.0);
            inside.then_some(q)
        }
        AreaShape::Rect { shape, normal } => {
            let q = plane_hit(shape.origin, *normal)?;
            let st = shape.to_square(q);
            (st.cmpge(Vec2::ZERO).all() && st.cmple(Vec2::ONE).all()).then_some(q)
        }
        AreaShape::Sphere {
            center,
            radius,
            inward,
        } => {
            let oc = p - *center;
            let b = oc.dot(wi);
            let disc = b * b - (oc.length_squared() - radius * radius);
            // Outward: the near side. Inward (seen from inside): the far root,
            // the one point ahead.
            let root = if *inward { disc.sqrt() } else { -disc.sqrt() };
            (disc >= 0.0).then(|| p + (-b + root) * wi)
        }
    }
}

fn check_area_light(name: &str, light: AreaLight, points: &[Vec3]) {
    let wrapped = Light::Area(light.clone());
    for &p in points {
        let outcome = Chi2Test::sphere(&format!("{name} from {p:?}"))
            .with_quadrature_panels(16)
            .run(
                |u| {
                    let s = wrapped.sample_li(p, Vec2::new(u[1], u[2]))?;
                    // The sampled distance must land on the light.
                    let q = hit_point(&light, p, s.wi)?;
                    let d = (q - p).length();
                    assert!(
                        (d - s.distance).abs() <= 1e-3 * d.max(1.0),
                        "{name}: distance {} vs {d}",
                        s.distance
                    );
                    Some((s.wi, s.pdf))
                },
                |wi| match hit_point(&light, p, wi) {
                    Some(q) => wrapped.pdf_li(p, wi, q),
                    None => 0.0,
                },
            );
        outcome.assert_ok();
    }
}

#[test]
fn triangle_light_sampling_matches_its_pdf() {
    let light = AreaLight {
        shape: AreaShape::Triangle {
            v: [
                Vec3::new(-0.5, 1.0, -0.3),
                Vec3::new(0.6, 1.0, -0.2),
                Vec3::new(0.1, 1.2, 0.7),
            ],
            normal: Vec3::ZERO,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    // Emitting downward, toward the points below.
    let AreaShape::Triangle { v, .. } = light.shape else {
        unreachable!()
    };
    let mut n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    if n.y > 0.0 {
        n = -n;
    }
    let light = AreaLight {
        shape: AreaShape::Triangle { v, normal: n },
        ..light
    };
    check_area_light(
        "triangle",
        light,
        // Below it, and off to the side where it is seen at a slant.
        &[Vec3::ZERO, Vec3::new(0.9, 0.6, -0.4)],
    );
}

#[test]
fn rectangle_light_sampling_matches_its_pdf() {
    let light = AreaLight {
        shape: AreaShape::Rect {
            shape: Parallelogram {
                origin: Vec3::new(-0.3, 1.0, -0.4),
                edge0: Vec3::new(0.6, 0.0, 0.0),
                edge1: Vec3::new(0.0, 0.0, 0.8),
            },
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    check_area_light(
        "rectangle",
        light.clone(),
        // Below, off to the side, near a corner (a wide solid angle), and so
        // close to the middle that it fills more than MAX_SOLID_ANGLE and is
        // sampled by area.
        &[
            Vec3::ZERO,
            Vec3::new(-1.0, 0.5, 0.3),
            Vec3::new(-0.25, 0.9, -0.35),
            Vec3::new(0.0, 0.998, 0.0),
        ],
    );
    let AreaShape::Rect { shape, .. } = &light.shape else {
        unreachable!()
    };
    let omega = crate::sampling::warp::rectangle_solid_angle(
        shape.origin - Vec3::new(0.0, 0.998, 0.0),
        shape.edge0,
        shape.edge1,
    );
    assert!(
        omega > area::MAX_SOLID_ANGLE,
        "{omega}: not the area fallback"
    );
}

#[test]
fn parallelogram_light_sampling_matches_its_pdf() {
    // Skewed edges: sampled as two spherical triangles.
    let light = AreaLight {
        shape: AreaShape::Rect {
            shape: Parallelogram {
                origin: Vec3::new(-0.4, 1.0, -0.3),
                edge0: Vec3::new(0.7, 0.0, 0.1),
                edge1: Vec3::new(0.3, 0.0, 0.6),
            },
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    check_area_light(
        "parallelogram",
        light,
        &[
            Vec3::ZERO,
            Vec3::new(0.8, 0.7, 0.9),
            Vec3::new(0.0, 0.8, 0.0),
        ],
    );
}

/// `pdf_li` at the point `sample_li` found equals the density it reported,
/// on both sides of the thresholds between solid-angle and area sampling
/// (the choice depends on the viewpoint only, so both agree on it).
#[test]
fn planar_lights_report_the_density_they_sampled_with() {
    let rect = |edge1: Vec3| AreaLight {
        shape: AreaShape::Rect {
            shape: Parallelogram {
                origin: Vec3::new(-0.05, 0.0, -0.05),
                edge0: Vec3::new(0.1, 0.0, 0.0),
                edge1,
            },
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    let triangle = AreaLight {
        shape: AreaShape::Triangle {
            v: [
                Vec3::new(-0.05, 0.0, -0.05),
                Vec3::new(0.05, 0.0, -0.05),
                Vec3::new(0.0, 0.0, 0.08),
            ],
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    let lights = [
        rect(Vec3::new(0.0, 0.0, 0.1)),
        rect(Vec3::new(0.03, 0.0, 0.1)),
        triangle,
    ];
    let (mut by_area, mut by_solid_angle) = (0, 0);
    for light in &lights {
        let area = light.shape.area();
        // Distances from 1 mm (a near hemisphere) to 20 (a tiny lamp).
        for k in 0..40 {
            let h = 1e-3 * 1.3f32.powi(k);
            let p = Vec3::new(0.01, -h, 0.02);
            for i in 0..8 {
                let u = Vec2::new((i as f32 + 0.5) / 8.0, 0.618 * i as f32 % 1.0);
                let Some(s) = light.sample_li(p, u) else {
                    continue;
                };
                let q = p + s.distance * s.wi;
                let pdf = light.pdf_li(p, s.wi, q);
                assert!(
                    (pdf - s.pdf).abs() <= 1e-3 * s.pdf,
                    "{:?} from {p:?}: sampled with {} but pdf_li says {pdf}",
                    light.shape,
                    s.pdf
                );
                let cos = s.wi.y;
                let area_pdf = s.distance * s.distance / (cos * area);
                if (area_pdf - s.pdf).abs() <= 1e-5 * s.pdf {
                    by_area += 1;
                } else {
                    by_solid_angle += 1;
                }
            }
        }
    }
    // Both methods were exercised.
    assert!(
        by_area > 50 && by_solid_angle > 200,
        "{by_area} {by_solid_angle}"
    );
}

#[test]
fn sphere_light_sampling_matches_its_pdf() {
    let light = AreaLight {
        shape: AreaShape::Sphere {
            center: Vec3::new(0.2, 1.0, -0.1),
            radius: 0.4,
            inward: false,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    // Far away (a narrow cone) and close (a wide one).
    check_area_light(
        "sphere",
        light,
        &[Vec3::new(0.0, -2.0, 0.5), Vec3::new(0.3, 0.5, 0.0)],
    );
}

#[test]
fn inward_sphere_light_sampling_matches_its_pdf_from_inside() {
    let light = AreaLight {
        shape: AreaShape::Sphere {
            center: Vec3::new(0.2, 1.0, -0.1),
            radius: 0.8,
            inward: true,
        },
        radiance: Vec3::ONE,
        textured: None,
    };
    // The centre (every direction alike) and near the wall (steep
    // density on the near side).
    check_area_light(
        "inward sphere",
        light,
        &[Vec3::new(0.2, 1.0, -0.1), Vec3::new(0.7, 1.3, 0.1)],
    );
}

#[test]
fn ambient_light_sampling_matches_its_pdf() {
    let sky = Light::Ambient(AmbientLight {
        radiance: Vec3::ONE,
    });
    let outcome = Chi2Test::sphere("ambient").run(
        |u| {
            let s = sky.sample_li(Vec3::ZERO, Vec2::new(u[1], u[2]))?;
            Some((s.wi, s.pdf))
        },
        |wi| {
            if wi.y > 0.0 {
                sky.pdf_li(Vec3::ZERO, wi, Vec3::ZERO)
            } else {
                0.0
            }
        },
    );
    outcome.assert_ok();
}

#[test]
fn one_sided_lights_are_dark_from_behind() {
    let rect = Light::Area(AreaLight {
        shape: AreaShape::Rect {
            shape: Parallelogram {
                origin: Vec3::new(-0.5, 1.0, -0.5),
                edge0: Vec3::X,
                edge1: Vec3::Z,
            },
            normal: -Vec3::Y,
        },
        radiance: Vec3::ONE,
        textured: None,
    });
    let above = Vec3::new(0.0, 2.0, 0.0);
    for i in 0..16 {
        let u = Vec2::new((i as f32 + 0.5) / 16.0, 0.37);
        assert!(rect.sample_li(above, u).is_none());
    }
    assert_eq!(rect.pdf_li(above, -Vec3::Y, Vec3::new(0.0, 1.0, 0.0)), 0.0);
    // A sphere emits outward: nothing reaches its inside.
    let sphere = Light::Area(AreaLight {
        shape: AreaShape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
            inward: false,
        },
        radiance: Vec3::ONE,
        textured: None,
    });
    assert!(sphere
        .sample_li(Vec3::new(0.1, 0.0, 0.0), Vec2::splat(0.5))
        .is_none());
    // One that emits inward (Mitsuba's flip_normals) shows the outside only
    // points q whose inside faces it: (q − c)·(q − p) > 0, for p = 3z and
    // the unit sphere q_z < ⅓ (the near side then blocks the shadow ray).
    let inward = Light::Area(AreaLight {
        shape: AreaShape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
            inward: true,
        },
        radiance: Vec3::ONE,
        textured: None,
    });
    let outside = Vec3::new(0.0, 0.0, 3.0);
    for i in 0..64 {
        let u = Vec2::new((i as f32 + 0.5) / 64.0, 0.61);
        if let Some(s) = inward.sample_li(outside, u) {
            let q = outside + s.distance * s.wi;
            assert!(
                q.z < 1.0 / 3.0,
                "a point {q} facing away sampled from outside"
            );
        }
    }
}
