//! The variance of a pixel's mean estimate: the one definition the film,
//! the EXR `variance` layer, `candela merge` and `candela compare` share.
//!
//! A pixel averages `n` independent samples `x_i`. Its estimate is the
//! sample mean `m = Σx / n`, whose variance `σ²/n` we estimate without bias
//! by
//!
//! ```text
//! s² = (Σx² − (Σx)²/n) / (n − 1)        (sample variance, n − 1 denominator)
//! Var[m] ≈ s² / n
//! ```
//!
//! A pixel with fewer than two samples has no spread to measure: its
//! variance is `+inf` (unknown, which a z-test then treats as "no
//! evidence"), never 0 (which would claim certainty).
//!
//! Independent estimates of the same pixel pool exactly by the parallel
//! algorithm of Chan, Golub and LeVeque ("Updating formulae and a pairwise
//! algorithm for computing sample variances", 1979): with
//! `M2 = (n − 1) · n · Var[m]` the sum of squared deviations of each part,
//! `M2 = M2_a + M2_b + δ² n_a n_b / n` with `δ = m_b − m_a`. This form
//! never subtracts two large sums, so pooling stored `f32` means and
//! variances stays accurate where `Σx² − (Σx)²/n` would cancel.

/// One pixel channel's estimate: sample count, mean and variance of the mean.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanEstimate {
    /// Number of samples (may be fractional after weighting; normally whole).
    pub count: f64,
    /// The sample mean.
    pub mean: f64,
    /// Variance of the mean, [`variance_of_mean`]; `+inf` below two samples.
    pub variance: f64,
}

/// `s² / n` from the sample count and the sums of the samples and of their
/// squares; `+inf` for fewer than two samples. Rounding can make the
/// numerator slightly negative for constant samples: it is clamped at 0.
pub fn variance_of_mean(count: f64, sum: f64, sum_sq: f64) -> f64 {
    if count < 2.0 {
        return f64::INFINITY;
    }
    let spread = (sum_sq - sum * (sum / count)).max(0.0);
    spread / (count - 1.0) / count
}

impl MeanEstimate {
    /// The sum of squared deviations `(n − 1) · n · Var[m]` (0 for one
    /// sample, whose variance is unknown but whose deviation is nil).
    fn squared_deviations(&self) -> f64 {
        if self.count < 2.0 {
            0.0
        } else {
            self.variance * self.count * (self.count - 1.0)
        }
    }

    /// The estimate from both sample sets (Chan et al.). Parts with no
    /// samples drop out.
    pub fn pooled(&self, other: &MeanEstimate) -> MeanEstimate {
        if other.count <= 0.0 {
            return *self;
        }
        if self.count <= 0.0 {
            return *other;
        }
        let n = self.count + other.count;
        let delta = other.mean - self.mean;
        let m2 = self.squared_deviations()
            + other.squared_deviations()
            + delta * delta * (self.count * other.count / n);
        MeanEstimate {
            count: n,
            mean: (self.count * self.mean + other.count * other.mean) / n,
            variance: if n < 2.0 {
                f64::INFINITY
            } else {
                m2 / (n - 1.0) / n
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean and variance of the mean straight from the samples.
    fn direct(samples: &[f64]) -> MeanEstimate {
        let n = samples.len() as f64;
        let sum: f64 = samples.iter().sum();
        let sum_sq: f64 = samples.iter().map(|x| x * x).sum();
        MeanEstimate {
            count: n,
            mean: if n > 0.0 { sum / n } else { 0.0 },
            variance: variance_of_mean(n, sum, sum_sq),
        }
    }

    #[test]
    fn known_variance_with_n_minus_one() {
        // Samples 1, 2, 3, 4: mean 2.5, s² = 5/3, Var[m] = 5/12.
        let e = direct(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(e.mean, 2.5);
        assert!((e.variance - 5.0 / 12.0).abs() < 1e-15);
        assert_eq!(direct(&[7.0]).variance, f64::INFINITY);
        assert_eq!(direct(&[]).variance, f64::INFINITY);
        // Constant samples: zero up to rounding, never negative.
        let constant = direct(&[0.1; 10]).variance;
        assert!((0.0..1e-17).contains(&constant), "{constant}");
    }

    #[test]
    fn pooling_equals_the_union() {
        let samples: Vec<f64> = (0..37).map(|i| ((i * 7919) % 101) as f64 * 0.37).collect();
        for split in [1, 2, 5, 18, 36] {
            let (a, b) = samples.split_at(split);
            let pooled = direct(a).pooled(&direct(b));
            let whole = direct(&samples);
            assert_eq!(pooled.count, whole.count);
            assert!((pooled.mean - whole.mean).abs() < 1e-12 * whole.mean);
            let rel = (pooled.variance - whole.variance).abs() / whole.variance;
            assert!(rel < 1e-12, "split {split}: {pooled:?} vs {whole:?}");
        }
        // A single sample pools as one sample; an empty part drops out.
        let one = direct(&[2.0]).pooled(&direct(&[4.0]));
        assert!((one.variance - direct(&[2.0, 4.0]).variance).abs() < 1e-15);
        assert_eq!(
            direct(&[]).pooled(&direct(&[3.0, 5.0])),
            direct(&[3.0, 5.0])
        );
    }
}
