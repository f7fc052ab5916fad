//! The `candela` binary end to end: exit codes, files written (and not
//! written), and the Part 5 flags. Renders the built-in demo scene small.

use candela_image::{read_exr_layers, read_png};
use candela_testkit::TempDir;
use std::path::Path;
use std::process::{Command, Output};

/// A fresh, empty folder for one test, removed afterwards.
fn scratch(name: &str) -> TempDir {
    TempDir::new(&format!("cli-{name}"))
}

/// Runs `candela` on the demo scene at 48 × 36, on 2 threads unless `args`
/// say otherwise.
fn candela(args: &[&str]) -> Output {
    let threads: &[&str] = if args.contains(&"-t") {
        &[]
    } else {
        &["-t", "2"]
    };
    Command::new(env!("CARGO_BIN_EXE_candela"))
        .args(["-r", "48", "36"])
        .args(threads)
        .args(args)
        .output()
        .expect("candela runs")
}

fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temp path")
}

#[test]
fn an_output_in_a_missing_folder_is_bad_input_and_leaves_no_file() {
    let dir = scratch("failwrite");
    let out = dir.join("missing").join("out.png");
    let run = candela(&["-s", "1", "-q", "-f", path(&out)]);
    assert_eq!(
        run.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(String::from_utf8_lossy(&run.stderr).contains("cannot create"));
    assert!(!out.exists());
    let left: Vec<_> = std::fs::read_dir(&dir).expect("folder").collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn output_is_byte_identical_for_any_thread_count_and_tiling() {
    let dir = scratch("determinism");
    let mut images = Vec::new();
    for (i, (threads, tile)) in [("1", "16"), ("2", "5"), ("8", "64")].iter().enumerate() {
        let out = dir.join(format!("out{i}.png"));
        let run = candela(&[
            "-s",
            "32",
            "-a",
            "8",
            "0.2",
            "-q",
            "-t",
            threads,
            "--tile",
            tile,
            "-f",
            path(&out),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let rate = std::fs::read(dir.join(format!("out{i}_rate.png"))).expect("rate image written");
        images.push((std::fs::read(&out).expect("image written"), rate));
    }
    assert!(images.windows(2).all(|w| w[0] == w[1]));
}

#[test]
fn exr_carries_the_denoiser_layers_and_sample_counts() {
    let dir = scratch("exr");
    let out = dir.join("out.exr");
    let run = candela(&["-s", "16", "-a", "8", "0.5", "-q", "-f", path(&out)]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let layers = read_exr_layers(&out).expect("EXR reads back");
    let albedo = layers.albedo.expect("albedo layer");
    let normal = layers.normal.expect("normal layer");
    let counts = layers.sample_count.expect("samples layer");
    assert!(albedo
        .pixels()
        .iter()
        .flatten()
        .all(|&a| (0.0..=1.0).contains(&a)));
    assert!(normal
        .pixels()
        .iter()
        .all(|n| n.iter().map(|c| c * c).sum::<f32>() <= 1.0 + 1e-3));
    // Adaptive: every pixel between one batch and -s, at a batch multiple.
    assert!(counts
        .values()
        .iter()
        .all(|&n| (8.0..=16.0).contains(&n) && n % 8.0 == 0.0));
    assert!(dir.join("out_rate.png").exists());
    // Depth and cost: every camera ray of the closed box hits a wall, and
    // every sample does traversal work.
    let extra = |name: &str| match layers.extra.iter().find(|(n, _)| n == name) {
        Some((_, candela_image::LayerData::Gray(image))) => image.values().to_vec(),
        _ => panic!(
            "no scalar layer {name}: {:?}",
            layers.extra.iter().map(|e| &e.0).collect::<Vec<_>>()
        ),
    };
    assert!(extra("depth").iter().all(|&d| d.is_finite() && d > 0.0));
    assert!(extra("cost.nodes").iter().all(|&n| n >= 1.0));
    assert!(extra("cost.prims").iter().all(|&n| n >= 1.0));
}

#[test]
fn a_cell_renders_into_the_full_frame() {
    let dir = scratch("cell");
    let (full, cell) = (dir.join("full.png"), dir.join("cell.png"));
    assert!(candela(&["-s", "4", "-q", "-f", path(&full)])
        .status
        .success());
    let run = candela(&[
        "-s",
        "4",
        "-q",
        "-p",
        "10",
        "5",
        "20",
        "12",
        "-f",
        path(&cell),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let (full, cell) = (read_png(&full).expect("png"), read_png(&cell).expect("png"));
    assert_eq!(cell.size(), (48, 36));
    for y in 0..36 {
        for x in 0..48 {
            let inside = (10..30).contains(&x) && (5..17).contains(&y);
            let expected = if inside {
                full.get(x, y)
            } else {
                Some([0.0; 3])
            };
            assert_eq!(cell.get(x, y), expected, "pixel ({x}, {y})");
        }
    }
}

#[test]
fn exr_compression_changes_the_file_not_the_pixels() {
    let dir = scratch("exr-compression");
    let mut beauty = Vec::new();
    for compression in ["zip", "none"] {
        let out = dir.join(format!("{compression}.exr"));
        let run = candela(&[
            "-s",
            "2",
            "-q",
            "--exr-compression",
            compression,
            "-f",
            path(&out),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        beauty.push(read_exr_layers(&out).expect("EXR reads back").beauty);
    }
    assert_eq!(beauty[0], beauty[1]);
    let size = |name: &str| std::fs::metadata(dir.join(name)).unwrap().len();
    // Raw 32-bit channels: at least 4 bytes per pixel per channel of the
    // beauty image alone; the default ZIP file is smaller than that.
    let raw_floor = 48 * 36 * 3 * 4;
    assert!(size("none.exr") > raw_floor, "{}", size("none.exr"));
    assert!(
        size("zip.exr") < size("none.exr"),
        "{} {}",
        size("zip.exr"),
        size("none.exr")
    );
}

#[test]
fn impossible_flags_are_usage_errors() {
    for args in [
        &["-a", "0", "0.05"][..],
        &["-a", "6.5", "0.05"],
        &["-a", "64", "-1"],
        &["-p", "40", "0", "20", "10"],
        &["-p", "0", "0", "0", "10"],
        &["--time", "0"],
        // A film that would not fit in memory, a non-finite number, a
        // focus at zero distance: refused before anything is loaded.
        &["-r", "100000", "100000", "-s", "1"],
        &["--exposure", "nan"],
        &["-d", "0", "-b", "0.1"],
        &["--integrator", "photons"],
        &["--exr-compression", "b44"],
        // A bounce past the depth, or with a view that picks its own.
        &["-m", "3", "--bounce", "4"],
        &["--bounce", "1", "--direct-only"],
    ] {
        // A writable output, so that the flags alone make the error; and
        // nothing may be written.
        let dir = scratch("usage");
        let out = dir.join("never.png");
        let run = candela(&[args, &["-q", "-f", out.to_str().unwrap()]].concat());
        assert_eq!(
            run.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{args:?}"
        );
    }
}

#[test]
fn an_output_folder_that_cannot_be_written_fails_before_the_render() {
    let dir = scratch("unwritable");
    let folder_as_output = dir.join("image.png");
    std::fs::create_dir(&folder_as_output).unwrap();
    for out in [
        "/nonexistent/never.png".to_string(),
        folder_as_output.display().to_string(),
    ] {
        // Slow settings: the check must come before the render, not after.
        let run = candela(&["-q", "-s", "100000", "-f", &out]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{out}: {err}");
        assert!(err.contains(&out) && err.lines().count() == 1, "{err}");
    }
}

#[test]
fn a_time_budget_ends_the_render_and_reports_samples() {
    let dir = scratch("time");
    let out = dir.join("out.png");
    let start = std::time::Instant::now();
    let run = candela(&["--time", "1", "-f", path(&out)]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(start.elapsed().as_secs_f64() < 10.0);
    let log = String::from_utf8_lossy(&run.stderr);
    assert!(
        log.contains("time budget spent: samples per pixel min"),
        "{log}"
    );
    assert!(out.exists());
}

#[cfg(unix)]
#[test]
fn ctrl_c_writes_the_partial_image_and_exits_130() {
    let dir = scratch("ctrlc");
    let out = dir.join("out.png");
    let child = Command::new(env!("CARGO_BIN_EXE_candela"))
        .args([
            "-r",
            "48",
            "36",
            "-t",
            "2",
            "-s",
            "1000000",
            "-f",
            path(&out),
        ])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("candela starts");
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(kill.success());
    let run = child.wait_with_output().expect("candela ends");
    let log = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(130), "{log}");
    assert!(log.contains("interrupted: the image is partial"), "{log}");
    let image = read_png(&out).expect("partial image written");
    assert!(image.pixels().iter().flatten().any(|&c| c > 0.0));
}

#[test]
fn the_help_names_every_scene_format() {
    let help = candela(&["--help"]);
    assert!(help.status.success());
    let text = String::from_utf8_lossy(&help.stdout);
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    for format in candela_scene::supported_formats().split(", ") {
        assert!(
            text.contains(format),
            "{format} missing from --help:\n{text}"
        );
    }
}

#[test]
fn the_bounce_view_is_a_documented_flag_and_renders() {
    let help = candela(&["--help"]);
    assert!(help.status.success());
    let text = String::from_utf8_lossy(&help.stdout);
    let at = text
        .find("--bounce <K>")
        .unwrap_or_else(|| panic!("--bounce missing from --help:\n{text}"));
    // The help may wrap: compare with the whitespace collapsed.
    let entry: Vec<&str> = text[at..].split_whitespace().take(16).collect();
    assert!(
        entry.join(" ").contains("after exactly K bounces"),
        "{entry:?}"
    );
    let dir = scratch("bounce");
    let out = dir.join("b1.png");
    let run = candela(&[
        "-s",
        "1",
        "-m",
        "2",
        "--bounce",
        "1",
        "-q",
        "-f",
        path(&out),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(read_png(&out).is_ok());
}

#[test]
fn camera_n_picks_the_files_nth_camera_and_refuses_one_it_lacks() {
    let dir = scratch("camera-n");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/gltf/textured.gltf");
    let render = |camera: &str, out: &Path| {
        candela(&[
            "-s",
            "1",
            "-q",
            "--camera",
            camera,
            "-f",
            path(out),
            path(&scene),
        ])
    };
    let images: Vec<_> = ["file", "0", "1"]
        .iter()
        .map(|camera| {
            let out = dir.join(format!("camera-{camera}.png"));
            let run = render(camera, &out);
            assert_eq!(
                run.status.code(),
                Some(0),
                "{}",
                String::from_utf8_lossy(&run.stderr)
            );
            read_png(&out).expect("image")
        })
        .collect();
    assert_eq!(images[0], images[1], "`file` is the first camera");
    assert_ne!(images[1], images[2], "camera 1 is another view");
    let out = dir.join("camera-2.png");
    let run = render("2", &out);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("--camera") && stderr.contains("2 camera(s)"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn quiet_silences_progress_and_statistics_but_not_warnings() {
    let dir = scratch("quiet-warns");
    let scene = dir.join("lonely.obj");
    std::fs::write(
        &scene,
        "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .expect("scene written");
    let out = dir.join("lonely.png");
    let run = candela(&["-q", "--normals", "-f", path(&out), path(&scene)]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("warning") && stderr.contains("missing.mtl"),
        "{stderr}"
    );
}
