//! The bounce views trace the same paths as the full render: the images of
//! `--bounce k` for k = 0..=m add up to the full image of the same seed,
//! sample for sample, and the CS184 direct and indirect views are sums of
//! them. Samples are a pure function of (seed, pixel, index, dimension),
//! and a view that leaves out a vertex's light samples skips their
//! dimensions, so the only difference allowed is f32 rounding in the order
//! the contributions are added (a few ulps of the pixel value).

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::film::Film;
use candela_render::integrator::{Estimator, IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::sampling::SamplerKind;
use candela_render::scene::{Scene, SceneOptions};
use common::glass_room;
use glam::DVec3;

const DEPTH: u32 = 4;
const SIZE: (u32, u32) = (24, 18);

fn scene() -> Scene {
    let opts = SceneOptions {
        width: SIZE.0,
        height: SIZE.1,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    Scene::build(&glass_room(), &opts).expect("test scene builds")
}

fn film(scene: &Scene, integrator: IntegratorSettings, sampler: SamplerKind) -> Film {
    let settings = RenderSettings {
        spp: 4,
        seed: 17,
        integrator,
        sampler,
        threads: 2,
        ..Default::default()
    };
    let out = render(scene, &settings, &|_| {}).expect("render runs");
    assert_eq!(out.stats.invalid_samples, 0);
    out.film
}

/// Per pixel, the sum of the radiance sums of `parts`.
fn sum_of(parts: &[Film]) -> Vec<DVec3> {
    let mut total = vec![DVec3::ZERO; parts[0].pixels.len()];
    for f in parts {
        for (t, p) in total.iter_mut().zip(&f.pixels) {
            *t += p.radiance;
        }
    }
    total
}

/// Every pixel's radiance sum in `whole` equals `parts` up to f32 rounding
/// of the per-sample sums (relative 1e-5: each sample adds at most
/// DEPTH + a few terms, each rounding by 6e-8).
fn assert_same(label: &str, whole: &Film, parts: Vec<DVec3>) {
    let mut nonzero = 0;
    for (i, (w, p)) in whole.pixels.iter().zip(parts).enumerate() {
        let w = w.radiance;
        let tol = 1e-5 * w.abs().max_element() + 1e-9;
        assert!(
            (w - p).abs().max_element() <= tol,
            "{label}: pixel {i}: whole {w} vs parts {p}"
        );
        nonzero += (w.max_element() > 0.0) as u32;
    }
    assert!(nonzero > 0, "{label}: the image is black");
}

fn with(lighting: LightingMode, f: impl FnOnce(&mut IntegratorSettings)) -> IntegratorSettings {
    let mut s = IntegratorSettings::path(DEPTH, lighting);
    f(&mut s);
    s
}

#[test]
fn bounce_images_add_up_to_the_full_image() {
    let scene = scene();
    for sampler in [SamplerKind::Sobol, SamplerKind::Independent] {
        for lighting in [
            LightingMode::Mis,
            LightingMode::Light,
            LightingMode::Hemisphere,
        ] {
            let label = format!("{lighting:?}, {sampler:?}");
            let full = film(&scene, with(lighting, |_| {}), sampler);
            let per_k: Vec<Film> = (0..=DEPTH)
                .map(|k| film(&scene, with(lighting, |s| s.bounce = Some(k)), sampler))
                .collect();
            // Every bounce carries light in this scene: no view is trivially black.
            for (k, f) in per_k.iter().enumerate() {
                let lit = f.pixels.iter().filter(|p| p.radiance.max_element() > 0.0);
                assert!(lit.count() > 0, "{label}: bounce {k} is black");
            }
            assert_same(&format!("{label}: sum over k"), &full, sum_of(&per_k));
            let direct = film(
                &scene,
                with(lighting, |s| s.estimator = Estimator::Direct),
                sampler,
            );
            assert_same(&format!("{label}: direct"), &direct, sum_of(&per_k[..2]));
            let indirect = film(
                &scene,
                with(lighting, |s| s.estimator = Estimator::Indirect),
                sampler,
            );
            assert_same(
                &format!("{label}: indirect"),
                &indirect,
                sum_of(&per_k[2..]),
            );
        }
    }
}
