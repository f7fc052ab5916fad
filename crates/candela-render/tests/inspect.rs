//! The path inspector agrees with the renderer: for pixels and sample
//! indices of a scene with an area light, a point light, a sky, glass and a
//! diffuse floor, each recorded path's contributions sum to its radiance,
//! and its value is exactly what the render adds to the pixel for that
//! sample (a render restricted to the pixel and the sample range).

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::film::PixelRect;
use candela_render::integrator::inspect::{trace_paths, InspectError, PathRecord, Strategy};
use candela_render::integrator::record::PathEnd;
use candela_render::integrator::{Estimator, IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use common::glass_room;
use glam::{DVec3, Vec3};
use std::ops::Range;

const SIZE: (u32, u32) = (24, 18);
const SAMPLES: Range<u32> = 3..9;

fn scene() -> Scene {
    let opts = SceneOptions {
        width: SIZE.0,
        height: SIZE.1,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    Scene::build(&glass_room(), &opts).expect("test scene builds")
}

fn settings(integrator: IntegratorSettings) -> RenderSettings {
    RenderSettings {
        spp: SAMPLES.end,
        seed: 29,
        integrator,
        threads: 1,
        ..Default::default()
    }
}

/// The pixels checked: a sparse grid over the whole image (sky, lamp,
/// glass ball, clay ball, floor and wall all appear).
fn pixels() -> impl Iterator<Item = (u32, u32)> {
    (0..SIZE.1)
        .step_by(3)
        .flat_map(|y| (0..SIZE.0).step_by(3).map(move |x| (x, y)))
}

/// Checks every path of `settings` at the grid pixels against a render of
/// each pixel alone; returns all records for coverage checks.
fn check_against_renderer(scene: &Scene, settings: &RenderSettings) -> Vec<PathRecord> {
    let mut all = Vec::new();
    for (x, y) in pixels() {
        let records = trace_paths(scene, settings, (x, y), SAMPLES).expect("paths traced");
        assert_eq!(records.len(), SAMPLES.len());
        let alone = RenderSettings {
            cell: Some(PixelRect::new(x, y, 1, 1)),
            sample_range: Some(SAMPLES),
            ..settings.clone()
        };
        let film = render(scene, &alone, &|_| {}).expect("render runs").film;
        let sums = film.pixel(x, y);
        assert_eq!(sums.count, SAMPLES.len() as u32);
        // The film adds the samples in index order: so does this sum.
        let mut total = DVec3::ZERO;
        for (r, index) in records.iter().zip(SAMPLES) {
            assert_eq!((r.pixel, r.sample), ((x, y), index));
            total += Vec3::from_array(r.value).as_dvec3();
            let radiance = Vec3::from_array(r.radiance);
            let sum: Vec3 = r
                .contributions
                .iter()
                .map(|c| Vec3::from_array(c.value))
                .sum();
            // Terms are non-negative, so rounding is relative to the total.
            let tol = 1e-5 * radiance.max_element() + 1e-12;
            assert!(
                (sum - radiance).abs().max_element() <= tol,
                "pixel ({x}, {y}) sample {index}: contributions {sum} vs radiance {radiance}"
            );
        }
        assert_eq!(
            total, sums.radiance,
            "pixel ({x}, {y}): recorded values vs the render"
        );
        all.extend(records);
    }
    all
}

fn strategies(records: &[PathRecord]) -> Vec<Strategy> {
    let mut seen: Vec<Strategy> = Vec::new();
    for c in records.iter().flat_map(|r| &r.contributions) {
        if !seen.contains(&c.strategy) {
            seen.push(c.strategy);
        }
    }
    seen
}

#[test]
fn recorded_paths_sum_to_what_the_renderer_adds_under_mis() {
    let scene = scene();
    let settings = settings(IntegratorSettings::path(6, LightingMode::Mis));
    let records = check_against_renderer(&scene, &settings);
    // Everything the inspector should show appears somewhere, so the test
    // cannot pass on paths that record nothing.
    let seen = strategies(&records);
    for s in [
        Strategy::Emission,
        Strategy::Environment,
        Strategy::LightSample,
        Strategy::DeltaLight,
    ] {
        assert!(seen.contains(&s), "no {s:?} contribution in {seen:?}");
    }
    let vertices: Vec<_> = records.iter().flat_map(|r| &r.vertices).collect();
    let lobes: Vec<&str> = vertices
        .iter()
        .filter_map(|v| v.scatter.as_ref().map(|s| s.lobe.as_str()))
        .collect();
    for lobe in ["specular transmission", "diffuse reflection"] {
        assert!(lobes.contains(&lobe), "no {lobe} in {lobes:?}");
    }
    assert!(vertices
        .iter()
        .any(|v| v.surface == "glass" && v.shape == "sphere 'glass ball'"));
    assert!(vertices.iter().any(|v| v.material == "floor"));
    let samples: Vec<_> = vertices.iter().flat_map(|v| &v.light_samples).collect();
    assert!(
        samples.iter().any(|s| s.visible == Some(false)),
        "no occluded light sample"
    );
    assert!(
        samples
            .iter()
            .any(|s| s.mis_weight > 0.0 && s.mis_weight < 1.0 && s.bsdf_pdf.is_some()),
        "no MIS-weighted light sample"
    );
    assert!(samples.iter().any(|s| s.light == "bulb" && s.delta));
    assert!(vertices.iter().any(|v| v.roulette.is_some()));
    assert!(records.iter().any(|r| r.end == PathEnd::Escaped));
    assert!(records.iter().any(|r| !r.contributions.is_empty()));
}

#[test]
fn recorded_paths_match_the_renderer_in_every_lighting_mode() {
    let scene = scene();
    for lighting in [LightingMode::Hemisphere, LightingMode::Light] {
        let settings = settings(IntegratorSettings::path(4, lighting));
        let records = check_against_renderer(&scene, &settings);
        let seen = strategies(&records);
        let expected = match lighting {
            LightingMode::Hemisphere => Strategy::Hemisphere,
            _ => Strategy::LightSample,
        };
        assert!(seen.contains(&expected), "{lighting:?}: {seen:?}");
        // Only light sampling (or hemisphere rays) counts emitters seen
        // after a diffuse bounce: no MIS-weighted path emission.
        for c in records.iter().flat_map(|r| &r.contributions) {
            if c.strategy == Strategy::Emission {
                assert_eq!(c.bounces, 0, "{lighting:?}: {c:?}");
            }
        }
    }
}

#[test]
fn clamped_and_single_bounce_renders_agree_too() {
    let scene = scene();
    let clamped = IntegratorSettings {
        clamp: Some(0.5),
        ..IntegratorSettings::path(5, LightingMode::Mis)
    };
    let records = check_against_renderer(&scene, &settings(clamped));
    assert!(
        records.iter().any(|r| r.value != r.radiance),
        "the clamp never acted"
    );
    let bounce2 = IntegratorSettings {
        bounce: Some(2),
        ..IntegratorSettings::path(5, LightingMode::Mis)
    };
    let records = check_against_renderer(&scene, &settings(bounce2));
    let contributions: Vec<_> = records.iter().flat_map(|r| &r.contributions).collect();
    assert!(!contributions.is_empty());
    assert!(
        contributions.iter().all(|c| c.bounces == 2),
        "{contributions:?}"
    );
}

#[test]
fn records_serialise_and_bad_requests_are_errors() {
    let scene = scene();
    let s = settings(IntegratorSettings::path(3, LightingMode::Mis));
    let records = trace_paths(&scene, &s, (12, 14), 0..2).unwrap();
    let json = serde_json::to_string(&records).expect("records serialise");
    for key in [
        "\"vertices\"",
        "\"light_samples\"",
        "\"mis_weight\"",
        "\"contributions\"",
    ] {
        assert!(json.contains(key), "{key} missing");
    }
    assert_eq!(
        trace_paths(&scene, &s, (24, 0), 0..1)
            .unwrap_err()
            .to_string(),
        "pixel (24, 0) lies outside the 24x18 image"
    );
    assert!(matches!(
        trace_paths(&scene, &s, (0, 0), 5..5),
        Err(InspectError::Samples { .. })
    ));
    assert!(matches!(
        trace_paths(&scene, &s, (0, 0), 0..100_000),
        Err(InspectError::Samples { .. })
    ));
    let normals = RenderSettings {
        integrator: IntegratorSettings {
            estimator: Estimator::Normals,
            ..IntegratorSettings::default()
        },
        ..s
    };
    assert_eq!(
        trace_paths(&scene, &normals, (0, 0), 0..1),
        Err(InspectError::Normals)
    );
}
