//! The adjoint relation of the transport modes: the importance BSDF is the
//! radiance BSDF with its directions swapped, for the non-symmetric models
//! (refraction: rough glass, glTF and principled transmission) and with
//! shading normals that differ from the true normal.

use glam::{Vec2, Vec3};

use super::test_support::direction_pairs;
use super::transport::{shading_normal_correction, TransportMode};
use super::Masking;
use super::{
    Blend, Bsdf, BsdfSample, MetallicRoughness, MicrofacetDistribution, Principled,
    PrincipledParameters,
};
use crate::geometry::Frame;
use crate::sampling::{Sampler, SamplerKind};

/// Relative agreement of two colours to 0.1 % (f32 half vectors near
/// grazing pairs lose a few digits), with an absolute floor of 10⁻⁵ for the
/// tiny values of such pairs; the two modes differ by η² ≈ 2.25 or by the
/// shading-normal factor, far beyond that.
fn assert_close(a: Vec3, b: Vec3, what: &str) {
    let scale = a.abs().max(b.abs()).max_element().max(1e-2);
    assert!(
        (a - b).abs().max_element() <= 1e-3 * scale,
        "{what}: {a} vs {b}"
    );
}

fn transmitting_bsdfs() -> Vec<(&'static str, Bsdf)> {
    vec![
        (
            "rough glass ggx",
            Bsdf::RoughGlass {
                distribution: MicrofacetDistribution::ggx(0.3),
                masking: Masking::HeightCorrelated,
                reflectance: Vec3::new(0.9, 0.8, 1.0),
                transmittance: Vec3::new(1.0, 0.7, 0.9),
                ior: 1.5,
            },
        ),
        (
            "rough glass beckmann, ior < 1",
            Bsdf::RoughGlass {
                distribution: MicrofacetDistribution::beckmann(0.5),
                masking: Masking::HeightCorrelated,
                reflectance: Vec3::ONE,
                transmittance: Vec3::ONE,
                ior: 0.8,
            },
        ),
        (
            "glTF transmission",
            Bsdf::MetallicRoughness(MetallicRoughness::new(
                Vec3::new(0.8, 0.6, 0.4),
                0.0,
                0.4,
                1.0,
                1.5,
            )),
        ),
        (
            "principled transmission",
            Bsdf::Principled(Principled::new(PrincipledParameters {
                base_color: Vec3::new(0.8, 0.6, 0.4),
                roughness: 0.5,
                metallic: 0.1,
                spec_trans: 0.7,
                eta: 1.4,
                sheen: 0.5,
                clearcoat: 0.5,
                ..PrincipledParameters::default()
            })),
        ),
        (
            // Each part takes its own η²: no one factor fits both.
            "blend of rough glasses of two IORs",
            Bsdf::Blend(Box::new(Blend::new(
                0.4,
                Some(Bsdf::RoughGlass {
                    distribution: MicrofacetDistribution::ggx(0.3),
                    masking: Masking::HeightCorrelated,
                    reflectance: Vec3::ONE,
                    transmittance: Vec3::new(1.0, 0.7, 0.9),
                    ior: 1.5,
                }),
                Some(Bsdf::RoughGlass {
                    distribution: MicrofacetDistribution::beckmann(0.4),
                    masking: Masking::HeightCorrelated,
                    reflectance: Vec3::ONE,
                    transmittance: Vec3::ONE,
                    ior: 1.2,
                }),
            ))),
        ),
    ]
}

#[test]
fn importance_bsdf_is_the_radiance_bsdf_with_directions_swapped() {
    let mut transmitted = 0;
    for (name, bsdf) in transmitting_bsdfs() {
        for (wo, wi) in direction_pairs(4000, 15) {
            let importance = bsdf.f_mode(wo, wi, TransportMode::Importance);
            let radiance_swapped = bsdf.f_mode(wi, wo, TransportMode::Radiance);
            assert_close(importance, radiance_swapped, name);
            if wo.z * wi.z < 0.0 && importance.max_element() > 0.0 {
                transmitted += 1;
                // Not symmetric in radiance mode: the test has teeth.
                let radiance = bsdf.f_mode(wo, wi, TransportMode::Radiance);
                assert!(
                    (radiance - importance).abs().max_element() > 1e-3 * importance.max_element()
                );
            }
        }
    }
    assert!(
        transmitted > 1000,
        "too few transmitted pairs: {transmitted}"
    );
}

/// Samples of `bsdf` at `wo` in radiance and in importance mode from the
/// same `n` random numbers (seeded by `seed`), where both succeed: the two
/// modes must pick the same directions with the same densities.
fn samples_in_both_modes(
    bsdf: &Bsdf,
    wo: Vec3,
    seed: u64,
    n: u32,
) -> Vec<(BsdfSample, BsdfSample)> {
    let mut sampler = Sampler::new(SamplerKind::Independent, seed);
    let mut pairs = Vec::new();
    for i in 0..n {
        sampler.start_pixel_sample(0, 0, i);
        let (u1, u2) = (sampler.next_1d(), sampler.next_2d());
        if let (Some(r), Some(m)) = (
            bsdf.sample_mode(wo, u1, u2, TransportMode::Radiance),
            bsdf.sample_mode(wo, u1, u2, TransportMode::Importance),
        ) {
            assert_eq!((r.wi, r.pdf), (m.wi, m.pdf), "{wo} {u1} {u2}");
            pairs.push((r, m));
        }
    }
    pairs
}

#[test]
fn sample_mode_scales_only_transmission_in_importance_mode() {
    let (_, bsdf) = transmitting_bsdfs().remove(0);
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    let mut seen = [false; 2];
    for (r, m) in samples_in_both_modes(&bsdf, wo, 3, 256) {
        let scale = if r.flags.is_transmission() {
            1.5 * 1.5
        } else {
            1.0
        };
        assert_close(m.f, r.f * scale, "sampled f");
        assert_close(
            m.f,
            bsdf.f_mode(wo, m.wi, TransportMode::Importance),
            "f of the sample",
        );
        seen[r.flags.is_transmission() as usize] = true;
    }
    assert_eq!(seen, [true, true], "both lobes sampled");
}

/// glTF materials under a clear coat, whose weight on the layers beneath
/// reads the view alone: opaque (rough and smooth coats) and transmissive.
fn coated_bsdfs() -> Vec<(&'static str, Bsdf)> {
    let coated = |metallic: f32, roughness: f32, transmission: f32, coat: (f32, f32)| {
        Bsdf::MetallicRoughness(
            MetallicRoughness::new(
                Vec3::new(0.8, 0.6, 0.4),
                metallic,
                roughness,
                transmission,
                1.5,
            )
            .with_clearcoat(coat.0, coat.1),
        )
    };
    vec![
        (
            "rough coat over dielectric",
            coated(0.0, 0.5, 0.0, (1.0, 0.3)),
        ),
        ("smooth coat over metal", coated(1.0, 0.4, 0.0, (0.8, 0.0))),
        ("rough coat over glass", coated(0.0, 0.4, 0.8, (1.0, 0.2))),
    ]
}

#[test]
fn a_coated_models_importance_is_its_radiance_with_directions_swapped() {
    let mut asymmetric = 0;
    for (name, bsdf) in coated_bsdfs() {
        for (wo, wi) in direction_pairs(4000, 17) {
            let importance = bsdf.f_mode(wo, wi, TransportMode::Importance);
            assert_close(
                importance,
                bsdf.f_mode(wi, wo, TransportMode::Radiance),
                name,
            );
            let radiance = bsdf.f_mode(wo, wi, TransportMode::Radiance);
            if wo.z * wi.z > 0.0
                && (radiance - importance).abs().max_element() > 1e-2 * importance.max_element()
            {
                asymmetric += 1;
            }
        }
        // Sampled values are the mode's too, at the same directions and
        // densities.
        let wo = Vec3::new(0.5, -0.1, 0.6).normalize();
        for (_, m) in samples_in_both_modes(&bsdf, wo, 5, 512) {
            if !m.is_specular() {
                assert_close(m.f, bsdf.f_mode(wo, m.wi, TransportMode::Importance), name);
            }
        }
    }
    // Reflected pairs whose two values differ: without the swap the
    // adjoint would be wrong, so the test has teeth.
    assert!(asymmetric > 1000, "only {asymmetric} asymmetric pairs");
}

/// The scattering kernel per unit projected solid angle of the *true*
/// surface, as a path carrying `mode` applies it: f · |wi·ns| / |wi·ng|,
/// times the shading-normal correction of the mode.
fn kernel(bsdf: &Bsdf, frame: &Frame, ng: Vec3, wo: Vec3, wi: Vec3, mode: TransportMode) -> Vec3 {
    let f = bsdf.f_mode(frame.to_local(wo), frame.to_local(wi), mode);
    f * (wi.dot(frame.z).abs() / wi.dot(ng).abs())
        * shading_normal_correction(mode, wo, wi, frame.z, ng)
}

#[test]
fn shading_normals_keep_the_adjoint_relation() {
    // A bent shading normal (a normal map's), 35° off the true normal.
    let ng = Vec3::Z;
    let frame = Frame::from_normal(Vec3::new(0.35f32.sin(), 0.0, 0.35f32.cos()).normalize());
    let mut bsdfs = transmitting_bsdfs();
    bsdfs.push((
        "diffuse",
        Bsdf::Diffuse {
            albedo: Vec3::new(0.7, 0.5, 0.3),
        },
    ));
    let mut asymmetric = 0;
    for (name, bsdf) in bsdfs {
        for (wo, wi) in direction_pairs(2000, 15) {
            if wo.dot(ng).abs() < 1e-3 || wi.dot(ng).abs() < 1e-3 {
                continue;
            }
            let importance = kernel(&bsdf, &frame, ng, wo, wi, TransportMode::Importance);
            let radiance_swapped = kernel(&bsdf, &frame, ng, wi, wo, TransportMode::Radiance);
            assert_close(importance, radiance_swapped, name);
            let radiance = kernel(&bsdf, &frame, ng, wo, wi, TransportMode::Radiance);
            if (radiance - importance).abs().max_element() > 1e-2 * importance.max_element() {
                asymmetric += 1;
            }
        }
    }
    // Without the correction the kernel is not symmetric: the test has teeth.
    assert!(asymmetric > 1000, "only {asymmetric} asymmetric pairs");
}

#[test]
fn radiance_mode_is_the_plain_bsdf() {
    let (_, bsdf) = transmitting_bsdfs().remove(0);
    for (wo, wi) in direction_pairs(200, 15) {
        assert_eq!(bsdf.f_mode(wo, wi, TransportMode::Radiance), bsdf.f(wo, wi));
    }
    let n = Vec3::Z;
    let (wo, wi) = (Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, 0.6, -0.8));
    assert_eq!(
        shading_normal_correction(TransportMode::Radiance, wo, wi, n, n),
        1.0
    );
    assert!(
        (shading_normal_correction(TransportMode::Importance, wo, wi, n, n) - 1.0).abs() < 1e-6
    );
    let _ = Vec2::ZERO;
}
