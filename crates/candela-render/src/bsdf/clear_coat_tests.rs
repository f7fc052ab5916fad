//! `KHR_materials_clearcoat` on the glTF metallic-roughness BSDF: chi-square
//! with a rough and a smooth coat (over rough, smooth and transmissive
//! bases), sample/eval/pdf consistency, the coat's weight on the base (of
//! the view alone), a white furnace, clearcoat 0 exactly the uncoated
//! model, and the coat alone over a black base against its analytic value.
//! (The adjoint of the non-reciprocal coated model is in
//! `transport_tests.rs`.)
//!
//! Furnace (energy albedo by the model's own sampling, 40k samples; white
//! base, coat strength 1; θo = 0°, 60°, 85°), printed by
//! `coated_white_furnace_stays_at_most_one`:
//!
//! | coat roughness | dielectric r = 0.5 | metal r = 0.3  |
//! |----------------|--------------------|----------------|
//! | 0.0            | 1.00 1.00 1.00     | 0.99 0.98 0.96 |
//! | 0.3            | 1.00 1.00 0.99     | 0.99 0.98 0.92 |
//! | 0.8            | 1.00 1.00 1.00     | 0.99 0.98 0.90 |
//!
//! The coat reflects its albedo c E(cos θo) and leaves the rest to the
//! base, so a coat loses nothing a white dielectric would not; the metal's
//! losses at grazing angles are its own single-scattering GGX's. (Dimming
//! the base once per crossing of the coat, as the model did before, gave
//! 0.93 0.92 0.81 over the dielectric and as little as 0.24 at 85° under
//! the roughest coat.)

use glam::{Vec2, Vec3};

use super::test_support::*;
use super::{Bsdf, BsdfFlags, BsdfSample, MetallicRoughness};
use crate::sampling::warp::square_to_uniform_hemisphere;
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
        (
            "smooth coat over smooth glass",
            coated(orange, 0.0, 0.0, 0.7, (0.9, 0.0)),
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
    assert_cases_sample_their_pdf(&cases());
}

#[test]
fn coated_samples_are_consistent() {
    assert_cases_sample_consistently(&cases());
}

#[test]
fn coated_f_agrees_with_its_sampling() {
    assert_cases_f_agrees_with_sampling(&cases(), &[Vec3::new(0.4, 0.2, 0.89)]);
}

#[test]
fn the_coat_dims_the_base_by_its_albedo_at_the_view_alone() {
    // f = (1 − c E(cos θo)) f_base + f_coat: with the coat's own lobe
    // taken away and divided by the uncoated base's value, what is left is
    // one factor of wo alone, the same for every wi and channel, and for
    // a smooth coat exactly 1 − c S(cos θo).
    let orange = Vec3::new(0.9, 0.5, 0.1);
    let base = coated(orange, 0.0, 0.5, 0.0, (0.0, 0.0));
    let mut sampler = Sampler::new(SamplerKind::Independent, 11);
    for (factor, coat_roughness) in [(1.0, 0.0), (0.7, 0.3), (1.0, 0.8)] {
        let bsdf = coated(orange, 0.0, 0.5, 0.0, (factor, coat_roughness));
        let lobe = coat_alone(factor, coat_roughness);
        for wo in test_directions() {
            let mut first: Option<f32> = None;
            for i in 0..64 {
                let (_, u2) = uniforms(&mut sampler, i);
                let w = square_to_uniform_hemisphere(u2);
                let wi = Vec3::new(w.x, w.y, w.z.copysign(wo.z));
                let under = base.f(wo, wi);
                let weight = (bsdf.f(wo, wi) - lobe.f(wo, wi)) / under;
                let w0 = *first.get_or_insert(weight.x);
                assert!(
                    (weight - Vec3::splat(w0)).abs().max_element() < 1e-4 && w0 > 0.0 && w0 < 1.0,
                    "c={factor} r={coat_roughness} {wo} {wi}: {weight} vs {w0}"
                );
            }
            if coat_roughness == 0.0 {
                let expected = 1.0 - factor * coat_fresnel(wo.z.abs());
                let w0 = first.expect("weights");
                assert!((w0 - expected).abs() < 1e-5, "{wo}: {w0} vs {expected}");
            }
        }
    }
}

#[test]
fn a_white_dielectric_under_any_coat_reflects_all_the_light() {
    // The coat reflects c E(cos θo), the white base (which alone reflects
    // everything, `metallic_roughness_tests.rs`) all of the 1 − c E it
    // leaves: 1 up to the tables' interpolation and the estimate's noise.
    for coat_roughness in [0.0f32, 0.3, 0.8] {
        for roughness in [0.0f32, 0.5, 1.0] {
            for theta in [0.0f32, 45.0, 70.0, 85.0] {
                let (s, c) = theta.to_radians().sin_cos();
                let bsdf = coated(Vec3::ONE, 0.0, roughness, 0.0, (1.0, coat_roughness));
                let e = energy_albedo_by_sampling(&bsdf, Vec3::new(s, 0.0, c), 1.0, 40_000);
                let bound = 5.0 * e.std_error.max_element() + 6e-3;
                assert!(
                    (e.mean - Vec3::ONE).abs().max_element() < bound,
                    "coat r={coat_roughness} r={roughness} θ={theta}: {:?} ± {:?}",
                    e.mean,
                    e.std_error
                );
            }
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
fn the_mirror_direction_carries_exactly_its_delta_lobes() {
    // A smooth coat over smooth coloured bases (metal and dielectric, and
    // glass): over u1, the delta samples in the mirror direction must
    // average to c S(cos) + (1 − c S(cos)) R_base(cos), the coat's
    // reflectance and the base's delta lobes (Schlick for the metal and the
    // dielectric layer, the exact Fresnel for the glass) under its weight,
    // whichever lobe u1 picked. A midpoint sum over u1, so the bound is the
    // quadrature's, not noise's.
    let orange = Vec3::new(0.9, 0.5, 0.1);
    let schlick = |f0: Vec3, cos: f32| f0 + (Vec3::ONE - f0) * (1.0 - cos).powi(5);
    for (metallic, transmission) in [(0.6, 0.0), (0.0, 0.0), (0.0, 0.7), (0.3, 0.5)] {
        let factor = 0.8;
        let bsdf = coated(orange, metallic, 0.0, transmission, (factor, 0.0));
        for wo in test_directions().into_iter().filter(|w| w.z > 0.05) {
            let cos = wo.z;
            let dielectric = (1.0 - metallic) * (1.0 - transmission);
            let glass = (1.0 - metallic) * transmission;
            let base = metallic * schlick(orange, cos)
                + dielectric * schlick(Vec3::splat(0.04), cos)
                + Vec3::splat(glass * crate::bsdf::fresnel::fresnel_dielectric(cos, 1.5));
            let coat = factor * coat_fresnel(cos);
            let expected = Vec3::splat(coat) + (1.0 - coat) * base;
            let n = 20_000;
            let mut sum = Vec3::ZERO;
            for i in 0..n {
                let u1 = (i as f32 + 0.5) / n as f32;
                if let Some(s) = bsdf.sample(wo, u1, Vec2::new(0.37, 0.61)) {
                    if s.is_specular() && s.wi == Vec3::new(-wo.x, -wo.y, wo.z) {
                        sum += s.weight();
                    }
                }
            }
            let mean = sum / n as f32;
            assert!(
                (mean - expected).abs().max_element() < 2e-3,
                "m={metallic} t={transmission} {wo}: {mean} vs {expected}"
            );
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
