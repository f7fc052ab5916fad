//! Every file a scene needs: the scene file, the files its loader reads
//! (meshes, material libraries, buffers, included files) and the images its
//! description names (textures, the environment map). This is what must
//! travel with a scene to a machine that has none of it (a Dask worker
//! without a shared disk).
//!
//! The loaders' reads are recorded where they happen (the few functions
//! that read files: `text_file::read_bytes` and glTF's two), so a new
//! format or reference is covered without a list kept by hand.

use crate::{load, LoadError, LoadOptions, SceneDesc};
use std::cell::RefCell;
use std::path::{Path, PathBuf};

thread_local! {
    /// The files read by the load in progress on this thread, when asked.
    static READS: RefCell<Option<Vec<PathBuf>>> = const { RefCell::new(None) };
}

/// Records that the loader read `path` (a no-op unless
/// [`referenced_files`] is loading on this thread).
pub(crate) fn note_read(path: &Path) {
    READS.with(|reads| {
        if let Some(list) = reads.borrow_mut().as_mut() {
            list.push(path.to_path_buf());
        }
    });
}

/// Loads the scene at `path` and lists every file it needs, each once, the
/// scene file first: the files the loader read, then the existing image
/// files the description names (textures, environment map). Images a
/// loader extracts from the scene itself (glTF's embedded ones, written to
/// a temporary folder) are left out: loading the scene makes them again.
pub fn referenced_files(path: &Path, opts: &LoadOptions) -> Result<Vec<PathBuf>, LoadError> {
    let previous = READS.with(|r| r.replace(Some(Vec::new())));
    let loaded = load(path, opts);
    let read = READS.with(|r| r.replace(previous)).unwrap_or_default();
    let desc = loaded?.scene;
    let mut files = vec![path.to_path_buf()];
    for file in read.into_iter().chain(images(&desc)) {
        if !files.contains(&file) {
            files.push(file);
        }
    }
    Ok(files)
}

/// The image files `desc` names that exist and were not extracted by the
/// loader.
fn images(desc: &SceneDesc) -> Vec<PathBuf> {
    let extracted = crate::gltf::extracted_images_dir();
    let textures = desc
        .materials
        .iter()
        .flat_map(|m| m.textures.iter().filter_map(|(_, t)| t.image_path()))
        .map(std::path::Path::to_path_buf);
    let environment = match &desc.environment {
        Some(crate::EnvironmentDesc::Map { path, .. }) => Some(path.clone()),
        _ => None,
    };
    textures
        .chain(environment)
        .filter(|p| p.is_file() && !p.starts_with(&extracted))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn repo(rel: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(rel)
    }

    fn names(files: &[PathBuf]) -> Vec<String> {
        files
            .iter()
            .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    }

    #[test]
    fn a_gltf_needs_its_buffer() {
        let scene = repo("scenes/cornell/cornell.gltf");
        let files = referenced_files(&scene, &LoadOptions::default()).unwrap();
        assert_eq!(names(&files), ["cornell.gltf", "cornell.bin"]);
    }

    #[test]
    fn an_obj_needs_its_material_library_and_textures() {
        let dir = candela_testkit::TempDir::new("referenced-obj");
        std::fs::create_dir(dir.join("tex")).unwrap();
        std::fs::write(
            dir.join("scene.obj"),
            "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n",
        )
        .unwrap();
        std::fs::write(dir.join("m.mtl"), "newmtl a\nKd 1 1 1\nmap_Kd tex/t.png\n").unwrap();
        std::fs::write(dir.join("tex/t.png"), b"only its bytes travel").unwrap();
        let files = referenced_files(&dir.join("scene.obj"), &LoadOptions::default()).unwrap();
        assert_eq!(
            files,
            [
                dir.join("scene.obj"),
                dir.join("m.mtl"),
                dir.join("tex/t.png")
            ]
        );
    }

    #[test]
    fn a_mitsuba_scene_needs_its_meshes() {
        let scene = repo("scenes/cornell/cornell.xml");
        let files = referenced_files(&scene, &LoadOptions::default()).unwrap();
        let plys = names(&files).iter().filter(|n| n.ends_with(".ply")).count();
        assert!(plys >= 2, "{files:?}");
        // Nothing is recorded outside a call.
        assert!(READS.with(|r| r.borrow().is_none()));
    }

    #[test]
    fn a_file_that_does_not_load_is_the_loads_error() {
        let err = referenced_files(Path::new("/nonexistent/x.dae"), &LoadOptions::default());
        assert!(err.is_err());
        assert!(READS.with(|r| r.borrow().is_none()));
    }
}
