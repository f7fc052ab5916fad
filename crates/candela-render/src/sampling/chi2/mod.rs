//! One generic chi-square goodness-of-fit harness for every sampling routine
//! in the crate: warps, BSDFs, lights (after Mitsuba's `chi2.py` and pbrt's
//! `bsdfs_test.cpp`).
//!
//! A routine under test maps three uniform numbers to a point and the
//! density it claims for that point; a separate `pdf` closure gives the
//! density the routine is supposed to have. The harness
//! 1. draws `samples` points from a fixed seed and histograms them on a grid
//!    over the domain (θ × φ for the sphere, x × y for a rectangle),
//!    counting failed samples in their own bin;
//! 2. integrates `pdf` over each cell with nested adaptive Simpson
//!    quadrature to get expected counts (the failure bin expects the missing
//!    mass `1 − ∫pdf`);
//! 3. pools cells expecting fewer than 5 samples, computes Pearson's
//!    statistic and its p-value from the incomplete gamma function, and
//!    rejects below 0.01, Šidák-corrected for [`TEST_COUNT`] tests;
//! 4. checks that the claimed density of every sample equals `pdf` there,
//!    and that `pdf` integrates to at most 1 (exactly 1 when the routine
//!    never fails).

mod gamma;
mod quadrature;

pub(crate) use gamma::chi2_p_value;

use glam::{Vec2, Vec3};

use super::{Sampler, SamplerKind};
pub(crate) use quadrature::integrate_2d;
use quadrature::integrate_2d_panels;

/// An upper bound on the number of chi-square tests in the crate, used for
/// the Šidák correction; overestimating only makes each test stricter about
/// rejecting, i.e. more conservative against false alarms. [`Chi2Test::run`]
/// counts the runs of the test process and fails once they exceed it, so
/// the bound cannot silently go stale as tests are added.
pub(crate) const TEST_COUNT: usize = 1000;

/// Chi-square runs so far in this process (see [`TEST_COUNT`]).
static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
/// Overall false-rejection rate of the whole suite.
pub(crate) const SIGNIFICANCE: f64 = 0.01;

/// The domain the histogram covers.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Domain {
    /// Unit directions, gridded in θ ∈ [0, π] × φ ∈ [0, 2π); densities are
    /// per unit solid angle.
    Sphere,
    /// The rectangle `[min, max]` of the plane (the `z` of samples is
    /// ignored); densities are per unit area.
    Plane {
        /// Lower corner.
        min: Vec2,
        /// Upper corner.
        max: Vec2,
    },
}

impl Domain {
    fn bounds(&self) -> (Vec2, Vec2) {
        match *self {
            Domain::Sphere => (
                Vec2::ZERO,
                Vec2::new(std::f32::consts::PI, 2.0 * std::f32::consts::PI),
            ),
            Domain::Plane { min, max } => (min, max),
        }
    }

    fn to_param(self, v: Vec3) -> Vec2 {
        match self {
            Domain::Sphere => {
                let theta = v.z.clamp(-1.0, 1.0).acos();
                let mut phi = v.y.atan2(v.x);
                if phi < 0.0 {
                    phi += 2.0 * std::f32::consts::PI;
                }
                Vec2::new(theta, phi)
            }
            Domain::Plane { .. } => v.truncate(),
        }
    }

    /// The point at parameters (s, t) and the Jacobian |d point / d(s, t)|.
    fn point_at(self, s: f64, t: f64) -> (Vec3, f64) {
        match self {
            Domain::Sphere => {
                let (sin_t, cos_t) = s.sin_cos();
                let (sin_p, cos_p) = t.sin_cos();
                let v = Vec3::new((sin_t * cos_p) as f32, (sin_t * sin_p) as f32, cos_t as f32);
                (v, sin_t.abs())
            }
            Domain::Plane { .. } => (Vec3::new(s as f32, t as f32, 0.0), 1.0),
        }
    }
}

/// A configured chi-square test.
#[derive(Clone, Debug)]
pub(crate) struct Chi2Test {
    name: String,
    domain: Domain,
    resolution: (usize, usize),
    samples: usize,
    seed: u64,
    panels: usize,
}

/// Everything a chi-square run measured, for assertions and messages.
#[derive(Clone, Debug)]
pub(crate) struct Chi2Outcome {
    /// Name of the routine under test.
    pub name: String,
    /// Pearson's statistic over the pooled bins.
    pub statistic: f64,
    /// Degrees of freedom (pooled bins − 1).
    pub dof: usize,
    /// Upper-tail probability of the statistic.
    pub p_value: f64,
    /// The Šidák-corrected rejection threshold for `p_value`.
    pub threshold: f64,
    /// ∫ pdf over the domain by quadrature.
    pub pdf_integral: f64,
    /// Fraction of samples the routine rejected.
    pub failure_fraction: f64,
    /// Largest relative difference between a sample's claimed pdf and `pdf`.
    pub worst_pdf_mismatch: f64,
}

impl Chi2Test {
    /// A test over the sphere of directions with a 21 × 41 grid: odd
    /// resolutions keep cell edges off the axes and the horizon, where
    /// warps tend to have their seams.
    pub(crate) fn sphere(name: &str) -> Self {
        Self::new(name, Domain::Sphere, (21, 41))
    }

    /// A test over the rectangle `[min, max]` with a 31 × 31 grid.
    pub(crate) fn plane(name: &str, min: Vec2, max: Vec2) -> Self {
        Self::new(name, Domain::Plane { min, max }, (31, 31))
    }

    fn new(name: &str, domain: Domain, resolution: (usize, usize)) -> Self {
        Self {
            name: name.to_string(),
            domain,
            resolution,
            samples: 1_000_000,
            seed: 0x5eed,
            panels: 4,
        }
    }

    /// Overrides the grid resolution (rows along the first parameter).
    pub(crate) fn with_resolution(mut self, rows: usize, cols: usize) -> Self {
        self.resolution = (rows, cols);
        self
    }

    /// Starts the per-cell quadrature from `panels` × `panels` panels (4 by
    /// default): densities with hard edges, such as lights seen from a
    /// point, need more so that cells the edge cuts are integrated right.
    pub(crate) fn with_quadrature_panels(mut self, panels: usize) -> Self {
        self.panels = panels.max(1);
        self
    }

    /// Overrides the number of samples.
    pub(crate) fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// Runs the test: `sample` maps three uniform numbers to a point and the
    /// density it claims (or `None` when it rejects the sample); `pdf` is the
    /// density the routine should have.
    pub(crate) fn run(
        &self,
        mut sample: impl FnMut([f32; 3]) -> Option<(Vec3, f32)>,
        pdf: impl Fn(Vec3) -> f32,
    ) -> Chi2Outcome {
        let runs = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        assert!(
            runs <= TEST_COUNT,
            "{runs} chi-square runs: raise TEST_COUNT so the Šidák correction holds"
        );
        let (rows, cols) = self.resolution;
        let (lo, hi) = self.domain.bounds();
        let cell = (hi - lo) / Vec2::new(rows as f32, cols as f32);
        let mut observed = vec![0f64; rows * cols + 1];
        let mut worst_mismatch = 0f64;
        let mut sampler = Sampler::new(SamplerKind::Independent, self.seed);
        for i in 0..self.samples {
            sampler.start_pixel_sample(0, 0, i as u32);
            let u = [sampler.next_1d(), sampler.next_1d(), sampler.next_1d()];
            let Some((point, claimed)) = sample(u) else {
                observed[rows * cols] += 1.0;
                continue;
            };
            let expected = pdf(point);
            let mismatch = (claimed - expected).abs() / expected.abs().max(claimed.abs()).max(1e-6);
            worst_mismatch = worst_mismatch.max(f64::from(mismatch));
            let p = (self.domain.to_param(point) - lo) / cell;
            let r = (p.x.max(0.0) as usize).min(rows - 1);
            let c = (p.y.max(0.0) as usize).min(cols - 1);
            observed[r * cols + c] += 1.0;
        }

        let n = self.samples as f64;
        let mut expected = Vec::with_capacity(rows * cols + 1);
        let mut pdf_integral = 0.0;
        for r in 0..rows {
            for c in 0..cols {
                let s0 = f64::from(lo.x) + r as f64 * f64::from(cell.x);
                let t0 = f64::from(lo.y) + c as f64 * f64::from(cell.y);
                let mass = integrate_2d_panels(
                    |s, t| {
                        let (point, jacobian) = self.domain.point_at(s, t);
                        f64::from(pdf(point)) * jacobian
                    },
                    (s0, s0 + f64::from(cell.x)),
                    (t0, t0 + f64::from(cell.y)),
                    self.panels,
                );
                pdf_integral += mass;
                expected.push(mass * n);
            }
        }
        expected.push((1.0 - pdf_integral).max(0.0) * n);

        let (statistic, dof) = pearson_pooled(&observed, &expected);
        Chi2Outcome {
            name: self.name.clone(),
            statistic,
            dof,
            p_value: chi2_p_value(statistic, dof),
            threshold: 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / TEST_COUNT as f64),
            pdf_integral,
            failure_fraction: observed[rows * cols] / n,
            worst_pdf_mismatch: worst_mismatch,
        }
    }
}

/// The chi-square test of a discrete choice: `counts[i]` draws of outcome
/// `i` (the last entry counting failed draws) against the probabilities
/// `pmf` of the outcomes (failures expect the missing mass `1 − Σ pmf`).
/// Counts toward [`TEST_COUNT`] like [`Chi2Test::run`]; the outcome's
/// `pdf_integral` is `Σ pmf`.
pub(crate) fn discrete_fit(name: &str, counts: &[u64], pmf: &[f64]) -> Chi2Outcome {
    let runs = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
    assert!(
        runs <= TEST_COUNT,
        "{runs} chi-square runs: raise TEST_COUNT so the Šidák correction holds"
    );
    assert_eq!(
        counts.len(),
        pmf.len() + 1,
        "one count per outcome plus failures"
    );
    let n: u64 = counts.iter().sum();
    let total: f64 = pmf.iter().sum();
    let mut expected: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
    expected.push((1.0 - total).max(0.0) * n as f64);
    let observed: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
    let (statistic, dof) = pearson_pooled(&observed, &expected);
    Chi2Outcome {
        name: name.to_string(),
        statistic,
        dof,
        p_value: chi2_p_value(statistic, dof),
        threshold: 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / TEST_COUNT as f64),
        pdf_integral: total,
        failure_fraction: counts[pmf.len()] as f64 / n.max(1) as f64,
        worst_pdf_mismatch: 0.0,
    }
}

/// Pearson's statistic with cells expecting fewer than 5 samples pooled into
/// one bin (merged into the smallest regular bin if the pool is still too
/// small). Returns the statistic and the degrees of freedom.
///
/// A sample in a cell expecting (almost) none is an outright rejection
/// (infinite statistic): pooling would otherwise hide a routine that puts
/// samples where its pdf is zero. The chance of a false alarm per cell is at
/// most its expected count, below [`IMPOSSIBLE`].
pub(crate) fn pearson_pooled(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    const MIN_EXPECTED: f64 = 5.0;
    const IMPOSSIBLE: f64 = 1e-6;
    if observed
        .iter()
        .zip(expected)
        .any(|(&o, &e)| e < IMPOSSIBLE && o > 0.0)
    {
        return (f64::INFINITY, observed.len().saturating_sub(1).max(1));
    }
    let mut bins: Vec<(f64, f64)> = Vec::new();
    let (mut pool_obs, mut pool_exp) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e < MIN_EXPECTED {
            pool_obs += o;
            pool_exp += e;
        } else {
            bins.push((o, e));
        }
    }
    if pool_exp >= MIN_EXPECTED || bins.is_empty() {
        bins.push((pool_obs, pool_exp));
    } else if let Some(smallest) = bins.iter_mut().min_by(|a, b| a.1.total_cmp(&b.1)) {
        smallest.0 += pool_obs;
        smallest.1 += pool_exp;
    }
    let statistic = bins
        .iter()
        .map(|&(o, e)| {
            if e > 0.0 {
                (o - e) * (o - e) / e
            } else if o > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        })
        .sum();
    (statistic, bins.len().saturating_sub(1).max(1))
}

impl Chi2Outcome {
    /// Whether the statistic is acceptable at the corrected significance.
    pub(crate) fn passed(&self) -> bool {
        self.p_value >= self.threshold
    }

    /// One line for logs: name, statistic, degrees of freedom, p-value.
    pub(crate) fn summary(&self) -> String {
        format!(
            "{}: chi2 = {:.1} with {} dof, p = {:.3e} (threshold {:.1e}), integral {:.5}",
            self.name, self.statistic, self.dof, self.p_value, self.threshold, self.pdf_integral
        )
    }

    /// Asserts the fit, the agreement of claimed and true densities, and the
    /// normalisation of `pdf` (exactly 1 when the routine never fails).
    pub(crate) fn assert_ok(&self) {
        eprintln!("{}", self.summary());
        assert!(self.passed(), "chi-square rejects {self:#?}");
        assert!(
            self.worst_pdf_mismatch < 2e-3,
            "claimed pdf differs from pdf: {self:#?}"
        );
        assert!(
            self.pdf_integral < 1.0 + 2e-3,
            "pdf integrates above 1: {self:#?}"
        );
        if self.failure_fraction == 0.0 {
            assert!(
                self.pdf_integral > 1.0 - 2e-3,
                "pdf integrates below 1: {self:#?}"
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pooling_merges_sparse_cells() {
        let observed = [10.0, 1.0, 2.0, 0.0];
        let expected = [10.0, 1.0, 2.5, 0.5];
        // The three sparse cells pool to 4 < 5, so they join the single bin.
        let (stat, dof) = pearson_pooled(&observed, &expected);
        assert_eq!(dof, 1);
        assert!((stat - (13.0f64 - 14.0).powi(2) / 14.0).abs() < 1e-12);
    }

    #[test]
    fn observed_samples_where_none_are_expected_reject() {
        let (stat, _) = pearson_pooled(&[500.0, 500.0, 1.0], &[1000.0, 1.0, 0.0]);
        assert!(stat.is_infinite());
        assert_eq!(chi2_p_value(stat, 2), 0.0);
    }
}
