//! `candela.Scene`: a loaded scene description that renders.

use crate::film::PyFilm;
use crate::settings::{split_samples, RenderKwargs, RenderRequest};
use crate::unit::render_cell;
use crate::watch::run_interruptible;
use crate::wire::PlacedFilm;
use candela_render::film::Adaptive;
use candela_render::light::{EnvironmentMap, EnvironmentOptions, ProceduralSky};
use candela_render::render::Cancel;
use candela_render::render::{RenderError, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::SceneDesc;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// A scene loaded by `candela.load`, with what the loader reported.
///
/// The render-ready scene (BVH, lights, camera) depends on the image size, so
/// it is built by `render` and kept for the next call with the same size,
/// camera and BVH options.
#[pyclass(name = "Scene", module = "candela._candela", frozen)]
pub struct PyScene {
    desc: Arc<SceneDesc>,
    warnings: Vec<String>,
    notes: Vec<String>,
    built: Mutex<Option<(BuildKey, Arc<Scene>)>>,
}

/// The scene options a built scene depends on.
type BuildKey = (u32, u32, String);

fn key(opts: &SceneOptions) -> BuildKey {
    (
        opts.width,
        opts.height,
        format!(
            "{:?}/{:?}/{}/{:?}/{:?}",
            opts.camera_mode,
            opts.bvh,
            opts.lens_radius,
            opts.focal_distance,
            opts.environment.as_ref().map(Arc::as_ptr)
        ),
    )
}

impl PyScene {
    /// The environment map a render asks for: a file, or `"sky"` for the
    /// built-in procedural sky (as the CLI's `-e`).
    fn environment(
        &self,
        path: Option<std::path::PathBuf>,
        scale: f32,
        rotate_y_deg: f32,
    ) -> PyResult<Option<Arc<EnvironmentMap>>> {
        let Some(path) = path else {
            return Ok(None);
        };
        let options = EnvironmentOptions {
            scale,
            rotate_y_deg,
        };
        let map = if path.as_os_str() == "sky" && !path.exists() {
            ProceduralSky::default()
                .image(512, 256)
                .map_err(|e| PyValueError::new_err(e.to_string()))
                .and_then(|image| {
                    EnvironmentMap::from_image(&image, &options)
                        .map_err(|e| PyValueError::new_err(e.to_string()))
                })?
        } else {
            EnvironmentMap::load(&path, &options)
                .map_err(|e| PyValueError::new_err(format!("env_map={}: {e}", path.display())))?
        };
        Ok(Some(Arc::new(map)))
    }

    /// Wraps a loaded description and its report lines.
    pub fn new(desc: SceneDesc, warnings: Vec<String>, notes: Vec<String>) -> Self {
        Self {
            desc: Arc::new(desc),
            warnings,
            notes,
            built: Mutex::new(None),
        }
    }

    fn built(&self, py: Python<'_>, opts: &SceneOptions) -> PyResult<Arc<Scene>> {
        let k = key(opts);
        let mut slot = self
            .built
            .lock()
            .map_err(|_| PyRuntimeError::new_err("scene cache poisoned"))?;
        if let Some((have, scene)) = slot.as_ref() {
            if *have == k {
                return Ok(scene.clone());
            }
        }
        let desc = self.desc.clone();
        let scene = py.detach(|| Scene::build(&desc, opts)).map_err(|e| {
            PyValueError::new_err(format!("cannot render {}: {e}", desc.source.display()))
        })?;
        let scene = Arc::new(scene);
        *slot = Some((k, scene.clone()));
        Ok(scene)
    }

    fn run(&self, py: Python<'_>, req: &RenderRequest) -> PyResult<PyFilm> {
        let scene = self.built(py, &req.scene)?;
        let cancel = Cancel::new();
        let passes = split_samples(&req.samples, req.passes);
        let result = run_interruptible(py, &cancel, || {
            let start = Instant::now();
            let mut merged: Option<PlacedFilm> = None;
            for samples in passes {
                let settings = RenderSettings {
                    sample_range: Some(samples),
                    ..req.settings.clone()
                };
                let Some(part) = render_cell(&scene, &settings, &cancel)? else {
                    return Ok(None);
                };
                match merged.as_mut() {
                    None => merged = Some(part),
                    Some(m) => {
                        for (a, b) in m.film.pixels.iter_mut().zip(&part.film.pixels) {
                            a.merge(b);
                        }
                        m.stats.add(&part.stats);
                    }
                }
            }
            if let Some(m) = merged.as_mut() {
                m.stats.wall_time_s = start.elapsed().as_secs_f64();
            }
            Ok(merged)
        })?;
        match result {
            Ok(Some(inner)) => Ok(PyFilm { inner }),
            Ok(None) => Err(PyRuntimeError::new_err("render cancelled")),
            Err(e) => Err(render_error(e)),
        }
    }
}

fn render_error(e: RenderError) -> PyErr {
    match e {
        RenderError::Settings(msg) => PyValueError::new_err(msg),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

/// `adaptive=`: None or False (off), True (the CS184 setting, batch 64 and
/// tolerance 0.05), a tolerance, or `(batch, tolerance)`.
fn adaptive_arg(a: Option<Bound<'_, PyAny>>) -> PyResult<Option<Adaptive>> {
    let Some(a) = a.filter(|a| !a.is_none()) else {
        return Ok(None);
    };
    if let Ok(on) = a.extract::<bool>() {
        return Ok(on.then(Adaptive::default));
    }
    if let Ok(tolerance) = a.extract::<f64>() {
        return Ok(Some(Adaptive {
            tolerance,
            ..Adaptive::default()
        }));
    }
    if let Ok((batch, tolerance)) = a.extract::<(u32, f64)>() {
        return Ok(Some(Adaptive { batch, tolerance }));
    }
    Err(PyValueError::new_err(
        "adaptive=: expected None, a bool, a tolerance or (batch, tolerance)",
    ))
}

#[pymethods]
impl PyScene {
    /// The file the scene was loaded from.
    #[getter]
    fn source(&self) -> PathBuf {
        self.desc.source.clone()
    }

    /// Elements and features the loader ignored, one line each
    /// (`file:line:col: <element>: why`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Decisions the loader took that change what is rendered (such as a
    /// lamp described twice and counted once).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// Renders the scene and returns its film.
    ///
    /// Options mirror the CLI: `integrator` is "path", "normals", "direct"
    /// (--direct-only) or "indirect" (--indirect-only); `lighting` is "mis",
    /// "light" (--light-only) or "hemisphere" (-H); `accumulate=False` is
    /// `-o 0`; `roulette=False` is --no-roulette. `cell=(x, y, width,
    /// height)` renders only those pixels (y = 0 at the top; CS184's `-p`)
    /// and returns a film of that rectangle; `sample_range=(start, end)` renders only those
    /// sample indices of each pixel (within 0..spp); `passes` cuts the sample
    /// range into that many consecutive parts added in order, as the
    /// distributed renderer does. `adaptive` stops each pixel once its mean
    /// is known well enough: True (CS184's `-a 64 0.05`), a tolerance, or
    /// `(batch, tolerance)`. `aperture` and `focal_distance` make a thin
    /// lens (the CLI's `-b` and `-d`); `env_map` lights the scene with an
    /// equirectangular map, or `"sky"` for the built-in sky (the CLI's `-e`,
    /// with `env_scale` and `env_rotate`). The GIL is released; Ctrl-C stops the
    /// render and raises KeyboardInterrupt.
    #[pyo3(signature = (
        *, spp=16, max_depth=5, light_samples=1, integrator="path", lighting="mis",
        accumulate=true, roulette=true, sampler="sobol", seed=0, width=800, height=600,
        camera="cs184", bvh="sah", cell=None, sample_range=None, passes=1, adaptive=None,
        threads=0, aperture=0.0, focal_distance=None, env_map=None, env_scale=1.0, env_rotate=0.0
    ))]
    #[allow(clippy::too_many_arguments)]
    fn render(
        &self,
        py: Python<'_>,
        spp: u32,
        max_depth: u32,
        light_samples: u32,
        integrator: &str,
        lighting: &str,
        accumulate: bool,
        roulette: bool,
        sampler: &str,
        seed: u64,
        width: u32,
        height: u32,
        camera: &str,
        bvh: &str,
        cell: Option<(u32, u32, u32, u32)>,
        sample_range: Option<(u32, u32)>,
        passes: u32,
        adaptive: Option<Bound<'_, PyAny>>,
        threads: usize,
        aperture: f32,
        focal_distance: Option<f32>,
        env_map: Option<std::path::PathBuf>,
        env_scale: f32,
        env_rotate: f32,
    ) -> PyResult<PyFilm> {
        let req = RenderKwargs {
            spp,
            max_depth,
            light_samples,
            integrator,
            lighting,
            accumulate,
            roulette,
            sampler,
            seed,
            width,
            height,
            camera,
            bvh,
            cell,
            sample_range,
            passes,
            threads,
            adaptive: adaptive_arg(adaptive)?,
            aperture,
            focal_distance,
            environment: self.environment(env_map, env_scale, env_rotate)?,
        }
        .validate()?;
        self.run(py, &req)
    }

    fn __repr__(&self) -> String {
        format!(
            "<candela.Scene {} ({} meshes, {} spheres, {} lights, {} warnings)>",
            self.desc.source.display(),
            self.desc.meshes.len(),
            self.desc.spheres.len(),
            self.desc.lights.len(),
            self.warnings.len()
        )
    }
}
