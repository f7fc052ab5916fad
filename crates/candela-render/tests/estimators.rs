//! Estimator tests: every integrator against a known answer.
//!
//! Bounds are variance-derived: a render pools n independent samples of
//! the same quantity, so its mean is within z standard errors of the truth
//! except with probability erfc(z/√2). With z = 4.5 and ~20 checks in this
//! file, a correct renderer fails one by chance with probability < 2e-4;
//! the seeds are fixed, so results do not flicker between runs.

mod common;

use candela_render::integrator::{IntegratorSettings, LightingMode};
use common::*;

const Z: f64 = 4.5;
const MODES: [LightingMode; 3] = [
    LightingMode::Hemisphere,
    LightingMode::Light,
    LightingMode::Mis,
];

/// Path tracing to depth `m`, adding every bounce or (`accumulate` false)
/// only light after exactly `m` bounces.
fn path(m: u32, accumulate: bool, lighting: LightingMode) -> IntegratorSettings {
    IntegratorSettings {
        accumulate,
        ..IntegratorSettings::path(m, lighting)
    }
}

#[test]
fn white_furnace_converges_to_le_over_one_minus_albedo() {
    let (albedo, le) = (0.6f64, 0.5f64);
    let scene = furnace(albedo as f32, le as f32);
    for mode in MODES {
        let e = estimate(&scene, path(100_000, true, mode), 16, 64, 1);
        assert_converges(
            &format!("{mode:?}, unlimited depth"),
            &e,
            le / (1.0 - albedo),
            Z,
        );
    }
}

#[test]
fn white_furnace_truncates_the_series_at_each_depth() {
    let (albedo, le) = (0.6f64, 0.5f64);
    let scene = furnace(albedo as f32, le as f32);
    for mode in MODES {
        for m in 0..=4u32 {
            let expected: f64 = (0..=m).map(|k| le * albedo.powi(k as i32)).sum();
            let e = estimate(&scene, path(m, true, mode), 8, 64, 2 + m as u64);
            assert_converges(&format!("{mode:?}, -m {m}"), &e, expected, Z);
        }
    }
}

#[test]
fn furnace_single_bounce_view_isolates_one_term() {
    // CS184 `-o 0`: only light after exactly m bounces.
    let (albedo, le) = (0.6f64, 0.5f64);
    let scene = furnace(albedo as f32, le as f32);
    for mode in MODES {
        for m in [1u32, 3] {
            let e = estimate(&scene, path(m, false, mode), 8, 64, 11 + m as u64);
            assert_converges(
                &format!("{mode:?}, -o 0 -m {m}"),
                &e,
                le * albedo.powi(m as i32),
                Z,
            );
        }
    }
}

#[test]
fn a_sphere_turned_inward_is_a_furnace_inside_and_black_outside() {
    // Mitsuba's flip_normals on an emitting sphere: a one-sided diffuse
    // wall that emits `le` toward the centre. Inside it is the white
    // furnace (le / (1 − albedo)); outside, its back, nothing is seen.
    let (albedo, le) = (0.6f64, 0.5f64);
    let mut scene = analytic_sphere();
    scene.lights.clear();
    scene.spheres[0].inward = true;
    scene.materials[0] = candela_scene::MaterialDesc {
        sides: candela_scene::Sides::Front,
        ..material(
            "wall",
            candela_scene::BsdfDesc::Diffuse {
                albedo: glam::Vec3::splat(albedo as f32),
            },
            Some(glam::Vec3::splat(le as f32)),
        )
    };
    for mode in MODES {
        let e = estimate(&scene, path(100_000, true, mode), 8, 32, 21);
        assert_converges(&format!("{mode:?}, inside"), &e, le / (1.0 - albedo), Z);
        let mut outside = scene.clone();
        outside.cameras = vec![camera_at(glam::Vec3::new(0.0, 0.0, 3.0))];
        let e = estimate(&outside, path(100_000, true, mode), 8, 8, 22);
        assert_eq!((e.mean, e.invalid), (0.0, 0), "{mode:?}, outside");
    }
}

#[test]
fn pbrt_analytic_sphere_has_unit_radiance() {
    let scene = analytic_sphere();
    for mode in [LightingMode::Light, LightingMode::Mis] {
        let e = estimate(&scene, path(100_000, true, mode), 16, 64, 7);
        assert_converges(&format!("{mode:?}"), &e, 1.0, Z);
        // The task's own bound too: within 2.5%.
        assert!((e.mean - 1.0).abs() < 0.025, "{mode:?}: {}", e.mean);
    }
}

#[test]
fn russian_roulette_changes_noise_not_the_mean() {
    let scene = furnace(0.8, 0.5);
    let with = |rr: bool, seed| {
        estimate(
            &scene,
            IntegratorSettings {
                max_depth: 8,
                lighting: LightingMode::Mis,
                roulette: rr,
                ..Default::default()
            },
            16,
            32,
            seed,
        )
    };
    let a = with(true, 21);
    let b = with(false, 22);
    let expected: f64 = (0..=8).map(|k| 0.5 * 0.8f64.powi(k)).sum();
    assert_converges("with roulette", &a, expected, Z);
    assert_converges("without roulette", &b, expected, Z);
    // Two independent estimates of the same mean.
    let z = (a.mean - b.mean).abs() / (a.std_error.powi(2) + b.std_error.powi(2)).sqrt();
    assert!(
        z < Z,
        "roulette moved the mean: {} vs {} (z = {z:.2})",
        a.mean,
        b.mean
    );
    assert!(
        a.std_error > b.std_error,
        "roulette should add noise here, not remove it"
    );
}

#[test]
fn russian_roulette_through_glass_keeps_the_furnace_mean() {
    // Roulette weighs throughput by the η² of the refractions so far; the
    // survivors' division keeps every mode converging to the closed form.
    let (albedo, le) = (0.6f64, 0.5f64);
    let scene = furnace_with_glass_ball(albedo as f32, le as f32);
    for mode in MODES {
        let e = estimate(&scene, path(100_000, true, mode), 16, 64, 31);
        assert_converges(&format!("{mode:?}, glass ball"), &e, le / (1.0 - albedo), Z);
    }
}

#[test]
fn a_clamp_bounds_every_sample_and_above_the_radiance_changes_nothing() {
    // The white furnace converges to le / (1 - albedo) = 1.
    let scene = furnace(0.5, 0.5);
    let clamped = |clamp: Option<f32>| IntegratorSettings {
        clamp,
        ..IntegratorSettings::path(100_000, LightingMode::Mis)
    };
    let low = estimate(&scene, clamped(Some(0.25)), 8, 16, 3);
    assert!(low.mean <= 0.25 + 1e-6, "clamped mean {}", low.mean);
    let free = estimate(&scene, clamped(None), 8, 16, 3);
    let high = estimate(&scene, clamped(Some(1e6)), 8, 16, 3);
    assert_eq!(free.mean.to_bits(), high.mean.to_bits());
    assert!(free.mean > 0.9, "unclamped mean {}", free.mean);
}
