//! Bad input: every file in `tests/malformed/` has exactly one problem, named
//! by its file-name prefix (the expected `ErrorKind`). A strict load must fail
//! with that kind, at a line in that file, and never panic. A default load
//! fails the same way, except for the defects listed in [`REPAIRS`] (README,
//! "Lenient loading"), which it repairs and reports once, at the place of the
//! strict error.

use candela_scene::{load, load_str, BsdfDesc, ErrorKind, LightKind, LoadOptions, Loaded};
use glam::Vec3;
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
        "Unsupported" => ErrorKind::Unsupported,
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
    let (mut n, mut repaired) = (0, 0);
    let mut entries: Vec<_> = std::fs::read_dir(dir().join("malformed"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let want = kind_named(name.split('-').next().unwrap());
        let err = match load(&path, &strict()) {
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
        match REPAIRS.iter().find(|r| r.file == name) {
            Some(repair) => {
                check_repaired(&path, repair, &err);
                repaired += 1;
            }
            None => {
                let lenient = load(&path, &LoadOptions::default())
                    .map(|_| ())
                    .unwrap_err();
                assert_eq!(
                    (lenient.kind, lenient.loc),
                    (err.kind, err.loc),
                    "{lenient}"
                );
            }
        }
        n += 1;
    }
    assert!(n >= 25 + 2 * 15, "only {n} malformed files");
    assert_eq!(repaired, REPAIRS.len(), "a listed repair has no file");
}

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..Default::default()
    }
}

/// A defect the default mode repairs: the file, words of the warning's fix,
/// and what the repaired scene must hold.
struct Repair {
    file: &'static str,
    fix: &'static str,
    check: fn(&Loaded),
}

fn near(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

/// The base file's point light at node (0 0 2) in Z_UP, i.e. (0, 2, 0), with `color`.
fn point_light_at_2(l: &Loaded, color: Vec3) {
    let LightKind::Point {
        position,
        intensity,
    } = l.scene.lights[0].kind
    else {
        panic!("{:?}", l.scene.lights)
    };
    assert!(near(position, Vec3::new(0.0, 2.0, 0.0)), "{position}");
    assert!(near(intensity, color), "{intensity}");
}

fn triangles(l: &Loaded, n: usize) {
    assert_eq!(l.scene.triangle_count(), n, "{:?}", l.scene.meshes);
}

fn red(l: &Loaded) -> &BsdfDesc {
    &l.scene
        .materials
        .iter()
        .find(|m| m.name == "red")
        .unwrap()
        .bsdf
}

const REPAIRS: &[Repair] = &[
    Repair {
        file: "CountMismatch-matrix.dae",
        fix: "last row completed as 0 0 0 1",
        check: |l| point_light_at_2(l, Vec3::ONE),
    },
    Repair {
        file: "CountMismatch-matrix-15.dae",
        fix: "last row completed as 0 0 0 1",
        check: |l| point_light_at_2(l, Vec3::ONE),
    },
    Repair {
        file: "CountMismatch-matrix-17.dae",
        fix: "after the 16th dropped",
        check: |l| point_light_at_2(l, Vec3::ONE),
    },
    Repair {
        file: "CountMismatch-float_array-count.dae",
        fix: "the 12 numbers present used",
        check: |l| {
            triangles(l, 2);
            assert_eq!(l.scene.meshes[0].positions.len(), 4);
        },
    },
    Repair {
        file: "CountMismatch-polylist-count.dae",
        fix: "the 1 polygons of <vcount> used",
        check: |l| triangles(l, 2),
    },
    Repair {
        file: "CountMismatch-vcount-vs-p.dae",
        fix: "incomplete last polygon dropped",
        check: |l| triangles(l, 0),
    },
    Repair {
        file: "CountMismatch-p-last-polygon.dae",
        fix: "incomplete last polygon dropped",
        check: |l| {
            triangles(l, 1);
            assert_eq!(l.scene.meshes[0].triangles, vec![[0, 1, 2]]);
        },
    },
    Repair {
        file: "CountMismatch-triangles-last.dae",
        fix: "incomplete last triangle dropped (1 kept)",
        check: |l| triangles(l, 1),
    },
    Repair {
        file: "CountMismatch-triangles-count.dae",
        fix: "the 2 triangles in <p> used",
        check: |l| triangles(l, 2),
    },
    Repair {
        file: "CountMismatch-polygons-count.dae",
        fix: "the 1 <p> polygons used",
        check: |l| triangles(l, 2),
    },
    Repair {
        file: "BadValue-light-color-negative.dae",
        fix: "clamped to (1, 0, 1)",
        check: |l| point_light_at_2(l, Vec3::new(1.0, 0.0, 1.0)),
    },
    Repair {
        file: "BadValue-diffuse-above-one.dae",
        fix: "clamped to (1, 0.1, 0.1)",
        check: |l| {
            let BsdfDesc::Diffuse { albedo } = red(l) else {
                panic!("{:?}", red(l))
            };
            assert!(near(*albedo, Vec3::new(1.0, 0.1, 0.1)), "{albedo}");
        },
    },
    Repair {
        file: "NonFinite-ior.dae",
        fix: "the default 1.5 used",
        check: |l| assert!(matches!(red(l), BsdfDesc::Glass { ior, .. } if *ior == 1.5)),
    },
    Repair {
        file: "NonFinite-reflectance.dae",
        fix: "the default (1, 1, 1) used",
        check: |l| {
            assert!(matches!(red(l), BsdfDesc::Mirror { reflectance } if *reflectance == Vec3::ONE))
        },
    },
];

/// The default load of `path` succeeds with exactly one warning, at the
/// strict error's place and element, saying how it was repaired.
fn check_repaired(path: &Path, repair: &Repair, strict_err: &candela_scene::LoadError) {
    let name = repair.file;
    let loaded =
        load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{name}: not repaired: {e}"));
    let w = match loaded.report.warnings.as_slice() {
        [w] => w,
        _ => panic!("{name}: expected one warning:\n{}", loaded.report),
    };
    assert_eq!(Some(w.loc), strict_err.loc, "{name}: {w}");
    assert_eq!(w.element, strict_err.element, "{name}: {w}");
    assert!(w.message.contains(repair.fix), "{name}: {w}");
    assert!(w.message.contains(&strict_err.message), "{name}: {w}");
    (repair.check)(&loaded);
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

/// The error line for `bytes` loaded as `name`, which must fail.
fn error_line(name: &str, bytes: &[u8]) -> String {
    let file = candela_testkit::TempFile::new("malformed", name, bytes);
    let line = load(&file, &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(line.starts_with(&file.display().to_string()), "{line}");
    line
}

#[test]
fn a_binary_body_read_as_text_is_quoted_short_and_printable() {
    // Found by the mutation sweep: a binary PLY whose header says "ascii"
    // quoted its whole body, NUL bytes and all, as the bad number.
    let mut ply = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n\
property float y\nproperty float z\nend_header\n"
        .to_vec();
    ply.extend((0..2000u32).map(|i| [0u8, 0x1b, 0xbf, 0x3f][i as usize % 4]));
    let line = error_line("body.ply", &ply);
    assert!(!line.chars().any(char::is_control), "{line:?}");
    assert!(
        line.contains("...\" is not a number") && line.len() < 400,
        "{line}"
    );
}

#[test]
fn control_characters_from_the_file_are_escaped() {
    // Found by the mutation sweep: a flipped byte reached the message raw
    // through the XML parser's and the PLY header's messages.
    for (name, bytes) in [
        ("flip.dae", &b"<COLLADA><asset\x1f/></COLLADA>"[..]),
        (
            "flip.ply",
            b"ply\nformat ascii 1.0\n\x06omment\nend_header\n",
        ),
    ] {
        let line = error_line(name, bytes);
        assert!(!line.chars().any(char::is_control), "{line:?}");
        assert!(line.contains("\\u{"), "{line}");
    }
}

#[test]
fn a_value_beyond_single_precision_is_printed_short() {
    // Found by the mutation sweep: 1e300 in an ASCII PLY was printed with
    // all its 301 digits.
    let ply = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n\
property float y\nproperty float z\nend_header\n0 1e300 0\n";
    let line = error_line("far.ply", ply);
    assert!(line.ends_with("y is 1e300"), "{line}");
}
