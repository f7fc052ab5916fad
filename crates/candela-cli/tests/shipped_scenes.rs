//! The scenes the repository ships (`scenes/`) load from a clean clone
//! without a warning: every file they refer to (meshes, textures) is in the
//! tree. A texture left out of version control would otherwise show only
//! as a warning and a flat colour in the README's examples.

use candela_testkit::TempDir;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Scene files under `scenes/`, in every format the CLI reads; PLY files
/// count too (each is a mesh the XML scenes place, and renders alone).
fn shipped_scenes() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut found = Vec::new();
    let mut folders = vec![root];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("scenes/ is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                folders.push(path);
            } else if matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("dae" | "gltf" | "glb" | "obj" | "ply" | "xml")
            ) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

#[test]
fn every_shipped_scene_loads_and_renders_without_a_warning() {
    let scenes = shipped_scenes();
    // The README's examples alone name a glTF, a Mitsuba XML, an OBJ and the
    // demo: far fewer than this means the walk above found nothing.
    assert!(
        scenes.len() >= 10,
        "only {} scenes: {scenes:?}",
        scenes.len()
    );
    let dir = TempDir::new("shipped-scenes");
    let out = dir.join("scene.png");
    for scene in &scenes {
        let run = Command::new(env!("CARGO_BIN_EXE_candela"))
            .args(["--normals", "-s", "1", "-t", "2", "-r", "16", "12", "-f"])
            .arg(&out)
            .arg(scene)
            .output()
            .expect("candela runs");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(0), "{}: {stderr}", scene.display());
        assert!(
            !stderr.contains("warning"),
            "{} warns: {stderr}",
            scene.display()
        );
    }
}
