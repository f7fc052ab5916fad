//! Thin dielectric (window pane): directions, branch frequencies, the
//! multiple-bounce reflectance, and exact energy conservation.

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_dielectric;
use super::specular::thin_slab_reflectance;
use super::test_support::{test_directions, uniforms};
use super::Bsdf;
use crate::sampling::{Sampler, SamplerKind};

const R: Vec3 = Vec3::new(0.9, 0.8, 0.7);
const T: Vec3 = Vec3::new(0.6, 0.95, 1.0);
const IOR: f32 = 1.5;

#[test]
fn thin_slab_reflectance_sums_the_internal_bounces() {
    // R + T² R (1 + R² + R⁴ + …), summed term by term.
    for cos_i in [1.0f32, 0.7, 0.3, 0.05, -0.5] {
        let r = f64::from(fresnel_dielectric(cos_i.abs(), IOR));
        let t = 1.0 - r;
        let series: f64 = r + (0..200).map(|k| t * t * r * r.powi(2 * k)).sum::<f64>();
        let closed = f64::from(thin_slab_reflectance(cos_i, IOR));
        assert!(
            (series - closed).abs() < 1e-6,
            "{cos_i}: {series} vs {closed}"
        );
    }
    // At normal incidence, glass of IOR 1.5: R = 0.04, slab 0.08/1.04.
    assert!((thin_slab_reflectance(1.0, 1.5) - 0.08 / 1.04).abs() < 1e-6);
    assert_eq!(thin_slab_reflectance(0.0, 1.5), 1.0);
}

#[test]
fn thin_glass_reflects_or_passes_straight_through() {
    let pane = Bsdf::ThinGlass {
        reflectance: R,
        transmittance: T,
        ior: IOR,
    };
    assert!(pane.is_specular() && pane.flags().is_reflection() && pane.flags().is_transmission());
    let mut sampler = Sampler::new(SamplerKind::Independent, 43);
    let n = 20_000;
    for wo in test_directions() {
        let r = thin_slab_reflectance(wo.z, IOR);
        let mut reflected = 0u32;
        for i in 0..n {
            let (u1, u2) = uniforms(&mut sampler, i);
            let s = pane.sample(wo, u1, u2).expect("a pane always scatters");
            let weight = s.weight();
            if s.wi.z * wo.z > 0.0 {
                reflected += 1;
                assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
                assert!((weight - R).abs().max_element() < 1e-5, "{weight:?}");
                assert!((s.pdf - r).abs() < 1e-6);
            } else {
                assert_eq!(s.wi, -wo, "no refraction through a thin pane");
                assert!((weight - T).abs().max_element() < 1e-5, "{weight:?}");
                assert!((s.pdf - (1.0 - r)).abs() < 1e-6);
            }
            assert_eq!(pane.f(wo, s.wi), Vec3::ZERO);
            assert_eq!(pane.pdf(wo, s.wi), 0.0);
        }
        // Binomial: the frequency of reflection is R within 5 σ.
        let p = f64::from(r);
        let sigma = (p * (1.0 - p) / f64::from(n)).sqrt();
        let freq = f64::from(reflected) / f64::from(n);
        assert!(
            (freq - p).abs() <= 5.0 * sigma + 1e-9,
            "{wo:?}: {freq} vs {p}"
        );
    }
}

#[test]
fn white_thin_glass_conserves_energy_exactly() {
    // Stratified u1: reflected plus transmitted throughput is 1 (no η²:
    // the light leaves into the medium it came from), the same from both
    // sides.
    let pane = Bsdf::ThinGlass {
        reflectance: Vec3::ONE,
        transmittance: Vec3::ONE,
        ior: IOR,
    };
    for wo in test_directions() {
        let n = 1000;
        let (mut reflected, mut total) = (0.0f32, 0.0f32);
        for i in 0..n {
            let u1 = (i as f32 + 0.5) / n as f32;
            let s = pane
                .sample(wo, u1, Vec2::ZERO)
                .expect("a pane always scatters");
            total += s.weight().x / n as f32;
            if s.wi.z * wo.z > 0.0 {
                reflected += s.weight().x / n as f32;
            }
        }
        assert!((total - 1.0).abs() < 1e-4, "{wo:?}: {total}");
        assert!(
            (reflected - thin_slab_reflectance(wo.z, IOR)).abs() < 2e-3,
            "{wo:?}"
        );
    }
}
