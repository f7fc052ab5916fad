//! Light tracing and BDPT against the MIS path tracer and an analytic
//! answer, and the splat film's determinism.
//!
//! Agreement: each estimator renders `BATCHES` independent batches
//! (different seeds); the per-8×8-block means and their variances from the
//! batches feed a block z-test with a Bonferroni-corrected threshold
//! (`candela_image::metrics::ztest`, false-alarm rate 10⁻³ per comparison).
//! Analytic: pbrt's sphere (albedo 0.5, a point light of intensity π at the
//! centre) has radiance Σ_{k=1..m} 0.5^k after at most m bounces; the image
//! mean of the batches must be within 4.5 standard errors of it.

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_render::camera::framing::CameraMode;
use candela_render::integrator::{Estimator, IntegratorSettings};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LightDesc, LightKind, LoadOptions, SceneDesc, SourceLoc};
use glam::Vec3;

const BATCHES: u64 = 12;
const FALSE_ALARM: f64 = 1e-3;
const Z: f64 = 4.5;

fn integrator(estimator: Estimator, max_depth: u32) -> IntegratorSettings {
    IntegratorSettings {
        estimator,
        max_depth,
        ..Default::default()
    }
}

fn batches(
    scene: &Scene,
    estimator: Estimator,
    max_depth: u32,
    spp: u32,
    seed: u64,
) -> Vec<RgbImage> {
    (0..BATCHES)
        .map(|b| {
            let settings = RenderSettings {
                spp,
                seed: seed + 1000 * b,
                integrator: integrator(estimator, max_depth),
                threads: 2,
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(
                out.stats.invalid_samples, 0,
                "{estimator:?}: NaN or infinite samples"
            );
            out.film.resolve()
        })
        .collect()
}

/// Asserts that `estimator` (at `spp`) and the MIS path tracer (at
/// `path_spp`) converge to the same image.
fn assert_agrees_with_path_tracer(
    label: &str,
    scene: &Scene,
    estimator: Estimator,
    spp: u32,
    path_spp: u32,
    max_depth: u32,
) {
    let ours = BlockStats::from_batches(&batches(scene, estimator, max_depth, spp, 11), 8).unwrap();
    let path =
        BlockStats::from_batches(&batches(scene, Estimator::Path, max_depth, path_spp, 7), 8)
            .unwrap();
    let summary = z_test(&ours, &path, FALSE_ALARM).unwrap().summary();
    eprintln!("{label}: {estimator:?} vs path: {summary:?}");
    assert!(
        summary.passed(),
        "{label}: {estimator:?} and the path tracer disagree: {summary:?}"
    );
}

fn cs184_scene(
    file: &str,
    (width, height): (u32, u32),
    edit: impl FnOnce(&mut SceneDesc),
) -> Scene {
    let path = common::cs184(file);
    let mut desc = load(&path, &LoadOptions::default())
        .expect("scene loads")
        .scene;
    edit(&mut desc);
    // The file's camera (49° wide): the CS184 framing keeps CS184's focal
    // length in pixels, so at test sizes it is a 2° view, where light
    // subpaths almost never reach the film and the tests would have little
    // power.
    let opts = SceneOptions {
        width,
        height,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    Scene::build(&desc, &opts).expect("scene builds")
}

/// CBspheres_lambertian with its area light replaced by a point light just
/// below the ceiling's centre.
fn point_lit(desc: &mut SceneDesc) {
    let (lo, hi) = desc.bounds().expect("the box has geometry");
    for m in &mut desc.materials {
        m.emission = None;
    }
    let c = 0.5 * (lo + hi);
    desc.lights = vec![LightDesc {
        name: "bulb".into(),
        kind: LightKind::Point {
            position: Vec3::new(c.x, hi.y - 0.1 * (hi.y - lo.y), c.z),
            intensity: Vec3::splat(1.0),
        },
        loc: SourceLoc::default(),
    }];
}

#[test]
fn light_tracer_agrees_with_the_path_tracer_under_an_area_light() {
    let scene = cs184_scene("CBspheres_lambertian.dae", (32, 24), |_| {});
    assert_agrees_with_path_tracer(
        "CBspheres_lambertian -m 3",
        &scene,
        Estimator::Light,
        16,
        16,
        3,
    );
}

#[test]
fn bdpt_agrees_with_the_path_tracer_under_an_area_light() {
    let scene = cs184_scene("CBspheres_lambertian.dae", (32, 24), |_| {});
    assert_agrees_with_path_tracer(
        "CBspheres_lambertian -m 3",
        &scene,
        Estimator::Bdpt,
        8,
        16,
        3,
    );
}

#[test]
fn light_tracer_and_bdpt_agree_with_the_path_tracer_under_a_point_light() {
    let scene = cs184_scene("CBspheres_lambertian.dae", (32, 24), point_lit);
    for estimator in [Estimator::Light, Estimator::Bdpt] {
        assert_agrees_with_path_tracer(
            "CBspheres_lambertian, point light, -m 4",
            &scene,
            estimator,
            16,
            16,
            4,
        );
    }
}

#[test]
fn bdpt_agrees_with_the_path_tracer_through_mirror_and_glass() {
    let scene = cs184_scene("CBspheres.dae", (32, 24), |_| {});
    assert_agrees_with_path_tracer("CBspheres -m 5", &scene, Estimator::Bdpt, 16, 32, 5);
}

#[test]
fn bdpt_agrees_with_the_path_tracer_with_sky_point_area_lights_and_glass() {
    let desc = common::glass_room();
    let opts = SceneOptions {
        width: 32,
        height: 24,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("scene builds");
    assert_agrees_with_path_tracer("glass room -m 4", &scene, Estimator::Bdpt, 16, 32, 4);
}

#[test]
fn light_tracer_and_bdpt_converge_on_the_analytic_sphere() {
    let opts = SceneOptions {
        width: 16,
        height: 16,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(&common::analytic_sphere(), &opts).expect("scene builds");
    for estimator in [Estimator::Light, Estimator::Bdpt] {
        for m in [1u32, 3] {
            let means: Vec<f64> = batches(&scene, estimator, m, 8, 3 + m as u64)
                .iter()
                .map(|img| {
                    let px = img.pixels();
                    px.iter()
                        .map(|c| (c[0] + c[1] + c[2]) as f64 / 3.0)
                        .sum::<f64>()
                        / px.len() as f64
                })
                .collect();
            let n = means.len() as f64;
            let mean = means.iter().sum::<f64>() / n;
            let var = means.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let se = (var / n).sqrt();
            let expected: f64 = (1..=m).map(|k| 0.5f64.powi(k as i32)).sum();
            eprintln!("{estimator:?} -m {m}: {mean:.5} ± {se:.5} (expected {expected:.5})");
            assert!(
                (mean - expected).abs() <= Z * se + 1e-5,
                "{estimator:?} -m {m}: {mean:.5} ± {se:.5}, expected {expected:.5}"
            );
        }
    }
}

#[test]
fn splatting_films_are_bit_identical_for_any_threads_and_tiles() {
    let scene = cs184_scene("CBspheres.dae", (24, 18), |_| {});
    for estimator in [Estimator::Light, Estimator::Bdpt] {
        let film = |threads: usize, tile: u32| {
            let settings = RenderSettings {
                spp: 6,
                seed: 5,
                integrator: integrator(estimator, 4),
                threads,
                tile,
                ..Default::default()
            };
            render(&scene, &settings, &|_| {}).expect("render").film
        };
        let reference = film(1, 8);
        assert!(
            reference.splats.light_paths == 24 * 18 * 6,
            "one light subpath per camera sample"
        );
        assert!(
            reference.splats.sums.iter().any(|s| s[0] != 0),
            "{estimator:?} splatted nothing"
        );
        for (threads, tile) in [(2, 8), (2, 5), (1, 32)] {
            assert!(
                film(threads, tile) == reference,
                "{estimator:?}: {threads} threads, tile {tile}"
            );
        }
        // Two sample ranges merged give the same splat sums exactly.
        let range = |r: std::ops::Range<u32>| {
            let settings = RenderSettings {
                spp: 6,
                seed: 5,
                integrator: integrator(estimator, 4),
                sample_range: Some(r),
                threads: 2,
                ..Default::default()
            };
            render(&scene, &settings, &|_| {}).expect("render").film
        };
        let mut merged = range(0..2);
        merged.merge(&range(2..6)).unwrap();
        assert_eq!(
            merged.splats, reference.splats,
            "{estimator:?}: merged sample ranges"
        );
    }
}

#[test]
fn technique_layers_split_the_bdpt_image_without_changing_it() {
    let scene = cs184_scene("CBspheres.dae", (16, 12), |_| {});
    let render_with_layers = |technique_layers: bool| {
        let settings = RenderSettings {
            spp: 4,
            seed: 9,
            integrator: IntegratorSettings {
                technique_layers,
                ..integrator(Estimator::Bdpt, 3)
            },
            threads: 2,
            ..Default::default()
        };
        render(&scene, &settings, &|_| {}).expect("render").film
    };
    let plain = render_with_layers(false);
    let layered = render_with_layers(true);
    let image = layered.resolve();
    assert_eq!(plain.resolve(), image, "the layers change the image");
    let names = candela_render::integrator::bdpt::techniques::layer_names(3);
    assert_eq!(layered.layers.names(), names.as_slice());
    // The weighted layers add up to the image (up to rounding).
    let mut sum = vec![[0.0f64; 3]; image.pixels().len()];
    for (k, name) in names.iter().enumerate() {
        let layer = layered.layer(k);
        let nonzero = layer.pixels().iter().any(|p| p.iter().any(|&c| c != 0.0));
        if name == "s0_t3" || name == "s1_t2" || name == "s2_t1" || name == "s3_t2" {
            assert!(nonzero, "{name} is black");
        }
        if name.ends_with("_unweighted") {
            continue;
        }
        for (acc, p) in sum.iter_mut().zip(layer.pixels()) {
            for c in 0..3 {
                acc[c] += p[c] as f64;
            }
        }
    }
    for (acc, p) in sum.iter().zip(image.pixels()) {
        for c in 0..3 {
            let want = p[c] as f64;
            assert!(
                (acc[c] - want).abs() <= 1e-4 * want.abs().max(1e-2),
                "{acc:?} vs {p:?}"
            );
        }
    }
}
