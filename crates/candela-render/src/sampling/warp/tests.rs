//! Round trips and chi-square fits of every warp.

use glam::{Vec2, Vec3};

use super::*;
use crate::sampling::chi2::Chi2Test;

/// A grid of points strictly inside the unit square, plus its corners' neighbours.
fn square_grid() -> impl Iterator<Item = Vec2> {
    (0..=40).flat_map(|i| {
        (0..=40).map(move |j| {
            Vec2::new(i as f32 / 40.0, j as f32 / 40.0).clamp(Vec2::ZERO, Vec2::splat(0.999_99))
        })
    })
}

fn assert_round_trip(name: &str, forward: impl Fn(Vec2) -> Vec3, inverse: impl Fn(Vec3) -> Vec2) {
    for u in square_grid() {
        let p = forward(u);
        let back = forward(inverse(p));
        assert!(
            (back - p).length() < 2e-4,
            "{name}: {u:?} -> {p:?} -> {back:?}"
        );
    }
}

#[test]
fn warps_round_trip_through_their_inverses() {
    assert_round_trip(
        "disk",
        |u| square_to_concentric_disk(u).extend(0.0),
        |p| concentric_disk_to_square(p.truncate()),
    );
    assert_round_trip(
        "hemisphere",
        square_to_uniform_hemisphere,
        uniform_hemisphere_to_square,
    );
    assert_round_trip("sphere", square_to_uniform_sphere, uniform_sphere_to_square);
    assert_round_trip(
        "cosine",
        // Compared on the disk: lifting to the hemisphere amplifies rounding
        // near the horizon by the slope of the square root.
        |u| square_to_cosine_hemisphere(u).truncate().extend(0.0),
        |p| {
            let z = (1.0 - p.truncate().length_squared()).max(0.0).sqrt();
            cosine_hemisphere_to_square(p.truncate().extend(z))
        },
    );
    for cos_max in [0.3, 0.99, -0.5] {
        assert_round_trip(
            "cone",
            |u| square_to_uniform_cone(u, cos_max),
            |w| uniform_cone_to_square(w, cos_max),
        );
    }
    assert_round_trip(
        "triangle",
        |u| square_to_uniform_triangle(u).extend(0.0),
        |b| uniform_triangle_to_square(b.truncate()),
    );
    let quad = Parallelogram {
        origin: Vec3::new(1.0, 2.0, 3.0),
        edge0: Vec3::new(2.0, 0.5, 0.0),
        edge1: Vec3::new(0.3, 0.0, 1.5),
    };
    assert_round_trip("parallelogram", |u| quad.sample(u), |p| quad.to_square(p));
    // The square-side round trip too, where the map is injective.
    for u in square_grid() {
        let back = quad.to_square(quad.sample(u));
        assert!(
            (back - u).length() < 1e-4,
            "parallelogram {u:?} -> {back:?}"
        );
    }
}

#[test]
fn directions_are_unit_and_in_their_domain() {
    for u in square_grid() {
        for (w, lower) in [
            (square_to_uniform_hemisphere(u), 0.0),
            (square_to_cosine_hemisphere(u), 0.0),
            (square_to_uniform_sphere(u), -1.0),
            (square_to_uniform_cone(u, 0.8), 0.8 - 1e-6),
        ] {
            assert!((w.length() - 1.0).abs() < 1e-5, "{u:?} {w:?}");
            assert!(w.z >= lower, "{u:?} {w:?}");
        }
    }
}

fn sphere_warp(
    warp: impl Fn(Vec2) -> Vec3,
    pdf: impl Fn(Vec3) -> f32 + Copy,
) -> impl FnMut([f32; 3]) -> Option<(Vec3, f32)> {
    move |u| {
        let w = warp(Vec2::new(u[0], u[1]));
        Some((w, pdf(w)))
    }
}

#[test]
fn spherical_warps_pass_chi_square() {
    Chi2Test::sphere("uniform hemisphere")
        .run(
            sphere_warp(square_to_uniform_hemisphere, uniform_hemisphere_pdf),
            uniform_hemisphere_pdf,
        )
        .assert_ok();
    Chi2Test::sphere("cosine hemisphere")
        .run(
            sphere_warp(square_to_cosine_hemisphere, cosine_hemisphere_pdf),
            cosine_hemisphere_pdf,
        )
        .assert_ok();
    Chi2Test::sphere("uniform sphere")
        .run(
            sphere_warp(square_to_uniform_sphere, uniform_sphere_pdf),
            uniform_sphere_pdf,
        )
        .assert_ok();
    for cos_max in [0.95f32, 0.2, -0.6] {
        let pdf = move |w| uniform_cone_pdf(w, cos_max);
        Chi2Test::sphere("uniform cone")
            .run(
                sphere_warp(move |u| square_to_uniform_cone(u, cos_max), pdf),
                pdf,
            )
            .assert_ok();
    }
}

#[test]
fn planar_warps_pass_chi_square() {
    let disk = |u: [f32; 3]| {
        let p = square_to_concentric_disk(Vec2::new(u[0], u[1]));
        Some((p.extend(0.0), uniform_disk_pdf(p)))
    };
    Chi2Test::plane("concentric disk", Vec2::NEG_ONE, Vec2::ONE)
        .run(disk, |p| uniform_disk_pdf(p.truncate()))
        .assert_ok();
    let triangle = |u: [f32; 3]| {
        let b = square_to_uniform_triangle(Vec2::new(u[0], u[1]));
        Some((b.extend(0.0), uniform_triangle_pdf(b)))
    };
    Chi2Test::plane("triangle", Vec2::ZERO, Vec2::ONE)
        .run(triangle, |b| uniform_triangle_pdf(b.truncate()))
        .assert_ok();
    let quad = Parallelogram {
        origin: Vec3::new(0.1, 0.2, 0.0),
        edge0: Vec3::new(0.6, 0.1, 0.0),
        edge1: Vec3::new(0.2, 0.5, 0.0),
    };
    let quad_pdf = |p: Vec3| {
        let st = quad.to_square(p);
        if st.cmpge(Vec2::ZERO).all() && st.cmple(Vec2::ONE).all() {
            quad.pdf()
        } else {
            0.0
        }
    };
    Chi2Test::plane("parallelogram", Vec2::ZERO, Vec2::ONE)
        .run(
            |u| Some((quad.sample(Vec2::new(u[0], u[1])), quad.pdf())),
            quad_pdf,
        )
        .assert_ok();
}

#[test]
fn chi_square_rejects_a_wrong_pdf() {
    // Uniform-hemisphere samples against the cosine density: both integrate
    // to 1, so only the histogram can tell them apart.
    let outcome = Chi2Test::sphere("uniform vs cosine").run(
        |u| {
            let w = square_to_uniform_hemisphere(Vec2::new(u[0], u[1]));
            Some((w, cosine_hemisphere_pdf(w)))
        },
        cosine_hemisphere_pdf,
    );
    assert!(!outcome.passed(), "{outcome:#?}");
    assert!((outcome.pdf_integral - 1.0).abs() < 1e-3);
    // A subtler error: a cone sampled with cos_max = 0.5 but checked as 0.52.
    let outcome = Chi2Test::sphere("cone mismatch").run(
        |u| {
            let w = square_to_uniform_cone(Vec2::new(u[0], u[1]), 0.5);
            Some((w, uniform_cone_pdf(w, 0.52)))
        },
        |w| uniform_cone_pdf(w, 0.52),
    );
    assert!(!outcome.passed(), "{outcome:#?}");
}
