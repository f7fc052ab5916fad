//! "Independent estimators converge to the same image": uniform hemisphere
//! sampling, light sampling and MIS each render K independent batches
//! (different seeds); the batches give every 8×8 block's mean and the
//! variance of that mean, and a per-block z-test with a Bonferroni-corrected
//! threshold (`candela_image::metrics::ztest`) compares each pair.

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::Scene;

/// Independent batches per estimator.
const BATCHES: u64 = 16;
/// Chance that a correct renderer fails one comparison.
const FALSE_ALARM: f64 = 1e-3;
const MODES: [LightingMode; 3] = [
    LightingMode::Hemisphere,
    LightingMode::Light,
    LightingMode::Mis,
];

/// What to compare.
pub struct Agreement<'a> {
    /// Names the case in messages.
    pub label: &'a str,
    /// Light of bounce counts 0..=max_bounces.
    pub max_bounces: u32,
    /// Samples per pixel per batch for hemisphere, light and MIS.
    pub spp: [u32; 3],
    /// Russian roulette from this bounce on.
    pub roulette_from: Option<u32>,
    /// Seeds of different cases differ.
    pub seed_base: u64,
}

fn batches(scene: &Scene, case: &Agreement, lighting: LightingMode, spp: u32) -> Vec<RgbImage> {
    (0..BATCHES)
        .map(|batch| {
            let settings = RenderSettings {
                spp,
                seed: case.seed_base + 1000 * batch + lighting as u64,
                integrator: IntegratorSettings {
                    max_depth: case.max_bounces,
                    lighting,
                    roulette: case.roulette_from.is_some(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(out.stats.invalid_samples, 0, "NaN or infinite samples");
            out.film.resolve()
        })
        .collect()
}

/// Asserts that the three estimators agree on `scene`.
pub fn assert_estimators_agree(scene: &Scene, case: &Agreement) {
    let stats: Vec<BlockStats> = MODES
        .iter()
        .zip(case.spp)
        .map(|(&mode, spp)| BlockStats::from_batches(&batches(scene, case, mode, spp), 8).unwrap())
        .collect();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let summary = z_test(&stats[i], &stats[j], FALSE_ALARM).unwrap().summary();
        let label = case.label;
        eprintln!("{label}: {:?} vs {:?}: {summary:?}", MODES[i], MODES[j]);
        assert!(
            summary.passed(),
            "{label}: {:?} and {:?} disagree: {summary:?}",
            MODES[i],
            MODES[j]
        );
    }
}
