//! Rough plastic: chi-square at every test direction (grazing included),
//! sample/f/pdf consistency, reciprocity, the coating table against
//! quadrature, and the white furnace with its energy curve.
//!
//! Furnace figures printed by `rough_plastic_furnace_curve` (white base and
//! coating, IOR 1.5; 20k samples, ±0.003): the albedo E(μo) + T(μo) R at
//! θo = 0°, 60°, 85°, R = T̄/(η²(1 − F_int)) (1 for a smooth coating). The
//! loss is the coating's single-scattering masking on the way in, out and
//! in its internal reflections, as in Mitsuba 3's `roughplastic` (whose
//! separable G1·G1 loses a little more); see `rough_plastic.rs`.
//!
//! | α    | Beckmann: R; albedo      | GGX: R; albedo           |
//! |------|--------------------------|--------------------------|
//! | 0.05 | 0.997; 0.997 0.997 0.951 | 0.979; 0.979 0.979 0.922 |
//! | 0.1  | 0.987; 0.988 0.989 0.928 | 0.932; 0.934 0.931 0.882 |
//! | 0.2  | 0.947; 0.949 0.945 0.919 | 0.807; 0.811 0.799 0.787 |
//! | 0.3  | 0.885; 0.889 0.876 0.882 | 0.701; 0.704 0.683 0.682 |
//! | 0.5  | 0.747; 0.754 0.735 0.764 | 0.561; 0.556 0.520 0.526 |
//! | 0.7  | 0.634; 0.637 0.623 0.647 | 0.477; 0.460 0.414 0.427 |
//! | 1.0  | 0.528; 0.520 0.502 0.522 | 0.400; 0.365 0.311 0.337 |

use glam::Vec3;

use super::coating::{coating_table, internal_reflectance, reflection_albedo};
use super::plastic::diffuse_fresnel_reflectance;
use super::test_support::*;
use super::{Bsdf, InternalReflectance, Masking, MicrofacetDistribution, RoughPlastic};

const IOR: f32 = 1.5;

fn red(dist: MicrofacetDistribution) -> Bsdf {
    Bsdf::RoughPlastic(RoughPlastic::new(
        dist,
        Vec3::new(0.8, 0.2, 0.1),
        Vec3::ONE,
        IOR,
        false,
    ))
}

fn white(dist: MicrofacetDistribution, nonlinear: bool) -> Bsdf {
    Bsdf::RoughPlastic(RoughPlastic::new(
        dist,
        Vec3::ONE,
        Vec3::ONE,
        IOR,
        nonlinear,
    ))
}

/// The coating alone: no base, white specular tint.
fn coating_only(dist: MicrofacetDistribution) -> Bsdf {
    Bsdf::RoughPlastic(RoughPlastic::new(dist, Vec3::ZERO, Vec3::ONE, IOR, false))
}

#[test]
fn rough_plastic_sampling_matches_its_pdf() {
    // A narrow Beckmann lobe (on a finer grid) and a wide GGX one.
    for dist in [
        MicrofacetDistribution::beckmann(0.05),
        MicrofacetDistribution::ggx(0.5),
    ] {
        let resolution = if dist.alphas().0 < 0.1 {
            (81, 161)
        } else {
            (21, 41)
        };
        for wo in test_directions() {
            assert_chi2_with(&format!("{dist:?}"), &red(dist), wo, 300_000, resolution);
        }
    }
}

#[test]
fn rough_plastic_samples_are_consistent() {
    for dist in [
        MicrofacetDistribution::beckmann(0.001),
        MicrofacetDistribution::beckmann(0.3),
        MicrofacetDistribution::ggx(1.0),
    ] {
        for bsdf in [red(dist), coating_only(dist), white(dist, true)] {
            for wo in test_directions() {
                assert_samples_consistent(&bsdf, wo);
            }
        }
    }
}

#[test]
fn rough_plastic_is_reciprocal_and_two_sided() {
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    for bsdf in [
        red(MicrofacetDistribution::beckmann(0.2)),
        red(MicrofacetDistribution::ggx(0.5)),
    ] {
        for (wo, wi) in [
            (Vec3::new(0.3, -0.2, 0.93), Vec3::new(-0.7, 0.1, 0.3)),
            (Vec3::new(0.9, 0.1, 0.05), Vec3::new(0.2, 0.3, 0.9)),
            (Vec3::new(-0.4, 0.4, 0.8), Vec3::new(0.35, -0.45, 0.82)),
        ] {
            let (wo, wi) = (wo.normalize(), wi.normalize());
            let (a, b) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
            assert!((a - b).abs().max_element() <= 1e-5 * a.max_element().max(1.0));
            assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)));
            assert_eq!(bsdf.f(wo, flip(wi)), Vec3::ZERO);
        }
        let flags = bsdf.flags();
        assert!(!bsdf.is_specular() && !flags.is_specular() && flags.is_non_specular());
    }
}

#[test]
fn coating_table_matches_quadrature() {
    // The coating's reflection albedo E and transmitted energy T against an
    // adaptive quadrature (independent of the tables' visible-normal grid)
    // of the coating lobe and of the rough dielectric's refraction lobe
    // (times η², undoing the radiance scaling), at the table's nodes and
    // between them.
    for dist in [
        MicrofacetDistribution::beckmann(0.1),
        MicrofacetDistribution::ggx(0.3),
        MicrofacetDistribution::beckmann(1.0),
    ] {
        let coat = coating_only(dist);
        let glass = Bsdf::RoughGlass {
            distribution: dist,
            masking: Masking::HeightCorrelated,
            reflectance: Vec3::ONE,
            transmittance: Vec3::ONE,
            ior: IOR,
        };
        let table = coating_table(
            dist,
            Masking::HeightCorrelated,
            InternalReflectance::Integral,
            IOR,
        );
        for mu in [1.0f32, 0.8, 0.51, 0.25, 0.1] {
            let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            let below = Vec3::new(wo.x, wo.y, -wo.z);
            let e = hemisphere_integral(wo, |wi| coat.f(wo, wi).x * wi.z.abs());
            let t = hemisphere_integral(below, |wi| glass.f(wo, wi).x * wi.z.abs() * IOR * IOR);
            let (e_table, t_table) = (
                reflection_albedo(dist, Masking::HeightCorrelated, IOR, mu, 64),
                table.transmittance(mu),
            );
            assert!(
                (e - e_table).abs() < 2e-3,
                "{dist:?} μ = {mu}: E {e} vs {e_table}"
            );
            assert!(
                (t - t_table).abs() < 3e-3,
                "{dist:?} μ = {mu}: T {t} vs {t_table}"
            );
            assert!(e + t <= 1.0 + 2e-3, "{dist:?} μ = {mu}: {e} + {t}");
        }
    }
}

#[test]
fn smooth_coating_limit_matches_the_smooth_plastic() {
    // As α → 0 the coating's albedos tend to the Fresnel reflectance and
    // F_int to the smooth interface's internal diffuse reflectance (0.596
    // for η = 1.5).
    let dist = MicrofacetDistribution::ggx(0.002);
    let table = coating_table(
        dist,
        Masking::HeightCorrelated,
        InternalReflectance::Integral,
        IOR,
    );
    let smooth = diffuse_fresnel_reflectance(1.0 / IOR);
    assert!(
        (table.internal_reflectance() - smooth).abs() < 5e-3,
        "{} vs {smooth}",
        table.internal_reflectance()
    );
    for mu in [1.0f32, 0.5, 0.2] {
        let fresnel = super::fresnel::fresnel_dielectric(mu, IOR);
        assert!(
            (reflection_albedo(dist, Masking::HeightCorrelated, IOR, mu, 32) - fresnel).abs()
                < 2e-3
        );
    }
}

/// (E(μo), T(μo), R): the furnace albedo at ρ = 1 is exactly E + T R,
/// R = T̄ / (η² (1 − F_int)) (1 for a smooth coating).
fn furnace_prediction(dist: MicrofacetDistribution, mu: f32) -> (f32, f32, f32) {
    let table = coating_table(
        dist,
        Masking::HeightCorrelated,
        InternalReflectance::Integral,
        IOR,
    );
    let n = 256;
    let diffuse_transmittance: f32 = (0..n)
        .map(|j| {
            let m = (j as f32 + 0.5) / n as f32;
            2.0 * m * table.transmittance(m)
        })
        .sum::<f32>()
        / n as f32;
    let ratio = diffuse_transmittance / (IOR * IOR * (1.0 - table.internal_reflectance()));
    (
        reflection_albedo(dist, Masking::HeightCorrelated, IOR, mu, 64),
        table.transmittance(mu),
        ratio,
    )
}

#[test]
fn rough_plastic_furnace_curve() {
    // White base and coating: the albedo is E(μo) + T(μo) R (module docs of
    // rough_plastic.rs); it never exceeds 1, and sampling agrees with the
    // prediction from the tables.
    eprintln!("rough plastic furnace (η = {IOR}): α, R, albedo at θo = 0°, 60°, 85°");
    for (kind, make) in [
        ("beckmann", MicrofacetDistribution::beckmann as fn(f32) -> _),
        ("ggx", MicrofacetDistribution::ggx),
    ] {
        for alpha in [0.05f32, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0] {
            let dist = make(alpha);
            let mut row = format!("{kind:8} α = {alpha:4}:");
            for theta in [0.0f32, 60.0, 85.0] {
                let (s, c) = theta.to_radians().sin_cos();
                let wo = Vec3::new(s * 0.8, s * 0.6, c);
                let (e, t, ratio) = furnace_prediction(dist, c);
                assert!(ratio <= 1.0 + 1e-3, "{kind} α = {alpha}: R = {ratio}");
                let predicted = e + t * ratio;
                let sampled = albedo_by_sampling(&white(dist, false), wo, 20_000);
                assert!(
                    sampled.mean.x <= 1.0 + 3.0 * sampled.std_error.x + 1e-6,
                    "{kind} α = {alpha} θ = {theta}: {} ± {}",
                    sampled.mean.x,
                    sampled.std_error.x
                );
                // The table's interpolation and grid add about 1e-3.
                assert_estimates_agree(
                    &format!("{kind} α = {alpha} θ = {theta}"),
                    &sampled,
                    Vec3::splat(predicted),
                    Vec3::splat(1e-3),
                );
                if theta == 0.0 {
                    row += &format!(" R = {ratio:.4}, albedo");
                }
                row += &format!(" {:.4}", sampled.mean.x);
            }
            eprintln!("{row}");
        }
    }
}

#[test]
fn nonlinear_mode_sums_the_round_trips() {
    // ρ' = ρ/(1 − ρ F_int) (nonlinear) against ρ/(1 − F_int) (linear): equal
    // at ρ = 1, the nonlinear one darker for ρ < 1, in the ratio of the two
    // denominators; the coating lobe is the same.
    let dist = MicrofacetDistribution::beckmann(0.3);
    let f_int = coating_table(
        dist,
        Masking::HeightCorrelated,
        InternalReflectance::Integral,
        IOR,
    )
    .internal_reflectance();
    let grey = |nonlinear| {
        Bsdf::RoughPlastic(RoughPlastic::new(
            dist,
            Vec3::splat(0.5),
            Vec3::ZERO,
            IOR,
            nonlinear,
        ))
    };
    let (wo, wi) = (Vec3::new(0.3, 0.0, 0.954), Vec3::new(-0.5, 0.2, 0.843));
    let ratio = grey(true).f(wo, wi).x / grey(false).f(wo, wi).x;
    assert!((ratio - (1.0 - f_int) / (1.0 - 0.5 * f_int)).abs() < 1e-5);
    let (a, b) = (white(dist, true).f(wo, wi), white(dist, false).f(wo, wi));
    assert!((a - b).abs().max_element() < 1e-6);
}

#[test]
fn even_sample_mean_is_the_coarse_average_of_the_smooth_limit() {
    // As α → 0, E_inside(μ) is the Fresnel reflectance R(μ) from inside, so
    // Mitsuba's F_int is (1/64) Σ 2 μ_j R(μ_j) at μ_j = j/63, summed here
    // from R directly, and the integral rule tends to the smooth
    // interface's internal diffuse reflectance. The two differ by about
    // (F_int − R(1))/64 = 0.0087 at η = 1.5, three times the tolerance,
    // which is the midpoint rule's error at the critical angle (R rises to
    // 1 there like a square root): about 2e-3 with 64 cosines.
    let dist = MicrofacetDistribution::ggx(0.002);
    let masking = Masking::Separable;
    let table = |rule| coating_table(dist, masking, rule, IOR).internal_reflectance();
    let even_sum: f32 = (1..64)
        .map(|j| {
            let mu = j as f32 / 63.0;
            2.0 * mu * super::fresnel::fresnel_dielectric(mu, 1.0 / IOR)
        })
        .sum();
    let (even, integral) = (
        table(InternalReflectance::EvenSampleMean),
        table(InternalReflectance::Integral),
    );
    let smooth = diffuse_fresnel_reflectance(1.0 / IOR);
    assert!(
        (even - even_sum / 64.0).abs() < 3e-3,
        "{even} vs {}",
        even_sum / 64.0
    );
    assert!((integral - smooth).abs() < 3e-3, "{integral} vs {smooth}");
}

#[test]
fn even_sample_mean_relates_to_the_integral_as_the_trapezoid_rule() {
    // The mean of g(μ) = 2 μ E(μ) at μ_j = j/63, j = 0..64, is
    // (63/64) × (the trapezoid rule) + (g(0) + g(1))/128, g(0) = 0: with
    // the trapezoid rule close to the integral, F_even = (63/64) F_int +
    // E(1)/64. The two sides come from different cosines (ends included
    // against midpoints); the edge of total internal reflection, a kink in
    // g, makes the trapezoid and midpoint rules differ by about 1e-3.
    for dist in [
        MicrofacetDistribution::beckmann(0.2),
        MicrofacetDistribution::ggx(0.3),
    ] {
        let masking = Masking::Separable;
        let table = |rule| coating_table(dist, masking, rule, IOR).internal_reflectance();
        let e1 = reflection_albedo(dist, masking, 1.0 / IOR, 1.0, 64);
        let predicted = 63.0 / 64.0 * table(InternalReflectance::Integral) + e1 / 64.0;
        let even = table(InternalReflectance::EvenSampleMean);
        assert!(
            (even - predicted).abs() < 1.5e-3,
            "{dist:?}: {even} vs {predicted}"
        );
    }
}

#[test]
fn internal_reflectance_grid_is_fine_enough() {
    // GGX's long tail: the midpoint grid over visible normals misses the
    // steepest normals, whose reflections go below the surface, so F_int
    // comes out high by about 0.13/grid (0.0042 at 32). The table's grid
    // against four times as fine a grid.
    let dist = MicrofacetDistribution::ggx(0.1);
    let masking = Masking::Separable;
    let rule = InternalReflectance::Integral;
    let table = coating_table(dist, masking, rule, IOR).internal_reflectance();
    let fine = internal_reflectance(dist, masking, rule, 1.0 / IOR, 256);
    assert!((table - fine).abs() < 2.5e-3, "{table} vs {fine}");
}

#[test]
fn textured_base_keeps_the_coating_conventions() {
    // A colour texture replaces the base only: the masking and F_int rule
    // the scene chose stay.
    let dist = MicrofacetDistribution::beckmann(0.2);
    let plastic = |diffuse| {
        RoughPlastic::with_conventions(
            dist,
            Masking::Separable,
            InternalReflectance::EvenSampleMean,
            diffuse,
            Vec3::ONE,
            IOR,
            false,
        )
    };
    let (a, b) = (Vec3::new(0.8, 0.2, 0.1), Vec3::new(0.1, 0.5, 0.9));
    assert_eq!(plastic(a).with_diffuse(b), plastic(b));
}
