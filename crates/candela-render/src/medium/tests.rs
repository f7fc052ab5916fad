use super::*;
use crate::sampling::{Sampler, SamplerKind};

fn fog(sigma_t: Vec3, albedo: Vec3) -> Medium {
    Medium::from_desc(&MediumDesc {
        name: "fog".into(),
        sigma_t,
        albedo,
        phase_g: 0.0,
        loc: Default::default(),
    })
}

/// The free-flight estimator is unbiased for what it stands for: over a
/// segment of length L, E[weight | passed] · P(passed) = T(L) and
/// E[weight · f(distance) | scattered] = ∫₀ᴸ σ_s T(t) f(t) dt. Checked with
/// a coloured medium (where one channel's sampling alone would weigh the
/// others without bound), against the closed forms, within 4.5 standard
/// errors of the sample means.
#[test]
fn free_flight_weights_are_unbiased() {
    let m = fog(Vec3::new(0.5, 1.0, 3.0), Vec3::new(0.9, 0.5, 0.2));
    let length = 1.3f32;
    let n = 400_000;
    let mut sampler = Sampler::new(SamplerKind::Independent, 7);
    let (mut pass, mut scatter) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        sampler.start_pixel_sample(0, 0, i as u32);
        let (p, s) = match m.sample_distance(length, sampler.next_2d()) {
            // f(t) = t: a weight that depends on where it scattered.
            FreeFlight::Scattered { distance, weight } => {
                assert!(distance >= 0.0 && distance < length);
                (Vec3::ZERO, weight * distance)
            }
            FreeFlight::Passed { weight } => (weight, Vec3::ZERO),
        };
        pass.push(p);
        scatter.push(s);
    }
    // ∫₀ᴸ σ_s e^{-σ t} t dt = σ_s (1 - e^{-σL}(1 + σL)) / σ².
    let expected_scatter = Vec3::from_array([0, 1, 2].map(|c| {
        let (s, a) = (m.sigma_t[c], m.sigma_s[c]);
        a * (1.0 - (-s * length).exp() * (1.0 + s * length)) / (s * s)
    }));
    for (name, values, expected) in [
        ("passing", &pass, m.transmittance(length)),
        ("scattering", &scatter, expected_scatter),
    ] {
        for c in 0..3 {
            let x: Vec<f64> = values.iter().map(|v| f64::from(v[c])).collect();
            let mean = x.iter().sum::<f64>() / n as f64;
            let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            let z = (mean - f64::from(expected[c])) / (var / n as f64).sqrt();
            assert!(
                z.abs() < 4.5,
                "{name}, channel {c}: mean {mean} against {} (z = {z})",
                expected[c]
            );
        }
    }
}

/// A medium without extinction in a channel passes that channel whole,
/// even along an unbounded ray (no 0 · ∞).
#[test]
fn clear_channels_pass_unbounded_rays() {
    let m = fog(Vec3::new(0.0, 2.0, 0.0), Vec3::ONE);
    assert_eq!(m.transmittance(f32::INFINITY), Vec3::new(1.0, 0.0, 1.0));
    match m.sample_distance(f32::INFINITY, Vec2::new(0.1, 0.5)) {
        FreeFlight::Passed { weight } => assert_eq!(weight, Vec3::new(1.5, 0.0, 1.5)),
        other => panic!("the clear channel cannot scatter: {other:?}"),
    }
}

/// Crossing a surface puts the ray in the medium of the side it goes to.
#[test]
fn interfaces_name_the_side_a_ray_goes_to() {
    let iface = MediumInterface {
        interior: Some(0),
        exterior: Some(1),
    };
    // Met from outside (front face): across is inside, back is outside.
    assert_eq!(iface.after(true, true), Some(0));
    assert_eq!(iface.after(true, false), Some(1));
    // Met from inside.
    assert_eq!(iface.after(false, true), Some(1));
    assert_eq!(iface.after(false, false), Some(0));
}
