//! Tests of the Lambertian BSDF.

use glam::{Vec2, Vec3};

use super::test_support::*;
use super::Bsdf;

const ALBEDO: Vec3 = Vec3::new(0.8, 0.5, 0.1);
const DIFFUSE: Bsdf = Bsdf::Diffuse { albedo: ALBEDO };

#[test]
fn diffuse_sampling_matches_its_pdf() {
    for wo in test_directions() {
        assert_chi2("diffuse", &DIFFUSE, wo);
    }
}

#[test]
fn diffuse_samples_are_consistent() {
    for wo in test_directions() {
        assert_samples_consistent(&DIFFUSE, wo);
    }
}

#[test]
fn diffuse_albedo_equals_its_reflectance() {
    let albedo = ALBEDO;
    for wo in test_directions() {
        // Cosine sampling cancels f·cos/pdf exactly: zero variance.
        let by_sampling = albedo_by_sampling(&DIFFUSE, wo, 20_000);
        assert_estimates_agree("diffuse sampling", &by_sampling, albedo, Vec3::ZERO);
        assert!(by_sampling.std_error.max_element() < 1e-5);
        // Uniform sphere directions check f itself, with real variance.
        let uniform = albedo_by_uniform_sphere(&DIFFUSE, wo, 200_000);
        assert_estimates_agree("diffuse uniform", &uniform, albedo, Vec3::ZERO);
        assert!(
            uniform.std_error.max_element() < 0.01,
            "{:?}",
            uniform.std_error
        );
    }
}

#[test]
fn diffuse_is_two_sided_and_reflects_only() {
    let up = Vec3::new(0.3, 0.1, 0.9).normalize();
    let down = Vec3::new(up.x, up.y, -up.z);
    assert_eq!(DIFFUSE.f(up, Vec3::Z), DIFFUSE.f(down, -Vec3::Z));
    assert_eq!(DIFFUSE.f(up, -Vec3::Z), Vec3::ZERO);
    assert_eq!(DIFFUSE.pdf(up, -Vec3::Z), 0.0);
    let s = DIFFUSE.sample(down, 0.5, Vec2::new(0.3, 0.7));
    assert!(s.is_some_and(|s| s.wi.z < 0.0));
    assert!(!DIFFUSE.flags().is_specular() && DIFFUSE.flags().is_reflection());
}
