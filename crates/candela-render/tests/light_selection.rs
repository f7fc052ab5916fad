//! Light selection strategies converge to the same image: the many-lights
//! hall (10,240 emitting triangles) rendered with the light tree and with
//! uniform selection agrees with power selection, by the block z-test of
//! the agreement suite (`tests/common/agreement.rs`: 16 independent batches
//! per strategy, per-pixel variance of the mean from their spread, 8×8
//! blocks, threshold Bonferroni-corrected over blocks, channels and the
//! comparisons here). Fixed seeds.

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_render::integrator::IntegratorSettings;
use candela_render::light::LightSelection;
use candela_render::render::{render, RenderSettings};
use candela_render::scene::Scene;
use common::agreement::{BATCHES, BLOCK};

/// False-alarm rate of this file's comparisons together.
const FALSE_ALARM: f64 = 1e-3;

fn block_stats(scene: &Scene, how: LightSelection, spp: u32, seed: u64) -> BlockStats {
    let images: Vec<RgbImage> = (0..BATCHES)
        .map(|b| {
            let settings = RenderSettings {
                spp,
                seed: seed + 1000 * b,
                integrator: IntegratorSettings {
                    max_depth: 2,
                    light_selection: how,
                    ..Default::default()
                },
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(
                out.stats.invalid_samples, 0,
                "{how:?}: NaN or infinite samples"
            );
            out.film.resolve()
        })
        .collect();
    let (w, h) = images[0].size();
    let k = images.len() as f64;
    let mut mean = RgbImage::new(w, h).expect("size");
    let mut error = RgbImage::new(w, h).expect("size");
    for i in 0..w * h {
        for c in 0..3 {
            let values = images.iter().map(|im| f64::from(im.pixels()[i][c]));
            let m = values.clone().sum::<f64>() / k;
            let var = values.map(|v| (v - m) * (v - m)).sum::<f64>() / (k - 1.0);
            mean.pixels_mut()[i][c] = m as f32;
            error.pixels_mut()[i][c] = (var / k).sqrt() as f32;
        }
    }
    BlockStats::from_pixel_errors(&mean, &error, BLOCK).expect("same sizes")
}

#[test]
fn tree_and_uniform_selection_agree_with_power_on_many_lights() {
    let scene = common::agreement_scenes::many_lights_hall();
    assert!(scene.lights.sampled_count() > 10_000);
    let reference = block_stats(&scene, LightSelection::Power, 16, 1);
    let others = [LightSelection::Bvh, LightSelection::Uniform];
    let mut failures = Vec::new();
    for (slot, how) in others.into_iter().enumerate() {
        let stats = block_stats(&scene, how, 8, 100 + slot as u64);
        let test = z_test(&stats, &reference, FALSE_ALARM / others.len() as f64).expect("sizes");
        let s = test.summary();
        eprintln!(
            "{how:?} vs power: max |z| {:.2} (block {:?}), global |z| {:.2}, threshold {:.2}",
            s.max_abs_z, s.worst, s.global_abs_z, s.threshold
        );
        if !s.passed() {
            failures.push(format!("{how:?}: {s:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
