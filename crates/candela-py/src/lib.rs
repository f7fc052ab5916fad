//! The Python package `candela` (native part `candela._candela`).
//!
//! `load` gives a [`scene::PyScene`]; its `render` gives a [`film::PyFilm`]
//! of per-pixel sums, which merge by addition (`merge`) and travel as bytes,
//! which is all `candela.distributed` needs to spread a render over Dask.

mod checkpoint;
mod compare;
mod denoise;
mod film;
mod scene;
mod settings;
mod stats;
mod unit;
mod watch;
mod wire;

use candela_image::{read_exr, read_png};
use candela_scene::LoadOptions;
use film::PyFilm;
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use scene::PyScene;
use std::path::PathBuf;

create_exception!(
    _candela,
    LoadError,
    PyValueError,
    "A scene file could not be loaded; the message locates the problem (file:line:col)."
);

/// Loads a COLLADA (.dae) scene. `strict=True` turns every load warning (an
/// ignored element) into an error, as the CLI's --strict.
#[pyfunction]
#[pyo3(signature = (path, *, strict=false))]
fn load(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<PyScene> {
    let opts = LoadOptions {
        strict,
        ..Default::default()
    };
    let loaded = py
        .detach(|| candela_scene::load(&path, &opts))
        .map_err(|e| LoadError::new_err(e.to_string()))?;
    Ok(PyScene::new(loaded))
}

/// Every file the scene at `path` needs, the scene file first: the files
/// its loader reads (meshes, material libraries, buffers) and the images
/// it names (textures, environment map). What `candela.distributed` ships
/// to workers that cannot read the scene's folder.
#[pyfunction]
#[pyo3(signature = (path, *, strict=false))]
fn scene_files(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<Vec<PathBuf>> {
    let opts = LoadOptions {
        strict,
        ..Default::default()
    };
    py.detach(|| candela_scene::referenced_files(&path, &opts))
        .map_err(|e| LoadError::new_err(e.to_string()))
}

/// The built-in demo scene (a Cornell box with two spheres), as the CLI
/// renders with no scene file.
#[pyfunction]
fn demo_scene() -> PyScene {
    PyScene::new(candela_scene::demo_scene())
}

/// Adds films of one image, in the order given, into a film of the whole
/// image. Each film may cover any rectangle of it and any sample range;
/// statistics add up.
#[pyfunction]
fn merge(films: Vec<PyRef<'_, PyFilm>>) -> PyResult<PyFilm> {
    let Some(first) = films.first() else {
        return Err(PyValueError::new_err("merge needs at least one film"));
    };
    let (w, h) = first.inner.full;
    let mut out = PyFilm::empty_full(w, h);
    for f in &films {
        out.add_placed(&f.inner)?;
    }
    Ok(out)
}

/// Reads a PNG (decoded to linear RGB) or an EXR (its RGB layer) as a float32
/// array of shape (H, W, 3).
#[pyfunction]
fn read_image<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let image = match ext.as_deref() {
        Some("png") => py.detach(|| read_png(&path)),
        Some("exr") => py.detach(|| read_exr(&path)),
        _ => {
            return Err(PyValueError::new_err(format!(
                "{}: expected .png or .exr",
                path.display()
            )))
        }
    }
    .map_err(|e| PyOSError::new_err(e.to_string()))?;
    let (w, h) = image.size();
    let v: Vec<f32> = image.into_pixels().into_iter().flatten().collect();
    PyArray1::from_vec(py, v).reshape([h, w, 3])
}

/// The help of every render setting, by name (the text of `candela
/// --help`): what `Scene.render` takes as keywords.
#[pyfunction]
fn settings_help() -> std::collections::BTreeMap<String, String> {
    settings::settings_help().into_iter().collect()
}

/// The native module; `candela/__init__.py` re-exports it.
#[pymodule]
fn _candela(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_class::<PyFilm>()?;
    m.add("LoadError", m.py().get_type::<LoadError>())?;
    m.add("DenoiseError", m.py().get_type::<denoise::DenoiseError>())?;
    m.add_function(wrap_pyfunction!(denoise::denoiser_library, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(demo_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene_files, m)?)?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add_function(wrap_pyfunction!(read_image, m)?)?;
    m.add_function(wrap_pyfunction!(settings_help, m)?)?;
    m.add_function(wrap_pyfunction!(checkpoint::write_checkpoint, m)?)?;
    m.add_function(wrap_pyfunction!(checkpoint::read_checkpoint, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare_json, m)?)?;
    Ok(())
}
