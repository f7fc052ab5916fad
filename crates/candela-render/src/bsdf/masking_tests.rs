//! The two ways of combining masking (`Masking`): separable G1·G1 never
//! exceeds the height-correlated G2, both give the sampled value `eval`
//! gives, and both stay reciprocal, for the rough conductor, the rough
//! dielectric and the rough plastic (whose coating table follows the
//! choice).

use glam::Vec3;

use super::coating::coating_table;
use super::test_support::*;
use super::{Bsdf, InternalReflectance, Masking, MicrofacetDistribution, RoughPlastic};
use crate::sampling::warp::square_to_uniform_sphere;
use crate::sampling::{Sampler, SamplerKind};

const BOTH: [Masking; 2] = [Masking::HeightCorrelated, Masking::Separable];

/// A rough conductor, rough glass and rough plastic of `dist`, combining
/// their masking as `masking` says.
fn models(dist: MicrofacetDistribution, masking: Masking) -> [(&'static str, Bsdf); 3] {
    [
        (
            "conductor",
            Bsdf::Microfacet {
                distribution: dist,
                masking,
                eta: Vec3::new(0.2, 0.9, 1.1),
                k: Vec3::new(3.9, 2.4, 2.2),
            },
        ),
        (
            "rough glass",
            Bsdf::RoughGlass {
                distribution: dist,
                masking,
                reflectance: Vec3::ONE,
                transmittance: Vec3::ONE,
                ior: 1.5,
            },
        ),
        (
            "rough plastic",
            Bsdf::RoughPlastic(RoughPlastic::with_conventions(
                dist,
                masking,
                InternalReflectance::Integral,
                Vec3::new(0.6, 0.3, 0.2),
                Vec3::ONE,
                1.49,
                false,
            )),
        ),
    ]
}

fn distributions() -> [MicrofacetDistribution; 3] {
    [
        MicrofacetDistribution::beckmann(0.2),
        MicrofacetDistribution::ggx(0.5),
        MicrofacetDistribution::Ggx {
            alpha_x: 0.1,
            alpha_y: 0.6,
        },
    ]
}

/// Random direction pairs on the sphere (fixed seed).
fn pairs(n: u32) -> Vec<(Vec3, Vec3)> {
    let mut sampler = Sampler::new(SamplerKind::Independent, 3);
    (0..n)
        .map(|i| {
            let (_, a) = uniforms(&mut sampler, 2 * i);
            let (_, b) = uniforms(&mut sampler, 2 * i + 1);
            (square_to_uniform_sphere(a), square_to_uniform_sphere(b))
        })
        .collect()
}

/// G1(wo)·G1(wi) ≤ 1 / (1 + Λ(wo) + Λ(wi)) for every pair, so each model
/// is at most as bright with separable masking at every pair, and darker
/// in sum over the pairs; the sampling densities do not depend on it.
#[test]
fn separable_masking_is_never_brighter() {
    for dist in distributions() {
        let correlated = models(dist, Masking::HeightCorrelated);
        let separable = models(dist, Masking::Separable);
        for ((name, hc), (_, sep)) in correlated.iter().zip(&separable) {
            let (mut sum_hc, mut sum_sep) = (0.0f64, 0.0f64);
            for (wo, wi) in pairs(4000) {
                let (a, b) = (hc.f(wo, wi), sep.f(wo, wi));
                // The plastic's base lobe uses the coating table of its own
                // masking, whose transmittances are also lower.
                assert!(
                    b.cmple(a * (1.0 + 1e-5) + 1e-7).all(),
                    "{name} {dist:?}: {b} > {a}"
                );
                sum_hc += f64::from(a.element_sum());
                sum_sep += f64::from(b.element_sum());
                if *name != "rough plastic" {
                    assert_eq!(hc.pdf(wo, wi), sep.pdf(wo, wi), "{name} {dist:?}");
                }
            }
            assert!(sum_sep < sum_hc, "{name} {dist:?}: {sum_sep} vs {sum_hc}");
        }
    }
}

/// A sample's value and density are what `f` and `pdf` give at its
/// direction, with either masking.
#[test]
fn samples_are_consistent_with_either_masking() {
    for masking in BOTH {
        for dist in distributions() {
            for (_, bsdf) in models(dist, masking) {
                for wo in test_directions() {
                    assert_samples_consistent(&bsdf, wo);
                }
            }
        }
    }
}

/// Reflection stays reciprocal: f(wo, wi) = f(wi, wo) for pairs on one
/// side, both models that only reflect and the glass's reflection.
#[test]
fn reflection_is_reciprocal_with_either_masking() {
    for masking in BOTH {
        for dist in distributions() {
            for (name, bsdf) in models(dist, masking) {
                for (wo, wi) in pairs(2000) {
                    if wo.z * wi.z <= 0.0 {
                        continue;
                    }
                    let (a, b) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
                    assert!(
                        (a - b)
                            .abs()
                            .cmple(1e-4 * a.abs().max(b.abs()) + 1e-6)
                            .all(),
                        "{name} {masking:?} {dist:?}: {a} vs {b}"
                    );
                }
            }
        }
    }
}

/// The coating table follows the masking: separable lets in no more at any
/// angle, less at a grazing one (G1(wt) < G2(wo, wt) / G1(wo) whenever both
/// Λ are positive), and reflects less inside.
#[test]
fn coating_table_follows_the_masking() {
    let dist = MicrofacetDistribution::beckmann(0.3);
    let hc = coating_table(
        dist,
        Masking::HeightCorrelated,
        InternalReflectance::Integral,
        1.49,
    );
    let sep = coating_table(
        dist,
        Masking::Separable,
        InternalReflectance::Integral,
        1.49,
    );
    for j in 0..=20 {
        let mu = (j as f32 / 20.0).max(0.02);
        assert!(
            sep.transmittance(mu) <= hc.transmittance(mu) + 1e-6,
            "mu {mu}"
        );
    }
    assert!(sep.transmittance(0.02) < hc.transmittance(0.02));
    assert!(sep.internal_reflectance() < hc.internal_reflectance());
}
