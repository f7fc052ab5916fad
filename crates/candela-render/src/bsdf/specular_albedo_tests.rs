//! The specular-albedo table against an independent estimate: uniform
//! hemisphere sampling of the reflected direction (not the table's
//! visible-normal quadrature), with bounds from its standard error.

use super::*;
use crate::sampling::warp::square_to_uniform_hemisphere;
use crate::sampling::{Sampler, SamplerKind};
use std::f64::consts::PI;

/// (A, B) at (μ, α) by uniform hemisphere sampling, with standard errors.
fn by_uniform_directions(mu: f32, alpha: f32, n: u32, seed: u64) -> ([f64; 2], [f64; 2]) {
    let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    let dist = MicrofacetDistribution::ggx(alpha);
    let mut sampler = Sampler::new(SamplerKind::Independent, seed);
    let (mut sum, mut sum2) = ([0.0f64; 2], [0.0f64; 2]);
    for k in 0..n {
        sampler.start_pixel_sample(0, 0, k);
        let wi = square_to_uniform_hemisphere(sampler.next_2d());
        let h = (wo + wi).normalize();
        let f = dist.d(h) * dist.g2(wo, wi) / (4.0 * wo.z * wi.z);
        // f μi / pdf with pdf = 1 / 2π.
        let v = (f * wi.z) as f64 * 2.0 * PI;
        let s5 = schlick_weight(wo.dot(h)) as f64;
        for (c, x) in [(1.0 - s5) * v, s5 * v].into_iter().enumerate() {
            sum[c] += x;
            sum2[c] += x * x;
        }
    }
    let n = n as f64;
    let mean = sum.map(|s| s / n);
    let err = [0, 1].map(|c| ((sum2[c] / n - mean[c] * mean[c]).max(0.0) / n).sqrt());
    (mean, err)
}

#[test]
fn the_quadrature_agrees_with_uniform_sampling() {
    // Rough lobes only: at small α the uniform estimate's variance explodes.
    for (i, &(mu, alpha)) in [(1.0, 0.3), (0.5, 0.5), (0.2, 0.8), (0.05, 1.0), (0.7, 0.15)]
        .iter()
        .enumerate()
    {
        let table = split_albedo(mu, alpha);
        let (mean, err) = by_uniform_directions(mu, alpha, 400_000, 11 + i as u64);
        for c in 0..2 {
            // 5σ of the estimate plus the quadrature's own error (32² strata).
            let bound = 5.0 * err[c] + 2e-3;
            assert!(
                (table[c] as f64 - mean[c]).abs() < bound,
                "μ={mu} α={alpha} part {c}: quadrature {} against {} ± {}",
                table[c],
                mean[c],
                err[c]
            );
        }
    }
}

#[test]
fn a_smooth_layer_is_schlick_at_mu_itself() {
    for mu in [0.0, 0.1, 0.5, 0.9, 1.0f32] {
        let s5 = (1.0 - mu).powi(5);
        assert_eq!(split_albedo(mu, 0.0), [1.0 - s5, s5]);
    }
}

#[test]
fn the_lookup_follows_the_quadrature_between_grid_points() {
    let table = SpecularAlbedo::get();
    for &(mu, alpha) in &[(0.33, 0.41), (0.77, 0.12), (0.08, 0.93), (0.5, 0.66)] {
        let (looked_up, direct) = (table.split(mu, alpha), split_albedo(mu, alpha));
        for c in 0..2 {
            assert!(
                (looked_up[c] - direct[c]).abs() < 5e-3,
                "μ={mu} α={alpha} part {c}: table {} direct {}",
                looked_up[c],
                direct[c]
            );
        }
    }
}

#[test]
fn the_lobe_never_reflects_more_than_arrives() {
    let table = SpecularAlbedo::get();
    for j in 0..ALPHA_STEPS {
        let alpha = grid(j, ALPHA_STEPS);
        for i in 0..MU_STEPS {
            let [a, b] = table.split(grid(i, MU_STEPS), alpha);
            // F0 = F90 = 1 is a perfect reflector: A + B is the lobe's
            // single-scattering albedo, at most 1.
            assert!(
                a >= 0.0 && b >= 0.0 && a + b <= 1.0 + 1e-3,
                "α={alpha}: {a} + {b}"
            );
        }
        let [a, b] = table.average(alpha);
        assert!(
            a + b <= 1.0 + 1e-3 && a + b > 0.3,
            "α={alpha}: average {a} + {b}"
        );
    }
}
