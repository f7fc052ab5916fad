//! Delta BSDFs: exact directions and weights, Fresnel branch frequencies.

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_dielectric;
use super::test_support::{test_directions, uniforms};
use super::Bsdf;
use crate::sampling::{Sampler, SamplerKind};

const R: Vec3 = Vec3::new(0.9, 0.8, 0.7);
const T: Vec3 = Vec3::new(0.6, 0.95, 1.0);

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol * b.abs().max_element().max(1.0)
}

/// sin θ of a unit local direction.
fn sin_theta(w: Vec3) -> f32 {
    w.truncate().length()
}

/// Checks `wi` is the refraction of `wo` with relative IOR `eta`: opposite
/// side, opposite azimuth, Snell's law.
fn assert_refracted(wo: Vec3, wi: Vec3, eta: f32) {
    assert!(wo.z * wi.z < 0.0, "{wo:?} {wi:?}");
    assert!((wi.length() - 1.0).abs() < 1e-5);
    assert!(
        (sin_theta(wo) - eta * sin_theta(wi)).abs() < 1e-5,
        "Snell: {wo:?} {wi:?} η = {eta}"
    );
    assert!(wo.truncate().dot(wi.truncate()) <= 1e-6, "azimuth flips");
    assert!(
        wo.truncate().perp_dot(wi.truncate()).abs() < 1e-5,
        "same plane of incidence"
    );
}

#[test]
fn mirror_reflects_exactly_with_weight_reflectance() {
    let mirror = Bsdf::Mirror { reflectance: R };
    assert!(mirror.is_specular() && mirror.flags().is_reflection());
    for wo in test_directions() {
        for u in [0.0f32, 0.3, 0.999] {
            let s = mirror
                .sample(wo, u, Vec2::splat(u))
                .expect("a mirror always reflects");
            assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
            assert!(s.is_specular());
            assert!(close(s.weight(), R, 1e-5), "{wo:?}: {:?}", s.weight());
        }
        assert_eq!(mirror.f(wo, Vec3::new(-wo.x, -wo.y, wo.z)), Vec3::ZERO);
        assert_eq!(mirror.pdf(wo, Vec3::new(-wo.x, -wo.y, wo.z)), 0.0);
    }
}

#[test]
fn refraction_follows_snell_with_radiance_scaling_and_fails_at_tir() {
    let ior = 1.5;
    let bsdf = Bsdf::Refraction {
        transmittance: T,
        ior,
    };
    assert!(bsdf.is_specular() && bsdf.flags().is_transmission() && !bsdf.flags().is_reflection());
    let critical_sin = 1.0 / ior;
    for wo in test_directions() {
        let eta = if wo.z > 0.0 { ior } else { 1.0 / ior };
        let s = bsdf.sample(wo, 0.5, Vec2::splat(0.5));
        if wo.z < 0.0 && sin_theta(wo) > critical_sin {
            assert!(
                s.is_none(),
                "total internal reflection loses the path: {wo:?}"
            );
            continue;
        }
        let s = s.expect("refraction below the critical angle");
        assert_refracted(wo, s.wi, eta);
        assert!(
            close(s.weight(), T / (eta * eta), 1e-5),
            "{wo:?}: {:?}",
            s.weight()
        );
        assert_eq!(bsdf.f(wo, s.wi), Vec3::ZERO);
        assert_eq!(bsdf.pdf(wo, s.wi), 0.0);
    }
}

#[test]
fn glass_chooses_reflection_with_fresnel_probability() {
    let ior = 1.5;
    let glass = Bsdf::Glass {
        reflectance: R,
        transmittance: T,
        ior,
    };
    assert!(
        glass.is_specular() && glass.flags().is_reflection() && glass.flags().is_transmission()
    );
    let mut sampler = Sampler::new(SamplerKind::Independent, 41);
    let n = 20_000;
    for wo in test_directions() {
        let fresnel = fresnel_dielectric(wo.z, ior);
        let eta = if wo.z > 0.0 { ior } else { 1.0 / ior };
        let mut reflected = 0u32;
        for i in 0..n {
            let (u1, u2) = uniforms(&mut sampler, i);
            let s = glass.sample(wo, u1, u2).expect("glass always scatters");
            if s.wi.z * wo.z > 0.0 {
                reflected += 1;
                assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
                assert!(close(s.weight(), R, 1e-5));
                assert!((s.pdf - fresnel).abs() < 1e-6);
            } else {
                assert_refracted(wo, s.wi, eta);
                assert!(close(s.weight(), T / (eta * eta), 1e-5));
                assert!((s.pdf - (1.0 - fresnel)).abs() < 1e-6);
            }
        }
        // Binomial: the frequency of reflection is F within 5 σ.
        let p = f64::from(fresnel);
        let sigma = (p * (1.0 - p) / f64::from(n)).sqrt();
        let freq = f64::from(reflected) / f64::from(n);
        assert!(
            (freq - p).abs() <= 5.0 * sigma + 1e-9,
            "{wo:?}: {freq} vs F = {p}"
        );
        if wo.z < 0.0 && sin_theta(wo) > 1.0 / ior {
            assert_eq!(reflected, n, "total internal reflection at {wo:?}");
        }
    }
}

#[test]
fn glass_conserves_energy_up_to_radiance_compression() {
    // With white tints, reflected plus η²-rescaled refracted throughput is
    // exactly 1 for every u1: the interface neither creates nor destroys flux.
    let glass = Bsdf::Glass {
        reflectance: Vec3::ONE,
        transmittance: Vec3::ONE,
        ior: 1.33,
    };
    for wo in test_directions() {
        let fresnel = fresnel_dielectric(wo.z, 1.33);
        let eta = if wo.z > 0.0 { 1.33f32 } else { 1.0 / 1.33 };
        let (mut reflected, mut refracted) = (0.0f32, 0.0f32);
        let n = 1000;
        for i in 0..n {
            let u1 = (i as f32 + 0.5) / n as f32;
            let Some(s) = glass.sample(wo, u1, Vec2::ZERO) else {
                continue;
            };
            if s.wi.z * wo.z > 0.0 {
                reflected += s.weight().x / n as f32;
            } else {
                refracted += s.weight().x * eta * eta / n as f32;
            }
        }
        assert!(
            (reflected + refracted - 1.0).abs() < 2e-3,
            "{wo:?}: {reflected} + {refracted}"
        );
        assert!((reflected - fresnel).abs() < 2e-3, "{wo:?}");
    }
}

#[test]
fn smooth_conductor_reflects_with_complex_fresnel() {
    use super::fresnel::fresnel_conductor;
    let (eta, k) = (
        Vec3::new(0.143, 0.375, 1.442),
        Vec3::new(3.983, 2.386, 1.603),
    );
    let bsdf = Bsdf::Conductor { eta, k };
    assert!(bsdf.is_specular() && bsdf.flags().is_reflection());
    for wo in test_directions() {
        let s = bsdf
            .sample(wo, 0.3, Vec2::new(0.1, 0.9))
            .expect("a delta sample");
        assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
        assert!(s.is_specular() && s.pdf == 1.0);
        let expected = fresnel_conductor(wo.z.abs(), eta, k);
        assert!((s.weight() - expected).abs().max_element() < 1e-5, "{wo:?}");
        assert_eq!(bsdf.f(wo, s.wi), Vec3::ZERO);
        assert_eq!(bsdf.pdf(wo, s.wi), 0.0);
    }
    // Brighter toward grazing angles, white at grazing, and Mitsuba's
    // "none" (eta 0, k 1) is a perfect mirror at every angle.
    let normal = bsdf.sample(Vec3::Z, 0.5, Vec2::ZERO).map(|s| s.weight());
    let grazing = bsdf
        .sample(Vec3::new(0.9999, 0.0, 0.0141), 0.5, Vec2::ZERO)
        .map(|s| s.weight());
    let (normal, grazing) = (normal.unwrap_or(Vec3::ZERO), grazing.unwrap_or(Vec3::ZERO));
    assert!(
        grazing.cmpgt(normal).all() && grazing.min_element() > 0.9,
        "{grazing:?}"
    );
    assert!((bsdf.albedo() - normal).abs().max_element() < 1e-5);
    let none = Bsdf::Conductor {
        eta: Vec3::ZERO,
        k: Vec3::ONE,
    };
    for wo in test_directions() {
        let w = none.sample(wo, 0.5, Vec2::ZERO).map(|s| s.weight());
        assert!((w.unwrap_or(Vec3::ZERO) - Vec3::ONE).abs().max_element() < 1e-5);
    }
}
