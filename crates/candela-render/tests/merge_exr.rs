//! `candela merge` on real renders: two 64-spp renders of disjoint sample
//! ranges of one seed, written as EXRs and merged, equal the 128-spp render
//! in mean and variance up to the f32 rounding of the stored values.

use candela_image::{merge_renders, read_exr_layers, ExrLayers, LayerData};
use candela_render::film::{write_film, OutputOptions};
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_testkit::TempDir;
use std::path::Path;

const W: u32 = 24;
const H: u32 = 18;
/// f32's unit roundoff, 2^-24.
const U: f64 = f32::EPSILON as f64 / 2.0;

fn render_exr(scene: &Scene, samples: std::ops::Range<u32>, path: &Path) -> ExrLayers {
    let settings = RenderSettings {
        spp: samples.end,
        sample_range: Some(samples),
        seed: 3,
        integrator: IntegratorSettings::default(),
        threads: 2,
        ..Default::default()
    };
    let output = render(scene, &settings, &|_| {}).expect("render runs");
    let opts = OutputOptions {
        aovs: true,
        depth: true,
        variance: true,
        info: output.info(&settings, None),
        ..Default::default()
    };
    write_film(path, &output.film, &opts).expect("EXR written");
    read_exr_layers(path).expect("EXR reads back")
}

fn rgb(layers: &ExrLayers) -> (&[[f32; 3]], &[[f32; 3]]) {
    (
        layers.beauty.pixels(),
        layers.variance().expect("variance layer").pixels(),
    )
}

#[test]
fn two_disjoint_64_spp_halves_merge_into_the_128_spp_render() {
    let loaded = candela_scene::demo_scene();
    let opts = SceneOptions {
        width: W,
        height: H,
        ..Default::default()
    };
    let scene = Scene::build(&loaded.scene, &opts).expect("demo scene builds");
    let dir = TempDir::new("merge-exr");
    let low = render_exr(&scene, 0..64, &dir.join("low.exr"));
    let high = render_exr(&scene, 64..128, &dir.join("high.exr"));
    let whole = render_exr(&scene, 0..128, &dir.join("whole.exr"));
    let merged = merge_renders(&[
        ("low.exr".into(), low.clone()),
        ("high.exr".into(), high.clone()),
    ])
    .expect("disjoint ranges of one seed merge");

    // Bounds, per pixel and channel, with u = 2^-24 the unit roundoff of
    // the stored f32 values (n_a = n_b = 64, N = 128):
    // - mean: each part's stored mean is off by at most u|m_k|, their
    //   average adds nothing in f64, and the merged and the whole render's
    //   means are each rounded once more to f32: |Δm| <= 3u max(|m_a|, |m_b|, |m|).
    // - variance: each part's M2 = n(n-1)v is off by u relative, the
    //   difference of stored means δ by at most Δδ = u(|m_a| + |m_b|), so the
    //   δ² n_a n_b / N term by (2|δ| + Δδ) Δδ n_a n_b / N; both results are
    //   rounded to f32 (2u relative), and the whole render's own f64 sums
    //   cancel in Σx² − (Σx)²/N to about N 2^-52 Σx². Dividing by N(N-1):
    let (n_a, n_b, n) = (64.0_f64, 64.0_f64, 128.0_f64);
    let (lo, hi, wh, me) = (rgb(&low), rgb(&high), rgb(&whole), rgb(&merged));
    let mut worst_mean: f64 = 0.0;
    let mut worst_variance: f64 = 0.0;
    for i in 0..(W * H) as usize {
        for c in 0..3 {
            let (ma, mb, mw, mm) = (
                lo.0[i][c] as f64,
                hi.0[i][c] as f64,
                wh.0[i][c] as f64,
                me.0[i][c] as f64,
            );
            let mean_bound = 3.0 * U * ma.abs().max(mb.abs()).max(mw.abs());
            assert!(
                (mm - mw).abs() <= mean_bound,
                "pixel {i} channel {c}: mean {mm} vs {mw}"
            );
            worst_mean = worst_mean.max((mm - mw).abs() / mean_bound.max(f64::MIN_POSITIVE));

            let (vw, vm) = (wh.1[i][c] as f64, me.1[i][c] as f64);
            let delta = (mb - ma).abs();
            let d_delta = U * (ma.abs() + mb.abs());
            let sum_sq = n * (mw * mw + n * vw);
            let bound = 3.0 * U * vw
                + (2.0 * delta + d_delta) * d_delta * (n_a * n_b / n) / (n * (n - 1.0))
                + n * f64::EPSILON * sum_sq / (n * (n - 1.0));
            assert!(
                (vm - vw).abs() <= bound,
                "pixel {i} channel {c}: variance {vm} vs {vw} (bound {bound:e})"
            );
            worst_variance = worst_variance.max((vm - vw).abs() / bound.max(f64::MIN_POSITIVE));
        }
    }
    eprintln!("worst |Δ| / bound: mean {worst_mean:.3}, variance {worst_variance:.3}");
    // Sample counts, the other layers and the header.
    assert_eq!(merged.sample_count, whole.sample_count);
    let Some(LayerData::Gray(depth)) = merged.layer("depth") else {
        panic!("no depth layer")
    };
    let Some(LayerData::Gray(whole_depth)) = whole.layer("depth") else {
        panic!("no depth layer")
    };
    for (a, b) in depth.values().iter().zip(whole_depth.values()) {
        assert!(
            a == b || (a - b).abs() <= 1e-5 * b.abs(),
            "depth {a} vs {b}"
        );
    }
    let info = &merged.info;
    assert_eq!(info.sample_range, Some(0..128));
    assert_eq!(info.spp.map(|s| (s.min, s.max)), Some((128, 128)));
    assert_eq!(info.seed.as_deref(), Some("3"));
    let summed = low.info.time_seconds.unwrap() + high.info.time_seconds.unwrap();
    assert!((info.time_seconds.unwrap() - summed).abs() <= 1e-6 * summed);
    // The same range twice is the same samples: refused.
    let twice = merge_renders(&[("low.exr".into(), low.clone()), ("again.exr".into(), low)]);
    assert!(twice
        .unwrap_err()
        .to_string()
        .contains("hold the same samples"));
}
