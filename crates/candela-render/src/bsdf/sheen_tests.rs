//! `KHR_materials_sheen` on the glTF metallic-roughness BSDF: the Charlie
//! distribution's normalisation and its fitted Λ against the exact Smith
//! Λ; the albedo table against an independent Monte Carlo estimate through
//! the BSDF's own `f`, against a finer quadrature and between its nodes;
//! chi-square of `sample` against `pdf` (sheen over dielectric, metal,
//! smooth layers, glass, and under rough and smooth coats); sample/eval/pdf
//! consistency; reciprocity; a white furnace; sheen colour 0 exactly the
//! sheenless model.
//!
//! Furnace (energy albedo by the model's own sampling, 40k samples; white
//! base, white sheen; θo = 0°, 60°, 85°), printed by
//! `sheen_white_furnace_stays_at_most_one`:
//!
//! | sheen roughness | sheen alone    | dielectric r = 0.5 | metal r = 0.3  | coated metal   |
//! |-----------------|----------------|--------------------|----------------|----------------|
//! | 0.0             | 0.00 0.08 0.59 | 0.94 0.96 0.80     | 0.98 0.94 0.94 | 0.95 0.86 0.74 |
//! | 0.5             | 0.03 0.19 0.59 | 0.90 0.96 0.80     | 0.98 0.95 0.95 | 0.93 0.86 0.76 |
//! | 1.0             | 0.16 0.36 0.74 | 0.88 0.97 0.87     | 0.97 0.95 0.96 | 0.92 0.87 0.78 |
//!
//! Alone, the sheen reflects E(cos θo), the table's (sheen roughness 0 is
//! the clamped α = 0.08, `sheen.rs`). Over a white base the sum is below
//! the base's own albedo (`metallic_roughness_tests.rs`: 1.00 0.99 0.52
//! and 1.00 1.00 0.92) near the normal, by what the extension's min form
//! withholds from the base towards grazing directions, where the sheen's
//! E is large, and above it at 85°, where the sheen catches light that the
//! rough base loses to masking. The coat (strength 1, roughness 0.2) takes
//! its share as in `clear_coat_tests.rs`.

use glam::Vec3;

use super::sheen::{charlie_d, charlie_lambda, MIN_ALPHA};
use super::sheen_albedo::{
    cosine_node, directional_albedo, roughness_node, sheen_albedo, GRID, NODES,
};
use super::test_support::*;
use super::{Bsdf, BsdfFlags, BsdfSample, MetallicRoughness};
use crate::sampling::{Sampler, SamplerKind};

/// The glTF model with a sheen and an optional coat (strength, roughness).
fn sheened(
    base: Vec3,
    metallic: f32,
    roughness: f32,
    transmission: f32,
    sheen: (Vec3, f32),
    coat: (f32, f32),
) -> Bsdf {
    Bsdf::MetallicRoughness(
        MetallicRoughness::new(base, metallic, roughness, transmission, 1.5)
            .with_sheen(sheen.0, sheen.1)
            .with_clearcoat(coat.0, coat.1),
    )
}

/// A white sheen over a base that reflects nothing (black, no dielectric
/// specular layer): the BSDF is the sheen lobe alone.
fn sheen_alone(roughness: f32) -> Bsdf {
    Bsdf::MetallicRoughness(
        MetallicRoughness::new(Vec3::ZERO, 0.0, 0.5, 0.0, 1.5)
            .with_specular(0.0, Vec3::ONE)
            .with_sheen(Vec3::ONE, roughness),
    )
}

fn cases() -> Vec<(&'static str, Bsdf)> {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    let blue = Vec3::new(0.3, 0.5, 1.0);
    let none = (0.0, 0.0);
    vec![
        (
            "sheen over dielectric",
            sheened(orange, 0.0, 0.5, 0.0, (blue, 0.5), none),
        ),
        (
            "smooth sheen over metal",
            sheened(orange, 1.0, 0.3, 0.0, (Vec3::ONE, 0.0), none),
        ),
        (
            "rough sheen over smooth dielectric",
            sheened(orange, 0.0, 0.0, 0.0, (blue, 1.0), none),
        ),
        ("sheen alone", sheen_alone(0.4)),
        (
            "sheen over glass",
            sheened(orange, 0.0, 0.4, 0.7, (blue, 0.6), none),
        ),
        (
            "rough coat over sheen",
            sheened(orange, 0.0, 0.6, 0.0, (blue, 0.7), (1.0, 0.3)),
        ),
        (
            "smooth coat over sheen over smooth metal",
            sheened(orange, 0.6, 0.0, 0.0, (Vec3::ONE, 0.5), (0.8, 0.0)),
        ),
    ]
}

fn parts(s: BsdfSample) -> (Vec3, Vec3, f32, BsdfFlags, Vec3) {
    (s.wi, s.f, s.pdf, s.flags, s.weight())
}

/// The direction at cosine `cos` in the xz plane.
fn at_cosine(cos: f32) -> Vec3 {
    Vec3::new((1.0 - cos * cos).max(0.0).sqrt(), 0.0, cos)
}

#[test]
fn charlie_distribution_is_normalised() {
    // ∫ D(h) cos θh dωh = 1 for every α.
    for alpha in [MIN_ALPHA, 0.25, 1.0] {
        let total = hemisphere_integral(Vec3::Z, |h| charlie_d(h.z, alpha) * h.z);
        assert!((total - 1.0).abs() < 1e-3, "α={alpha}: {total}");
    }
}

#[test]
fn fitted_lambda_follows_the_exact_smith_lambda_where_it_is_used() {
    // Smith's Λ(μ) = (1/μ) ∫ D(h) ⟨wo·h⟩ dωh − 1. The fit follows it within
    // 4% at α = 1 and within 12% (below it) at the clamp, where the sheen's
    // albedo still stays below 1 (`sheen_albedo_stays_below_one`); at
    // α = 0.005 it is about a third of it (what the clamp avoids).
    let exact = |cos: f32, alpha: f32| {
        let wo = at_cosine(cos);
        hemisphere_integral(Vec3::Z, |h| charlie_d(h.z, alpha) * wo.dot(h).max(0.0)) / cos - 1.0
    };
    for (alpha, tolerance) in [(1.0f32, 0.04), (MIN_ALPHA, 0.12)] {
        for cos in [0.05f32, 0.2, 0.5, 0.8] {
            let (fitted, exact) = (charlie_lambda(cos, alpha), exact(cos, alpha));
            assert!(
                (fitted - exact).abs() <= tolerance * exact,
                "α={alpha} μ={cos}: fitted {fitted} vs exact {exact}"
            );
        }
    }
    for cos in [0.05f32, 0.2, 0.5] {
        let ratio = charlie_lambda(cos, 0.005) / exact(cos, 0.005);
        assert!(ratio > 0.2 && ratio < 0.4, "μ={cos}: {ratio}");
    }
}

#[test]
fn sheen_albedo_table_matches_monte_carlo() {
    // Every other node off the horizon, at four roughnesses: the table's
    // entry (our quadrature) against ∫ f |cos θi| of the BSDF itself by
    // uniform directions, an estimate that shares nothing with the
    // quadrature but the lobe. Bound: 5 standard errors plus the
    // quadrature's 10⁻⁴ (`table_quadrature_has_converged`).
    let (cosines, roughnesses) = NODES;
    for k in [0, roughnesses / 3, 2 * roughnesses / 3, roughnesses - 1] {
        let r = roughness_node(k);
        let bsdf = sheen_alone(r);
        for j in (1..cosines).step_by(2) {
            let mu = cosine_node(j);
            let entry = sheen_albedo(mu, r);
            let mc = albedo_by_uniform_sphere(&bsdf, at_cosine(mu), 200_000);
            let bound = 5.0 * mc.std_error.x + 1e-4;
            assert!(
                (entry - mc.mean.x).abs() <= bound,
                "r={r} μ={mu}: table {entry} vs {} ± {}",
                mc.mean.x,
                mc.std_error.x
            );
        }
    }
}

#[test]
fn table_quadrature_has_converged() {
    for (cos, alpha) in [(0.0f32, 1.0f32), (0.02, MIN_ALPHA), (0.3, 0.3), (1.0, 1.0)] {
        let (a, b) = (
            directional_albedo(cos, alpha, GRID),
            directional_albedo(cos, alpha, 2 * GRID),
        );
        assert!((a - b).abs() < 1e-4, "μ={cos} α={alpha}: {a} vs {b}");
    }
}

#[test]
fn table_interpolates_within_half_a_percent() {
    // Bilinear lookups at the middle of every cell against the quadrature
    // there: worst near the cosine floor (`sheen::MIN_COSINE`), where E
    // has a kink.
    let (cosines, roughnesses) = NODES;
    for k in 0..roughnesses - 1 {
        for j in 0..cosines - 1 {
            let s = (cosine_node(j).sqrt() + cosine_node(j + 1).sqrt()) / 2.0;
            let (mu, r) = (s * s, (roughness_node(k) + roughness_node(k + 1)) / 2.0);
            let exact = directional_albedo(mu, (r * r).max(MIN_ALPHA), GRID);
            let lookup = sheen_albedo(mu, r);
            assert!(
                (lookup - exact).abs() < 0.005,
                "μ={mu} r={r}: {lookup} vs {exact}"
            );
        }
    }
}

#[test]
fn sheen_albedo_stays_below_one() {
    // What the α clamp is for: the largest E anywhere is 0.955.
    let (cosines, roughnesses) = NODES;
    let worst = (0..roughnesses)
        .flat_map(|k| (0..cosines).map(move |j| sheen_albedo(cosine_node(j), roughness_node(k))))
        .fold(0.0f32, f32::max);
    assert!(worst > 0.9 && worst < 0.96, "{worst}");
    // Roughness below the clamp is the clamped lobe.
    assert_eq!(sheen_albedo(0.1, 0.0), sheen_albedo(0.1, MIN_ALPHA.sqrt()));
}

#[test]
fn sheened_sampling_matches_its_pdf() {
    assert_cases_sample_their_pdf(&cases());
}

#[test]
fn sheened_samples_are_consistent() {
    assert_cases_sample_consistently(&cases());
}

#[test]
fn sheened_f_agrees_with_its_sampling() {
    assert_cases_f_agrees_with_sampling(
        &cases(),
        &[Vec3::new(0.4, 0.2, 0.89), Vec3::new(0.95, 0.1, 0.12)],
    );
}

#[test]
fn sheened_opaque_model_is_reciprocal() {
    // Without a coat: the coat's weight reads the view alone (its adjoint
    // is tested in `transport_tests.rs`).
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    let reciprocal = |b: &Bsdf| matches!(b, Bsdf::MetallicRoughness(m) if m.is_reciprocal());
    let opaque: Vec<_> = cases()
        .into_iter()
        .filter(|(_, b)| !b.flags().is_transmission() && reciprocal(b))
        .collect();
    assert!(
        opaque.len() >= 2,
        "only {} uncoated opaque cases",
        opaque.len()
    );
    for (name, bsdf) in opaque {
        for (wo, wi) in direction_pairs(200, 5) {
            let wi = if wi.z * wo.z < 0.0 { flip(wi) } else { wi };
            let (a, b) = (bsdf.f(wo, wi), bsdf.f(wi, wo));
            assert!(
                (a - b).abs().max_element() <= 1e-5 * a.max_element().max(1.0),
                "{name} {wo} {wi}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn sheen_white_furnace_stays_at_most_one() {
    let mut table = String::new();
    for roughness in [0.0f32, 0.5, 1.0] {
        let sheen = (Vec3::ONE, roughness);
        table += &format!("| {roughness:.1} |");
        for (what, bsdf) in [
            ("alone", sheen_alone(roughness)),
            (
                "dielectric",
                sheened(Vec3::ONE, 0.0, 0.5, 0.0, sheen, (0.0, 0.0)),
            ),
            (
                "metal",
                sheened(Vec3::ONE, 1.0, 0.3, 0.0, sheen, (0.0, 0.0)),
            ),
            (
                "coated metal",
                sheened(Vec3::ONE, 1.0, 0.3, 0.0, sheen, (1.0, 0.2)),
            ),
        ] {
            let what = format!("{what}, sheen r={roughness}");
            table += &furnace_row(&bsdf, 1.0, true, 1e-4, &what);
            table += " |";
        }
        table += "\n";
    }
    println!("{table}");
}

#[test]
fn a_sheen_over_a_perfect_mirror_keeps_all_the_energy() {
    // The mirror keeps exactly 1 − E(cos θo) (the table's), the sheen
    // reflects E (its integral): the sum is 1 within the estimate's noise
    // and the table's interpolation.
    for roughness in [0.0f32, 0.6] {
        let bsdf = sheened(Vec3::ONE, 1.0, 0.0, 0.0, (Vec3::ONE, roughness), (0.0, 0.0));
        for cos in [1.0f32, 0.5, 0.1] {
            let e = energy_albedo_by_sampling(&bsdf, at_cosine(cos), 1.0, 100_000);
            let bound = 5.0 * e.std_error.x + 0.005;
            assert!(
                (e.mean.x - 1.0).abs() <= bound,
                "r={roughness} μ={cos}: {} ± {}",
                e.mean.x,
                e.std_error.x
            );
        }
    }
}

#[test]
fn sheen_colour_zero_is_exactly_the_sheenless_model() {
    let orange = Vec3::new(0.9, 0.5, 0.1);
    let mut sampler = Sampler::new(SamplerKind::Independent, 11);
    for (metallic, roughness, transmission, coat) in [
        (0.0, 0.5, 0.0, (0.0, 0.0)),
        (0.4, 0.0, 0.0, (0.0, 0.0)),
        (0.2, 0.3, 0.6, (0.0, 0.0)),
        (0.0, 0.5, 0.0, (1.0, 0.3)),
        (0.6, 0.0, 0.0, (0.8, 0.0)),
    ] {
        let base = MetallicRoughness::new(orange, metallic, roughness, transmission, 1.5)
            .with_clearcoat(coat.0, coat.1);
        let plain = Bsdf::MetallicRoughness(base);
        assert_eq!(
            sheened(
                orange,
                metallic,
                roughness,
                transmission,
                (Vec3::ZERO, 0.0),
                coat
            ),
            plain
        );
        let zero = sheened(
            orange,
            metallic,
            roughness,
            transmission,
            (Vec3::ZERO, 0.7),
            coat,
        );
        assert_eq!(zero.flags(), plain.flags());
        for wo in test_directions() {
            for i in 0..2_000 {
                let (u1, u2) = uniforms(&mut sampler, i);
                let (a, b) = (zero.sample(wo, u1, u2), plain.sample(wo, u1, u2));
                assert_eq!(a.map(parts), b.map(parts), "{wo} {u1} {u2}");
                let wi = Vec3::new(u2.x - 0.5, u2.y - 0.5, u1 - 0.5).normalize();
                assert_eq!(zero.f(wo, wi), plain.f(wo, wi), "{wo} {wi}");
                assert_eq!(zero.pdf(wo, wi), plain.pdf(wo, wi), "{wo} {wi}");
            }
        }
    }
}

#[test]
fn the_sheen_lobe_scales_with_its_colour_and_rises_at_grazing_angles() {
    // f = colour · D · V: a grey sheen of 0.5 is half the white one's value
    // (up to the colour's 16-bit storage), and the lobe (back-scattering fibres) is brighter seen and lit at
    // grazing angles than at normal incidence.
    let (white, grey) = (
        sheen_alone(0.5),
        Bsdf::MetallicRoughness(
            MetallicRoughness::new(Vec3::ZERO, 0.0, 0.5, 0.0, 1.5)
                .with_specular(0.0, Vec3::ONE)
                .with_sheen(Vec3::splat(0.5), 0.5),
        ),
    );
    for (wo, wi) in direction_pairs(50, 9) {
        let (wo, wi) = (
            Vec3::new(wo.x, wo.y, wo.z.abs()),
            Vec3::new(wi.x, wi.y, wi.z.abs()),
        );
        let (a, b) = (white.f(wo, wi), grey.f(wo, wi));
        assert!((b - 0.5 * a).abs().max_element() <= 2e-5 * a.max_element().max(1.0));
    }
    let grazing = at_cosine(0.1);
    let back = Vec3::new(grazing.x * 0.9, 0.3, grazing.z).normalize();
    assert!(white.f(grazing, back).x > 10.0 * white.f(Vec3::Z, Vec3::Z).x);
}
