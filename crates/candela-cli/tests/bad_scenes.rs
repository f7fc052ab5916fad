//! Scenes that load as text but describe something unrenderable: each is
//! bad input (exit code 2) with one error line naming the file, and leaves
//! no image behind. Found by mutating the shipped scenes' numbers.

use candela_testkit::TempDir;
use std::path::Path;
use std::process::Output;

fn render(scene: &Path, out: &Path) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_candela"))
        .args(["-q", "-t", "1", "-s", "1", "-r", "16", "12", "-f"])
        .arg(out)
        .arg(scene)
        .output()
        .expect("candela runs")
}

/// Exit code 2, exactly one line on stderr, naming `file` and containing
/// `expect`, and no output file.
fn assert_bad_input(run: &Output, file: &Path, expect: &str, out: &Path) {
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].contains(&file.display().to_string()) && lines[0].contains(expect),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn a_vertex_at_a_finite_but_absurd_coordinate_is_refused_where_it_is() {
    // 1e38 is a valid float; framed by the CS184 orbit camera it made an
    // infinite camera ("non-finite camera", exit 1, no place in the file).
    let dir = TempDir::new("bad-scene-far-vertex");
    let obj = dir.join("far.obj");
    std::fs::write(&obj, "o tri\nv 0 0 0\nv 1 0 0\nv 0 -1e38 1\nf 1 2 3\n").unwrap();
    let out = dir.join("far.exr");
    let run = render(&obj, &out);
    assert_bad_input(&run, &obj, "vertex 2 lies at", &out);
}

#[test]
fn an_environment_map_that_is_not_an_image_is_bad_input() {
    // The loader finds the file; only the scene build reads it.
    let dir = TempDir::new("bad-scene-envmap");
    std::fs::write(dir.join("sky.exr"), b"not an EXR").unwrap();
    let xml = dir.join("sky.xml");
    std::fs::write(
        &xml,
        r#"<scene version="3.0.0">
  <emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>
  <shape type="sphere"/>
</scene>
"#,
    )
    .unwrap();
    let out = dir.join("sky-out.exr");
    let run = render(&xml, &out);
    assert_bad_input(&run, &xml, "environment", &out);
}
