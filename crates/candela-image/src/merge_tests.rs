//! Merging simulated renders whose samples are known.

use super::*;
use crate::variance::variance_of_mean;
use candela_testkit::SplitMix64;

const W: usize = 6;
const H: usize = 4;

/// A render of per-pixel samples `samples[i]` (one list per pixel, the same
/// value in all three channels), as the film would write it.
fn render(samples: &[Vec<f64>], seed: &str, range: std::ops::Range<u32>) -> ExrLayers {
    let stat = |f: &dyn Fn(&[f64]) -> f64| {
        RgbImage::from_pixels(W, H, samples.iter().map(|s| [f(s) as f32; 3]).collect()).unwrap()
    };
    let mean = stat(&|s| s.iter().sum::<f64>() / s.len().max(1) as f64);
    let variance = stat(&|s| {
        let sum: f64 = s.iter().sum();
        let sq: f64 = s.iter().map(|x| x * x).sum();
        variance_of_mean(s.len() as f64, sum, sq)
    });
    let counts = samples.iter().map(|s| s.len() as f32).collect();
    let depth = samples
        .iter()
        .map(|s| if s.is_empty() { f32::INFINITY } else { 2.0 })
        .collect();
    ExrLayers {
        sample_count: Some(GrayImage::from_values(W, H, counts).unwrap()),
        extra: vec![
            (
                "depth".into(),
                LayerData::Gray(GrayImage::from_values(W, H, depth).unwrap()),
            ),
            (VARIANCE_LAYER.into(), LayerData::Rgb(variance)),
        ],
        info: RenderInfo {
            time_seconds: Some(1.25),
            seed: Some(seed.into()),
            sample_range: Some(range),
            scene: Some("box.dae".into()),
            ..RenderInfo::default()
        },
        ..ExrLayers::beauty(mean)
    }
}

fn samples(rng: &mut SplitMix64, per_pixel: impl Fn(usize) -> usize) -> Vec<Vec<f64>> {
    (0..W * H)
        .map(|i| {
            (0..per_pixel(i))
                .map(|_| -(1.0 - rng.uniform()).ln() * 0.7)
                .collect()
        })
        .collect()
}

#[test]
fn merged_parts_equal_the_render_of_all_samples() {
    let mut rng = SplitMix64::new(9);
    // Adaptive-like counts: some pixels with 0, 1 or many samples per part.
    let a = samples(&mut rng, |i| [0, 1, 5, 16][i % 4]);
    let b = samples(&mut rng, |i| [0, 3, 1, 16][i % 4]);
    let both: Vec<Vec<f64>> = a
        .iter()
        .zip(&b)
        .map(|(x, y)| [x.clone(), y.clone()].concat())
        .collect();
    let merged = merge_renders(&[
        ("a.exr".into(), render(&a, "1", 0..16)),
        ("b.exr".into(), render(&b, "2", 0..16)),
    ])
    .unwrap();
    let whole = render(&both, "3", 0..16);
    assert_eq!(merged.sample_count, whole.sample_count);
    let (mv, wv) = (merged.variance().unwrap(), whole.variance().unwrap());
    for i in 0..W * H {
        let (m, w) = (merged.beauty.pixels()[i][0], whole.beauty.pixels()[i][0]);
        // Each stored f32 is within 2^-24 relative; the merge adds a few roundings.
        assert!(
            (m - w).abs() <= 4.0 * f32::EPSILON * w.abs(),
            "pixel {i}: {m} vs {w}"
        );
        let (v, u) = (mv.pixels()[i][0], wv.pixels()[i][0]);
        assert!(
            v == u || (v - u).abs() <= 1e-5 * u,
            "pixel {i}: variance {v} vs {u}"
        );
    }
    // Depth: +inf (no hit) only where neither part has samples.
    let Some(LayerData::Gray(depth)) = merged.layer("depth") else {
        panic!("no depth")
    };
    assert_eq!(depth.values()[0], f32::INFINITY);
    assert_eq!(depth.values()[1], 2.0);
    assert_eq!(merged.info.time_seconds, Some(2.5));
    assert_eq!(merged.info.seed.as_deref(), Some("1,2"));
    assert_eq!(merged.info.spp.map(|s| (s.min, s.max)), Some((4, 32)));
}

#[test]
fn disjoint_ranges_of_one_seed_merge_and_report_their_union() {
    let mut rng = SplitMix64::new(4);
    let a = samples(&mut rng, |_| 4);
    let b = samples(&mut rng, |_| 4);
    let merged = merge_renders(&[
        ("hi.exr".into(), render(&b, "7", 4..8)),
        ("lo.exr".into(), render(&a, "7", 0..4)),
    ])
    .unwrap();
    assert_eq!(merged.info.sample_range, Some(0..8));
    assert_eq!(merged.info.seed.as_deref(), Some("7"));
}

#[test]
fn refuses_what_cannot_be_merged() {
    let mut rng = SplitMix64::new(5);
    let a = render(&samples(&mut rng, |_| 4), "1", 0..4);
    let message = |parts: &[MergePart]| merge_renders(parts).unwrap_err().to_string();
    // The same samples twice.
    let same = message(&[("a.exr".into(), a.clone()), ("b.exr".into(), a.clone())]);
    assert!(
        same.contains("a.exr and b.exr hold the same samples"),
        "{same}"
    );
    // Another size.
    let mut small = a.clone();
    small.beauty = RgbImage::new(2, 2).unwrap();
    small.info.seed = Some("2".into());
    let size = message(&[("a.exr".into(), a.clone()), ("s.exr".into(), small)]);
    assert!(size.contains("s.exr is 2x2, a.exr is 6x4"), "{size}");
    // A missing layer.
    let mut bare = a.clone();
    bare.extra.retain(|(n, _)| n != "depth");
    bare.info.seed = Some("3".into());
    let layers = message(&[("a.exr".into(), a.clone()), ("c.exr".into(), bare)]);
    assert!(layers.contains("only in a.exr: [depth]"), "{layers}");
    // Another scene.
    let mut other = a.clone();
    other.info.seed = Some("4".into());
    other.info.scene = Some("bunny.dae".into());
    let scene = message(&[("a.exr".into(), a.clone()), ("d.exr".into(), other)]);
    assert!(
        scene.contains("different scenes (box.dae vs bunny.dae)"),
        "{scene}"
    );
    // No counts at all.
    let mut plain = ExrLayers::beauty(a.beauty.clone());
    plain.info.spp = None;
    let counts = message(&[("p.exr".into(), plain.clone()), ("q.exr".into(), plain)]);
    assert!(
        counts.contains("p.exr: no per-pixel sample counts"),
        "{counts}"
    );
}
