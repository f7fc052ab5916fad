//! `candela.compare`: the comparison report of `candela compare`, from the
//! same Rust code (`candela_image::metrics::comparison`), as JSON text that
//! `candela/_compare.py` turns into a dict.

use candela_image::metrics::compare::{error_heatmap, CompareImage, CompareOptions};
use candela_image::metrics::comparison::compare_images;
use candela_image::{write_png_display, ImageError, RgbImage};
use numpy::{PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A file path, or a float32 array of shape (H, W, 3) with a name.
#[derive(FromPyObject)]
pub enum ImageArg<'py> {
    /// An .exr or .png file.
    Path(PathBuf),
    /// Linear RGB values and the name to report them by.
    Array(PyReadonlyArray3<'py, f32>, String),
}

impl ImageArg<'_> {
    fn load(&self) -> PyResult<CompareImage> {
        match self {
            ImageArg::Path(path) => CompareImage::load(path).map_err(image_error),
            ImageArg::Array(array, name) => {
                let shape = array.shape();
                if shape.len() != 3 || shape[2] != 3 {
                    return Err(PyValueError::new_err(format!(
                        "{name}: expected an array of shape (H, W, 3), got {shape:?}"
                    )));
                }
                let values = array
                    .as_slice()
                    .map_err(|e| PyValueError::new_err(e.to_string()))?;
                let pixels = values.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
                let image =
                    RgbImage::from_pixels(shape[1], shape[0], pixels).map_err(image_error)?;
                Ok(CompareImage::plain(name.clone(), image))
            }
        }
    }
}

/// Missing or unreadable files are OSError, everything else ValueError.
fn image_error(e: ImageError) -> PyErr {
    match e {
        ImageError::Io { .. } | ImageError::Read { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// The report of `candela compare --json` for `a` and `b` (and a
/// `reference`), as JSON text; optionally writes the error heat map.
#[pyfunction]
#[pyo3(signature = (a, b, reference=None, *, block=8, false_alarm=0.01, heatmap=None))]
pub fn compare_json(
    py: Python<'_>,
    a: ImageArg<'_>,
    b: ImageArg<'_>,
    reference: Option<ImageArg<'_>>,
    block: usize,
    false_alarm: f64,
    heatmap: Option<PathBuf>,
) -> PyResult<String> {
    if block == 0 || !(false_alarm > 0.0 && false_alarm < 1.0) {
        return Err(PyValueError::new_err(
            "block must be at least 1 and false_alarm between 0 and 1",
        ));
    }
    let (a, b) = (a.load()?, b.load()?);
    let reference = reference.map(|r| r.load()).transpose()?;
    let options = CompareOptions {
        block_size: block,
        false_alarm_rate: false_alarm,
    };
    py.detach(|| {
        let comparison =
            compare_images(&a, &b, reference.as_ref(), &options).map_err(image_error)?;
        if let Some(path) = &heatmap {
            let heat = error_heatmap(&a, reference.as_ref().unwrap_or(&b)).map_err(image_error)?;
            write_png_display(path, &heat).map_err(|e| PyOSError::new_err(e.to_string()))?;
        }
        Ok(comparison.to_json().to_string())
    })
}
