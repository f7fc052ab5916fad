//! The sheen lobe's directional albedo E(μ, r) = ∫ D V cos θi dωi per unit
//! sheen colour (`sheen.rs`), which scales the base beneath the sheen:
//! tabulated once per process (built on first use, `OnceLock`) over the
//! cosine μ and the perceptual roughness r, read bilinearly.
//!
//! The table is our own quadrature of the lobe (no published table): a
//! midpoint rule over (cos θi, φi), which sees the whole hemisphere evenly.
//! The integrand is continuous there: at the horizon the fitted Λ(μi)
//! (about e¹⁷ at μi = 0) drives the visibility to 0, so no edge cuts the
//! grid. At [`GRID`] it agrees with a grid twice as fine within 10⁻⁴
//! (checked in `sheen_tests.rs`, which also checks entries against an
//! independent Monte Carlo estimate through the BSDF's own `f`).
//!
//! Nodes: μ at (j / (N − 1))², so that they crowd where E changes fastest,
//! near the horizon; r uniform from √[`MIN_ALPHA`] (anything smoother is
//! the same lobe, α being clamped) to 1. Bilinear lookups between them are
//! within 0.005 of the quadrature (`sheen_tests.rs`). Building the table
//! (32 × 16 entries) takes about 0.1 s, once per process, on the first
//! sheen met.

use std::sync::OnceLock;

use glam::Vec3;

use super::sheen::{sheen_value_from, Shadowing, MIN_ALPHA};

/// Nodes along √μ.
const COSINES: usize = 32;
/// Nodes along the perceptual roughness.
const ROUGHNESSES: usize = 16;
/// Midpoint nodes per axis of (cos θi, φi ∈ [0, π]) per entry.
pub(super) const GRID: usize = 96;

/// E at every node: `values[k][j]` for roughness node k, cosine node j.
struct SheenAlbedoTable {
    values: [[f32; COSINES]; ROUGHNESSES],
}

static TABLE: OnceLock<SheenAlbedoTable> = OnceLock::new();

/// E(μ, r): the sheen's albedo at cosine `cos` (either side) for perceptual
/// roughness `roughness`, bilinear between the table's nodes.
pub(super) fn sheen_albedo(cos: f32, roughness: f32) -> f32 {
    let table = TABLE.get_or_init(SheenAlbedoTable::compute);
    let x = cos.abs().min(1.0).sqrt() * (COSINES - 1) as f32;
    let y = ((roughness - min_roughness()) / (1.0 - min_roughness())).clamp(0.0, 1.0)
        * (ROUGHNESSES - 1) as f32;
    let (j, k) = (
        (x as usize).min(COSINES - 2),
        (y as usize).min(ROUGHNESSES - 2),
    );
    let (wx, wy) = (x - j as f32, y - k as f32);
    let row = |k: usize| table.values[k][j] * (1.0 - wx) + table.values[k][j + 1] * wx;
    row(k) * (1.0 - wy) + row(k + 1) * wy
}

/// The cosine of node `j`.
pub(super) fn cosine_node(j: usize) -> f32 {
    let s = j as f32 / (COSINES - 1) as f32;
    s * s
}

/// The perceptual roughness of node `k`.
pub(super) fn roughness_node(k: usize) -> f32 {
    min_roughness() + (1.0 - min_roughness()) * k as f32 / (ROUGHNESSES - 1) as f32
}

/// The number of (cosine, roughness) nodes.
#[cfg(test)]
pub(super) const NODES: (usize, usize) = (COSINES, ROUGHNESSES);

/// The smallest perceptual roughness the table tells apart, √[`MIN_ALPHA`].
fn min_roughness() -> f32 {
    MIN_ALPHA.sqrt()
}

impl SheenAlbedoTable {
    fn compute() -> Self {
        let mut values = [[0.0; COSINES]; ROUGHNESSES];
        for (k, row) in values.iter_mut().enumerate() {
            let r = roughness_node(k);
            let alpha = (r * r).max(MIN_ALPHA);
            for (j, e) in row.iter_mut().enumerate() {
                *e = directional_albedo(cosine_node(j), alpha, GRID);
            }
        }
        Self { values }
    }
}

/// ∫ D V cos θi dωi at cosine `cos` and α `alpha`, by a `grid` × `grid`
/// midpoint rule over (t, φi) ∈ [0, 1] × [0, π] with cos θi = [`crowded`]
/// (t) (see the module docs), doubled for the mirror half (wo lies in the
/// xz plane).
pub(super) fn directional_albedo(cos: f32, alpha: f32, grid: usize) -> f32 {
    let wo = Vec3::new((1.0 - cos * cos).max(0.0).sqrt(), 0.0, cos);
    let o = Shadowing::at(cos, alpha);
    let step = 1.0 / grid as f64;
    let azimuths: Vec<(f32, f32)> = (0..grid)
        .map(|b| (((b as f64 + 0.5) * step * std::f64::consts::PI) as f32).sin_cos())
        .collect();
    let mut sum = 0.0f64;
    for a in 0..grid {
        let (cos_i, jacobian) = crowded((a as f64 + 0.5) * step);
        let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
        let i = Shadowing::at(cos_i, alpha);
        let mut row = 0.0f64;
        for &(sin_phi, cos_phi) in &azimuths {
            let wi = Vec3::new(sin_i * cos_phi, sin_i * sin_phi, cos_i);
            row += f64::from(sheen_value_from(wo, wi, alpha, o, i));
        }
        sum += row * f64::from(cos_i) * jacobian;
    }
    // Each cell is step × (π step) of (t, φi); the mirror half doubles.
    (sum * step * step * std::f64::consts::TAU) as f32
}

/// cos θi = g(t) = t⁵ / (t⁵ + (1 − t)²) and dg/dt: nodes crowd at the
/// horizon, where the fitted Λ(μ) changes as μ^0.2 does (g ≈ t⁵ makes that
/// smooth in t), and at the normal, where D at normal incidence changes as
/// √(1 − μ) does for α = 1 (1 − g ≈ (1 − t)² makes that smooth).
fn crowded(t: f64) -> (f32, f64) {
    let (t5, s2) = (t.powi(5), (1.0 - t) * (1.0 - t));
    let den = t5 + s2;
    let g = t5 / den;
    let dg = (5.0 * t.powi(4) * s2 + 2.0 * t5 * (1.0 - t)) / (den * den);
    (g as f32, dg)
}
