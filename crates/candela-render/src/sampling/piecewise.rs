//! Piecewise-constant distributions on [0, 1) and [0, 1)², sampled by
//! inverting their CDFs (pbrt's `PiecewiseConstant1D/2D`).
//!
//! A 2-D distribution over a grid of `nu × nv` cells is a marginal density
//! over rows (`v`) and one conditional density per row over columns (`u`):
//! `p(u, v) = p(v) p(u | v) = f(u, v) / ∫∫ f`. Both steps are invertible, so
//! every sample has an inverse ([`Distribution2D::invert`]) that tests use
//! to check round trips. Cells of zero weight are never sampled; a
//! distribution whose weights are all zero falls back to uniform, so it
//! stays a valid density (callers that care check
//! [`Distribution1D::integral`]).

use glam::Vec2;

/// A piecewise-constant density over [0, 1) with `n` equal cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution1D {
    /// Non-negative weight per cell (uniform if all were zero).
    func: Vec<f32>,
    /// `cdf[i]` = probability of the cells before `i`; `n + 1` entries,
    /// `cdf[n] = 1`.
    cdf: Vec<f32>,
    /// ∫ f over [0, 1) as given (0 for an all-zero input).
    integral: f32,
    /// Mean of `func` (after the uniform fallback): the density's
    /// normalisation.
    mean: f32,
}

impl Distribution1D {
    /// Builds the distribution of `weights` (negative and non-finite
    /// weights count as zero). An empty slice gives one uniform cell.
    pub fn new(weights: &[f32]) -> Self {
        let mut func: Vec<f32> = weights
            .iter()
            .map(|&w| if w.is_finite() && w > 0.0 { w } else { 0.0 })
            .collect();
        if func.is_empty() {
            func.push(0.0);
        }
        let n = func.len() as f64;
        let sum: f64 = func.iter().map(|&w| f64::from(w)).sum();
        let integral = (sum / n) as f32;
        if sum <= 0.0 {
            func.iter_mut().for_each(|w| *w = 1.0);
        }
        let total: f64 = func.iter().map(|&w| f64::from(w)).sum();
        let mut cdf = Vec::with_capacity(func.len() + 1);
        let mut running = 0.0f64;
        cdf.push(0.0);
        for &w in &func {
            running += f64::from(w);
            cdf.push((running / total) as f32);
        }
        // Rounding must not leave the last entry short of 1.
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Self {
            mean: (total / n) as f32,
            func,
            cdf,
            integral: if sum > 0.0 { integral } else { 0.0 },
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// Always false: there is at least one cell.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// ∫ f over [0, 1) of the weights given (0 if they were all zero).
    pub fn integral(&self) -> f32 {
        self.integral
    }

    /// Maps `u` in [0, 1) to `(x, pdf(x), cell)`.
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.len();
        let i = self
            .cdf
            .partition_point(|&c| c <= u)
            .saturating_sub(1)
            .min(n - 1);
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let du = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let x = ((i as f32 + du) / n as f32).min(1.0 - f32::EPSILON / 2.0);
        (x, self.pdf_of_cell(i), i)
    }

    /// The density at `x` (0 outside [0, 1)).
    pub fn pdf(&self, x: f32) -> f32 {
        if !(0.0..1.0).contains(&x) {
            return 0.0;
        }
        self.pdf_of_cell(self.cell_of(x))
    }

    /// The cell holding `x` in [0, 1).
    pub fn cell_of(&self, x: f32) -> usize {
        ((x * self.len() as f32) as usize).min(self.len() - 1)
    }

    fn pdf_of_cell(&self, i: usize) -> f32 {
        self.func[i] / self.mean
    }

    /// The `u` that [`Distribution1D::sample`] maps to `x` (for `x` in a
    /// cell of non-zero density).
    pub fn invert(&self, x: f32) -> f32 {
        let n = self.len();
        let i = self.cell_of(x);
        let du = x * n as f32 - i as f32;
        self.cdf[i] + du * (self.cdf[i + 1] - self.cdf[i])
    }
}

/// A piecewise-constant density over [0, 1)² on a grid of `nu` columns
/// (along `u`) by `nv` rows (along `v`).
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2D {
    conditional: Vec<Distribution1D>,
    marginal: Distribution1D,
}

impl Distribution2D {
    /// Builds the distribution of `weights`, row-major (`weights[row * nu +
    /// col]`, `nv = weights.len() / nu` rows). `nu` of 0 is treated as 1.
    pub fn new(weights: &[f32], nu: usize) -> Self {
        let nu = nu.max(1);
        let conditional: Vec<Distribution1D> = if weights.is_empty() {
            vec![Distribution1D::new(&[])]
        } else {
            weights.chunks(nu).map(Distribution1D::new).collect()
        };
        let row_integrals: Vec<f32> = conditional.iter().map(|d| d.integral()).collect();
        let marginal = Distribution1D::new(&row_integrals);
        Self {
            conditional,
            marginal,
        }
    }

    /// ∫∫ f over the unit square of the weights given.
    pub fn integral(&self) -> f32 {
        self.marginal.integral()
    }

    /// Maps `u` in [0, 1)² to a point and its density: `u.y` picks the row
    /// from the marginal, `u.x` the column within it.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (v, pdf_v, row) = self.marginal.sample(u.y);
        let (x, pdf_u, _) = self.conditional[row].sample(u.x);
        (Vec2::new(x, v), pdf_v * pdf_u)
    }

    /// The density at `p` (0 outside the unit square).
    pub fn pdf(&self, p: Vec2) -> f32 {
        let pdf_v = self.marginal.pdf(p.y);
        if pdf_v == 0.0 {
            return 0.0;
        }
        let row = self.marginal.cell_of(p.y);
        pdf_v * self.conditional[row].pdf(p.x)
    }

    /// The `u` that [`Distribution2D::sample`] maps to `p`.
    pub fn invert(&self, p: Vec2) -> Vec2 {
        let row = self.marginal.cell_of(p.y);
        Vec2::new(self.conditional[row].invert(p.x), self.marginal.invert(p.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::Chi2Test;
    use glam::Vec3;

    fn bumpy(nu: usize, nv: usize) -> Vec<f32> {
        (0..nu * nv)
            .map(|k| {
                let (c, r) = ((k % nu) as f32, (k / nu) as f32);
                let spot = if (c - 3.0).abs() < 1.0 && (r - 2.0).abs() < 1.0 {
                    40.0
                } else {
                    0.0
                };
                // A zero column and a zero row test the empty cells.
                if c == 5.0 || r == 6.0 {
                    0.0
                } else {
                    0.2 + 0.1 * c + spot
                }
            })
            .collect()
    }

    #[test]
    fn one_dimensional_cdf_and_pdf_match_the_weights() {
        let d = Distribution1D::new(&[1.0, 0.0, 3.0]);
        assert!((d.integral() - 4.0 / 3.0).abs() < 1e-6);
        assert!((d.pdf(0.1) - 0.75).abs() < 1e-6);
        assert_eq!(d.pdf(0.5), 0.0);
        assert!((d.pdf(0.9) - 2.25).abs() < 1e-6);
        // u = 0.25 ends the first cell; anything above skips the empty one.
        let (x, pdf, cell) = d.sample(0.5);
        assert_eq!(cell, 2);
        assert!((x - (2.0 + 1.0 / 3.0) / 3.0).abs() < 1e-6, "{x}");
        assert!((pdf - 2.25).abs() < 1e-6);
        for u in [0.0, 0.1, 0.2499, 0.26, 0.7, 0.9999] {
            let (x, _, _) = d.sample(u);
            assert!((d.invert(x) - u).abs() < 1e-5, "{u} -> {x}");
        }
    }

    #[test]
    fn all_zero_weights_fall_back_to_uniform() {
        let d = Distribution2D::new(&[0.0; 6], 3);
        assert_eq!(d.integral(), 0.0);
        let (p, pdf) = d.sample(Vec2::new(0.3, 0.8));
        assert!((p - Vec2::new(0.3, 0.8)).length() < 1e-6);
        assert!((pdf - 1.0).abs() < 1e-6);
    }

    #[test]
    fn two_dimensional_sampling_inverts_exactly() {
        let (nu, nv) = (8, 7);
        let d = Distribution2D::new(&bumpy(nu, nv), nu);
        for i in 0..50 {
            let u = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 + 0.5) / 50.0);
            let (p, pdf) = d.sample(u);
            assert!(pdf > 0.0);
            assert!((d.pdf(p) - pdf).abs() <= 1e-5 * pdf);
            assert!((d.invert(p) - u).abs().max_element() < 1e-4, "{u} -> {p}");
        }
    }

    #[test]
    fn two_dimensional_sampling_matches_its_pdf() {
        let (nu, nv) = (8, 7);
        let d = Distribution2D::new(&bumpy(nu, nv), nu);
        // The exact integral: the mean of the weights.
        let weights = bumpy(nu, nv);
        let mean = weights.iter().sum::<f32>() / weights.len() as f32;
        assert!((d.integral() - mean).abs() < 1e-5 * mean);
        let outcome = Chi2Test::plane("distribution 2d", Vec2::ZERO, Vec2::ONE)
            // Cell edges of the test grid off the distribution's.
            .with_resolution(27, 29)
            .run(
                |u| {
                    let (p, pdf) = d.sample(Vec2::new(u[1], u[2]));
                    Some((Vec3::new(p.x, p.y, 0.0), pdf))
                },
                |p| d.pdf(Vec2::new(p.x, p.y)),
            );
        outcome.assert_ok();
    }
}
