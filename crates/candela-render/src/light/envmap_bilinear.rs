//! An environment image read bilinearly, and sampled exactly in proportion
//! to a bilinear function, so that radiance and density share one grid.
//!
//! # The grid
//! Values sit on *vertices* in the map's `(u', v)` square, where
//! `u' = u − ½/W` (wrapped into [0, 1)) puts column `i`'s pixel centre at
//! `u' = i/W`; vertex column `W` repeats column 0, so the map wraps across
//! the `u = 0` seam. Vertex rows depend on the convention
//! ([`EnvironmentLookup`]):
//!
//! - `Bilinear` (CS184): row `j` at its pixel centre `v = (j + ½)/H`, plus
//!   a copy of row 0 at the zenith `v = 0` and of row `H − 1` at the nadir
//!   `v = 1`: the lookup is clamped within half a row of each pole.
//! - `BilinearPoleRows` (Mitsuba 3's `envmap`): row `j` at
//!   `v = j/(H − 1)`, the first row on the zenith and the last on the
//!   nadir (a one-row image is constant in `v`).
//!
//! Between vertices a value is the bilinear blend of the cell's four
//! corners.
//!
//! # Sampling
//! The density over `(u', v)` is `g ∝` the bilinear blend of per-vertex
//! weights `Y · s(θ)`: luminance times `s(θ) = max(sin θ, sin(π/4H))`, the
//! mapping's Jacobian kept away from zero at the poles so that the density
//! is positive wherever radiance is (light samples alone stay unbiased).
//! A cell is picked in proportion to its integral (a [`Distribution2D`]
//! over the cells, whose within-cell offsets are uniform and are reused),
//! then a point inside it exactly in proportion to the bilinear patch: `v`
//! from its linear marginal, `u'` from the linear conditional at that `v`.
//! The density per solid angle is `g / (2π² sin θ)`.

use super::luminance;
use crate::sampling::piecewise::Distribution2D;
use candela_scene::EnvironmentLookup;
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// The vertex grid of a bilinearly read map, with its sampling tables.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct BilinearGrid {
    /// Pixel columns `W` (vertex columns are `W + 1`).
    width: usize,
    /// `v` of each vertex row, increasing from 0 to 1.
    rows: Vec<f32>,
    /// Radiance per vertex, row-major, `W + 1` per row.
    radiance: Vec<Vec3>,
    /// Sampling weight per vertex (`Y · s(θ)`), laid out like `radiance`.
    weight: Vec<f32>,
    /// Cells in proportion to their integrals of the weight.
    cells: Distribution2D,
    /// ∫∫ bilinear weight du' dv over the square.
    total: f32,
}

impl BilinearGrid {
    /// The grid of a `width` × `height` image of (scaled) `pixels`, row 0
    /// at the zenith, under `lookup` (not [`EnvironmentLookup::Nearest`]).
    pub(super) fn new(
        pixels: &[Vec3],
        width: usize,
        height: usize,
        lookup: EnvironmentLookup,
    ) -> Self {
        // (v, image row) of each vertex row.
        let layout: Vec<(f64, usize)> = match lookup {
            EnvironmentLookup::BilinearPoleRows if height >= 2 => (0..height)
                .map(|j| (j as f64 / (height - 1) as f64, j))
                .collect(),
            EnvironmentLookup::BilinearPoleRows => vec![(0.0, 0), (1.0, 0)],
            _ => std::iter::once((0.0, 0))
                .chain((0..height).map(|j| ((j as f64 + 0.5) / height as f64, j)))
                .chain(std::iter::once((1.0, height - 1)))
                .collect(),
        };
        let nx = width + 1;
        let floor = (PI / (4.0 * height as f64)).sin();
        let mut radiance = Vec::with_capacity(nx * layout.len());
        let mut weight = Vec::with_capacity(nx * layout.len());
        for &(v, row) in &layout {
            let s = (PI * v).sin().max(floor);
            for i in 0..nx {
                let c = pixels[row * width + i % width];
                radiance.push(c);
                weight.push((f64::from(luminance(c)) * s) as f32);
            }
        }
        let rows: Vec<f32> = layout.iter().map(|&(v, _)| v as f32).collect();
        let mut cell_weights = Vec::with_capacity(width * (rows.len() - 1));
        let mut total = 0.0f64;
        for k in 0..rows.len() - 1 {
            let dv = f64::from(rows[k + 1] - rows[k]);
            for i in 0..width {
                let at = |kk: usize, ii: usize| f64::from(weight[kk * nx + ii]);
                let mean = 0.25 * (at(k, i) + at(k, i + 1) + at(k + 1, i) + at(k + 1, i + 1));
                let integral = mean * dv / width as f64;
                cell_weights.push(integral as f32);
                total += integral;
            }
        }
        Self {
            width,
            rows,
            radiance,
            weight,
            cells: Distribution2D::new(&cell_weights, width),
            total: total as f32,
        }
    }

    /// The cell `(column, row)` holding `(u, v)` and the offsets in it, in
    /// [0, 1]².
    fn locate(&self, uv: Vec2) -> (usize, usize, Vec2) {
        let w = self.width as f32;
        let x = (uv.x - 0.5 / w).rem_euclid(1.0) * w;
        let i = (x as usize).min(self.width - 1);
        let last = self.rows.len() - 2;
        let k = self.rows.partition_point(|&r| r <= uv.y).clamp(1, last + 1) - 1;
        let (v0, v1) = (self.rows[k], self.rows[k + 1]);
        let fy = ((uv.y - v0) / (v1 - v0)).clamp(0.0, 1.0);
        (i, k, Vec2::new((x - i as f32).clamp(0.0, 1.0), fy))
    }

    /// The bilinear blend of `values` (a per-vertex array) at cell `(i, k)`,
    /// offsets `f`.
    fn blend<T>(&self, values: &[T], i: usize, k: usize, f: Vec2) -> T
    where
        T: Copy + std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
    {
        let nx = self.width + 1;
        let at = |kk: usize, ii: usize| values[kk * nx + ii];
        let top = at(k, i) * (1.0 - f.x) + at(k, i + 1) * f.x;
        let bottom = at(k + 1, i) * (1.0 - f.x) + at(k + 1, i + 1) * f.x;
        top * (1.0 - f.y) + bottom * f.y
    }

    /// Radiance at map coordinates `uv`.
    pub(super) fn radiance(&self, uv: Vec2) -> Vec3 {
        let (i, k, f) = self.locate(uv);
        self.blend(&self.radiance, i, k, f)
    }

    /// Density per unit area of `(u, v)` with which [`Self::sample`]
    /// returns `uv`.
    pub(super) fn pdf(&self, uv: Vec2) -> f32 {
        if self.total <= 0.0 {
            return 0.0;
        }
        let (i, k, f) = self.locate(uv);
        self.blend(&self.weight, i, k, f) / self.total
    }

    /// Map coordinates `(u, v)` drawn in proportion to the bilinear weight,
    /// or `None` for an all-black map.
    pub(super) fn sample(&self, u: Vec2) -> Option<Vec2> {
        if self.total <= 0.0 {
            return None;
        }
        let (cell, pdf) = self.cells.sample(u);
        if pdf <= 0.0 {
            return None;
        }
        let n_rows = self.rows.len() - 1;
        let (x, y) = (cell.x * self.width as f32, cell.y * n_rows as f32);
        let (i, k) = (
            (x as usize).min(self.width - 1),
            (y as usize).min(n_rows - 1),
        );
        // The piecewise-constant pick leaves a uniform offset in the cell.
        let (ux, uy) = (
            (x - i as f32).clamp(0.0, 1.0),
            (y - k as f32).clamp(0.0, 1.0),
        );
        let nx = self.width + 1;
        let at = |kk: usize, ii: usize| self.weight[kk * nx + ii];
        let fy = sample_linear(uy, at(k, i) + at(k, i + 1), at(k + 1, i) + at(k + 1, i + 1));
        let left = at(k, i) * (1.0 - fy) + at(k + 1, i) * fy;
        let right = at(k, i + 1) * (1.0 - fy) + at(k + 1, i + 1) * fy;
        let fx = sample_linear(ux, left, right);
        let w = self.width as f32;
        let u_map = ((i as f32 + fx) / w + 0.5 / w).rem_euclid(1.0);
        let v0 = self.rows[k];
        let v = v0 + fy * (self.rows[k + 1] - v0);
        Some(Vec2::new(u_map, v))
    }

    /// ∫ luminance(L(ω)) dω, each cell's radiance taken as its corners'
    /// mean over the cell's solid angle (for the light's power only).
    pub(super) fn luminance_integral(&self) -> f32 {
        let nx = self.width + 1;
        let d_phi = 2.0 * PI / self.width as f64;
        let mut sum = 0.0f64;
        for k in 0..self.rows.len() - 1 {
            let (c0, c1) = (
                (PI * f64::from(self.rows[k])).cos(),
                (PI * f64::from(self.rows[k + 1])).cos(),
            );
            for i in 0..self.width {
                let y = |kk: usize, ii: usize| f64::from(luminance(self.radiance[kk * nx + ii]));
                let mean = 0.25 * (y(k, i) + y(k, i + 1) + y(k + 1, i) + y(k + 1, i + 1));
                sum += mean * d_phi * (c0 - c1);
            }
        }
        sum as f32
    }
}

/// Inverts the CDF of the density on [0, 1] proportional to
/// `(1 − t)·a + t·b` (`a, b ≥ 0`, not both 0) at `u`, in the form that
/// stays exact as `a → b` and at `a = 0`.
pub(super) fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    let (u, a, b) = (f64::from(u), f64::from(a), f64::from(b));
    let denom = a + ((1.0 - u) * a * a + u * b * b).sqrt();
    if denom <= 0.0 {
        return u as f32;
    }
    ((u * (a + b)) / denom).clamp(0.0, 1.0) as f32
}
