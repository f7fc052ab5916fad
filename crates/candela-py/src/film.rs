//! `candela.Film`: per-pixel sums as NumPy arrays, files and bytes.

use crate::settings::{kwargs_json, value_error};
use crate::stats::StatsRecord;
use crate::wire::{self, PlacedFilm};
use candela_image::RenderInfo;
use candela_render::film::OutputError;
use candela_render::film::{
    denoise_film, denoised_path, write_denoised, write_film, Film, OutputOptions, PixelSums,
};
use candela_render::settings::Settings;
use glam::DVec3;
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::path::PathBuf;

/// The result of a render: per-pixel sums of radiance, luminance, squared
/// luminance and sample count, over a rectangle of the image.
///
/// Films merge by addition (`candela.merge`, `Film.add`), which is how tiles,
/// sample passes and machines are combined; the image is resolved only when
/// asked for.
#[pyclass(name = "Film", module = "candela._candela")]
pub struct PyFilm {
    /// The sums and their placement.
    pub inner: PlacedFilm,
}

fn reshape3<'py>(
    py: Python<'py>,
    v: Vec<f32>,
    h: u32,
    w: u32,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    PyArray1::from_vec(py, v).reshape([h as usize, w as usize, 3])
}

impl PyFilm {
    fn size(&self) -> (u32, u32) {
        (self.inner.film.width, self.inner.film.height)
    }

    /// A zero film covering the whole `width` × `height` image.
    pub fn empty_full(width: u32, height: u32) -> Self {
        Self {
            inner: PlacedFilm {
                film: Film::new(width, height),
                origin: (0, 0),
                full: (width, height),
                stats: StatsRecord::default(),
            },
        }
    }

    /// Adds `other`'s sums at its place; it must lie inside this film.
    pub fn add_placed(&mut self, other: &PlacedFilm) -> PyResult<()> {
        let (me, it) = (&self.inner, other);
        let inside = me.full == it.full
            && it.origin.0 >= me.origin.0
            && it.origin.1 >= me.origin.1
            && it.origin.0 + it.film.width <= me.origin.0 + me.film.width
            && it.origin.1 + it.film.height <= me.origin.1 + me.film.height;
        if !inside {
            return Err(PyValueError::new_err(format!(
                "cannot add a {}x{} film at {:?} of a {:?} image to a {}x{} film at {:?} of a {:?} image",
                it.film.width, it.film.height, it.origin, it.full,
                me.film.width, me.film.height, me.origin, me.full
            )));
        }
        let (dx, dy) = (it.origin.0 - me.origin.0, it.origin.1 - me.origin.1);
        let w = self.inner.film.width as usize;
        for (i, src) in it.film.pixels.iter().enumerate() {
            let (x, y) = (i % it.film.width as usize, i / it.film.width as usize);
            self.inner.film.pixels[(y + dy as usize) * w + x + dx as usize].merge(src);
        }
        self.inner.stats.add(&it.stats);
        Ok(())
    }
}

#[pymethods]
impl PyFilm {
    /// A film of zeros covering a whole `width` × `height` image, to add
    /// parts into.
    #[staticmethod]
    fn empty(width: u32, height: u32) -> Self {
        Self::empty_full(width, height)
    }

    /// Width of the covered rectangle in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.inner.film.width
    }

    /// Height of the covered rectangle in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.inner.film.height
    }

    /// `(x, y)` of the rectangle's top-left pixel in the full image.
    #[getter]
    fn origin(&self) -> (u32, u32) {
        self.inner.origin
    }

    /// `(width, height)` of the full image.
    #[getter]
    fn full_size(&self) -> (u32, u32) {
        self.inner.full
    }

    /// Render statistics: rays by kind, samples, times, Mrays/s, ...
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.inner.stats.to_dict(py)
    }

    /// Records the elapsed time of the whole render (for rates of renders
    /// whose parts ran concurrently).
    fn set_wall_time(&mut self, seconds: f64) {
        self.inner.stats.wall_time_s = seconds;
    }

    /// The image: mean linear radiance per pixel, float32, shape (H, W, 3).
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let (w, h) = self.size();
        let v = self
            .inner
            .film
            .resolve()
            .into_pixels()
            .into_iter()
            .flatten()
            .collect();
        reshape3(py, v, h, w)
    }

    /// The image denoised by Intel Open Image Denoise, guided by the film's
    /// albedo and normal (prefiltered), float32, shape (H, W, 3). Needs the
    /// library (`pip install pyoidn`); raises `candela.DenoiseError` saying
    /// so where it is missing.
    fn denoise<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let oidn = crate::denoise::oidn(py)?;
        let (w, h) = self.size();
        let image = py
            .detach(|| denoise_film(&self.inner.film, oidn))
            .map_err(|e| crate::denoise::DenoiseError::new_err(e.to_string()))?;
        let v = image.into_pixels().into_iter().flatten().collect();
        reshape3(py, v, h, w)
    }

    /// Samples taken per pixel, uint32, shape (H, W).
    fn sample_counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let (w, h) = self.size();
        let v: Vec<u32> = self.inner.film.pixels.iter().map(|p| p.count).collect();
        PyArray1::from_vec(py, v).reshape([h as usize, w as usize])
    }

    /// The raw sums as NumPy arrays: `radiance`, `radiance_sq`, `albedo`,
    /// `normal` (H, W, 3) float64; `lum`, `lum_sq` and `depth` (H, W)
    /// float64; `count` and `depth_count` (H, W) uint32; `nodes` and
    /// `prim_tests` (H, W) uint64. Divide by `count` for means (and, from
    /// the squares, variances for statistical tests); `depth` by
    /// `depth_count`, the samples whose camera ray hit something (the EXR's
    /// depth layer); `nodes` and `prim_tests` by `count` for the BVH work
    /// per sample (the EXR's cost layers).
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (w, h) = self.size();
        let (w, h) = (w as usize, h as usize);
        let px = &self.inner.film.pixels;
        let d = PyDict::new(py);
        let rgb = |f: fn(&PixelSums) -> DVec3| -> PyResult<_> {
            let v: Vec<f64> = px.iter().flat_map(|p| f(p).to_array()).collect();
            PyArray1::from_vec(py, v).reshape([h, w, 3])
        };
        d.set_item("radiance", rgb(|p| p.radiance)?)?;
        d.set_item("radiance_sq", rgb(|p| p.radiance_sq)?)?;
        d.set_item("albedo", rgb(|p| p.albedo)?)?;
        d.set_item("normal", rgb(|p| p.normal)?)?;
        let plane = |name: &str, array: PyResult<Bound<'py, PyAny>>| d.set_item(name, array?);
        plane("lum", per_pixel(py, px, w, h, |p| p.lum))?;
        plane("lum_sq", per_pixel(py, px, w, h, |p| p.lum_sq))?;
        plane("depth", per_pixel(py, px, w, h, |p| p.depth))?;
        plane("count", per_pixel(py, px, w, h, |p| p.count))?;
        plane("depth_count", per_pixel(py, px, w, h, |p| p.depth_count))?;
        plane("nodes", per_pixel(py, px, w, h, |p| p.nodes))?;
        plane("prim_tests", per_pixel(py, px, w, h, |p| p.prim_tests))?;
        Ok(d)
    }

    /// Writes the image: `.png` (tone-mapped 8-bit sRGB, as the CLI) or
    /// `.exr` (linear float with the `variance` layer of each pixel's mean
    /// and the `samples` layer it needs, the render time in the header; the
    /// albedo and normal layers denoisers read, the depth and the cost
    /// layers when `aovs`). The output
    /// settings (`exposure`, `tone`, `denoise`) may be given as keywords, as
    /// to `render`; `denoise=True` also writes the denoised image to
    /// `<stem>.denoised.<ext>` (see `denoise`).
    #[pyo3(signature = (path, *, samples=false, aovs=false, **settings))]
    fn save(
        &self,
        py: Python<'_>,
        path: PathBuf,
        samples: bool,
        aovs: bool,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<()> {
        let output = Settings::from_json(&kwargs_json(settings)?)
            .map_err(value_error)?
            .output;
        let opts = OutputOptions {
            tone: output.tone_map(),
            aovs,
            sample_counts: samples,
            depth: aovs,
            cost: aovs,
            variance: true,
            info: RenderInfo {
                time_seconds: Some(self.inner.stats.wall_time_s).filter(|&t| t > 0.0),
                software: Some(RenderInfo::candela_software()),
                ..RenderInfo::default()
            },
            rate_image: None,
            exr_compression: output.exr_compression,
        };
        // Found before anything is written, so a missing library leaves no
        // half of the output.
        let oidn = output
            .denoise
            .then(|| crate::denoise::oidn(py))
            .transpose()?;
        let film = &self.inner.film;
        let denoised = py.detach(|| oidn.map(|oidn| denoise_film(film, oidn)).transpose());
        let denoised =
            denoised.map_err(|e| crate::denoise::DenoiseError::new_err(e.to_string()))?;
        py.detach(|| {
            write_film(&path, film, &opts)?;
            match &denoised {
                Some(image) => write_denoised(&denoised_path(&path), image, &opts.tone),
                None => Ok(()),
            }
        })
        .map_err(|e| match e {
            OutputError::Format(_) => PyValueError::new_err(e.to_string()),
            OutputError::Write(..) => PyOSError::new_err(e.to_string()),
        })
    }

    /// Adds `other`'s sums (a part of the same image lying inside this film)
    /// in place. Addition order matters in the last bit: add parts in a fixed
    /// order for reproducible sums.
    fn add(&mut self, other: PyRef<'_, PyFilm>) -> PyResult<()> {
        let other = other.inner.clone();
        self.add_placed(&other)
    }

    /// The raw sums, placement and statistics as bytes (exact: floats travel
    /// as their bits). Inverse of `Film.from_bytes`.
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &wire::encode(&self.inner))
    }

    /// A film from `Film.to_bytes` output.
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<Self> {
        wire::decode(data)
            .map(|inner| Self { inner })
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Pickle support (how Dask moves films between processes).
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let ctor = py.get_type::<PyFilm>().getattr("from_bytes")?;
        let bytes = slf.borrow().to_bytes(py);
        Ok((ctor, PyTuple::new(py, [bytes])?))
    }

    fn __repr__(&self) -> String {
        let p = &self.inner;
        format!(
            "<candela.Film {}x{} at {:?} of {}x{}, {} samples>",
            p.film.width, p.film.height, p.origin, p.full.0, p.full.1, p.stats.samples
        )
    }
}

/// One value of each pixel's sums as an (H, W) array.
fn per_pixel<'py, T: numpy::Element>(
    py: Python<'py>,
    px: &[PixelSums],
    w: usize,
    h: usize,
    f: impl Fn(&PixelSums) -> T,
) -> PyResult<Bound<'py, PyAny>> {
    let array = PyArray1::from_vec(py, px.iter().map(f).collect()).reshape([h, w])?;
    Ok(array.into_any())
}
