//! The glTF metallic-roughness BSDF: chi-square at every test direction
//! (grazing included) for a dielectric, a metal, a half-metal, a
//! transmissive material and a tinted, weakened specular layer
//! (`KHR_materials_specular`), smooth layers over a diffuse base included;
//! sample/eval/pdf consistency; reciprocity of the opaque model; white
//! furnace, and a white dielectric and a white metal that reflect all the
//! light; `specularFactor` 0 is exactly Lambert, metallic 1, roughness 0,
//! white is exactly the perfect mirror, and a smooth, fully transmissive
//! material is the smooth glass.
//!
//! Furnace curve (energy albedo by the model's own sampling, 40k samples,
//! ±0.003; white base colour; θo = 0°, 60°, 85°), printed by
//! `metallic_roughness_white_furnace_stays_at_most_one` (s: the
//! `KHR_materials_specular` strength, with a tint that clamps F0 in blue):
//!
//! | roughness | dielectric (m = 0) | metal (m = 1)  | glass (t = 1, outside) | dielectric, s = 0.5 |
//! |-----------|--------------------|----------------|------------------------|---------------------|
//! | 0.2       | 1.00 1.00 1.00     | 1.00 1.00 1.00 | 1.00 1.00 0.94         | 1.00 1.00 1.00      |
//! | 0.5       | 1.00 1.00 1.00     | 1.00 1.00 1.00 | 0.99 0.96 0.92         | 1.00 1.00 1.00      |
//! | 0.8       | 1.00 1.00 1.00     | 1.00 1.00 1.00 | 0.95 0.85 0.82         | 1.00 1.00 1.00      |
//! | 1.0       | 1.00 1.00 1.00     | 1.00 1.00 1.00 | 0.89 0.74 0.75         | 1.00 1.00 1.00      |
//!
//! The opaque model keeps all the light: the dielectric's Lambert base
//! takes what its rough specular layer leaves (by the layer's tabulated
//! albedo), and the metal returns what single scattering loses as its
//! multiple-scattering lobe (without it, the metal at roughness 1 kept
//! 0.31 0.45 0.78, GGX's single scattering; Heitz et al. 2016). The glass
//! still loses its rough interface's single-scattering share.

use glam::Vec3;

use glam::Vec2;

use super::test_support::*;
use super::{Bsdf, BsdfFlags, BsdfSample, MetallicRoughness};
use crate::sampling::{Sampler, SamplerKind};

fn mr(base: Vec3, metallic: f32, roughness: f32, transmission: f32) -> Bsdf {
    Bsdf::MetallicRoughness(MetallicRoughness::new(
        base,
        metallic,
        roughness,
        transmission,
        1.5,
    ))
}

fn cases() -> Vec<(&'static str, Bsdf)> {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    vec![
        ("dielectric r=0.5", mr(orange, 0.0, 0.5, 0.0)),
        ("metal r=0.3", mr(orange, 1.0, 0.3, 0.0)),
        ("half metal r=0.7", mr(orange, 0.5, 0.7, 0.0)),
        ("transmissive r=0.4", mr(orange, 0.2, 0.4, 0.6)),
        (
            "weak tinted specular r=0.3",
            specular(mr(orange, 0.0, 0.3, 0.0), 0.5),
        ),
        (
            "smooth weak specular",
            specular(mr(orange, 0.3, 0.0, 0.0), 0.5),
        ),
        // Delta glass, mirror and metal beside the diffuse lobe.
        ("smooth transmissive", mr(orange, 0.2, 0.0, 0.6)),
    ]
}

#[test]
fn a_smooth_fully_transmissive_material_is_the_smooth_glass() {
    // Roughness 0, transmission 1: Fresnel-weighted reflection and
    // refraction, the same directions, probabilities and weights as
    // `Bsdf::Glass` of transmittance = base colour.
    let tint = Vec3::new(0.9, 0.7, 0.5);
    let gltf = mr(tint, 0.0, 0.0, 1.0);
    let glass = Bsdf::Glass {
        reflectance: Vec3::ONE,
        transmittance: tint,
        ior: 1.5,
    };
    assert_eq!(gltf.flags(), glass.flags());
    let mut sampler = Sampler::new(SamplerKind::Independent, 21);
    let mut refracted = 0;
    for wo in test_directions() {
        for i in 0..500 {
            let (u1, u2) = uniforms(&mut sampler, i);
            let (a, b) = (gltf.sample(wo, u1, u2), glass.sample(wo, u1, u2));
            let (Some(a), Some(b)) = (a, b) else {
                assert_eq!(a.is_none(), b.is_none(), "{wo} {u1}");
                continue;
            };
            assert_eq!((a.wi, a.flags), (b.wi, b.flags), "{wo} {u1}");
            assert!((a.pdf - b.pdf).abs() <= 1e-6 * b.pdf, "{wo} {u1}");
            assert!(
                (a.weight() - b.weight()).abs().max_element() <= 1e-6,
                "{wo} {u1}: {} vs {}",
                a.weight(),
                b.weight()
            );
            refracted += a.flags.is_transmission() as u32;
        }
    }
    assert!(refracted > 1000, "{refracted} refractions");
}

/// `KHR_materials_specular` on `bsdf`: strength `factor`, a blue-green
/// tint strong enough that F0 is clamped in one channel.
fn specular(bsdf: Bsdf, factor: f32) -> Bsdf {
    match bsdf {
        Bsdf::MetallicRoughness(m) => {
            Bsdf::MetallicRoughness(m.with_specular(factor, Vec3::new(0.5, 1.0, 30.0)))
        }
        other => other,
    }
}

/// Everything a sample says, for exact comparisons.
fn parts(s: BsdfSample) -> (Vec3, Vec3, f32, BsdfFlags, Vec3) {
    (s.wi, s.f, s.pdf, s.flags, s.weight())
}

#[test]
fn specular_factor_zero_is_exactly_lambert() {
    let albedo = Vec3::new(0.7, 0.4, 0.1);
    let lambert = Bsdf::Diffuse { albedo };
    let mut sampler = Sampler::new(SamplerKind::Independent, 5);
    for roughness in [0.0, 0.5, 1.0] {
        let gltf = specular(mr(albedo, 0.0, roughness, 0.0), 0.0);
        assert_eq!(gltf.flags(), lambert.flags());
        for wo in test_directions() {
            for i in 0..2_000 {
                let (u1, u2) = uniforms(&mut sampler, i);
                let (a, b) = (gltf.sample(wo, u1, u2), lambert.sample(wo, u1, u2));
                assert_eq!(a.map(parts), b.map(parts), "{wo} {u1} {u2}");
                let wi = Vec3::new(u2.x - 0.5, u2.y - 0.5, u1 - 0.5).normalize();
                assert_eq!(gltf.f(wo, wi), lambert.f(wo, wi), "{wo} {wi}");
                assert_eq!(gltf.pdf(wo, wi), lambert.pdf(wo, wi), "{wo} {wi}");
            }
        }
    }
}

#[test]
fn smooth_white_metal_is_exactly_the_perfect_mirror() {
    let gltf = mr(Vec3::ONE, 1.0, 0.0, 0.0);
    let mirror = Bsdf::Mirror {
        reflectance: Vec3::ONE,
    };
    assert_eq!(gltf.flags(), mirror.flags());
    assert!(gltf.is_specular());
    for wo in test_directions() {
        for u1 in [0.0, 0.5, 0.999] {
            let u2 = Vec2::new(0.3, 0.8);
            let (a, b) = (gltf.sample(wo, u1, u2), mirror.sample(wo, u1, u2));
            assert!(a.is_some(), "{wo}");
            assert_eq!(a.map(parts), b.map(parts), "{wo}");
            let wi = a.map_or(Vec3::Z, |s| s.wi);
            assert_eq!(gltf.f(wo, wi), Vec3::ZERO);
            assert_eq!(gltf.pdf(wo, wi), 0.0);
        }
    }
}

#[test]
fn metallic_roughness_sampling_matches_its_pdf() {
    assert_cases_sample_their_pdf(&cases());
}

#[test]
fn metallic_roughness_samples_are_consistent() {
    assert_cases_sample_consistently(&cases());
    // Smooth (clamped to the minimum α) and black still sample consistently.
    for bsdf in [mr(Vec3::ONE, 1.0, 0.0, 0.0), mr(Vec3::ZERO, 0.0, 0.5, 0.0)] {
        assert_samples_consistent(&bsdf, Vec3::new(0.3, 0.1, 0.9).normalize());
    }
}

#[test]
fn opaque_metallic_roughness_is_reciprocal_and_two_sided() {
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    let wo = Vec3::new(0.3, -0.2, 0.93).normalize();
    let wi = Vec3::new(-0.7, 0.1, 0.3).normalize();
    for (_, bsdf) in cases().into_iter().take(3) {
        let (a, b) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
        assert!(
            (a - b).abs().max_element() < 1e-5 * a.max_element().max(1.0),
            "{a} vs {b}"
        );
        assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)));
        assert_eq!(bsdf.f(wo, flip(wi)), Vec3::ZERO, "no transmission");
        assert!(!bsdf.flags().is_transmission());
    }
}

#[test]
fn metallic_roughness_f_agrees_with_its_sampling() {
    // ∫ f |cos| by the model's own sampling and by uniform sphere
    // directions: checks f and sample against each other as integrals.
    // (Delta lobes are invisible to uniform directions: smooth cases skip.)
    assert_cases_f_agrees_with_sampling(&cases(), &[Vec3::new(0.4, 0.2, 0.89)]);
}

#[test]
fn metallic_roughness_white_furnace_stays_at_most_one() {
    let mut table = String::new();
    for roughness in [0.2f32, 0.5, 0.8, 1.0] {
        table += &format!("| {roughness:.1} |");
        for (metallic, transmission, strength) in [
            (0.0, 0.0, 1.0),
            (1.0, 0.0, 1.0),
            (0.0, 1.0, 1.0),
            (0.0, 0.0, 0.5),
        ] {
            let bsdf = specular(mr(Vec3::ONE, metallic, roughness, transmission), strength);
            let what = format!("m={metallic} t={transmission} s={strength} r={roughness}");
            table += &furnace_row(&bsdf, 1.5, true, 1e-4, &what);
            table += " |";
        }
        table += "\n";
    }
    println!("{table}");
    // A smooth white dielectric at normal incidence keeps nearly all the
    // energy: F0 reflected, the rest diffusely.
    let e = energy_albedo_by_sampling(&mr(Vec3::ONE, 0.0, 0.2, 0.0), Vec3::Z, 1.0, 40_000);
    assert!(e.mean.x > 0.95, "{:?}", e.mean);
}

#[test]
fn a_white_metal_reflects_all_the_light_at_every_angle_and_roughness() {
    // Single scattering returns E (the table's A + B under a white
    // Fresnel), the multiple-scattering lobe exactly the 1 − E it loses:
    // 1 up to the table's interpolation and the estimate's noise. A
    // coloured metal keeps less (F_ms < 1), but more than single scattering.
    for roughness in [0.3f32, 0.6, 1.0] {
        for theta in [0.0f32, 45.0, 70.0, 85.0] {
            let (s, c) = theta.to_radians().sin_cos();
            let wo = Vec3::new(s, 0.0, c);
            let white = mr(Vec3::ONE, 1.0, roughness, 0.0);
            let e = energy_albedo_by_sampling(&white, wo, 1.0, 40_000);
            let bound = 5.0 * e.std_error.max_element() + 6e-3;
            assert!(
                (e.mean - Vec3::ONE).abs().max_element() < bound,
                "r={roughness} θ={theta}: {:?} ± {:?}",
                e.mean,
                e.std_error
            );
        }
    }
}

#[test]
fn a_white_dielectric_reflects_all_the_light_at_every_angle_and_roughness() {
    // The base gets exactly what the specular layer leaves (its albedo E
    // from `specular_albedo.rs`), so the sum is 1 up to the table's
    // interpolation (a few thousandths) and the estimate's noise.
    for roughness in [0.0f32, 0.3, 0.6, 1.0] {
        for strength in [1.0f32, 0.5] {
            for theta in [0.0f32, 45.0, 70.0, 85.0] {
                let (s, c) = theta.to_radians().sin_cos();
                let bsdf = specular(mr(Vec3::ONE, 0.0, roughness, 0.0), strength);
                let e = energy_albedo_by_sampling(&bsdf, Vec3::new(s, 0.0, c), 1.0, 40_000);
                let bound = 5.0 * e.std_error.max_element() + 6e-3;
                assert!(
                    (e.mean - Vec3::ONE).abs().max_element() < bound,
                    "r={roughness} s={strength} θ={theta}: {:?} ± {:?}",
                    e.mean,
                    e.std_error
                );
            }
        }
    }
}
