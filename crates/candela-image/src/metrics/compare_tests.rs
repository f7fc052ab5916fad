//! The comparison report on small images with known answers.

use super::*;
use crate::{write_exr, write_png_display, ExrLayers, LayerData, SppSpread, VARIANCE_LAYER};
use candela_testkit::TempDir;

fn flat(value: f32) -> RgbImage {
    RgbImage::from_fn(16, 16, |_, _| [value; 3]).unwrap()
}

fn render_file(dir: &TempDir, name: &str, value: f32, variance: f32) -> PathBuf {
    let path = dir.path().join(name);
    let layers = ExrLayers {
        extra: vec![(VARIANCE_LAYER.into(), LayerData::Rgb(flat(variance)))],
        info: RenderInfo {
            spp: Some(SppSpread {
                min: 4,
                mean: 4.0,
                max: 4,
            }),
            time_seconds: Some(2.0),
            ..RenderInfo::default()
        },
        ..ExrLayers::beauty(flat(value))
    };
    write_exr(&path, &layers).unwrap();
    path
}

#[test]
fn reports_metrics_variance_source_and_efficiency() {
    let dir = TempDir::new("compare");
    let a = CompareImage::load(render_file(&dir, "a.exr", 0.5, 1e-4)).unwrap();
    let b = CompareImage::load(render_file(&dir, "b.exr", 0.49, 1e-4)).unwrap();
    let report = compare_pair(&a, &b, &CompareOptions::default()).unwrap();
    assert_eq!(report.variance_source, VarianceSource::PixelVariance);
    assert!((report.mse - 1e-4).abs() < 1e-9);
    assert!((report.rel_mse - 1e-4 / (0.5 * 0.5)).abs() < 1e-8);
    assert!((report.psnr - 40.0).abs() < 1e-4);
    // Each 8x8 block: difference 0.01, variance 2e-4 / 64: z = 0.01 / sqrt(2e-4/64) = 5.66.
    assert!((report.z.max_abs_z - 5.657).abs() < 1e-2, "{:?}", report.z);
    assert!(!report.z.passed());
    let efficiency = a.efficiency(report.rel_mse).unwrap();
    assert!((efficiency - 1.0 / (report.rel_mse * 2.0)).abs() < 1e-9);
    // A PNG: no variance, no metadata, so the block spread and no efficiency.
    let png = dir.path().join("c.png");
    write_png_display(&png, &flat(0.5)).unwrap();
    let c = CompareImage::load(&png).unwrap();
    let report = compare_pair(&c, &a, &CompareOptions::default()).unwrap();
    assert_eq!(report.variance_source, VarianceSource::BlockSpread);
    assert_eq!(c.efficiency(report.rel_mse), None);
    let heat = error_heatmap(&a, &b).unwrap();
    assert_eq!(heat.size(), (16, 16));
}

#[test]
fn bad_inputs_name_the_file() {
    let dir = TempDir::new("compare-bad");
    let missing = dir.path().join("missing.exr");
    let err = CompareImage::load(&missing).unwrap_err().to_string();
    assert!(err.contains("missing.exr"), "{err}");
    let text = dir.path().join("notes.txt");
    std::fs::write(&text, "hello").unwrap();
    let err = CompareImage::load(&text).unwrap_err().to_string();
    assert!(err.contains("notes.txt: not an image"), "{err}");
    let fake = dir.path().join("fake.exr");
    std::fs::write(&fake, "not an exr").unwrap();
    let err = CompareImage::load(&fake).unwrap_err().to_string();
    assert!(err.contains("fake.exr"), "{err}");
    let small = CompareImage::plain("small.png", RgbImage::new(4, 4).unwrap());
    let big = CompareImage::plain("big.png", flat(0.0));
    let err = compare_pair(&small, &big, &CompareOptions::default()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "small.png is 4x4 but big.png is 16x16: images must have the same size"
    );
}
