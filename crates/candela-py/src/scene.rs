//! `candela.Scene`: a loaded scene description that renders.

use crate::film::PyFilm;
use crate::settings::{kwargs_json, request, split_samples, value_error, RenderRequest};
use crate::unit::render_cell;
use crate::watch::run_interruptible;
use crate::wire::PlacedFilm;
use candela_render::checkpoint::scene_hash;
use candela_render::render::Cancel;
use candela_render::render::{RenderError, RenderSettings};
use candela_render::scene::Scene;
use candela_render::settings::Settings;
use candela_scene::{RenderHints, SceneDesc};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
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
    hints: RenderHints,
    warnings: Vec<String>,
    notes: Vec<String>,
    built: Mutex<Option<(BuildKey, Arc<Scene>)>>,
}

/// The settings a built scene depends on (size, camera, lens,
/// environment, BVH), as JSON text.
type BuildKey = String;

fn key(settings: &Settings) -> BuildKey {
    let s = settings.to_json();
    let keys = [
        "width",
        "height",
        "camera",
        "aperture",
        "focal_distance",
        "env_map",
        "env_scale",
        "env_rotate",
        "bvh",
    ];
    let picked: serde_json::Map<_, _> = keys
        .iter()
        .filter_map(|k| s.get(*k).map(|v| (k.to_string(), v.clone())))
        .collect();
    serde_json::Value::Object(picked).to_string()
}

impl PyScene {
    /// Wraps a loaded description and its report lines.
    pub fn new(loaded: candela_scene::Loaded) -> Self {
        let lines = |ws: &[candela_scene::Warning]| ws.iter().map(|w| w.to_string()).collect();
        let warnings = lines(&loaded.report.warnings);
        let notes = lines(&loaded.report.notes);
        Self {
            desc: Arc::new(loaded.scene),
            hints: loaded.hints,
            warnings,
            notes,
            built: Mutex::new(None),
        }
    }

    /// The render scene for `settings`, built once per distinct set of
    /// scene options. The cache's lock is only ever taken with the GIL
    /// released: a thread holding it while waiting for the GIL and another
    /// holding the GIL while waiting for it would deadlock (two Dask worker
    /// threads rendering the same scene did).
    fn built(&self, py: Python<'_>, settings: &Settings) -> PyResult<Arc<Scene>> {
        let k = key(settings);
        py.detach(|| {
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
            let opts = settings.scene_options().map_err(value_error)?;
            let scene = settings
                .with_threads(|| Scene::build(&desc, &opts))
                .map_err(value_error)?
                .map_err(|e| {
                    PyValueError::new_err(format!("cannot render {}: {e}", desc.source.display()))
                })?;
            let scene = Arc::new(scene);
            *slot = Some((k, scene.clone()));
            Ok(scene)
        })
    }

    fn run(&self, py: Python<'_>, req: &RenderRequest) -> PyResult<PyFilm> {
        let scene = self.built(py, &req.settings)?;
        if req.settings.run.checkpoint.is_some() {
            return crate::checkpoint::render_checkpointed(py, &self.desc, &scene, req);
        }
        let base = req.settings.render_settings();
        let cancel = Cancel::new();
        let passes = split_samples(&req.samples, req.passes);
        let result = run_interruptible(py, &cancel, || {
            let start = Instant::now();
            let mut merged: Option<PlacedFilm> = None;
            for samples in passes {
                let settings = RenderSettings {
                    sample_range: Some(samples),
                    ..base.clone()
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
    /// The keywords are the render settings, with the same names and
    /// meanings as the CLI's long flags (`candela.settings_help()` lists
    /// them with their help): `spp`, `max_depth`, `light_samples`,
    /// `integrator` ("path", "normals", "direct", "indirect"), `lighting`
    /// ("mis", "light", "hemisphere"), `light_selection` ("auto", "uniform",
    /// "power", "bvh"), `accumulate`, `bounce` (only the light
    /// after exactly that many bounces), `roulette`, `hide_emitters`, `seed`,
    /// `sampler`, `width`, `height`, `cell=(x, y, w, h)`, `camera`,
    /// `aperture`, `focal_distance`, `env_map` (a file or "sky"), `adaptive`
    /// (True, a tolerance or (batch, tolerance)), `time`, `threads`, `bvh`,
    /// ... Settings not given take the scene's suggestion (the demo's
    /// camera, a Mitsuba file's spp), else the default. Two more keywords
    /// split the work: `sample_range=(start, end)` renders only those sample
    /// indices of each pixel, and `passes` cuts them into that many
    /// consecutive parts added in order, as the distributed renderer does.
    /// A film of a `cell` covers that rectangle. The GIL is released;
    /// Ctrl-C stops the render and raises KeyboardInterrupt.
    #[pyo3(signature = (**kwargs))]
    fn render(&self, py: Python<'_>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<PyFilm> {
        let req = request(&self.hints, kwargs_json(kwargs)?)?;
        self.run(py, &req)
    }

    /// The settings a `render` with these keywords would use, every one of
    /// them, as a dict (defaults < the scene's suggestions < keywords).
    #[pyo3(signature = (**kwargs))]
    fn settings<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let req = request(&self.hints, kwargs_json(kwargs)?)?;
        let text = serde_json::Value::Object(req.settings.to_json()).to_string();
        py.import("json")?.call_method1("loads", (text,))
    }

    /// A content hash of the scene (geometry, materials, the bytes of its
    /// textures, lights, cameras) and of the environment map these settings
    /// add, as 32 hex digits: what a checkpoint records so that it is never
    /// continued with another scene.
    #[pyo3(signature = (**kwargs))]
    fn content_hash(&self, py: Python<'_>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
        let req = request(&self.hints, kwargs_json(kwargs)?)?;
        let desc = self.desc.clone();
        let env = req.settings.image.env_map.clone();
        Ok(py.detach(|| scene_hash(&desc, env.as_deref())).to_string())
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
