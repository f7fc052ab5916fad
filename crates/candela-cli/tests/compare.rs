//! `candela compare` and `candela merge` end to end: the z-test's power on
//! a CS184 scene, the report, merges, and one-line errors with exit code 2.

use candela_image::{read_exr_layers, write_exr, LayerData, RgbImage, VARIANCE_LAYER};
use candela_testkit::{cs184_scene, TempDir};
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

fn candela(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_candela"))
        .args(args)
        .output()
        .expect("candela runs")
}

fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temp path")
}

fn ok(run: &Output) -> String {
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8_lossy(&run.stdout).into_owned()
}

/// Renders `scene` at `w` × `h`, `spp`, `seed` into `out` (an EXR).
fn render(scene: &Path, (w, h): (u32, u32), spp: u32, seed: u32, out: &Path) {
    let (w, h, spp, seed) = (
        w.to_string(),
        h.to_string(),
        spp.to_string(),
        seed.to_string(),
    );
    ok(&candela(&[
        "-q",
        "-t",
        "2",
        "-r",
        &w,
        &h,
        "-s",
        &spp,
        "--seed",
        &seed,
        "-f",
        path(out),
        path(scene),
    ]));
}

fn compare_json(args: &[&str]) -> Value {
    let mut all = vec!["compare", "--json"];
    all.extend_from_slice(args);
    serde_json::from_str(&ok(&candela(&all))).expect("compare prints JSON")
}

/// Scales an EXR's beauty by `factor` and its variance by `factor²`: the
/// same render of a scene `factor` times as bright.
fn scaled_copy(from: &Path, to: &Path, factor: f32) {
    let mut layers = read_exr_layers(from).expect("render reads back");
    let scale = |image: &mut RgbImage, k: f32| {
        for p in image.pixels_mut() {
            *p = p.map(|v| v * k);
        }
    };
    scale(&mut layers.beauty, factor);
    for (name, data) in &mut layers.extra {
        if let (VARIANCE_LAYER, LayerData::Rgb(image)) = (name.as_str(), data) {
            scale(image, factor * factor);
        }
    }
    write_exr(to, &layers).expect("scaled copy written");
}

/// The z-test of the issue: at 256 spp on CBspheres_lambertian, two
/// independent renders pass and a 2% brighter one fails.
///
/// Power. At 32 × 24 the image has N = 768 pixels in 4 × 3 = 12 blocks of
/// 8 × 8; the Bonferroni threshold over 39 tests at 1% is |z| = 3.66. For a
/// channel with image mean μ and mean per-pixel variance of the mean v̄
/// (both renders alike), a 2% shift of the whole image gives a global
/// z = 0.02 μ / sqrt(2 v̄ / N). This scene's renders at 256 spp have a
/// per-pixel relative standard error sqrt(v̄)/μ of about 0.027 (measured
/// from the variance layers), so z ≈ 0.02 · sqrt(768/2) / 0.027 ≈ 14.5,
/// far above the threshold: a miss has probability below 1e-20. A single
/// block (64 pixels) sees z ≈ 0.02 · sqrt(32) / 0.027 ≈ 4.2, so some blocks
/// flag too. The test computes the expected z from the files and requires
/// it to exceed the threshold by 3 (a miss then has probability below
/// 0.2%) before asserting the verdict, so a change that makes the scene
/// noisier fails loudly here instead of weakening the test. Two renders of
/// 256 spp at this size take about a second of CPU in the test profile.
#[test]
fn z_test_flags_a_two_percent_change_and_passes_independent_renders() {
    let scene = cs184_scene("CBspheres_lambertian.dae");
    let dir = TempDir::new("compare-power");
    let size = (32, 24);
    let (a, b, bright) = (dir.join("a.exr"), dir.join("b.exr"), dir.join("bright.exr"));
    render(&scene, size, 256, 1, &a);
    render(&scene, size, 256, 2, &b);
    scaled_copy(&b, &bright, 1.02);

    let same = compare_json(&[path(&a), path(&b)]);
    let z = &same["comparisons"][0]["z_test"];
    assert_eq!(z["variance_source"], "pixel variance");
    assert_eq!(z["passed"], true, "independent renders fail: {same:#}");
    let threshold = z["threshold"].as_f64().unwrap();

    // The expected global z of the 2% shift, from the renders' own variance.
    let (la, lb) = (read_exr_layers(&a).unwrap(), read_exr_layers(&b).unwrap());
    let pixels = la.beauty.pixels().len() as f64;
    let expected_z = (0..3)
        .map(|c| {
            let mean: f64 = lb.beauty.pixels().iter().map(|p| p[c] as f64).sum::<f64>() / pixels;
            let var = |l: &candela_image::ExrLayers| -> f64 {
                l.variance()
                    .unwrap()
                    .pixels()
                    .iter()
                    .map(|p| p[c] as f64)
                    .sum::<f64>()
            };
            let var_of_global = (var(&la) + var(&lb)) / (pixels * pixels);
            0.02 * mean / var_of_global.sqrt()
        })
        .fold(f64::INFINITY, f64::min);
    eprintln!("expected global z of a 2% shift: {expected_z:.1} (threshold {threshold:.2})");
    assert!(
        expected_z > threshold + 3.0,
        "too little power: expected z {expected_z}"
    );

    let shifted = compare_json(&[path(&a), path(&bright)]);
    let z = &shifted["comparisons"][0]["z_test"];
    eprintln!(
        "observed: independent max block |z| {}, global |z| {}; shifted global |z| {}, {} tests over",
        same["comparisons"][0]["z_test"]["max_abs_z"],
        same["comparisons"][0]["z_test"]["global_abs_z"],
        z["global_abs_z"],
        z["tests_over_threshold"]
    );
    assert_eq!(z["passed"], false, "a 2% change passes: {shifted:#}");
    assert!(z["global_abs_z"].as_f64().unwrap() > threshold);

    // The readable table says the same.
    let table = ok(&candela(&["compare", path(&a), path(&bright)]));
    assert!(
        table.contains("FAIL") && table.contains("pixel variance"),
        "{table}"
    );
}

#[test]
fn reference_gives_efficiencies_and_heatmap() {
    let scene = cs184_scene("CBspheres_lambertian.dae");
    let dir = TempDir::new("compare-efficiency");
    let (r, a, b) = (dir.join("r.exr"), dir.join("a.exr"), dir.join("b.exr"));
    render(&scene, (24, 18), 64, 9, &r);
    render(&scene, (24, 18), 4, 1, &a);
    render(&scene, (24, 18), 16, 2, &b);
    let heat = dir.join("heat.png");
    let report = compare_json(&[
        "--reference",
        path(&r),
        "--heatmap",
        path(&heat),
        path(&a),
        path(&b),
    ]);
    let entries = report["comparisons"].as_array().unwrap();
    assert_eq!(entries.len(), 2);
    let efficiency = |e: &Value| {
        let (rel, time) = (
            e["rel_mse"].as_f64().unwrap(),
            e["time_seconds"].as_f64().unwrap(),
        );
        // The report's own division may round differently in the last
        // place (its product is formed before the JSON rounds the inputs).
        let expected = 1.0 / (rel * time);
        let reported = e["efficiency"].as_f64().unwrap();
        assert!(
            (reported - expected).abs() <= 1e-12 * expected,
            "{reported} vs {expected}"
        );
        expected
    };
    let ratio = report["efficiency_ratio"].as_f64().unwrap();
    assert!((ratio - efficiency(&entries[0]) / efficiency(&entries[1])).abs() <= 1e-12 * ratio);
    assert_eq!(entries[1]["spp"]["min"], 16);
    assert_eq!(candela_image::read_png(&heat).unwrap().size(), (24, 18));
    // A PNG compares too (block spread; no efficiency without a header).
    let png = dir.join("a.png");
    ok(&candela(&[
        "-q",
        "-r",
        "24",
        "18",
        "-s",
        "4",
        "-f",
        path(&png),
        path(&scene),
    ]));
    let mixed = compare_json(&[path(&png), path(&a)]);
    assert_eq!(
        mixed["comparisons"][0]["z_test"]["variance_source"],
        "block spread"
    );
}

#[test]
fn merge_adds_renders_of_other_seeds() {
    let dir = TempDir::new("merge-cli");
    let (a, b, out) = (dir.join("a.exr"), dir.join("b.exr"), dir.join("ab.exr"));
    let demo = |seed: &str, out: &Path| {
        ok(&candela(&[
            "-q",
            "-r",
            "16",
            "12",
            "-s",
            "8",
            "--seed",
            seed,
            "-f",
            path(out),
        ]));
    };
    demo("1", &a);
    demo("2", &b);
    ok(&candela(&[
        "merge",
        "-q",
        path(&a),
        path(&b),
        "-o",
        path(&out),
    ]));
    let merged = read_exr_layers(&out).unwrap();
    assert_eq!(merged.info.spp.map(|s| (s.min, s.max)), Some((16, 16)));
    assert_eq!(merged.info.seed.as_deref(), Some("1,2"));
    assert!(merged.variance().is_some());
    // The same file twice: the same samples, refused.
    let twice = candela(&["merge", path(&a), path(&a), "-o", path(&out)]);
    assert_eq!(twice.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&twice.stderr).contains("hold the same samples"));
}

#[test]
fn bad_input_is_one_line_naming_the_file_with_exit_code_2() {
    let dir = TempDir::new("compare-bad");
    let (a, small) = (dir.join("a.exr"), dir.join("small.exr"));
    ok(&candela(&[
        "-q",
        "-r",
        "16",
        "12",
        "-s",
        "2",
        "-f",
        path(&a),
    ]));
    ok(&candela(&[
        "-q",
        "-r",
        "8",
        "6",
        "-s",
        "2",
        "--seed",
        "5",
        "-f",
        path(&small),
    ]));
    let text = dir.join("notes.txt");
    std::fs::write(&text, "not an image").unwrap();
    let fake = dir.join("fake.png");
    std::fs::write(&fake, "not a png").unwrap();
    let missing = dir.join("missing.exr");
    let out = dir.join("out.exr");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["compare", path(&a), path(&missing)], "missing.exr"),
        (
            vec!["compare", path(&a), path(&text)],
            "notes.txt: not an image",
        ),
        (vec!["compare", path(&fake), path(&a)], "fake.png"),
        (vec!["compare", path(&a), path(&small)], "small.exr is 8x6"),
        (
            vec!["merge", path(&a), path(&small), "-o", path(&out)],
            "small.exr is 8x6",
        ),
        (
            vec!["merge", path(&a), path(&missing), "-o", path(&out)],
            "missing.exr",
        ),
    ];
    for (args, needle) in cases {
        let run = candela(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
    assert!(!out.exists());
}
