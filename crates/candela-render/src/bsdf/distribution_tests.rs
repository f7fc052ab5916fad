//! Microfacet distributions: normalisation, Smith's masking identity, and
//! visible-normal sampling against its density, for Beckmann and GGX,
//! isotropic and anisotropic.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::{Vec2, Vec3};

use super::distribution::MicrofacetDistribution;
use crate::sampling::chi2::{integrate_2d, Chi2Test};

/// Isotropic and anisotropic roughnesses of both kinds.
fn distributions() -> Vec<MicrofacetDistribution> {
    let mut all = Vec::new();
    for (alpha_x, alpha_y) in [
        (0.05f32, 0.05f32),
        (0.3, 0.3),
        (1.0, 1.0),
        (0.1, 0.6),
        (0.8, 0.2),
    ] {
        all.push(MicrofacetDistribution::Beckmann { alpha_x, alpha_y });
        all.push(MicrofacetDistribution::Ggx { alpha_x, alpha_y });
    }
    all
}

fn direction(theta: f64, phi: f64) -> Vec3 {
    let (s, c) = theta.sin_cos();
    Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32)
}

/// ∫ g over the upper hemisphere, 8 × 16 cells each refined adaptively so
/// that the narrow lobes are resolved.
fn upper_hemisphere_integral(g: impl Fn(Vec3) -> f64) -> f64 {
    let (rows, cols) = (8, 16);
    let (dt, dp) = (FRAC_PI_2 / rows as f64, 2.0 * PI / cols as f64);
    let mut total = 0.0;
    for r in 0..rows {
        for c in 0..cols {
            total += integrate_2d(
                |theta, phi| g(direction(theta, phi)) * theta.sin(),
                (r as f64 * dt, (r + 1) as f64 * dt),
                (c as f64 * dp, (c + 1) as f64 * dp),
            );
        }
    }
    total
}

#[test]
fn projected_microfacet_area_is_one() {
    // ∫ D(m) cos θm dωm = 1: the microfacets project onto the macro surface.
    for dist in distributions() {
        let area = upper_hemisphere_integral(|m| f64::from(dist.d(m)) * f64::from(m.z));
        assert!((area - 1.0).abs() < 2e-3, "{dist:?}: {area}");
    }
}

#[test]
fn smith_lambda_satisfies_the_masking_identity() {
    // Projected visible microfacet area equals the projected macro area:
    // ∫ G1(w) max(0, w·m) D(m) dωm = cos θ, for every w.
    for dist in distributions() {
        for (theta, phi) in [(0.0, 0.0), (0.7, 0.3), (1.3, 1.2), (1.5, 2.5)] {
            let w = direction(theta, phi);
            let visible = upper_hemisphere_integral(|m| f64::from(dist.d(m) * w.dot(m).max(0.0)));
            let lhs = f64::from(dist.g1(w)) * visible;
            assert!(
                (lhs - f64::from(w.z)).abs() < 2e-3 * f64::from(w.z).max(0.1),
                "{dist:?}, θ = {theta}: {lhs} vs {}",
                w.z
            );
        }
    }
}

#[test]
fn visible_normals_match_their_density() {
    for dist in distributions() {
        // Beckmann's sampler solves an equation per sample: fewer samples.
        let samples = match dist {
            MicrofacetDistribution::Beckmann { .. } => 200_000,
            MicrofacetDistribution::Ggx { .. } => 300_000,
        };
        let narrow = dist.alphas().0.min(dist.alphas().1) < 0.1;
        let resolution = if narrow { (41, 81) } else { (21, 41) };
        for (theta, phi) in [(0.0f32, 0.0f32), (0.9, 0.9), (1.56, -0.5)] {
            let wo = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            Chi2Test::sphere(&format!("visible normals {dist:?} θ = {theta}"))
                .with_samples(samples)
                .with_resolution(resolution.0, resolution.1)
                .run(
                    |u| {
                        let m = dist.sample_visible_normal(wo, Vec2::new(u[0], u[1]));
                        Some((m, dist.visible_pdf(wo, m)))
                    },
                    |m| dist.visible_pdf(wo, m),
                )
                .assert_ok();
        }
    }
}

#[test]
fn ggx_matches_its_closed_forms() {
    // D(n) = 1 / (π α²) at the normal; Λ = (√(1 + α² tan²θ) − 1) / 2.
    let dist = MicrofacetDistribution::ggx(0.4);
    assert!((dist.d(Vec3::Z) - 1.0 / (std::f32::consts::PI * 0.16)).abs() < 1e-4);
    let w = Vec3::new(0.6, 0.0, 0.8);
    let expected = ((1.0f32 + 0.16 * 0.75 * 0.75).sqrt() - 1.0) / 2.0;
    assert!((dist.lambda(w) - expected).abs() < 1e-6);
    assert_eq!(dist.lambda(Vec3::Z), 0.0);
    assert_eq!(dist.g1(Vec3::X), 0.0);
    // Anisotropy: α along the direction's azimuth is what counts.
    let aniso = MicrofacetDistribution::Ggx {
        alpha_x: 0.4,
        alpha_y: 0.9,
    };
    assert!((aniso.lambda(w) - expected).abs() < 1e-6);
    let clamped = MicrofacetDistribution::ggx(0.0);
    assert!(clamped.d(Vec3::Z).is_finite());
}
