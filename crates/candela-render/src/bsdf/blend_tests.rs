//! The blend (Mitsuba's `blendbsdf`): its sampling against its pdf, its
//! value as the weighted sum of its parts, the choice of part by `u1`, the
//! delta lobes of a part beside the smooth ones of the other, a black part,
//! and white furnaces of lossless parts.

use glam::{Vec2, Vec3};

use super::test_support::*;
use super::{Blend, Bsdf, Masking, MicrofacetDistribution, Plastic, RoughPlastic, TransportMode};

fn blend(weight: f32, a: Bsdf, b: Bsdf) -> Bsdf {
    Bsdf::Blend(Box::new(Blend::new(weight, Some(a), Some(b))))
}

fn diffuse(albedo: Vec3) -> Bsdf {
    Bsdf::Diffuse { albedo }
}

fn rough_gold() -> Bsdf {
    Bsdf::Microfacet {
        distribution: MicrofacetDistribution::ggx(0.3),
        masking: Masking::Separable,
        eta: Vec3::new(0.143, 0.374, 1.442),
        k: Vec3::new(3.983, 2.385, 1.603),
    }
}

fn glass(ior: f32) -> Bsdf {
    Bsdf::Glass {
        reflectance: Vec3::ONE,
        transmittance: Vec3::ONE,
        ior,
    }
}

fn rough_glass(alpha: f32, ior: f32) -> Bsdf {
    Bsdf::RoughGlass {
        distribution: MicrofacetDistribution::beckmann(alpha),
        masking: Masking::HeightCorrelated,
        reflectance: Vec3::ONE,
        transmittance: Vec3::new(0.9, 0.8, 1.0),
        ior,
    }
}

/// The blends under test: smooth parts, a delta part beside a smooth one,
/// a transmitting part, and blends nested in blends.
fn blends() -> Vec<(&'static str, Bsdf)> {
    let red = diffuse(Vec3::new(0.8, 0.3, 0.2));
    vec![
        (
            "diffuse + rough gold, w 0.3",
            blend(0.3, red.clone(), rough_gold()),
        ),
        (
            "smooth glass + diffuse, w 0.5",
            blend(0.5, glass(1.5), red.clone()),
        ),
        (
            "rough glass + rough plastic, w 0.7",
            blend(
                0.7,
                rough_glass(0.3, 1.5),
                Bsdf::RoughPlastic(RoughPlastic::new(
                    MicrofacetDistribution::beckmann(0.2),
                    Vec3::new(0.2, 0.5, 0.7),
                    Vec3::ONE,
                    1.5,
                    false,
                )),
            ),
        ),
        (
            "nested: (diffuse + gold) + smooth plastic, w 0.4",
            blend(
                0.4,
                blend(0.6, red, rough_gold()),
                Bsdf::Plastic(Plastic::new(Vec3::new(0.1, 0.6, 0.2), Vec3::ONE, 1.5)),
            ),
        ),
    ]
}

#[test]
fn blend_sampling_matches_its_pdf() {
    for (name, bsdf) in blends() {
        for wo in test_directions() {
            assert_chi2_with(name, &bsdf, wo, 300_000, (21, 41));
        }
    }
}

#[test]
fn blend_with_a_black_part_samples_its_pdf() {
    // A one-sided part seen from behind: picking it ends the path.
    let bsdf = Bsdf::Blend(Box::new(Blend::new(0.35, Some(rough_gold()), None)));
    for wo in test_directions() {
        assert_chi2_with("gold + black", &bsdf, wo, 300_000, (21, 41));
        assert_samples_consistent(&bsdf, wo);
    }
}

#[test]
fn blend_samples_are_consistent() {
    for (_, bsdf) in blends() {
        for wo in test_directions() {
            assert_samples_consistent(&bsdf, wo);
        }
    }
}

#[test]
fn value_and_density_are_the_weighted_sums_of_the_parts() {
    let parts = [
        (rough_glass(0.4, 1.5), rough_gold()),
        (rough_glass(0.2, 1.2), rough_glass(0.5, 1.7)),
        (diffuse(Vec3::splat(0.6)), glass(1.5)),
    ];
    let mut nonzero = 0;
    for (a, b) in parts {
        for w in [0.0, 0.25, 0.8, 1.0] {
            let mix = blend(w, a.clone(), b.clone());
            for (wo, wi) in direction_pairs(500, 41) {
                for mode in [TransportMode::Radiance, TransportMode::Importance] {
                    let expected = (1.0 - w) * a.f_mode(wo, wi, mode) + w * b.f_mode(wo, wi, mode);
                    let got = mix.f_mode(wo, wi, mode);
                    let scale = expected.abs().max_element().max(1e-6);
                    assert!(
                        (got - expected).abs().max_element() <= 1e-5 * scale,
                        "{mix:?} {wo} {wi} {mode:?}: {got} vs {expected}"
                    );
                }
                let expected = (1.0 - w) * a.pdf(wo, wi) + w * b.pdf(wo, wi);
                let got = mix.pdf(wo, wi);
                assert!((got - expected).abs() <= 1e-5 * expected.max(1e-6));
                nonzero += usize::from(got > 0.0);
            }
        }
    }
    assert!(nonzero > 3000, "too few pairs with a density: {nonzero}");
}

#[test]
fn u1_below_the_weight_picks_the_second_part() {
    // Diffuse first, a mirror second: the mirror's delta sample says which
    // part was picked, and keeps its own weight with the pick's
    // probability as its discrete density.
    let w = 0.3;
    let bsdf = blend(
        w,
        diffuse(Vec3::ONE),
        Bsdf::Mirror {
            reflectance: Vec3::splat(0.5),
        },
    );
    let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
    let u2 = Vec2::new(0.4, 0.7);
    for u1 in [0.0, 0.1, 0.29] {
        let s = bsdf.sample(wo, u1, u2).expect("the mirror reflects");
        assert!(s.is_specular(), "u1 = {u1}: {s:?}");
        assert!(
            (s.pdf - w).abs() < 1e-6 && (s.weight() - Vec3::splat(0.5)).abs().max_element() < 1e-5
        );
    }
    for u1 in [0.3, 0.5, 0.999] {
        let s = bsdf.sample(wo, u1, u2).expect("the diffuse part reflects");
        assert!(!s.is_specular(), "u1 = {u1}: {s:?}");
        // Only the diffuse part has a density: the weight is its albedo.
        assert!((s.weight() - Vec3::ONE).abs().max_element() < 1e-5, "{s:?}");
    }
    // The smooth part reaches light sampling, the delta one does not.
    assert!(!bsdf.is_specular() && bsdf.flags().intersects(super::BsdfFlags::SPECULAR));
    assert!(blend(
        0.5,
        glass(1.5),
        Bsdf::Mirror {
            reflectance: Vec3::ONE
        }
    )
    .is_specular());
}

#[test]
fn blends_of_lossless_parts_pass_the_white_furnace() {
    // Every part conserves energy, so every mixture does: the sampled
    // energy albedo (refraction's η² undone, see `test_support`) is 1.
    let white = diffuse(Vec3::ONE);
    let cases = [
        (
            "white diffuse + smooth glass",
            blend(0.3, white.clone(), glass(1.5)),
            1.5,
        ),
        (
            "white diffuse + white smooth plastic",
            blend(
                0.6,
                white.clone(),
                Bsdf::Plastic(Plastic::new(Vec3::ONE, Vec3::ONE, 1.5)),
            ),
            1.0,
        ),
        (
            "nested: (white diffuse + mirror) + smooth glass",
            blend(
                0.5,
                blend(
                    0.2,
                    white.clone(),
                    Bsdf::Mirror {
                        reflectance: Vec3::ONE,
                    },
                ),
                glass(1.5),
            ),
            1.5,
        ),
    ];
    for (name, bsdf, ior) in cases {
        for wo in test_directions() {
            // Opaque parts are two-sided here; glass reads the side.
            let e = energy_albedo_by_sampling(&bsdf, wo, ior, 20_000);
            assert_estimates_agree(&format!("{name} at {wo}"), &e, Vec3::ONE, Vec3::ZERO);
        }
    }
    // The smooth part alone, by quadrature of f: (1 − w) of the white
    // diffuse; the mirror's w is a delta that f does not see.
    let bsdf = blend(
        0.2,
        white,
        Bsdf::Mirror {
            reflectance: Vec3::ONE,
        },
    );
    for wo in test_directions() {
        let smooth = hemisphere_integral(wo, |wi| bsdf.f(wo, wi).x * wi.z.abs());
        assert!((smooth - 0.8).abs() < 1e-3, "{wo}: {smooth}");
    }
}

#[test]
fn a_black_part_loses_its_share() {
    let bsdf = Bsdf::Blend(Box::new(Blend::new(0.35, None, Some(diffuse(Vec3::ONE)))));
    let wo = Vec3::new(0.2, -0.4, 0.8).normalize();
    let e = albedo_by_sampling(&bsdf, wo, 40_000);
    let u = albedo_by_uniform_sphere(&bsdf, wo, 40_000);
    assert_estimates_agree(
        "black + white diffuse (sampled)",
        &e,
        Vec3::splat(0.35),
        Vec3::ZERO,
    );
    assert_estimates_agree(
        "black + white diffuse (uniform)",
        &u,
        Vec3::splat(0.35),
        Vec3::ZERO,
    );
}

#[test]
fn a_weight_out_of_range_is_clamped() {
    let [a, b] = [diffuse(Vec3::ONE), rough_gold()];
    for (w, expected) in [(-0.5, 0.0), (1.5, 1.0), (f32::NAN, 0.0)] {
        let m = Blend::new(w, Some(a.clone()), Some(b.clone()));
        assert_eq!(m.weight, expected, "{w}");
    }
}
