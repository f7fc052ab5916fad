//! The film and the render loop: determinism across threads, tilings, cells
//! and sample ranges, adaptive sampling, cancellation and time budgets.
//!
//! Films are compared bit for bit where the design promises it (each
//! pixel's samples and their order are fixed), and statistically where
//! only the distribution is fixed (another seed).

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_render::film::adaptive::converged;
use candela_render::film::{Adaptive, Film, PixelRect};
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{
    render, render_with, Cancel, RenderControl, RenderSettings, StopReason,
};
use candela_render::scene::{Scene, SceneOptions};
use glam::Vec3;
use std::time::{Duration, Instant};

const W: u32 = 40;
const H: u32 = 30;

/// The built-in Cornell box at a small size: shadows, soft edges and flat
/// lit walls, so adaptive sampling has easy and hard pixels.
fn cornell() -> Scene {
    let loaded = candela_scene::demo_scene();
    let opts = SceneOptions {
        width: W,
        height: H,
        ..Default::default()
    };
    Scene::build(&loaded.scene, &opts).expect("demo scene builds")
}

fn settings(spp: u32) -> RenderSettings {
    RenderSettings {
        spp,
        seed: 7,
        integrator: IntegratorSettings::default(),
        threads: 2,
        ..Default::default()
    }
}

/// A loose rule, so that some pixels converge and others run to the end.
fn adaptive() -> Option<Adaptive> {
    Some(Adaptive {
        batch: 8,
        tolerance: 0.3,
    })
}

fn film(scene: &Scene, s: &RenderSettings) -> Film {
    render(scene, s, &|_| {}).expect("render runs").film
}

/// Every number of the film as bits, so that equality is byte equality.
fn bits(film: &Film) -> Vec<u64> {
    film.pixels
        .iter()
        .flat_map(|p| {
            let v = [p.radiance, p.radiance_sq, p.albedo, p.normal];
            v.into_iter()
                .flat_map(|d| d.to_array())
                .chain([p.lum, p.lum_sq])
                .map(f64::to_bits)
                .chain([p.count as u64])
        })
        .collect()
}

#[test]
fn film_is_identical_for_any_thread_count_and_tiling() {
    let scene = cornell();
    for adaptive in [None, adaptive()] {
        let reference = bits(&film(
            &scene,
            &RenderSettings {
                threads: 1,
                adaptive,
                ..settings(24)
            },
        ));
        for (threads, tile) in [(2, 16), (8, 16), (1, 7), (8, 1), (2, 64)] {
            let s = RenderSettings {
                threads,
                tile,
                adaptive,
                ..settings(24)
            };
            assert!(
                bits(&film(&scene, &s)) == reference,
                "-t {threads} --tile {tile}, adaptive {adaptive:?}: the film differs"
            );
        }
    }
}

#[test]
fn adaptive_sampling_stops_easy_pixels_early() {
    let scene = cornell();
    let rule = Adaptive {
        batch: 16,
        tolerance: 0.05,
    };
    let s = RenderSettings {
        adaptive: Some(rule),
        ..settings(512)
    };
    let out = render(&scene, &s, &|_| {}).expect("render runs");
    let counts = out.film.sample_counts();
    // Every pixel takes at least one batch and stops only at a check; easy
    // ones stop early, noisy ones (shadows, the light's rim) run longer.
    assert!(counts.iter().all(|&n| (16..=512).contains(&n)));
    assert!(counts.iter().all(|&n| n % 16 == 0));
    let spread = out.film.sample_spread(out.film.rect());
    assert!(spread.min < 512, "no pixel converged early");
    assert!(
        spread.max - spread.min >= 32,
        "pixels hardly differ: {spread:?}"
    );
    // A pixel stopped early exactly when its sums pass the rule.
    for p in &out.film.pixels {
        let stopped = converged(p.count, p.lum, p.lum_sq, rule.tolerance);
        if p.count < 512 {
            assert!(stopped, "pixel stopped at {} without converging", p.count);
        }
    }
    assert_eq!(out.stop, StopReason::Complete);
    assert!(out.stats.converged_pixels > 0);
    assert_eq!(
        out.stats.samples,
        counts.iter().map(|&n| n as u64).sum::<u64>()
    );
}

#[test]
fn cells_union_is_the_full_render() {
    let scene = cornell();
    for adaptive in [None, adaptive()] {
        let full = film(
            &scene,
            &RenderSettings {
                adaptive,
                ..settings(16)
            },
        );
        // Uneven cells that do not follow the tile grid.
        let cells = [
            PixelRect::new(0, 0, 13, 30),
            PixelRect::new(13, 0, 27, 11),
            PixelRect::new(13, 11, 27, 19),
        ];
        let mut union = Film::new(W, H);
        for cell in cells {
            let part = film(
                &scene,
                &RenderSettings {
                    cell: Some(cell),
                    adaptive,
                    ..settings(16)
                },
            );
            // Nothing outside the cell.
            for (i, p) in part.pixels.iter().enumerate() {
                let (x, y) = (i as u32 % W, i as u32 / W);
                let inside = cell.pixels().any(|q| q == (x, y));
                assert_eq!(p.count > 0, inside, "pixel ({x}, {y}) of cell {cell:?}");
            }
            union.merge(&part).expect("same size");
        }
        assert!(bits(&union) == bits(&full), "adaptive {adaptive:?}");
    }
}

#[test]
fn a_cell_outside_the_frame_is_an_error() {
    let scene = cornell();
    let s = RenderSettings {
        cell: Some(PixelRect::new(30, 0, 20, 5)),
        ..settings(1)
    };
    assert!(render(&scene, &s, &|_| {}).is_err());
    let s = RenderSettings {
        sample_range: Some(5..5),
        ..settings(1)
    };
    assert!(render(&scene, &s, &|_| {}).is_err());
}

#[test]
fn two_sample_ranges_merge_into_one_render() {
    let scene = cornell();
    let whole = film(&scene, &settings(40));
    let mut merged = film(
        &scene,
        &RenderSettings {
            sample_range: Some(0..15),
            ..settings(40)
        },
    );
    let rest = film(
        &scene,
        &RenderSettings {
            sample_range: Some(15..40),
            ..settings(40)
        },
    );
    merged.merge(&rest).expect("same size");
    // The same samples summed in another order: equal up to f64 rounding,
    // a few ulps of the sum (1e-12 relative is ~4500 ulps of slack).
    for (a, b) in merged.pixels.iter().zip(&whole.pixels) {
        assert_eq!(a.count, b.count);
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1e-300);
        for (x, y) in a.radiance.to_array().iter().zip(b.radiance.to_array()) {
            assert!(close(*x, y), "{x} vs {y}");
        }
        assert!(close(a.lum_sq, b.lum_sq));
        assert!(close(a.albedo.x, b.albedo.x));
    }
}

#[test]
fn another_seed_gives_other_noise_around_the_same_mean() {
    let scene = cornell();
    let a = film(&scene, &settings(32));
    let b = film(
        &scene,
        &RenderSettings {
            seed: 8,
            ..settings(32)
        },
    );
    let differing = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.radiance != q.radiance)
        .count();
    assert!(
        differing > a.pixels.len() * 9 / 10,
        "only {differing} pixels differ"
    );
    let stats = |f: &Film| {
        BlockStats::from_pixel_errors(&f.resolve(), &f.std_error(), 8).expect("same sizes")
    };
    let summary = z_test(&stats(&a), &stats(&b), 0.01)
        .expect("same sizes")
        .summary();
    assert!(summary.passed(), "{summary:?}");
}

#[test]
fn aovs_hold_the_first_hit_albedo_and_a_camera_facing_normal() {
    let scene = cornell();
    let out = film(&scene, &settings(4));
    let albedo: Vec<Vec3> = out
        .albedo()
        .pixels()
        .iter()
        .map(|&p| Vec3::from(p))
        .collect();
    let normal: Vec<Vec3> = out
        .normal()
        .pixels()
        .iter()
        .map(|&p| Vec3::from(p))
        .collect();
    let (cx, cy) = (W / 2, H / 2);
    // Every camera ray hits the box; albedos are reflectances in [0, 1].
    assert!(albedo
        .iter()
        .all(|a| a.min_element() >= 0.0 && a.max_element() <= 1.0));
    // Normals face the camera: against the forward direction everywhere.
    for n in &normal {
        assert!(n.length() <= 1.0 + 1e-5);
        assert!(n.dot(scene.camera.forward) < 0.0, "normal {n} faces away");
    }
    // The centre pixel looks at the back wall head on.
    let c = normal[(cy * W + cx) as usize];
    assert!(c.dot(-scene.camera.forward) > 0.9, "centre normal {c}");
}

#[test]
fn cancelling_keeps_the_finished_passes_only() {
    let scene = cornell();
    let cancel = Cancel::new();
    // Cancel as soon as the second pass reports: it must be discarded.
    let on_progress = |p: &candela_render::render::Progress| {
        if p.pass >= 1 {
            cancel.cancel();
        }
    };
    let control = RenderControl {
        cancel: Some(cancel.clone()),
        progress: Some(&on_progress),
    };
    let out = render_with(&scene, &settings(4096), &control).expect("render runs");
    assert_eq!(out.stop, StopReason::Cancelled);
    assert_eq!(out.stats.passes, 1);
    // Pass 0 takes one sample per pixel: a uniform 1-spp image.
    assert!(out.film.sample_counts().iter().all(|&n| n == 1));
    assert_eq!(out.stats.samples, (W * H) as u64);
    // And it equals a 1-spp render.
    assert!(bits(&out.film) == bits(&film(&scene, &settings(1))));
}

#[test]
fn a_time_budget_stops_with_uniform_samples() {
    let scene = cornell();
    let budget = Duration::from_millis(300);
    let s = RenderSettings {
        time_budget: Some(budget),
        ..settings(1_000_000)
    };
    let start = Instant::now();
    let out = render(&scene, &s, &|_| {}).expect("render runs");
    let took = start.elapsed();
    assert_eq!(out.stop, StopReason::TimeBudget);
    // One pass of overrun at most; passes aim at 0.5 s (slack for a busy machine).
    assert!(took < budget + Duration::from_secs(3), "took {took:?}");
    let spread = out.film.sample_spread(out.film.rect());
    assert_eq!(spread.min, spread.max, "passes cover the whole image");
    assert!(spread.min >= 1);
}
