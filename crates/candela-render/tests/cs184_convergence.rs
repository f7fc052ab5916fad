//! Independent estimators converge to the same image on the CS184 scenes:
//! uniform hemisphere sampling, light sampling and MIS differ only in
//! noise (the task's "hemisphere vs light sampling" comparison, made a
//! statistical test).
//!
//! Each estimator renders K independent batches (different seeds); the
//! batches give every 8×8 block's mean and the variance of that mean, and
//! a per-block z-test with a Bonferroni-corrected threshold compares the
//! estimators (`candela_image::metrics::ztest`).

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_render::integrator::{IntegratorKind, LightingMode, PathSettings};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LoadOptions};

const BATCHES: u64 = 16;
const FALSE_ALARM: f64 = 1e-3;

fn batches(scene: &Scene, lighting: LightingMode, bounces: u32, spp: u32) -> Vec<RgbImage> {
    (0..BATCHES)
        .map(|seed| {
            let settings = RenderSettings {
                spp,
                seed: 1000 * seed + lighting as u64,
                integrator: IntegratorKind::Path(PathSettings {
                    bounces: 0..=bounces,
                    lighting,
                    light_samples: 1,
                    roulette_from: Some(3),
                }),
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(out.stats.invalid_samples, 0, "NaN or infinite samples");
            let pixels = out.film.resolve().iter().map(|c| c.to_array()).collect();
            RgbImage::from_pixels(out.film.width as usize, out.film.height as usize, pixels)
                .expect("image")
        })
        .collect()
}

fn estimators_agree(file: &str, bounces: u32, spp: [u32; 3]) {
    let Some(path) = common::cs184(file) else {
        return;
    };
    let desc = load(&path, &LoadOptions::default())
        .expect("scene loads")
        .scene;
    let opts = SceneOptions {
        width: 64,
        height: 48,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("scene builds");
    let modes = [
        LightingMode::Hemisphere,
        LightingMode::Light,
        LightingMode::Mis,
    ];
    let stats: Vec<BlockStats> = modes
        .iter()
        .zip(spp)
        .map(|(&mode, spp)| {
            BlockStats::from_batches(&batches(&scene, mode, bounces, spp), 8).unwrap()
        })
        .collect();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let summary = z_test(&stats[i], &stats[j], FALSE_ALARM).unwrap().summary();
        eprintln!(
            "{file} -m {bounces}: {:?} vs {:?}: {summary:?}",
            modes[i], modes[j]
        );
        assert!(
            summary.passed(),
            "{file} -m {bounces}: {:?} and {:?} disagree: {summary:?}",
            modes[i],
            modes[j]
        );
    }
}

#[test]
fn direct_lighting_estimators_agree_on_cbspheres() {
    // Hemisphere sampling finds the small lamp rarely: give it more samples.
    estimators_agree("CBspheres_lambertian.dae", 1, [64, 8, 8]);
}

#[test]
fn direct_lighting_estimators_agree_on_cbbunny() {
    estimators_agree("CBbunny.dae", 1, [64, 8, 8]);
}

#[test]
fn global_illumination_estimators_agree_on_cbspheres() {
    estimators_agree("CBspheres_lambertian.dae", 4, [64, 16, 16]);
}
