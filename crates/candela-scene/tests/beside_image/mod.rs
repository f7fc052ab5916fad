//! A Mitsuba scene written to a temporary folder beside a copy of the
//! conformance scenes' image (`t.png`, four coloured quadrants), so that
//! loader tests can name a bitmap without depending on the working folder.

use candela_testkit::TempDir;
use std::path::PathBuf;

/// Writes `scene` as `scene.xml` beside `t.png` in a new folder named after
/// `name`; keep the folder while the scene is loaded (dropping it deletes
/// the files).
pub fn write_scene(name: &str, scene: &str) -> (TempDir, PathBuf) {
    let dir = TempDir::new(name);
    std::fs::write(
        dir.join("t.png"),
        include_bytes!("../../../../benches/mitsuba_conformance/textures/quadrants.png"),
    )
    .unwrap();
    let path = dir.join("scene.xml");
    std::fs::write(&path, scene).unwrap();
    (dir, path)
}
