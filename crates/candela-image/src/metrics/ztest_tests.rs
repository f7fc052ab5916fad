//! Tests of the block z-test on simulated renders with known truth.

use super::*;
use candela_testkit::{SplitMix64, TempDir};

const SIZE: (usize, usize) = (32, 24);
const SPP: usize = 16;

/// The noiseless image the simulated renders estimate.
fn truth(x: usize, y: usize) -> [f32; 3] {
    let (w, h) = (SIZE.0 as f32, SIZE.1 as f32);
    [0.2 + 0.6 * x as f32 / w, 0.5, 0.3 + 0.4 * y as f32 / h]
}

/// A simulated render: each pixel averages `SPP` samples `truth * E` with
/// `E` exponential of mean 1 (skewed, like Monte Carlo radiance), and
/// reports the mean and its standard error as a renderer would.
fn render(seed: u64, truth: impl Fn(usize, usize) -> [f32; 3]) -> (RgbImage, RgbImage) {
    let mut rng = SplitMix64::new(seed);
    let mut se = RgbImage::new(SIZE.0, SIZE.1).unwrap();
    let mean = RgbImage::from_fn(SIZE.0, SIZE.1, |x, y| {
        let t = truth(x, y);
        let mut out = [0.0; 3];
        for c in 0..3 {
            let samples: Vec<f64> = (0..SPP)
                .map(|_| t[c] as f64 * -(1.0 - rng.uniform()).ln())
                .collect();
            let m = samples.iter().sum::<f64>() / SPP as f64;
            let var = samples.iter().map(|s| (s - m) * (s - m)).sum::<f64>() / (SPP - 1) as f64;
            out[c] = m as f32;
            if let Some(p) = se.get_mut(x, y) {
                p[c] = (var / SPP as f64).sqrt() as f32;
            }
        }
        out
    })
    .unwrap();
    (mean, se)
}

fn stats(seed: u64, truth: impl Fn(usize, usize) -> [f32; 3]) -> BlockStats {
    let (mean, se) = render(seed, truth);
    BlockStats::from_pixel_errors(&mean, &se, 8).unwrap()
}

#[test]
fn accepts_an_independent_noisy_copy() {
    let result = z_test(&stats(1, truth), &stats(2, truth), 0.01).unwrap();
    let summary = result.summary();
    // 32x24 in 8x8 blocks: 4 x 3 blocks.
    assert_eq!(summary.blocks, 12);
    assert_eq!(result.blocks(), (4, 3));
    assert!(summary.passed(), "{summary:?}");
    // Bonferroni over 12 * 3 + 3 = 39 tests at 1 %.
    assert!((summary.threshold - two_sided_z_threshold(0.01, 39)).abs() < 1e-12);
}

#[test]
fn detects_a_bright_patch() {
    // Brighten one 8x8 block by 30 %. Channel values there are 0.35 to 0.7
    // with per-pixel standard error a quarter of that (exponential noise,
    // 16 samples); the block difference has sigma about 0.5 / 4 / 8 * sqrt(2)
    // = 0.022, so the shift of 0.1 to 0.2 is 5 to 9 sigma per channel,
    // against a threshold of 3.66.
    let shifted = |x: usize, y: usize| {
        let t = truth(x, y);
        if (8..16).contains(&x) && (16..24).contains(&y) {
            t.map(|v| v * 1.3)
        } else {
            t
        }
    };
    let result = z_test(&stats(3, truth), &stats(4, shifted), 0.01).unwrap();
    let summary = result.summary();
    assert!(!summary.passed());
    assert!(summary.count_over >= 1, "{summary:?}");
    assert_eq!((summary.worst.0, summary.worst.1), (1, 2), "{summary:?}");
    // The patch is darker in the first render: the z-score is negative.
    assert!(result.block_z()[2 * 4 + 1].iter().all(|&z| z < 0.0));
}

#[test]
fn global_z_detects_a_small_bias_everywhere() {
    // 10 % too dark everywhere. Channel means are about 0.5 with per-pixel
    // standard error 0.5 / sqrt(16) = 0.125 (exponential noise): per block
    // the difference has sigma 0.125 / 8 * sqrt(2) = 0.022, so the 0.05 bias
    // is about 2.3 sigma, under the threshold of 3.66; over the 768 pixels
    // sigma is 0.0064 and the bias about 7.8 sigma.
    let dimmer = |x: usize, y: usize| truth(x, y).map(|v| v * 0.9);
    let summary = z_test(&stats(5, truth), &stats(6, dimmer), 0.01)
        .unwrap()
        .summary();
    assert!(summary.global_abs_z > 5.0, "{summary:?}");
    assert!(!summary.passed());
}

#[test]
fn false_alarm_rate_is_bounded() {
    // 200 unbiased pairs at a 5 % family-wise rate: Bonferroni promises at
    // most 5 % failures (10 expected at worst; more than 22 has probability
    // below 1e-3 under Binomial(200, 0.05)).
    let failures = (0..200u64)
        .filter(|&i| {
            let result = z_test(&stats(100 + 2 * i, truth), &stats(101 + 2 * i, truth), 0.05);
            !result.unwrap().summary().passed()
        })
        .count();
    assert!(failures <= 22, "{failures} false alarms of 200");
}

#[test]
fn batches_variant_accepts_copies_and_rejects_shifts() {
    let batches = |seed: u64, scale: f32| -> Vec<RgbImage> {
        (0..16)
            .map(|k| render(seed * 1000 + k, |x, y| truth(x, y).map(|v| v * scale)).0)
            .collect()
    };
    let a = BlockStats::from_batches(&batches(7, 1.0), 8).unwrap();
    let b = BlockStats::from_batches(&batches(8, 1.0), 8).unwrap();
    let c = BlockStats::from_batches(&batches(9, 1.1), 8).unwrap();
    assert!(z_test(&a, &b, 0.01).unwrap().summary().passed());
    let shifted = z_test(&a, &c, 0.01).unwrap().summary();
    assert!(!shifted.passed() && shifted.count_over > 10, "{shifted:?}");
}

#[test]
fn zero_variance_blocks_pass_only_when_equal_and_nan_fails() {
    let black = RgbImage::new(16, 8).unwrap();
    let zero = RgbImage::new(16, 8).unwrap();
    let a = BlockStats::from_pixel_errors(&black, &zero, 8).unwrap();
    assert!(z_test(&a, &a, 0.01).unwrap().summary().passed());
    let mut lit = black.clone();
    lit.pixels_mut()[0] = [1e-3, 0.0, 0.0];
    let b = BlockStats::from_pixel_errors(&lit, &zero, 8).unwrap();
    let summary = z_test(&a, &b, 0.01).unwrap().summary();
    assert_eq!(summary.max_abs_z, f64::INFINITY);
    assert_eq!(summary.count_over, 1);
    let mut broken = black.clone();
    broken.pixels_mut()[9] = [f32::NAN, 0.0, 0.0];
    let c = BlockStats::from_pixel_errors(&broken, &zero, 8).unwrap();
    assert!(!z_test(&a, &c, 0.01).unwrap().summary().passed());
}

#[test]
fn partial_edge_blocks_and_mismatches() {
    let image = RgbImage::from_fn(10, 9, |x, _| [x as f32; 3]).unwrap();
    let zero = RgbImage::new(10, 9).unwrap();
    let stats = BlockStats::from_pixel_errors(&image, &zero, 8).unwrap();
    assert_eq!((stats.blocks_x, stats.blocks_y), (2, 2));
    // The right-hand partial block holds columns 8 and 9: mean 8.5.
    assert_eq!(stats.mean[1], [8.5; 3]);
    let other = BlockStats::from_pixel_errors(&image, &zero, 4).unwrap();
    assert!(matches!(
        z_test(&stats, &other, 0.01),
        Err(ImageError::SizeMismatch { .. })
    ));
    assert!(BlockStats::from_pixel_errors(&image, &zero, 0).is_err());
    assert!(BlockStats::from_batches(std::slice::from_ref(&image), 8).is_err());
}

#[test]
fn difference_image_marks_the_failing_block() {
    let dir = TempDir::new("ztest-diff");
    let brighter = |x: usize, y: usize| {
        let t = truth(x, y);
        if x < 8 && y < 8 {
            t.map(|v| v * 1.5)
        } else {
            t
        }
    };
    let result = z_test(&stats(11, brighter), &stats(12, truth), 0.01).unwrap();
    let image = result.difference_image().unwrap();
    assert_eq!(image.size(), SIZE);
    assert_eq!(image.get(3, 3), Some([1.0, 1.0, 0.0]));
    let elsewhere = image.get(20, 20).unwrap();
    assert!(elsewhere[1] == 0.0 && elsewhere[0].max(elsewhere[2]) <= 1.0);
    let path = dir.path().join("diff.png");
    result.write_difference_png(&path).unwrap();
    assert_eq!(crate::read_png(&path).unwrap().size(), SIZE);
}
