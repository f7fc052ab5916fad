//! The directional albedo of a rough GGX reflection lobe with Schlick's
//! Fresnel, for the glTF model's dielectric layer: how much of the light
//! arriving from μ = cos θ the specular layer reflects, so that the Lambert
//! base below it gets exactly the rest (`metallic_roughness`'s
//! `lambert_weight`).
//!
//! Schlick's S = F0 + (F90 − F0)(1 − wo·h)⁵ is linear in F0 and F90, so the
//! albedo of the lobe D·G2·S / (4 μo μi) splits into two numbers that do
//! not depend on them:
//! E(μ) = F0 · A(μ, α) + F90 · B(μ, α), with
//! A = ∫ (1 − (1 − wo·h)⁵) D G2 / (4 μo μi) μi dωi and
//! B = ∫ (1 − wo·h)⁵ D G2 / (4 μo μi) μi dωi
//! (the split Karis 2013 uses for prefiltered environment lighting). Both
//! are tabulated over μ and α = roughness² once, on first use, by our own
//! quadrature: a stratified grid of visible normals (Heitz 2018;
//! `coating.rs`'s `visible_normal_mean`, shared with the coating tables),
//! whose weight per reflected direction is G2 / G1(wo). Their cosine-weighted
//! hemispherical averages Ā = 2∫A μ dμ and B̄ likewise give the layer's
//! average albedo Ē = F0 Ā + F90 B̄. At α = 0 (a delta layer) the row is
//! exact: A = 1 − (1 − μ)⁵, B = (1 − μ)⁵, Schlick at μ itself.

use std::sync::OnceLock;

use glam::Vec3;

use super::coating::visible_normal_mean;
use super::distribution::MicrofacetDistribution;
use super::metallic_roughness::schlick_weight;

/// Grid points in μ = cos θ, from 0 to 1.
const MU_STEPS: usize = 32;
/// Grid points in α, from 0 to 1.
const ALPHA_STEPS: usize = 32;
/// Quadrature points per axis of the visible-normal square, per cell.
const QUADRATURE: usize = 32;
/// The smallest μ integrated (μ = 0 itself has no visible normals).
const MIN_MU: f32 = 1e-3;

/// A(μ, α) and B(μ, α) on the grid, and their averages over μ per α.
pub(super) struct SpecularAlbedo {
    /// `[α][μ]` pairs (A, B).
    table: Vec<[f32; 2]>,
    /// Per α: (Ā, B̄).
    averages: Vec<[f32; 2]>,
}

impl SpecularAlbedo {
    /// The table, built on first use (two 32 × 32 quadratures per grid
    /// node, about 2M visible normals in all; a fraction of a second).
    pub(super) fn get() -> &'static Self {
        static TABLE: OnceLock<SpecularAlbedo> = OnceLock::new();
        TABLE.get_or_init(Self::build)
    }

    fn build() -> Self {
        let mut table = Vec::with_capacity(ALPHA_STEPS * MU_STEPS);
        let mut averages = Vec::with_capacity(ALPHA_STEPS);
        for j in 0..ALPHA_STEPS {
            let alpha = grid(j, ALPHA_STEPS);
            let row: Vec<[f32; 2]> = (0..MU_STEPS)
                .map(|i| split_albedo(grid(i, MU_STEPS), alpha))
                .collect();
            averages.push(cosine_average(&row));
            table.extend(row);
        }
        Self { table, averages }
    }

    /// (A, B) at `mu` and `alpha`, bilinear between grid points.
    pub(super) fn split(&self, mu: f32, alpha: f32) -> [f32; 2] {
        let (j0, j1, tj) = cell(alpha, ALPHA_STEPS);
        let (i0, i1, ti) = cell(mu, MU_STEPS);
        let at = |j: usize, i: usize| self.table[j * MU_STEPS + i];
        let lerp2 =
            |a: [f32; 2], b: [f32; 2], t: f32| [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
        let low = lerp2(at(j0, i0), at(j0, i1), ti);
        let high = lerp2(at(j1, i0), at(j1, i1), ti);
        lerp2(low, high, tj)
    }

    /// (Ā, B̄) at `alpha`, linear between grid rows.
    pub(super) fn average(&self, alpha: f32) -> [f32; 2] {
        let (j0, j1, t) = cell(alpha, ALPHA_STEPS);
        let (a, b) = (self.averages[j0], self.averages[j1]);
        [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
    }

    /// The lobe's albedo at `mu` for Fresnel (F0, F90), per channel.
    pub(super) fn albedo(&self, mu: f32, alpha: f32, f0: Vec3, f90: f32) -> Vec3 {
        let [a, b] = self.split(mu, alpha);
        f0 * a + Vec3::splat(f90 * b)
    }

    /// The lobe's cosine-weighted average albedo for (F0, F90).
    pub(super) fn average_albedo(&self, alpha: f32, f0: Vec3, f90: f32) -> Vec3 {
        let [a, b] = self.average(alpha);
        f0 * a + Vec3::splat(f90 * b)
    }
}

/// Grid point `k` of `n` on [0, 1].
fn grid(k: usize, n: usize) -> f32 {
    k as f32 / (n - 1) as f32
}

/// The grid points around `x` (clamped to [0, 1]) and the fraction between.
fn cell(x: f32, n: usize) -> (usize, usize, f32) {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let s = x * (n - 1) as f32;
    let k = (s as usize).min(n - 2);
    (k, k + 1, s - k as f32)
}

/// (A, B) at one (μ, α) by the stratified visible-normal quadrature; the
/// exact Schlick pair at α = 0.
pub(super) fn split_albedo(mu: f32, alpha: f32) -> [f32; 2] {
    if alpha == 0.0 {
        let s5 = schlick_weight(mu);
        return [1.0 - s5, s5];
    }
    let dist = MicrofacetDistribution::ggx(alpha);
    // f · μi / pdf for a visible-normal sample is G2 / G1(wo); the mean
    // divides by G1, the part of Schlick's weight splits the numerator.
    let part = |weight: fn(f32) -> f32| {
        visible_normal_mean(dist, mu.max(MIN_MU), QUADRATURE, |wo, m, cos_om| {
            let wi = 2.0 * cos_om * m - wo;
            (wi.z > 0.0).then(|| weight(cos_om) * dist.g2(wo, wi))
        })
    };
    [part(|c| 1.0 - schlick_weight(c)), part(schlick_weight)]
}

/// 2∫ v(μ) μ dμ over the grid (trapezoids), per component.
fn cosine_average(row: &[[f32; 2]]) -> [f32; 2] {
    let mut sum = [0.0f64; 2];
    for i in 0..row.len() - 1 {
        let (m0, m1) = (grid(i, MU_STEPS) as f64, grid(i + 1, MU_STEPS) as f64);
        for (c, s) in sum.iter_mut().enumerate() {
            let (v0, v1) = (row[i][c] as f64, row[i + 1][c] as f64);
            // ∫ over [m0, m1] of the linear interpolant times 2μ, exactly.
            let dm = m1 - m0;
            *s += dm * (v0 * (2.0 * m0 + m1) + v1 * (m0 + 2.0 * m1)) / 3.0;
        }
    }
    sum.map(|s| s as f32)
}

#[cfg(test)]
#[path = "specular_albedo_tests.rs"]
mod tests;
