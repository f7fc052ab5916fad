//! The bounce views trace the same paths as the full render: the images of
//! `--bounce k` for k = 0..=m add up to the full image of the same seed,
//! sample for sample, and the CS184 direct and indirect views are sums of
//! them. Samples are a pure function of (seed, pixel, index, dimension),
//! and a view that leaves out a vertex's light samples skips their
//! dimensions, so the only difference allowed is f32 rounding in the order
//! the contributions are added (a few ulps of the pixel value).
//!
//! The per-bounce layers (`--bounce-layers K`) of one render hold, layer k,
//! the very values a `--bounce k` render adds, in the same order: they
//! equal those renders bit for bit, and add up to the beauty image.

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

fn layered(
    scene: &Scene,
    integrator: IntegratorSettings,
    sampler: SamplerKind,
    threads: usize,
    tile: u32,
) -> Film {
    let settings = RenderSettings {
        spp: 4,
        seed: 17,
        integrator,
        sampler,
        threads,
        tile,
        ..Default::default()
    };
    let out = render(scene, &settings, &|_| {}).expect("render runs");
    assert_eq!(out.stats.invalid_samples, 0);
    out.film
}

#[test]
fn bounce_layers_are_the_bounce_views_of_one_render() {
    let scene = scene();
    for sampler in [SamplerKind::Sobol, SamplerKind::Independent] {
        for lighting in [
            LightingMode::Mis,
            LightingMode::Light,
            LightingMode::Hemisphere,
        ] {
            let label = format!("{lighting:?}, {sampler:?}");
            let full = film(&scene, with(lighting, |_| {}), sampler);
            let settings = with(lighting, |s| s.bounce_layers = Some(DEPTH));
            let layers = layered(&scene, settings.clone(), sampler, 2, 8);
            let names: Vec<String> = (0..=DEPTH).map(|k| format!("bounce_{k}")).collect();
            assert_eq!(layers.layers.names(), names);
            // Asking for layers leaves the image as it was, bit for bit.
            assert_eq!(layers.pixels, full.pixels, "{label}: the beauty changed");
            // Layer k is the `--bounce k` render, sum for sum.
            for k in 0..=DEPTH {
                let view = film(&scene, with(lighting, |s| s.bounce = Some(k)), sampler);
                let mut lit = 0;
                for (i, p) in view.pixels.iter().enumerate() {
                    let layer = layers.layers.pixel(i)[k as usize];
                    assert_eq!(layer, p.radiance, "{label}: bounce {k}, pixel {i}");
                    lit += (layer.max_element() > 0.0) as u32;
                }
                assert!(lit > 0, "{label}: bounce {k} is black");
            }
            // With K = -m the layers split every term of the image.
            let total: Vec<DVec3> = (0..layers.pixels.len())
                .map(|i| layers.layers.pixel(i).iter().sum())
                .collect();
            assert_same(&format!("{label}: sum of the layers"), &full, total);
            // Any thread count and tiling give the same layers.
            assert_eq!(layered(&scene, settings, sampler, 1, 5), layers, "{label}");
        }
    }
}

#[test]
fn fewer_bounce_layers_than_bounces_keep_the_first_ones() {
    let scene = scene();
    let lighting = LightingMode::Mis;
    let sampler = SamplerKind::Sobol;
    let all = layered(
        &scene,
        with(lighting, |s| s.bounce_layers = Some(DEPTH)),
        sampler,
        2,
        8,
    );
    let first = layered(
        &scene,
        with(lighting, |s| s.bounce_layers = Some(1)),
        sampler,
        2,
        8,
    );
    assert_eq!(first.layers.names(), ["bounce_0", "bounce_1"]);
    assert_eq!(first.pixels, all.pixels);
    for i in 0..all.pixels.len() {
        assert_eq!(first.layers.pixel(i), &all.layers.pixel(i)[..2]);
    }
}
