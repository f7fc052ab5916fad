//! The principled BSDF: chi-square of its sampling at every test direction
//! (inside included) for seven parameter sets, and of the clearcoat's GTR1
//! normals; sample/eval/pdf consistency; `f` against its own sampling as
//! integrals; reciprocity (generalised by η² across the interface); the
//! white furnace; the limits (metallic 1 has no diffuse, sheen or
//! transmission; full transmission without extra lobes is exactly the
//! rough dielectric; an opaque material is two-sided).

use glam::{Vec2, Vec3};

use super::clearcoat::Gtr1;
use super::{Principled, PrincipledParameters};
use crate::bsdf::distribution::{Masking, MicrofacetDistribution};
use crate::bsdf::rough_dielectric::RoughDielectric;
use crate::bsdf::test_support::*;
use crate::bsdf::{Bsdf, BsdfFlags};
use crate::sampling::chi2::Chi2Test;
use crate::sampling::{Sampler, SamplerKind};

fn principled(p: PrincipledParameters) -> Bsdf {
    Bsdf::Principled(Principled::new(p))
}

fn params() -> PrincipledParameters {
    PrincipledParameters::default()
}

/// The parameter sets under test: the conformance scene's four, then
/// anisotropy, clearcoat, and every lobe at once.
fn cases() -> Vec<(&'static str, Bsdf)> {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    vec![
        (
            "dielectric r=0.5",
            principled(PrincipledParameters {
                base_color: Vec3::new(0.7, 0.2, 0.1),
                ..params()
            }),
        ),
        (
            "metallic r=0.3",
            principled(PrincipledParameters {
                base_color: Vec3::new(0.9, 0.7, 0.3),
                metallic: 1.0,
                roughness: 0.3,
                ..params()
            }),
        ),
        (
            "specular 1 r=0.2",
            principled(PrincipledParameters {
                base_color: Vec3::new(0.1, 0.3, 0.7),
                roughness: 0.2,
                eta: 2.0 / (1.0 - 0.08f32.sqrt()) - 1.0,
                ..params()
            }),
        ),
        (
            "spec_trans 1 r=0.3",
            principled(PrincipledParameters {
                base_color: Vec3::splat(0.9),
                spec_trans: 1.0,
                roughness: 0.3,
                ..params()
            }),
        ),
        (
            "anisotropic half metal",
            principled(PrincipledParameters {
                base_color: orange,
                roughness: 0.4,
                anisotropic: 0.8,
                metallic: 0.5,
                ..params()
            }),
        ),
        (
            "clearcoat",
            principled(PrincipledParameters {
                base_color: orange,
                roughness: 0.6,
                clearcoat: 1.0,
                clearcoat_gloss: 0.5,
                ..params()
            }),
        ),
        (
            "every lobe",
            principled(PrincipledParameters {
                base_color: orange,
                roughness: 0.45,
                anisotropic: 0.5,
                metallic: 0.2,
                spec_trans: 0.4,
                eta: 1.4,
                spec_tint: 0.5,
                sheen: 0.7,
                sheen_tint: 0.5,
                flatness: 0.3,
                clearcoat: 0.6,
                clearcoat_gloss: 0.3,
            }),
        ),
    ]
}

#[test]
fn principled_sampling_matches_its_pdf() {
    assert_cases_sample_their_pdf(&cases());
}

#[test]
fn clearcoat_normals_follow_gtr1() {
    for gloss in [0.0, 0.5] {
        let gtr1 = Gtr1::of_gloss(gloss);
        Chi2Test::sphere(&format!("GTR1 normals, gloss {gloss}"))
            .with_samples(200_000)
            .with_resolution(41, 21)
            .run(
                |u| {
                    let m = gtr1.sample(Vec2::new(u[0], u[1]));
                    Some((m, gtr1.pdf(m)))
                },
                |m| gtr1.pdf(m),
            )
            .assert_ok();
    }
}

#[test]
fn principled_samples_are_consistent() {
    assert_cases_sample_consistently(&cases());
}

#[test]
fn principled_f_agrees_with_its_sampling() {
    // ∫ f |cos| by the model's own sampling and by uniform directions on
    // the sphere: checks f and sample against each other as integrals.
    // (No case has a delta lobe: every one is checked.)
    let cases = cases();
    assert!(cases
        .iter()
        .all(|(_, b)| !b.flags().contains(BsdfFlags::SPECULAR)));
    assert_cases_f_agrees_with_sampling(
        &cases,
        &[Vec3::new(0.4, 0.2, 0.89), Vec3::new(-0.5, 0.3, -0.81)],
    );
}

#[test]
fn principled_is_reciprocal() {
    // Reflection is symmetric; transmission obeys f(wo, wi) η(wi)² =
    // f(wi, wo) η(wo)² (η the absolute IOR on the side of each direction).
    let mut sampler = Sampler::new(SamplerKind::Independent, 41);
    let mut transmitted = 0;
    for (name, bsdf) in cases() {
        let Bsdf::Principled(p) = bsdf else {
            continue;
        };
        let eta = p.ior();
        let side_eta2 = |w: Vec3| if w.z < 0.0 { eta * eta } else { 1.0 };
        for i in 0..2_000 {
            let (u1, u2) = uniforms(&mut sampler, i);
            let wo = crate::sampling::warp::square_to_uniform_sphere(u2);
            let wi = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(u1, u2.x));
            let a = bsdf.f(wo, wi) * side_eta2(wi);
            let b = bsdf.f(wi, wo) * side_eta2(wo);
            let scale = a.abs().max(b.abs()).max_element().max(1e-2);
            assert!(
                (a - b).abs().max_element() <= 2e-3 * scale,
                "{name}: {wo} {wi}: {a} vs {b}"
            );
            if wo.z * wi.z < 0.0 && a.max_element() > 0.0 {
                transmitted += 1;
            }
        }
    }
    assert!(
        transmitted > 100,
        "too few transmitted pairs: {transmitted}"
    );
}

#[test]
fn principled_white_furnace() {
    // Energy albedo (refraction multiplied back by η²) of white materials,
    // 40k samples, at θo = 0°, 60°, 85°. Metals (isotropic and
    // anisotropic), glass and half-metal glass are single-scattering
    // microfacet lobes whose Fresnel weights sum to at most 1, so they never
    // exceed 1: asserted. The opaque dielectric adds its specular lobe on
    // top of Burley's diffuse, which alone nearly reflects everything and
    // more than Lambert where the retro-reflection peaks (roughness 1,
    // grazing), and the clearcoat adds to that: Mitsuba's model creates
    // energy there; the printed table (the module docs of `mod.rs` quote
    // it) shows by how much.
    let mut table = String::new();
    for roughness in [0.1f32, 0.5, 1.0] {
        table += &format!("| {roughness:.1} |");
        for (metallic, anisotropic, spec_trans, clearcoat, bounded) in [
            (1.0, 0.0, 0.0, 0.0, true),
            (1.0, 0.8, 0.0, 0.0, true),
            (0.0, 0.0, 1.0, 0.0, true),
            (0.5, 0.0, 1.0, 0.0, true),
            (0.0, 0.0, 0.0, 0.0, false),
            (0.0, 0.0, 0.0, 1.0, false),
        ] {
            let bsdf = principled(PrincipledParameters {
                base_color: Vec3::ONE,
                roughness,
                anisotropic,
                metallic,
                spec_trans,
                clearcoat,
                ..params()
            });
            let what = format!("m={metallic} a={anisotropic} t={spec_trans} r={roughness}");
            table += &furnace_row(&bsdf, 1.5, bounded, 0.0, &what);
            table += " |";
        }
        table += "\n";
    }
    println!("{table}");
}

#[test]
fn metallic_one_has_no_diffuse_sheen_or_transmission() {
    let metal = |extra: PrincipledParameters| {
        principled(PrincipledParameters {
            base_color: Vec3::new(0.9, 0.6, 0.2),
            roughness: 0.35,
            metallic: 1.0,
            ..extra
        })
    };
    let plain = metal(params());
    let loaded = metal(PrincipledParameters {
        spec_trans: 1.0,
        sheen: 1.0,
        sheen_tint: 0.5,
        flatness: 0.7,
        spec_tint: 0.8,
        ..params()
    });
    assert!(!plain
        .flags()
        .intersects(BsdfFlags::DIFFUSE | BsdfFlags::TRANSMISSION));
    assert!(!loaded
        .flags()
        .intersects(BsdfFlags::DIFFUSE | BsdfFlags::TRANSMISSION));
    let mut sampler = Sampler::new(SamplerKind::Independent, 43);
    for i in 0..4_000 {
        let (u1, u2) = uniforms(&mut sampler, i);
        let wo = crate::sampling::warp::square_to_uniform_sphere(u2);
        let wi = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(u1, u2.y));
        assert_eq!(plain.f(wo, wi), loaded.f(wo, wi), "{wo} {wi}");
        assert_eq!(plain.pdf(wo, wi), loaded.pdf(wo, wi), "{wo} {wi}");
        if wo.z * wi.z < 0.0 {
            assert_eq!(plain.f(wo, wi), Vec3::ZERO);
        }
    }
}

#[test]
fn full_transmission_is_the_rough_dielectric() {
    // metallic 0, spec_trans 1, no tint, sheen or coat: reflection is the
    // exact dielectric Fresnel, transmission √c (1 − F), sampled as the
    // rough dielectric alone, on both sides.
    let color = Vec3::new(0.81, 0.49, 0.25);
    let bsdf = principled(PrincipledParameters {
        base_color: color,
        roughness: 0.5,
        spec_trans: 1.0,
        eta: 1.33,
        ..params()
    });
    let glass = RoughDielectric {
        dist: MicrofacetDistribution::ggx(0.25),
        reflectance: Vec3::ONE,
        transmittance: Vec3::new(0.9, 0.7, 0.5),
        ior: 1.33,
        masking: Masking::Separable,
    };
    let mut sampler = Sampler::new(SamplerKind::Independent, 47);
    for i in 0..4_000 {
        let (u1, u2) = uniforms(&mut sampler, i);
        let wo = crate::sampling::warp::square_to_uniform_sphere(u2);
        let wi = crate::sampling::warp::square_to_uniform_sphere(Vec2::new(u1, u2.y));
        let (a, b) = (bsdf.f(wo, wi), glass.f(wo, wi));
        assert!(
            (a - b).abs().max_element() <= 1e-5 * b.max_element().max(1.0),
            "{wo} {wi}: {a} vs {b}"
        );
        let (a, b) = (bsdf.pdf(wo, wi), glass.pdf(wo, wi));
        assert!((a - b).abs() <= 1e-5 * b.max(1.0), "{wo} {wi}: {a} vs {b}");
    }
}

#[test]
fn opaque_principled_is_two_sided() {
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    let wo = Vec3::new(0.3, -0.2, 0.93).normalize();
    for (name, bsdf) in cases() {
        if bsdf.flags().is_transmission() {
            continue;
        }
        for wi in [
            Vec3::new(-0.7, 0.1, 0.3).normalize(),
            Vec3::new(-0.2, 0.3, 0.9).normalize(),
        ] {
            assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)), "{name}");
            assert_eq!(bsdf.pdf(wo, wi), bsdf.pdf(flip(wo), flip(wi)), "{name}");
            assert!(bsdf.f(wo, wi).max_element() > 0.0, "{name}");
            assert_eq!(bsdf.f(wo, flip(wi)), Vec3::ZERO, "{name}: no transmission");
        }
    }
}
