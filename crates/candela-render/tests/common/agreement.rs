//! The estimator-agreement suite's machinery (the table itself is in
//! `tests/agreement_suite.rs`): every estimator ([`Method`]) renders every
//! scene of the table ([`Case`]) in [`BATCHES`] independent batches
//! (different seeds), and so does a **reference**: the MIS path tracer at
//! [`REFERENCE_SPP_FACTOR`] times the samples, with seeds of its own. Each
//! pixel's mean over the batches and the variance of that mean (from the
//! batches' spread at that pixel, which holds for any sample sequence:
//! batches are independent, the samples within one need not be) give each
//! 8×8 block's mean and the variance of that mean, and a per-block z-test
//! (`candela_image::metrics::ztest`) compares each estimator with the
//! reference:
//!
//! ```text
//! z = (mean_estimator - mean_reference) / sqrt(var_estimator + var_reference)
//! ```
//!
//! so the reference's own noise enters the statistic. A block's variance
//! pools the 64 pixels' variances, each estimated with `BATCHES - 1`
//! degrees of freedom, so it is known well enough for the normal
//! threshold far out in the tail where the Bonferroni correction puts it
//! (the spread of 16 block means alone, 15 degrees of freedom, is not: a
//! Student t with 15 degrees of freedom exceeds 5 four hundred times more
//! often than a normal variable). The threshold is
//! Bonferroni-corrected over every block and channel of a comparison (the
//! z-test does that) and over every comparison of the table (here: the
//! rate handed to the z-test is [`SUITE_FALSE_ALARM`] divided by the
//! table's number of comparisons), so a correct renderer fails the whole
//! suite with probability at most [`SUITE_FALSE_ALARM`]. Seeds are fixed:
//! the outcome does not change between runs.

use candela_image::metrics::ztest::{z_test, BlockStats, ZTest};
use candela_image::RgbImage;
use candela_render::integrator::{Estimator, IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::Scene;
use std::time::Instant;

/// Independent batches per estimator (≥ 16 for the normal threshold to
/// hold with a variance estimated from the batches).
pub const BATCHES: u64 = 16;
/// Block edge of the z-test, in pixels.
pub const BLOCK: usize = 8;
/// Chance that a correct renderer fails any comparison of the table.
pub const SUITE_FALSE_ALARM: f64 = 1e-3;
/// The reference takes this many times the MIS estimator's samples.
pub const REFERENCE_SPP_FACTOR: u32 = 4;

/// An estimator of the image: a row of the suite's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Path tracing gathering direct light with CS184's uniform hemisphere
    /// rays (`-H`).
    Hemisphere,
    /// Path tracing with light sampling only.
    LightSampling,
    /// Path tracing with multiple importance sampling of lights and BSDFs
    /// (the default, and the reference's estimator).
    Mis,
    /// Bidirectional path tracing (`--integrator bdpt`), every strategy
    /// weighted by the power heuristic.
    Bdpt,
    /// Light tracing (`--integrator light`): particles from the lights,
    /// each vertex connected to the camera.
    LightTracer,
    // ADD ESTIMATORS HERE. Light tracing and BDPT land as variants of
    // `settings::Estimator`; give each a variant here, an arm in
    // `Method::integrator` and `Method::spp_factor`, and a place in
    // `Method::ALL`. Every case of the table then runs it; exclude it from
    // a case (with the reason) where it cannot converge to the reference,
    // e.g. the delta light seen through glass in `glass room`, whose
    // caustic the reference (a unidirectional path tracer) cannot find
    // but light tracing can.
}

impl Method {
    /// Every estimator the suite runs.
    pub const ALL: [Method; 5] = [
        Method::Hemisphere,
        Method::LightSampling,
        Method::Mis,
        Method::Bdpt,
        Method::LightTracer,
    ];

    /// Its integrator settings for light of up to `max_depth` bounces
    /// (Russian roulette on, as rendered by default).
    pub fn integrator(self, max_depth: u32) -> IntegratorSettings {
        let lighting = match self {
            Method::Hemisphere => LightingMode::Hemisphere,
            Method::LightSampling => LightingMode::Light,
            Method::Mis => LightingMode::Mis,
            Method::Bdpt | Method::LightTracer => {
                return IntegratorSettings {
                    estimator: if self == Method::Bdpt {
                        Estimator::Bdpt
                    } else {
                        Estimator::Light
                    },
                    ..IntegratorSettings::path(max_depth, LightingMode::Mis)
                }
            }
        };
        IntegratorSettings::path(max_depth, lighting)
    }

    /// Samples per batch relative to a case's `spp`: uniform hemisphere
    /// rays find small lamps rarely, so they take more.
    pub fn spp_factor(self) -> u32 {
        match self {
            Method::Hemisphere => 4,
            Method::LightSampling | Method::Mis | Method::Bdpt => 1,
            // One light path per camera sample spreads its light over the
            // whole film: noisier per pixel than a camera path.
            Method::LightTracer => 4,
        }
    }
}

/// A scene of the table: what to render and how.
pub struct Case {
    /// Names the case in messages.
    pub name: &'static str,
    /// Builds the scene at the suite's resolution.
    pub scene: fn() -> Scene,
    /// Light of bounce counts `0..=max_depth`.
    pub max_depth: u32,
    /// Samples per pixel per batch (times [`Method::spp_factor`]).
    pub spp: u32,
    /// Estimators left out, each with the reason it cannot converge to the
    /// reference here.
    pub excluded: &'static [(Method, &'static str)],
    /// Distinguishes the seeds of different cases.
    pub seed: u64,
}

impl Case {
    /// The estimators compared with the reference.
    pub fn methods(&self) -> impl Iterator<Item = Method> + '_ {
        Method::ALL
            .into_iter()
            .filter(|m| !self.excluded.iter().any(|(x, _)| x == m))
    }
}

/// Number of comparisons of a table: the Bonferroni factor.
pub fn comparisons(cases: &[Case]) -> usize {
    cases.iter().map(|c| c.methods().count()).sum()
}

/// Block statistics of `BATCHES` renders of `case` with `integrator` at
/// `spp`; batch `b` has seed `seed + 1000 b`.
fn render_stats(
    scene: &Scene,
    case: &Case,
    integrator: IntegratorSettings,
    spp: u32,
    seed: u64,
) -> BlockStats {
    let images: Vec<RgbImage> = (0..BATCHES)
        .map(|batch| {
            let settings = RenderSettings {
                spp,
                seed: seed + 1000 * batch,
                integrator: integrator.clone(),
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(
                out.stats.invalid_samples, 0,
                "{}: NaN or infinite samples",
                case.name
            );
            out.film.resolve()
        })
        .collect();
    let (mean, std_error) = pixel_mean_and_error(&images);
    BlockStats::from_pixel_errors(&mean, &std_error, BLOCK).expect("same sizes")
}

/// Per pixel and channel, the mean of independent images and its
/// standard error `sqrt(s² / K)` from their spread.
fn pixel_mean_and_error(images: &[RgbImage]) -> (RgbImage, RgbImage) {
    let k = images.len() as f64;
    assert!(k >= 2.0, "a spread needs two images");
    let (w, h) = images[0].size();
    let mut mean = RgbImage::new(w, h).expect("size");
    let mut error = RgbImage::new(w, h).expect("size");
    for i in 0..w * h {
        for c in 0..3 {
            let values = images.iter().map(|im| im.pixels()[i][c] as f64);
            let m = values.clone().sum::<f64>() / k;
            let var = values.map(|v| (v - m) * (v - m)).sum::<f64>() / (k - 1.0);
            mean.pixels_mut()[i][c] = m as f32;
            error.pixels_mut()[i][c] = (var / k).sqrt() as f32;
        }
    }
    (mean, error)
}

/// A scene of the table, rendered once, with its reference.
pub struct Setup<'a> {
    /// The case.
    pub case: &'a Case,
    /// Its scene.
    pub scene: Scene,
    /// The reference's block statistics.
    pub reference: BlockStats,
}

impl<'a> Setup<'a> {
    /// Builds the scene of `case` and renders its reference.
    pub fn new(case: &'a Case) -> Self {
        let scene = (case.scene)();
        let reference = render_stats(
            &scene,
            case,
            Method::Mis.integrator(case.max_depth),
            case.spp * REFERENCE_SPP_FACTOR,
            case.seed * 1_000_000,
        );
        Self {
            case,
            scene,
            reference,
        }
    }

    /// Renders `method` with `integrator` (normally
    /// `method.integrator(case.max_depth)`) and z-tests it against the
    /// reference at the false-alarm rate `rate`, printing the outcome.
    /// Seeds: `case.seed · 10⁶ + slot + 1000 b`, where the reference has
    /// slot 0 and the estimators 1, 2, ...
    pub fn compare(&self, method: Method, integrator: IntegratorSettings, rate: f64) -> ZTest {
        let case = self.case;
        let slot = 1 + Method::ALL.iter().position(|&m| m == method).unwrap_or(0) as u64;
        let stats = render_stats(
            &self.scene,
            case,
            integrator,
            case.spp * method.spp_factor(),
            case.seed * 1_000_000 + slot,
        );
        let test = z_test(&stats, &self.reference, rate).expect("same sizes");
        let summary = test.summary();
        eprintln!(
            "{} -m {}: {method:?} vs reference: max |z| {:.2} (block {:?}), global |z| {:.2}, \
             threshold {:.2}",
            case.name,
            case.max_depth,
            summary.max_abs_z,
            summary.worst,
            summary.global_abs_z,
            summary.threshold
        );
        test
    }
}

/// Why a comparison failed: the summary and the difference picture
/// (`ZTest::difference_image`: yellow where the estimator is brighter than
/// the reference, cyan where darker), written to the temporary folder.
fn failure(case: &Case, method: Method, test: &ZTest) -> String {
    let name = format!("agreement-{}-{method:?}.png", case.name.replace(' ', "_"));
    let path = std::env::temp_dir().join(name);
    let picture = match test.write_difference_png(&path) {
        Ok(()) => path.display().to_string(),
        Err(e) => format!("not written: {e}"),
    };
    format!(
        "{}: {method:?} disagrees with the reference: {:?} (difference image: {picture})",
        case.name,
        test.summary()
    )
}

/// Runs every case of `cases`, then fails listing every comparison that
/// disagreed (with its difference picture). `all_comparisons` counts the
/// comparisons of every table of the suite (the Bonferroni factor), so that
/// running all of them keeps the suite's false-alarm rate.
pub fn assert_all_agree(cases: &[Case], all_comparisons: usize) {
    assert!(!cases.is_empty(), "an empty table checks nothing");
    assert!(all_comparisons >= comparisons(cases));
    let rate = SUITE_FALSE_ALARM / all_comparisons as f64;
    let mut failures = Vec::new();
    for case in cases {
        assert!(
            case.methods().count() > 0,
            "{}: every estimator is excluded",
            case.name
        );
        let start = Instant::now();
        for (method, why) in case.excluded {
            eprintln!("{}: {method:?} excluded: {why}", case.name);
        }
        let setup = Setup::new(case);
        for method in case.methods() {
            let test = setup.compare(method, method.integrator(case.max_depth), rate);
            if !test.summary().passed() {
                failures.push(failure(case, method, &test));
            }
        }
        eprintln!("{}: {:.1} s", case.name, start.elapsed().as_secs_f64());
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
