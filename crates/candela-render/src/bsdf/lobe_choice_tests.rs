//! [`Bsdf::samples_a_lobe`]: a BSDF that says it does not read `u1` must
//! sample the same whatever `u1` is (the path tracer then skips drawing
//! it), and smooth glass, which chooses between reflection and refraction
//! with it, must say so.

use glam::{Vec2, Vec3};

use super::test_support::{test_directions, uniforms};
use super::Masking;
use super::{Bsdf, MicrofacetDistribution};
use crate::sampling::{Sampler, SamplerKind};

/// One BSDF of every variant with a single lobe.
fn one_lobe_bsdfs() -> [Bsdf; 6] {
    let (eta, k) = (Vec3::new(0.2, 0.9, 1.1), Vec3::new(3.9, 2.4, 2.2));
    [
        Bsdf::Diffuse {
            albedo: Vec3::splat(0.7),
        },
        Bsdf::Mirror {
            reflectance: Vec3::ONE,
        },
        Bsdf::Refraction {
            transmittance: Vec3::ONE,
            ior: 1.5,
        },
        Bsdf::Conductor { eta, k },
        Bsdf::Microfacet {
            distribution: MicrofacetDistribution::beckmann(0.3),
            masking: Masking::HeightCorrelated,
            eta,
            k,
        },
        Bsdf::Microfacet {
            distribution: MicrofacetDistribution::ggx(0.3),
            masking: Masking::HeightCorrelated,
            eta,
            k,
        },
    ]
}

#[test]
fn one_lobe_bsdfs_sample_the_same_for_every_u1() {
    let mut sampler = Sampler::new(SamplerKind::Independent, 3);
    for bsdf in one_lobe_bsdfs() {
        assert!(!bsdf.samples_a_lobe(), "{bsdf:?}");
        for wo in test_directions() {
            for i in 0..200 {
                let (_, u2) = uniforms(&mut sampler, i);
                let at_zero = bsdf.sample(wo, 0.0, u2);
                for u1 in [0.25, 0.5, 0.999_999] {
                    assert_eq!(bsdf.sample(wo, u1, u2), at_zero, "{bsdf:?} wo {wo} u1 {u1}");
                }
            }
        }
    }
}

#[test]
fn smooth_glass_reads_u1() {
    let glass = Bsdf::Glass {
        reflectance: Vec3::ONE,
        transmittance: Vec3::ONE,
        ior: 1.5,
    };
    assert!(glass.samples_a_lobe());
    let wo = Vec3::new(0.3, 0.2, 0.9).normalize();
    assert_ne!(
        glass.sample(wo, 0.0, Vec2::ZERO),
        glass.sample(wo, 0.999, Vec2::ZERO),
        "reflection and refraction"
    );
}
