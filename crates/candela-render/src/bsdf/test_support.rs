//! Checks every BSDF must pass, shared by the per-model tests.

use glam::{DVec3, Vec2, Vec3};

use super::{Bsdf, BsdfFlags};
use crate::sampling::chi2::Chi2Test;
use crate::sampling::warp::{square_to_uniform_sphere, uniform_sphere_pdf};
use crate::sampling::{Sampler, SamplerKind};

/// Outgoing directions at θ = 0°, 30°, 60°, 85° and 89.5° (grazing), some at
/// an azimuth off the axes, and the mirror images below the surface (the
/// other side of a two-sided surface, or the inside of glass).
pub(crate) fn test_directions() -> Vec<Vec3> {
    let mut dirs = Vec::new();
    for (theta_deg, phi) in [
        (0.0f32, 0.0f32),
        (30.0, 0.4),
        (60.0, 2.0),
        (85.0, -1.0),
        (89.5, 0.0),
    ] {
        let (sin_t, cos_t) = theta_deg.to_radians().sin_cos();
        let w = Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t);
        dirs.push(w);
        dirs.push(Vec3::new(w.x, w.y, -w.z));
    }
    dirs
}

/// Random numbers for the `i`-th test sample: (u1, u2).
pub(crate) fn uniforms(sampler: &mut Sampler, i: u32) -> (f32, Vec2) {
    sampler.start_pixel_sample(0, 0, i);
    (sampler.next_1d(), sampler.next_2d())
}

/// Chi-square of `sample` against `pdf` at `wo` (delta samples count as
/// failures: their directions are not part of the density).
pub(crate) fn assert_chi2(name: &str, bsdf: &Bsdf, wo: Vec3) {
    assert_chi2_with(name, bsdf, wo, 1_000_000, (21, 41));
}

/// [`assert_chi2`] with a given sample count (for costly samplers) and
/// θ × φ resolution (finer for narrow lobes, so they span many cells).
pub(crate) fn assert_chi2_with(
    name: &str,
    bsdf: &Bsdf,
    wo: Vec3,
    samples: usize,
    resolution: (usize, usize),
) {
    Chi2Test::sphere(&format!("{name} at wo = {wo:?}"))
        .with_samples(samples)
        .with_resolution(resolution.0, resolution.1)
        .run(
            |u| {
                let s = bsdf.sample(wo, u[0], Vec2::new(u[1], u[2]))?;
                (!s.is_specular()).then_some((s.wi, s.pdf))
            },
            |wi| bsdf.pdf(wo, wi),
        )
        .assert_ok();
}

/// Every returned sample agrees with `f` and `pdf`, is finite, and its
/// weight is `f·|cos|/pdf`.
pub(crate) fn assert_samples_consistent(bsdf: &Bsdf, wo: Vec3) {
    let mut sampler = Sampler::new(SamplerKind::Independent, 17);
    for i in 0..10_000 {
        let (u1, u2) = uniforms(&mut sampler, i);
        let Some(s) = bsdf.sample(wo, u1, u2) else {
            continue;
        };
        assert!((s.wi.length() - 1.0).abs() < 1e-4, "{bsdf:?} {wo:?}: {s:?}");
        assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{bsdf:?} {wo:?}: {s:?}");
        assert!(
            s.f.is_finite() && s.f.cmpge(Vec3::ZERO).all(),
            "{bsdf:?} {wo:?}: {s:?}"
        );
        if !s.is_specular() {
            let (f, pdf) = (bsdf.f(wo, s.wi), bsdf.pdf(wo, s.wi));
            assert!(
                (f - s.f).abs().max_element() <= 1e-4 * f.max_element().max(1.0),
                "{bsdf:?} {wo:?}: {s:?} vs f {f:?}"
            );
            assert!(
                (pdf - s.pdf).abs() <= 1e-3 * pdf.max(1.0),
                "{bsdf:?} {wo:?}: {s:?} vs pdf {pdf}"
            );
        }
        let weight = s.weight();
        let expected = s.f * s.wi.z.abs() / s.pdf;
        assert!((weight - expected).abs().max_element() < 1e-5 * expected.max_element().max(1.0));
    }
}

/// Mean and standard error of a Monte Carlo estimate from per-sample values.
pub(crate) struct Estimate {
    /// Sample mean per channel.
    pub mean: Vec3,
    /// Standard error of the mean per channel.
    pub std_error: Vec3,
}

fn estimate(n: u32, mut value: impl FnMut(u32) -> Vec3) -> Estimate {
    // Accumulated in f64: sum of squares minus squared mean cancels badly
    // in f32 when the variance is tiny.
    let (mut sum, mut sum_sq) = (DVec3::ZERO, DVec3::ZERO);
    for i in 0..n {
        let v = value(i).as_dvec3();
        sum += v;
        sum_sq += v * v;
    }
    let n = f64::from(n);
    let mean = sum / n;
    let variance = (sum_sq / n - mean * mean).max(DVec3::ZERO) * (n / (n - 1.0));
    Estimate {
        mean: mean.as_vec3(),
        std_error: (variance / n).powf(0.5).as_vec3(),
    }
}

/// [`assert_chi2_with`] (100k samples, 21 × 41 cells) for every named
/// case of a model's table at every test direction.
pub(crate) fn assert_cases_sample_their_pdf(cases: &[(&str, Bsdf)]) {
    for (name, bsdf) in cases {
        for wo in test_directions() {
            assert_chi2_with(name, bsdf, wo, 100_000, (21, 41));
        }
    }
}

/// [`assert_samples_consistent`] for every case at every test direction.
pub(crate) fn assert_cases_sample_consistently(cases: &[(&str, Bsdf)]) {
    for (_, bsdf) in cases {
        for wo in test_directions() {
            assert_samples_consistent(bsdf, wo);
        }
    }
}

/// ∫ f |cos| by each case's own sampling (100k samples) and by uniform
/// sphere directions (400k) agree within [`assert_estimates_agree`] at
/// each of `wos`: checks `f` and `sample` against each other as
/// integrals. Cases with a delta lobe are skipped (uniform directions
/// never see it); at least one case must remain.
pub(crate) fn assert_cases_f_agrees_with_sampling(cases: &[(&str, Bsdf)], wos: &[Vec3]) {
    let glossy: Vec<_> = cases
        .iter()
        .filter(|(_, b)| !b.flags().contains(BsdfFlags::SPECULAR))
        .collect();
    assert!(!glossy.is_empty(), "every case has a delta lobe");
    for (name, bsdf) in glossy {
        for &wo in wos {
            let wo = wo.normalize();
            let a = albedo_by_sampling(bsdf, wo, 100_000);
            let b = albedo_by_uniform_sphere(bsdf, wo, 400_000);
            assert_estimates_agree(name, &a, b.mean, b.std_error);
        }
    }
}

/// The directional albedo ∫ f·|cos θi| dωi by the BSDF's own sampling.
pub(crate) fn albedo_by_sampling(bsdf: &Bsdf, wo: Vec3, n: u32) -> Estimate {
    let mut sampler = Sampler::new(SamplerKind::Independent, 23);
    estimate(n, |i| {
        let (u1, u2) = uniforms(&mut sampler, i);
        bsdf.sample(wo, u1, u2).map_or(Vec3::ZERO, |s| s.weight())
    })
}

/// The same integral with directions uniform on the sphere: independent of
/// `sample` and `pdf`, so it checks `f` alone.
pub(crate) fn albedo_by_uniform_sphere(bsdf: &Bsdf, wo: Vec3, n: u32) -> Estimate {
    let mut sampler = Sampler::new(SamplerKind::Independent, 29);
    estimate(n, |i| {
        sampler.start_pixel_sample(0, 0, i);
        let wi = square_to_uniform_sphere(sampler.next_2d());
        bsdf.f(wo, wi) * wi.z.abs() / uniform_sphere_pdf(wi)
    })
}

/// Asserts |a − b| ≤ 5 combined standard errors (+ a float slack), per channel.
pub(crate) fn assert_estimates_agree(what: &str, a: &Estimate, b: Vec3, b_error: Vec3) {
    let bound = 5.0 * (a.std_error * a.std_error + b_error * b_error).powf(0.5) + Vec3::splat(1e-4);
    assert!(
        (a.mean - b).abs().cmple(bound).all(),
        "{what}: {:?} ± {:?} vs {b:?} ± {b_error:?}",
        a.mean,
        a.std_error
    );
}

/// ∫ g(wi) dωi over the hemisphere on the side of `wo`, by quadrature on a
/// 16 × 32 grid of (θ, φ) cells each refined adaptively, so that glossy
/// lobes narrower than the initial nodes are not missed (cells are 0.1 ×
/// 0.2 rad, each starting with 4 × 4 Simpson panels).
pub(crate) fn hemisphere_integral(wo: Vec3, g: impl Fn(Vec3) -> f32) -> f32 {
    use crate::sampling::chi2::integrate_2d;
    let side = if wo.z < 0.0 { -1.0 } else { 1.0 };
    let (rows, cols) = (16, 32);
    let (dt, dp) = (
        std::f64::consts::FRAC_PI_2 / rows as f64,
        2.0 * std::f64::consts::PI / cols as f64,
    );
    let mut total = 0.0;
    for r in 0..rows {
        for c in 0..cols {
            total += integrate_2d(
                |theta, phi| {
                    let (s, co) = theta.sin_cos();
                    let wi = Vec3::new(
                        (s * phi.cos()) as f32,
                        (s * phi.sin()) as f32,
                        (side * co) as f32,
                    );
                    f64::from(g(wi)) * s
                },
                (r as f64 * dt, (r + 1) as f64 * dt),
                (c as f64 * dp, (c + 1) as f64 * dp),
            );
        }
    }
    total as f32
}

/// The directional albedo by the BSDF's own sampling as *energy*: refracted
/// throughput is multiplied back by η² (η the relative IOR, far side over
/// the side of `wo`, from the inside-over-outside `ior`), undoing the
/// radiance scaling of the module docs. At most 1 for a passive interface;
/// pass `ior = 1` for BSDFs that do not bend light.
pub(crate) fn energy_albedo_by_sampling(bsdf: &Bsdf, wo: Vec3, ior: f32, n: u32) -> Estimate {
    let mut sampler = Sampler::new(SamplerKind::Independent, 31);
    estimate(n, |i| {
        let (u1, u2) = uniforms(&mut sampler, i);
        bsdf.sample(wo, u1, u2)
            .map_or(Vec3::ZERO, |s| s.weight() * energy_factor(wo, s.wi, ior))
    })
}

/// A white furnace row: the energy albedo (see [`energy_albedo_by_sampling`],
/// 40,000 samples) at 0°, 60° and 85° from the normal, asserted to be at
/// most 1 within four standard errors plus `slack` when `bounded` (a model
/// that may gain energy is tabulated only); `what` names the case in the
/// failure. Returns the red channel's values as a table row, " a b c".
pub(crate) fn furnace_row(bsdf: &Bsdf, ior: f32, bounded: bool, slack: f32, what: &str) -> String {
    let mut row = String::new();
    for theta in [0.0f32, 60.0, 85.0] {
        let (s, c) = theta.to_radians().sin_cos();
        let wo = Vec3::new(s, 0.0, c);
        let e = energy_albedo_by_sampling(bsdf, wo, ior, 40_000);
        assert!(
            !bounded || e.mean.max_element() <= 1.0 + 4.0 * e.std_error.max_element() + slack,
            "{what} θ={theta}: {:?} ± {:?}",
            e.mean,
            e.std_error
        );
        row += &format!(" {:.2}", e.mean.x);
    }
    row
}

/// η² for a refracted pair, 1 for a reflected one (see
/// [`energy_albedo_by_sampling`]).
pub(crate) fn energy_factor(wo: Vec3, wi: Vec3, ior: f32) -> f32 {
    if wo.z * wi.z >= 0.0 {
        return 1.0;
    }
    let eta = if wo.z > 0.0 { ior } else { 1.0 / ior };
    eta * eta
}

/// `n` pairs of independent uniform directions on the sphere, from `seed`.
pub(crate) fn direction_pairs(n: u32, seed: u64) -> Vec<(Vec3, Vec3)> {
    let mut sampler = Sampler::new(SamplerKind::Independent, seed);
    (0..n)
        .map(|i| {
            sampler.start_pixel_sample(0, 0, i);
            (
                square_to_uniform_sphere(sampler.next_2d()),
                square_to_uniform_sphere(sampler.next_2d()),
            )
        })
        .collect()
}
