//! Open Image Denoise from Python: the library is found as the CLI finds it
//! (`CANDELA_OIDN_LIB`, then the system), trying first the `pyoidn`
//! package of the running interpreter, which is where `pip install pyoidn`
//! put it (the interpreter on the path may be another one).

use candela_image::denoise::{pyoidn_lib_folder, Oidn};
use pyo3::create_exception;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

create_exception!(
    _candela,
    DenoiseError,
    PyRuntimeError,
    "Open Image Denoise is missing or failed; the message says what is missing and how to get it."
);

/// The library folder of this interpreter's `pyoidn`, if it is installed
/// (found without importing it).
fn pyoidn_dirs(py: Python<'_>) -> Vec<PathBuf> {
    let origin = || -> PyResult<Option<PathBuf>> {
        let spec = py
            .import("importlib.util")?
            .call_method1("find_spec", ("pyoidn",))?;
        if spec.is_none() {
            return Ok(None);
        }
        let origin: Option<PathBuf> = spec.getattr("origin")?.extract()?;
        Ok(origin.and_then(|o| o.parent().map(Path::to_path_buf)))
    };
    match origin() {
        Ok(Some(package)) => vec![pyoidn_lib_folder(&package)],
        _ => Vec::new(),
    }
}

/// The loaded library, or `DenoiseError` with the one-line reason.
pub fn oidn(py: Python<'_>) -> PyResult<&'static Oidn> {
    let hints = pyoidn_dirs(py);
    py.detach(|| Oidn::load_with(&hints))
        .map_err(|e| DenoiseError::new_err(e.to_string()))
}

/// The path of the Open Image Denoise library `Film.denoise` uses; raises
/// `DenoiseError` (saying what is missing and how to get it) if there is
/// none.
#[pyfunction]
pub fn denoiser_library(py: Python<'_>) -> PyResult<PathBuf> {
    Ok(oidn(py)?.library_path().to_path_buf())
}
