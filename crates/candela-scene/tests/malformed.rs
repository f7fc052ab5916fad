//! Bad input: every file in `tests/malformed/` has exactly one problem, named
//! by its file-name prefix (the expected `ErrorKind`). Loading must fail with
//! that kind, at a line in that file, and never panic.

use candela_scene::{load, load_str, ErrorKind, LoadOptions};
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests")
}

fn kind_named(prefix: &str) -> ErrorKind {
    match prefix {
        "NotXml" => ErrorKind::NotXml,
        "NotCollada" => ErrorKind::NotCollada,
        "Dtd" => ErrorKind::Dtd,
        "DanglingUrl" => ErrorKind::MissingReference,
        "CountMismatch" => ErrorKind::CountMismatch,
        "IndexOutOfRange" => ErrorKind::IndexOutOfRange,
        "BadNumber" => ErrorKind::BadNumber,
        "NonFinite" => ErrorKind::NonFinite,
        "BadPolygon" => ErrorKind::BadPolygon,
        "DegenerateCamera" => ErrorKind::DegenerateCamera,
        "TooLarge" => ErrorKind::TooLarge,
        "TooDeep" => ErrorKind::TooDeep,
        "MissingElement" => ErrorKind::MissingElement,
        "BadValue" => ErrorKind::BadValue,
        "Truncated" => ErrorKind::Truncated,
        "NotText" => ErrorKind::NotText,
        "MissingReference" => ErrorKind::MissingReference,
        other => panic!("unknown expected kind {other}"),
    }
}

#[test]
fn the_valid_base_file_loads() {
    // The corpus is the base file with one change each; the base itself is fine.
    let l = load(
        &dir().join("valid_base.dae"),
        &LoadOptions {
            strict: true,
            ..Default::default()
        },
    )
    .unwrap();
    let s = l.scene;
    assert_eq!(
        (s.meshes.len(), s.triangle_count(), s.spheres.len()),
        (1, 2, 1)
    );
    assert_eq!((s.cameras.len(), s.lights.len()), (1, 1));
    // Sphere node translate (0 0 1) in Z_UP is (0, 1, 0) in Y-up.
    assert!((s.spheres[0].center - glam::Vec3::Y).length() < 1e-6);
}

#[test]
fn every_malformed_file_fails_with_its_kind_and_location() {
    let mut n = 0;
    let mut entries: Vec<_> = std::fs::read_dir(dir().join("malformed"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let want = kind_named(name.split('-').next().unwrap());
        let err = match load(&path, &LoadOptions::default()) {
            Ok(_) => panic!("{name}: loaded, expected {want:?}"),
            Err(e) => e,
        };
        assert_eq!(err.kind, want, "{name}: {err}");
        let line = err.to_string();
        assert!(!line.contains('\n'), "{line}");
        assert!(line.starts_with(&path.display().to_string()), "{line}");
        let loc = err
            .loc
            .unwrap_or_else(|| panic!("{name}: no location: {line}"));
        assert!(loc.line >= 1 && loc.col >= 1);
        assert!(
            line.contains(&format!(":{}:{}: ", loc.line, loc.col)),
            "{line}"
        );
        n += 1;
    }
    assert!(n >= 25 + 2 * 15, "only {n} malformed files");
}

#[test]
fn errors_point_at_the_offending_token() {
    let path = dir().join("malformed/IndexOutOfRange-p.dae");
    let text = std::fs::read_to_string(&path).unwrap();
    let err = load(&path, &LoadOptions::default()).unwrap_err();
    let loc = err.loc.unwrap();
    let line = text.lines().nth(loc.line as usize - 1).unwrap();
    // Column of the bad index `4` in `<p>0 1 2 4</p>`.
    assert_eq!(&line[loc.col as usize - 1..loc.col as usize], "4", "{err}");
    assert!(err.element.starts_with("<p"), "{err}");
}

#[test]
fn missing_file_is_an_io_error() {
    let err = load(Path::new("/nonexistent/scene.dae"), &LoadOptions::default()).unwrap_err();
    assert_eq!(err.kind, ErrorKind::Io);
    assert!(
        err.to_string().starts_with("/nonexistent/scene.dae: "),
        "{err}"
    );
}

fn nested_nodes(depth: usize) -> String {
    let mut s = String::from("<COLLADA><library_visual_scenes><visual_scene id=\"s\">");
    s.push_str(&"<node>".repeat(depth));
    s.push_str(&"</node>".repeat(depth));
    s.push_str("</visual_scene></library_visual_scenes></COLLADA>");
    s
}

#[test]
fn deep_nesting_fails_fast() {
    let opts = LoadOptions::default();
    assert!(load_str(&nested_nodes(200), Path::new("ok.dae"), &opts).is_ok());
    for depth in [300, 100_000] {
        let t = std::time::Instant::now();
        let err = load_str(&nested_nodes(depth), Path::new("deep.dae"), &opts).unwrap_err();
        assert_eq!(err.kind, ErrorKind::TooDeep, "{err}");
        assert!(t.elapsed().as_secs() < 5);
    }
}

#[test]
fn unsupported_features_warn_once_or_fail_in_strict_mode() {
    let base = std::fs::read_to_string(dir().join("valid_base.dae")).unwrap();
    let text = base
        .replace("<library_cameras>", "<library_animations><animation id=\"a\"/></library_animations>\n  <library_cameras>")
        .replace(
            "<input semantic=\"VERTEX\" source=\"#quad-verts\" offset=\"0\"/>",
            "<input semantic=\"VERTEX\" source=\"#quad-verts\" offset=\"0\"/><input semantic=\"COLOR\" source=\"#quad-pos\" offset=\"0\"/>",
        )
        .replace("<node id=\"ballnode\">", "<node id=\"b2\"><instance_geometry url=\"#quad\"/></node><node id=\"ballnode\">");
    let l = load_str(&text, Path::new("warn.dae"), &LoadOptions::default()).unwrap();
    assert_eq!(l.report.len(), 2, "{}", l.report);
    assert!(l.report.mentions("library_animations"));
    let color = l
        .report
        .warnings
        .iter()
        .find(|w| w.message.contains("COLOR"))
        .unwrap();
    assert_eq!(color.count, 2, "{}", l.report);
    let err = load_str(
        &text,
        Path::new("warn.dae"),
        &LoadOptions {
            strict: true,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert_eq!(err.kind, ErrorKind::Unsupported, "{err}");
}
