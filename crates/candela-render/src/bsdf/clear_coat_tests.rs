//! `KHR_materials_clearcoat` on the glTF metallic-roughness BSDF: chi-square
//! with a rough and a smooth coat (over rough, smooth and transmissive
//! bases), sample/eval/pdf consistency, reciprocity of the coated opaque
//! model, a white furnace, clearcoat 0 exactly the uncoated model, and the
//! coat alone over a black base against its analytic value.
//!
//! Furnace (energy albedo by the model's own sampling, 40k samples; white
//! base, coat strength 1; θo = 0°, 60°, 85°), printed by
//! `coated_white_furnace_stays_at_most_one`:
//!
//! | coat roughness | dielectric r = 0.5 | metal r = 0.3  |
//! |----------------|--------------------|----------------|
//! | 0.0            | 0.93 0.92 0.81     | 0.95 0.89 0.86 |
//! | 0.3            | 0.93 0.92 0.52     | 0.95 0.89 0.57 |
//! | 0.8            | 0.91 0.88 0.24     | 0.93 0.85 0.29 |
//!
//! Below the uncoated values (`metallic_roughness_tests.rs`) by what the
//! coat reflects back towards the base, which a single layer does not
//! follow (the base is dimmed at both directions, see
//! `metallic_roughness/`). At grazing angles a rough coat loses more:
//! the base gets 1 − S(cos θo) (0.36 at 85°) while the rough coat's masked
//! reflection is far below S, as for the base's own rough specular layer.

use glam::{Vec2, Vec3};

use super::test_support::*;
use super::{Bsdf, BsdfFlags, BsdfSample, MetallicRoughness};
use crate::sampling::{Sampler, SamplerKind};

fn coated(base: Vec3, metallic: f32, roughness: f32, transmission: f32, coat: (f32, f32)) -> Bsdf {
    Bsdf::MetallicRoughness(
        MetallicRoughness::new(base, metallic, roughness, transmission, 1.5)
            .with_clearcoat(coat.0, coat.1),
    )
}

fn cases() -> Vec<(&'static str, Bsdf)> {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    vec![
        (
            "rough coat over dielectric",
            coated(orange, 0.0, 0.5, 0.0, (1.0, 0.2)),
        ),
        (
            "rough coat over metal",
            coated(orange, 1.0, 0.4, 0.0, (0.7, 0.5)),
        ),
        (
            "smooth coat over dielectric",
            coated(orange, 0.0, 0.6, 0.0, (0.8, 0.0)),
        ),
        (
            "smooth coat over smooth metal",
            coated(orange, 0.6, 0.0, 0.0, (1.0, 0.0)),
        ),
        (
            "rough coat over glass",
            coated(orange, 0.0, 0.4, 0.7, (1.0, 0.3)),
        ),
    ]
}

/// A base that reflects nothing: black, no dielectric specular layer
/// (`KHR_materials_specular` strength 0), under a coat.
fn coat_alone(factor: f32, roughness: f32) -> Bsdf {
    Bsdf::MetallicRoughness(
        MetallicRoughness::new(Vec3::ZERO, 0.0, 0.5, 0.0, 1.5)
            .with_specular(0.0, Vec3::ONE)
            .with_clearcoat(factor, roughness),
    )
}

/// Schlick's Fresnel of the coat, F0 = 0.04.
fn coat_fresnel(cos: f32) -> f32 {
    0.04 + 0.96 * (1.0 - cos).powi(5)
}

fn parts(s: BsdfSample) -> (Vec3, Vec3, f32, BsdfFlags, Vec3) {
    (s.wi, s.f, s.pdf, s.flags, s.weight())
}

#[test]
fn coated_sampling_matches_its_pdf() {
    for (name, bsdf) in cases() {
        for wo in test_directions() {
            assert_chi2_with(name, &bsdf, wo, 100_000, (21, 41));
        }
    }
}

#[test]
fn coated_samples_are_consistent() {
    for (_, bsdf) in cases() {
        for wo in test_directions() {
            assert_samples_consistent(&bsdf, wo);
        }
    }
}

#[test]
fn coated_f_agrees_with_its_sampling() {
    let glossy = cases()
        .into_iter()
        .filter(|(_, b)| !b.flags().contains(BsdfFlags::SPECULAR));
    for (name, bsdf) in glossy {
        let wo = Vec3::new(0.4, 0.2, 0.89).normalize();
        let a = albedo_by_sampling(&bsdf, wo, 100_000);
        let b = albedo_by_uniform_sphere(&bsdf, wo, 400_000);
        assert_estimates_agree(name, &a, b.mean, b.std_error);
    }
}

#[test]
fn coated_opaque_model_is_reciprocal() {
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    for (wo, wi) in direction_pairs(200, 3) {
        let wi = if wi.z * wo.z < 0.0 { flip(wi) } else { wi };
        for (name, bsdf) in cases().into_iter().take(3) {
            let (a, b) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
            assert!(
                (a - b).abs().max_element() <= 1e-5 * a.max_element().max(1.0),
                "{name} {wo} {wi}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn coated_white_furnace_stays_at_most_one() {
    let mut table = String::new();
    for coat_roughness in [0.0f32, 0.3, 0.8] {
        table += &format!("| {coat_roughness:.1} |");
        for (metallic, roughness) in [(0.0, 0.5), (1.0, 0.3)] {
            let bsdf = coated(Vec3::ONE, metallic, roughness, 0.0, (1.0, coat_roughness));
            let what = format!("m={metallic} r={roughness} coat r={coat_roughness}");
            table += &furnace_row(&bsdf, 1.0, true, 1e-4, &what);
            table += " |";
        }
        table += "\n";
    }
    println!("{table}");
}

#[test]
fn clearcoat_zero_is_exactly_the_uncoated_model() {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    let mut sampler = Sampler::new(SamplerKind::Independent, 7);
    for (metallic, roughness, transmission) in [(0.0, 0.5, 0.0), (0.4, 0.0, 0.0), (0.2, 0.3, 0.6)] {
        let plain = coated(orange, metallic, roughness, transmission, (0.0, 0.0));
        let base = MetallicRoughness::new(orange, metallic, roughness, transmission, 1.5);
        assert_eq!(plain, Bsdf::MetallicRoughness(base));
        let zero = coated(orange, metallic, roughness, transmission, (0.0, 0.4));
        assert_eq!(zero.flags(), plain.flags());
        for wo in test_directions() {
            for i in 0..2_000 {
                let (u1, u2) = uniforms(&mut sampler, i);
                let (a, b) = (zero.sample(wo, u1, u2), plain.sample(wo, u1, u2));
                assert_eq!(a.map(parts), b.map(parts), "{wo} {u1} {u2}");
                let wi = Vec3::new(u2.x - 0.5, u2.y - 0.5, u1 - 0.5).normalize();
                assert_eq!(zero.f(wo, wi), plain.f(wo, wi), "{wo} {wi}");
                assert_eq!(zero.pdf(wo, wi), plain.pdf(wo, wi), "{wo} {wi}");
            }
        }
    }
}

#[test]
fn a_smooth_coat_over_black_reflects_exactly_its_fresnel() {
    let factor = 0.8;
    let bsdf = coat_alone(factor, 0.0);
    for wo in test_directions() {
        for u1 in [0.0, 0.5, 0.999] {
            let s = bsdf
                .sample(wo, u1, Vec2::new(0.3, 0.7))
                .expect("a mirror sample");
            let expected = factor * coat_fresnel(wo.z.abs());
            assert!(s.is_specular());
            assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
            assert!(
                (s.weight() - Vec3::splat(expected)).abs().max_element() < 1e-6,
                "{wo}: {} vs {expected}",
                s.weight()
            );
        }
    }
}

#[test]
fn a_rough_coat_over_black_is_the_coat_lobe_alone() {
    // Its value is c S(wo·h) D G2 / (4 cos θo cos θi), nothing of the base.
    let (factor, roughness) = (0.9, 0.4);
    let bsdf = coat_alone(factor, roughness);
    let dist = super::MicrofacetDistribution::ggx(roughness * roughness);
    for (wo, wi) in direction_pairs(100, 11) {
        let (wo, wi) = (
            Vec3::new(wo.x, wo.y, wo.z.abs()),
            Vec3::new(wi.x, wi.y, wi.z.abs()),
        );
        let h = (wo + wi).normalize();
        let expected =
            factor * coat_fresnel(wo.dot(h)) * dist.d(h) * dist.g2(wo, wi) / (4.0 * wo.z * wi.z);
        let f = bsdf.f(wo, wi);
        assert!(
            (f - Vec3::splat(expected)).abs().max_element() <= 1e-5 * expected.max(1.0),
            "{wo} {wi}: {f} vs {expected}"
        );
    }
    // Its albedo by quadrature of f: the smooth coat's c S(cos θo) in the
    // limit of a smooth coat, and less for a rough one (masking), agreeing
    // with the model's own sampling.
    for theta in [0.0f32, 45.0, 75.0] {
        let (s, c) = theta.to_radians().sin_cos();
        let wo = Vec3::new(s, 0.0, c);
        let smooth = factor * coat_fresnel(c);
        let nearly = coat_alone(factor, 0.1);
        let a = hemisphere_integral(wo, |wi| nearly.f(wo, wi).x * wi.z.abs());
        assert!(
            (a - smooth).abs() < 0.01 * smooth,
            "θ={theta}: {a} vs {smooth}"
        );
        let a = hemisphere_integral(wo, |wi| bsdf.f(wo, wi).x * wi.z.abs());
        assert!(a > 0.0 && a < 1.05 * smooth, "θ={theta}: {a} vs {smooth}");
        let e = albedo_by_sampling(&bsdf, wo, 100_000);
        assert_estimates_agree("rough coat alone", &e, Vec3::splat(a), Vec3::ZERO);
    }
}
