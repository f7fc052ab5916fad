//! Statistical and determinism tests of both sampler kinds.

use glam::{Vec2, Vec3};

use super::chi2::{chi2_p_value, pearson_pooled, Chi2Test, SIGNIFICANCE, TEST_COUNT};
use super::{Sampler, SamplerKind};

const KINDS: [SamplerKind; 2] = [SamplerKind::Independent, SamplerKind::Sobol];

/// Draws `count` values per pixel sample from pixels of a 32 × 32 block
/// with 64 samples each, calling `draw` for each pixel sample.
fn for_pixel_samples(kind: SamplerKind, seed: u64, mut draw: impl FnMut(&mut Sampler)) {
    let mut sampler = Sampler::new(kind, seed);
    for py in 0..32 {
        for px in 0..32 {
            for index in 0..64 {
                sampler.start_pixel_sample(px, py, index);
                draw(&mut sampler);
            }
        }
    }
}

#[test]
fn values_are_a_pure_function_of_seed_pixel_index_dimension() {
    for kind in KINDS {
        let mut a = Sampler::new(kind, 7);
        let mut b = Sampler::new(kind, 7);
        // Visit other pixels with `b` first: no state may leak through.
        b.start_pixel_sample(99, 3, 5);
        let _ = (b.next_1d(), b.next_2d());
        a.start_pixel_sample(4, 9, 17);
        b.start_pixel_sample(4, 9, 17);
        for _ in 0..10 {
            assert_eq!(a.next_1d(), b.next_1d(), "{kind:?}");
            assert_eq!(a.next_2d(), b.next_2d(), "{kind:?}");
        }
        assert_eq!(a.dimension(), 30);
    }
}

/// A dimension passed over with `skip_one` and drawn later gives what
/// `next_1d` would have given there, and the draws after it are those of a
/// stream that drew it.
#[test]
fn a_skipped_dimension_draws_the_value_next_1d_gives() {
    for kind in KINDS {
        let mut a = Sampler::new(kind, 3);
        let mut b = Sampler::new(kind, 3);
        for index in 0..16 {
            a.start_pixel_sample(5, 8, index);
            b.start_pixel_sample(5, 8, index);
            let _ = (a.next_2d(), b.next_2d());
            let skipped = a.skip_one();
            let drawn = b.next_1d();
            assert_eq!(a.next_2d(), b.next_2d(), "{kind:?}");
            assert_eq!(
                a.draw_skipped(skipped).to_bits(),
                drawn.to_bits(),
                "{kind:?}"
            );
            assert_eq!(a.dimension(), b.dimension());
        }
    }
}

#[test]
fn different_seeds_pixels_and_indices_give_different_values() {
    for kind in KINDS {
        let first = |seed, px, index| {
            let mut s = Sampler::new(kind, seed);
            s.start_pixel_sample(px, 0, index);
            (s.next_1d(), s.next_2d())
        };
        let base = first(1, 0, 0);
        assert_ne!(base, first(2, 0, 0), "{kind:?} seed");
        assert_ne!(base, first(1, 1, 0), "{kind:?} pixel");
        assert_ne!(base, first(1, 0, 1), "{kind:?} index");
        // Across many seeds, the first value of one pixel sample is uniform.
        let mut hist = [0f64; 16];
        for seed in 0..16_000 {
            hist[(first(seed, 3, 2).0 * 16.0) as usize] += 1.0;
        }
        let (stat, dof) = pearson_pooled(&hist, &[1000.0; 16]);
        assert!(chi2_p_value(stat, dof) > threshold(), "{kind:?} over seeds");
    }
}

fn threshold() -> f64 {
    1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / TEST_COUNT as f64)
}

#[test]
fn one_dimensional_values_are_uniform_in_every_dimension() {
    for kind in KINDS {
        for dim in [0usize, 1, 5] {
            let mut hist = vec![0f64; 100];
            for_pixel_samples(kind, 11, |s| {
                let v = (0..=dim).map(|_| s.next_1d()).last().unwrap_or(0.0);
                assert!((0.0..1.0).contains(&v));
                hist[(v * 100.0) as usize] += 1.0;
            });
            let n: f64 = hist.iter().sum();
            let (stat, dof) = pearson_pooled(&hist, &vec![n / 100.0; 100]);
            let p = chi2_p_value(stat, dof);
            assert!(p > threshold(), "{kind:?} dimension {dim}: p = {p}");
        }
    }
}

/// Chi-square of pairs on the unit square against the uniform density: the
/// pair (dimension d, d + 1) from two `next_1d` calls tests independence of
/// consecutive dimensions; `next_2d` tests joint uniformity.
#[test]
fn consecutive_dimensions_are_independent_and_pairs_uniform() {
    for kind in KINDS {
        for joint in [false, true] {
            let mut points = Vec::with_capacity(1 << 16);
            for_pixel_samples(kind, 3, |s| {
                let _ = s.next_1d();
                let p = if joint {
                    s.next_2d()
                } else {
                    Vec2::new(s.next_1d(), s.next_1d())
                };
                points.push(p);
            });
            let mut next = points.into_iter();
            let outcome = Chi2Test::plane("sampler pairs", Vec2::ZERO, Vec2::ONE)
                .with_resolution(16, 16)
                .with_samples(32 * 32 * 64)
                .run(|_| next.next().map(|p| (p.extend(0.0), 1.0)), |_: Vec3| 1.0);
            outcome.assert_ok();
        }
    }
}

#[test]
fn sobol_prefixes_are_stratified_nets() {
    // The first 2^m pairs of a pixel hit every elementary interval of area
    // 2^-m exactly once, for every split of m into x and y bits.
    let mut sampler = Sampler::new(SamplerKind::Sobol, 5);
    for m in [2u32, 4, 6] {
        let n = 1u32 << m;
        let points: Vec<Vec2> = (0..n)
            .map(|i| {
                sampler.start_pixel_sample(2, 3, i);
                let _ = sampler.next_1d();
                sampler.next_2d()
            })
            .collect();
        for x_bits in 0..=m {
            let (nx, ny) = ((1u32 << x_bits) as f32, (1u32 << (m - x_bits)) as f32);
            let mut seen = vec![false; n as usize];
            for p in &points {
                let cell = (p.x * nx) as usize * (ny as usize) + (p.y * ny) as usize;
                assert!(
                    !seen[cell],
                    "m = {m}, x bits = {x_bits}: two points in one interval"
                );
                seen[cell] = true;
            }
        }
    }
}

#[test]
fn sobol_has_lower_error_than_independent_at_equal_spp() {
    // Per-pixel estimates of ∫∫ exp(-(x² + y²)) over the unit square with
    // 64 samples; the squared error over 1024 pixels measures the variance.
    let exact = {
        let erf1 = 0.842_700_792_949_714_9_f64; // erf(1)
        (std::f64::consts::PI.sqrt() / 2.0 * erf1).powi(2)
    };
    let mse = |kind| {
        let mut total = 0.0;
        for pixel in 0..1024u32 {
            let mut sampler = Sampler::new(kind, 9);
            let mut sum = 0.0;
            for index in 0..64 {
                sampler.start_pixel_sample(pixel, 0, index);
                let p = sampler.next_2d();
                sum += f64::from((-(p.x * p.x + p.y * p.y)).exp());
            }
            total += (sum / 64.0 - exact).powi(2);
        }
        total / 1024.0
    };
    let (independent, sobol) = (mse(SamplerKind::Independent), mse(SamplerKind::Sobol));
    eprintln!("64 spp Gaussian integral MSE: independent {independent:e}, sobol {sobol:e}");
    // Independent: variance / 64 ≈ 6e-4; Owen-scrambled Sobol converges as
    // n^-3 for smooth integrands, orders of magnitude lower at 64 spp.
    assert!(
        sobol < independent / 20.0,
        "sobol {sobol:e} vs independent {independent:e}"
    );
}

/// The sampler composes the scrambles in reversed bit order for speed; its
/// values must be exactly Burley's construction written out plainly:
/// `owen(sobol_d(owen(i, k1)), k2)` per coordinate.
#[test]
fn sobol_values_equal_the_plain_burley_construction() {
    use super::hash::{combine, pixel_hash, unit_f32};
    use super::sobol::{owen_scramble, sobol_dim0, sobol_dim1};
    let seed = 42;
    let mut sampler = Sampler::new(SamplerKind::Sobol, seed);
    for (px, py, index) in [(0, 0, 0), (3, 7, 1), (479, 359, 63), (12, 5, 1_000_003)] {
        sampler.start_pixel_sample(px, py, index);
        let pixel = pixel_hash(seed, px, py);
        // Dimension 0 as a single value, then pairs at 1-2, 3-4, 5-6.
        let key = combine(pixel, 0);
        let j = owen_scramble(index, key as u32);
        let expected = unit_f32(owen_scramble(sobol_dim0(j), (key >> 32) as u32));
        assert_eq!(sampler.next_1d().to_bits(), expected.to_bits());
        for dim in [1u32, 3, 5] {
            let key = combine(pixel, dim);
            let scramble = combine(key, u32::MAX);
            let j = owen_scramble(index, key as u32);
            let x = unit_f32(owen_scramble(sobol_dim0(j), (key >> 32) as u32));
            let y = unit_f32(owen_scramble(sobol_dim1(j), scramble as u32));
            let got = sampler.next_2d();
            assert_eq!(
                (got.x.to_bits(), got.y.to_bits()),
                (x.to_bits(), y.to_bits())
            );
        }
    }
}
