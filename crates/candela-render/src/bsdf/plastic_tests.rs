//! Smooth plastic: chi-square (the delta lobe counts as the harness's
//! failures), consistency, reciprocity, and an exact white furnace.

use glam::Vec3;

use super::fresnel::fresnel_dielectric;
use super::plastic::diffuse_fresnel_reflectance;
use super::test_support::*;
use super::{Bsdf, Plastic};

const IOR: f32 = 1.5;

fn red_plastic() -> Bsdf {
    Bsdf::Plastic(Plastic::new(Vec3::new(0.8, 0.2, 0.1), Vec3::ONE, IOR))
}

#[test]
fn plastic_sampling_matches_its_pdf() {
    for wo in test_directions() {
        assert_chi2_with("plastic", &red_plastic(), wo, 300_000, (21, 41));
    }
}

#[test]
fn plastic_samples_are_consistent() {
    for bsdf in [
        red_plastic(),
        Bsdf::Plastic(Plastic::new(Vec3::ZERO, Vec3::ONE, 1.3)),
        Bsdf::Plastic(Plastic::new(Vec3::ONE, Vec3::ZERO, 2.0)),
    ] {
        for wo in test_directions() {
            assert_samples_consistent(&bsdf, wo);
        }
    }
}

#[test]
fn plastic_is_reciprocal_and_two_sided() {
    let bsdf = red_plastic();
    let wo = Vec3::new(0.3, -0.2, 0.93).normalize();
    let wi = Vec3::new(-0.7, 0.1, 0.3).normalize();
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    assert!((bsdf.f(wo, wi) - bsdf.f(wi, wo)).abs().max_element() < 1e-6);
    assert_eq!(bsdf.f(wo, wi), bsdf.f(flip(wo), flip(wi)));
    assert_eq!(bsdf.f(wo, flip(wi)), Vec3::ZERO);
    // A delta lobe beside a diffuse one: not specular as a whole (the path
    // tracer samples lights here), but its flags name the delta lobe.
    let flags = bsdf.flags();
    assert!(!bsdf.is_specular() && !flags.is_specular() && flags.is_non_specular());
    assert!(flags.intersects(super::BsdfFlags::SPECULAR));
}

#[test]
fn diffuse_fresnel_reflectance_matches_known_values() {
    // Glass (η = 1.5): about 0.092 from outside, and from inside
    // 1 − (1 − 0.092)/η² ≈ 0.596 (the transmittances of both sides are
    // related by η², a consequence of reciprocity).
    let outside = diffuse_fresnel_reflectance(IOR);
    let inside = diffuse_fresnel_reflectance(1.0 / IOR);
    assert!((outside - 0.0918).abs() < 1e-3, "{outside}");
    // Simpson's rule converges only as h^1.5 across the square-root onset
    // of transmission at the critical angle: 1e-4 (the furnace needs 1e-3).
    assert!(
        ((1.0 - outside) - IOR * IOR * (1.0 - inside)).abs() < 1e-4,
        "{inside}"
    );
    assert!(
        diffuse_fresnel_reflectance(1.0).abs() < 1e-7,
        "no interface, no reflection"
    );
}

#[test]
fn white_plastic_furnace_is_exactly_one() {
    // With ρ = 1 and a white coating, specular F(cos θo) plus the
    // renormalised diffuse lobe reflect everything, at every angle.
    let bsdf = Bsdf::Plastic(Plastic::new(Vec3::ONE, Vec3::ONE, IOR));
    for wo in test_directions() {
        let diffuse = hemisphere_integral(wo, |wi| bsdf.f(wo, wi).x * wi.z.abs());
        let total = diffuse + fresnel_dielectric(wo.z.abs(), IOR);
        assert!((total - 1.0).abs() < 1e-3, "{wo:?}: {total}");
        let sampled = energy_albedo_by_sampling(&bsdf, wo, 1.0, 50_000);
        assert!(
            sampled.mean.x <= 1.0 + 3.0 * sampled.std_error.x + 1e-6,
            "{wo:?}"
        );
        assert_estimates_agree(&format!("{wo:?}"), &sampled, Vec3::ONE, Vec3::ZERO);
    }
    // A darker base reflects less, never more.
    let grey = Bsdf::Plastic(Plastic::new(Vec3::splat(0.5), Vec3::ONE, IOR));
    let albedo = albedo_by_sampling(&grey, Vec3::Z, 50_000);
    assert!(albedo.mean.x < 0.6, "{:?}", albedo.mean);
}

#[test]
fn linear_plastic_keeps_the_base_colour_linear() {
    // Mitsuba's default (`nonlinear` false): ρ/(1 − F_dr) instead of
    // ρ/(1 − ρ F_dr); the same at ρ = 1, brighter in the ratio of the
    // denominators below, and linear in ρ.
    let f_dr = diffuse_fresnel_reflectance(1.0 / IOR);
    let (wo, wi) = (Vec3::new(0.3, 0.0, 0.954), Vec3::new(-0.5, 0.2, 0.843));
    let make = |rho: f32, nonlinear| {
        Bsdf::Plastic(Plastic::new(Vec3::splat(rho), Vec3::ONE, IOR).with_nonlinear(nonlinear))
    };
    let ratio = make(0.5, false).f(wo, wi).x / make(0.5, true).f(wo, wi).x;
    assert!(
        (ratio - (1.0 - 0.5 * f_dr) / (1.0 - f_dr)).abs() < 1e-5,
        "{ratio}"
    );
    assert!(
        (make(1.0, false).f(wo, wi) - make(1.0, true).f(wo, wi))
            .abs()
            .max_element()
            < 1e-6
    );
    let half = make(0.25, false).f(wo, wi).x / make(0.5, false).f(wo, wi).x;
    assert!((half - 0.5).abs() < 1e-5);
    for wo in test_directions() {
        let a = albedo_by_sampling(&make(0.8, false), wo, 20_000);
        assert!(
            a.mean.x <= 1.0 + 3.0 * a.std_error.x,
            "{wo:?}: {:?}",
            a.mean
        );
    }
}
