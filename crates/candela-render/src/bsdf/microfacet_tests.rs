//! Rough conductor: chi-square, consistency, and energy.

use glam::Vec3;

use super::test_support::*;
use super::Masking;
use super::{Bsdf, MicrofacetDistribution};

/// Gold-like complex IOR (RGB), as in CS184's scenes.
const GOLD_ETA: Vec3 = Vec3::new(0.143, 0.375, 1.442);
const GOLD_K: Vec3 = Vec3::new(3.983, 2.386, 1.603);

fn gold(alpha: f32) -> Bsdf {
    gold_on(MicrofacetDistribution::beckmann(alpha))
}

fn gold_on(distribution: MicrofacetDistribution) -> Bsdf {
    Bsdf::Microfacet {
        distribution,
        masking: Masking::HeightCorrelated,
        eta: GOLD_ETA,
        k: GOLD_K,
    }
}

/// A conductor with F = 1 exactly (purely imaginary IOR): a white furnace.
fn furnace(alpha: f32) -> Bsdf {
    furnace_on(MicrofacetDistribution::beckmann(alpha))
}

fn furnace_on(distribution: MicrofacetDistribution) -> Bsdf {
    Bsdf::Microfacet {
        distribution,
        masking: Masking::HeightCorrelated,
        eta: Vec3::ZERO,
        k: Vec3::ONE,
    }
}

#[test]
fn microfacet_sampling_matches_its_pdf() {
    for alpha in [0.05f32, 0.2, 0.6] {
        for wo in test_directions() {
            // Half a million samples: visible-normal sampling solves two
            // equations per sample; narrow lobes get a finer grid so that
            // they still fill many cells.
            let resolution = if alpha < 0.1 { (81, 161) } else { (21, 41) };
            assert_chi2_with(
                &format!("beckmann α = {alpha}"),
                &gold(alpha),
                wo,
                500_000,
                resolution,
            );
        }
    }
}

#[test]
fn ggx_conductor_sampling_matches_its_pdf() {
    // GGX's sampler is closed-form, so cheaper than Beckmann's.
    let distributions = [
        MicrofacetDistribution::ggx(0.05),
        MicrofacetDistribution::ggx(0.4),
        MicrofacetDistribution::Ggx {
            alpha_x: 0.1,
            alpha_y: 0.5,
        },
    ];
    for dist in distributions {
        let resolution = if dist.alphas().0 < 0.1 {
            (81, 161)
        } else {
            (21, 41)
        };
        for wo in test_directions() {
            assert_chi2_with(
                &format!("{dist:?}"),
                &gold_on(dist),
                wo,
                400_000,
                resolution,
            );
        }
    }
}

#[test]
fn microfacet_samples_are_consistent() {
    for alpha in [0.001f32, 0.05, 0.5, 1.0] {
        for wo in test_directions() {
            assert_samples_consistent(&gold(alpha), wo);
            assert_samples_consistent(&gold_on(MicrofacetDistribution::ggx(alpha)), wo);
        }
    }
    let aniso = MicrofacetDistribution::Ggx {
        alpha_x: 0.05,
        alpha_y: 0.7,
    };
    for wo in test_directions() {
        assert_samples_consistent(&gold_on(aniso), wo);
    }
}

#[test]
fn microfacet_albedo_by_sampling_matches_quadrature() {
    for alpha in [0.1f32, 0.3, 0.7] {
        let bsdf = gold(alpha);
        check_albedo_against_quadrature(alpha, bsdf);
    }
    check_albedo_against_quadrature(0.3, gold_on(MicrofacetDistribution::ggx(0.3)));
}

fn check_albedo_against_quadrature(alpha: f32, bsdf: Bsdf) {
    for wo in test_directions() {
        let channel = |c: usize| hemisphere_integral(wo, |wi| bsdf.f(wo, wi)[c] * wi.z.abs());
        let quadrature = Vec3::new(channel(0), channel(1), channel(2));
        let sampled = albedo_by_sampling(&bsdf, wo, 200_000);
        // Quadrature error is far below 1e-3; sampling error is 5 σ.
        assert_estimates_agree(
            &format!("α = {alpha}, wo = {wo:?}"),
            &sampled,
            quadrature,
            Vec3::splat(2e-4),
        );
    }
}

#[test]
fn white_furnace_conductor_never_creates_energy() {
    // With F = 1 single scattering can only lose energy (to masking), and a
    // smooth surface loses little of it away from grazing angles.
    for alpha in [0.1f32, 0.3, 0.7, 1.0] {
        // GGX's longer tail loses more energy: nearly lossless only when
        // smoother (see the curve in `furnace_tests.rs`).
        check_furnace(alpha, furnace(alpha), alpha <= 0.3, 0.97);
        check_furnace(
            alpha,
            furnace_on(MicrofacetDistribution::ggx(alpha)),
            alpha <= 0.1,
            0.95,
        );
    }
}

/// Albedo ≤ 1 by quadrature and sampling; when `nearly_lossless`, at least
/// `lossless_bound` away from grazing angles.
fn check_furnace(alpha: f32, bsdf: Bsdf, nearly_lossless: bool, lossless_bound: f32) {
    for wo in test_directions() {
        let albedo = hemisphere_integral(wo, |wi| bsdf.f(wo, wi).x * wi.z.abs());
        assert!(albedo <= 1.0 + 1e-3, "α = {alpha}, wo = {wo:?}: {albedo}");
        let sampled = albedo_by_sampling(&bsdf, wo, 50_000);
        assert!(
            sampled.mean.x <= 1.0 + 5.0 * sampled.std_error.x,
            "α = {alpha}, wo = {wo:?}"
        );
        if nearly_lossless && wo.z.abs() >= 0.5 {
            assert!(
                albedo > lossless_bound,
                "α = {alpha}, wo = {wo:?}: {albedo}"
            );
        }
    }
}

#[test]
fn microfacet_is_two_sided_and_reciprocal() {
    for bsdf in [
        gold(0.3),
        gold_on(MicrofacetDistribution::Ggx {
            alpha_x: 0.2,
            alpha_y: 0.6,
        }),
    ] {
        check_two_sided_and_reciprocal(bsdf);
    }
}

fn check_two_sided_and_reciprocal(bsdf: Bsdf) {
    let wo = Vec3::new(0.3, -0.2, 0.93).normalize();
    let wi = Vec3::new(-0.5, 0.1, 0.86).normalize();
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)));
    assert!((bsdf.f(wo, wi) - bsdf.f(wi, wo)).abs().max_element() < 1e-5);
    assert_eq!(bsdf.f(wo, flip(wi)), Vec3::ZERO);
    assert!(!bsdf.is_specular() && bsdf.flags().is_non_specular());
    let normal = ((GOLD_ETA - 1.0).powf(2.0) + GOLD_K * GOLD_K)
        / ((GOLD_ETA + 1.0).powf(2.0) + GOLD_K * GOLD_K);
    assert!((bsdf.albedo() - normal).abs().max_element() < 1e-5);
}

#[test]
fn visible_normal_sampling_bounds_the_weight() {
    // With F = 1 the weight f·cos/pdf of visible-normal sampling is
    // G2(wo, wi) / G1(wo) ≤ 1: no fireflies even at grazing angles (plain
    // D·cos sampling gives weights far above 1 there).
    let mut sampler = crate::sampling::Sampler::new(crate::sampling::SamplerKind::Independent, 3);
    for alpha in [0.05f32, 0.5, 1.0] {
        for bsdf in [
            furnace(alpha),
            furnace_on(MicrofacetDistribution::ggx(alpha)),
        ] {
            for wo in test_directions() {
                for i in 0..5_000 {
                    let (u1, u2) = uniforms(&mut sampler, i);
                    if let Some(s) = bsdf.sample(wo, u1, u2) {
                        assert!(
                            s.weight().max_element() <= 1.0 + 1e-3,
                            "α = {alpha}, wo = {wo:?}: {s:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn ggx_furnace_albedo_at_normal_incidence_is_one_minus_ln_2() {
    // For α = 1, D(h)·cos θh is the cosine distribution and Λ(w) =
    // (1/cos θ − 1)/2, so seen from above the albedo is
    // ∫₀¹ u / (1 + u) du = 1 − ln 2 (u = cos θi = cos 2θh; normals beyond
    // 45° reflect below the horizon and are lost).
    let bsdf = furnace_on(MicrofacetDistribution::ggx(1.0));
    let sampled = albedo_by_sampling(&bsdf, Vec3::Z, 100_000);
    let exact = 1.0 - std::f32::consts::LN_2;
    assert_estimates_agree(
        "GGX α = 1 at normal incidence",
        &sampled,
        Vec3::splat(exact),
        Vec3::ZERO,
    );
}
