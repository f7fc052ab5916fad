//! Adaptive sampling, the CS184 rule (Part 5).
//!
//! Every `batch` samples a pixel computes the mean μ and standard deviation
//! σ of its samples' illuminance over its n samples, and stops once the 95%
//! confidence half-width `I = 1.96 σ / √n` is at most `tolerance · μ`.
//! The rule reads only the pixel's own sums, checked at fixed sample counts,
//! so an adaptive render is as deterministic as a uniform one.

/// Adaptive-sampling settings (`-a BATCH TOL`; the course uses `-a 64 0.05`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Adaptive {
    /// Samples between two convergence checks of a pixel.
    pub batch: u32,
    /// Largest accepted confidence half-width, relative to the mean.
    pub tolerance: f64,
}

impl Default for Adaptive {
    /// The CS184 course setting.
    fn default() -> Self {
        Self {
            batch: 64,
            tolerance: 0.05,
        }
    }
}

/// z of a two-sided 95% confidence interval, as in CS184.
pub const Z_95: f64 = 1.96;

/// Whether a pixel whose `n` samples of illuminance have sum `s1` and sum of
/// squares `s2` has converged to `tolerance`: `1.96 σ / √n ≤ tolerance · μ`.
///
/// A black pixel (all samples zero) has μ = σ = 0 and stops, with no division
/// by zero. Fewer than two samples cannot estimate σ, so they never
/// converge.
pub fn converged(n: u32, s1: f64, s2: f64, tolerance: f64) -> bool {
    if n < 2 {
        return false;
    }
    let n = n as f64;
    let mean = s1 / n;
    // Rounding can make the numerator slightly negative for constant pixels.
    let variance = ((s2 - s1 * mean) / (n - 1.0)).max(0.0);
    Z_95 * (variance / n).sqrt() <= tolerance * mean
}

impl Adaptive {
    /// Whether a pixel that has taken `taken` samples in this render, with
    /// illuminance sums `s1` and `s2`, should stop: only at multiples of the
    /// batch, and only if [`converged`].
    pub fn should_stop(&self, taken: u32, s1: f64, s2: f64) -> bool {
        let batch = self.batch.max(1);
        taken.is_multiple_of(batch) && converged(taken, s1, s2, self.tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `stream` through the rule in batches; returns the sample count
    /// at which the pixel stops, or `None` if it uses the whole stream.
    fn stop_at(adaptive: &Adaptive, stream: impl IntoIterator<Item = f64>) -> Option<u32> {
        let (mut n, mut s1, mut s2) = (0u32, 0.0, 0.0);
        for y in stream {
            n += 1;
            s1 += y;
            s2 += y * y;
            if adaptive.should_stop(n, s1, s2) {
                return Some(n);
            }
        }
        None
    }

    /// A deterministic uniform stream in [0, 1) (a 64-bit LCG).
    fn uniform(seed: u64, n: usize) -> Vec<f64> {
        let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        (0..n)
            .map(|_| {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (state >> 11) as f64 / (1u64 << 53) as f64
            })
            .collect()
    }

    #[test]
    fn black_pixel_stops_at_the_first_check() {
        let a = Adaptive::default();
        assert_eq!(stop_at(&a, vec![0.0; 2048]), Some(64));
        assert!(converged(64, 0.0, 0.0, 0.05));
    }

    #[test]
    fn constant_pixel_stops_at_the_first_check() {
        // Zero variance up to rounding, which the clamp absorbs.
        let a = Adaptive::default();
        assert_eq!(stop_at(&a, vec![0.1; 2048]), Some(64));
    }

    #[test]
    fn too_few_samples_never_converge() {
        assert!(!converged(0, 0.0, 0.0, 0.05));
        assert!(!converged(1, 5.0, 25.0, 0.05));
        let a = Adaptive {
            batch: 1,
            tolerance: 0.05,
        };
        assert_eq!(stop_at(&a, vec![0.0; 4]), Some(2));
    }

    #[test]
    fn checks_only_at_batch_multiples() {
        let a = Adaptive {
            batch: 10,
            tolerance: 0.05,
        };
        assert!(!a.should_stop(15, 0.0, 0.0));
        assert!(a.should_stop(20, 0.0, 0.0));
    }

    #[test]
    fn uniform_noise_stops_where_the_interval_predicts() {
        // U(0,1): μ = 1/2, σ² = 1/12. I ≤ tol·μ needs
        // n ≥ (1.96 σ / (tol μ))² = 1.96² / (3 tol²) ≈ 512 at tol = 0.05.
        let a = Adaptive::default();
        let expected = Z_95 * Z_95 / (3.0 * 0.05 * 0.05);
        for seed in 0..8 {
            let n = stop_at(&a, uniform(seed, 4096)).expect("converges within 4096") as f64;
            // At n ≈ 500 the estimated σ and μ each wander by 2-3%, so the
            // threshold moves by ~7% (one standard deviation); allow ±2 batches.
            assert!(
                (expected - 128.0..=expected + 192.0).contains(&n),
                "seed {seed}: stopped at {n}, expected about {expected:.0}"
            );
        }
    }

    #[test]
    fn single_outlier_delays_convergence() {
        // 1000 samples of 0.1 and one of 100: the outlier dominates σ.
        let a = Adaptive::default();
        let mut stream = vec![0.1; 4096];
        stream[10] = 100.0;
        let stop = stop_at(&a, stream.clone());
        // With the outlier, σ ≈ 100/√n and μ ≈ 0.1 + 100/n, so the interval
        // 1.96·100/n ≤ 0.05·(0.1 n + 100)/n needs 0.005 n ≥ 191: n ≥ 38 200.
        assert_eq!(stop, None, "an outlier pixel must keep sampling");
        // Without it the same stream stops at once.
        stream[10] = 0.1;
        assert_eq!(stop_at(&a, stream), Some(64));
        // And it does converge once n is large enough.
        let (n, s1, s2) = (38_400u32, 0.1 * 38_399.0 + 100.0, 0.01 * 38_399.0 + 1e4);
        assert!(converged(n, s1, s2, 0.05));
        assert!(!converged(
            30_000,
            0.1 * 29_999.0 + 100.0,
            0.01 * 29_999.0 + 1e4,
            0.05
        ));
    }
}
