//! `candela.Scene`: a loaded scene description that renders.

use crate::film::PyFilm;
use crate::interim::{render_unit, UnitError};
use crate::settings::{split_samples, RenderKwargs, RenderRequest};
use crate::stats::StatsRecord;
use crate::watch::run_interruptible;
use crate::wire::PlacedFilm;
use candela_render::film::Film;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::SceneDesc;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
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
        format!("{:?}/{:?}", opts.camera_mode, opts.bvh),
    )
}

impl PyScene {
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
        let cancel = AtomicBool::new(false);
        let passes = split_samples(&req.samples, req.passes);
        let full = (req.scene.width, req.scene.height);
        let rect = req.cell;
        let result = run_interruptible(py, &cancel, || -> Result<PlacedFilm, UnitError> {
            let start = Instant::now();
            let mut film = Film::new(rect.width(), rect.height());
            let mut stats = StatsRecord::default();
            for (k, samples) in passes.into_iter().enumerate() {
                let (part, part_stats) =
                    render_unit(&scene, &req.settings, rect, samples, &cancel)?;
                if k == 0 {
                    film = part;
                } else {
                    film.merge(&part);
                }
                stats.add(&StatsRecord::from(&part_stats));
            }
            stats.wall_time_s = start.elapsed().as_secs_f64();
            Ok(PlacedFilm {
                film,
                origin: (rect.x0, rect.y0),
                full,
                stats,
            })
        })?;
        match result {
            Ok(inner) => Ok(PyFilm { inner }),
            Err(e) => Err(PyRuntimeError::new_err(e.to_string())),
        }
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
    /// Options mirror the CLI: `integrator` is "path", "normals", "direct"
    /// (--direct-only) or "indirect" (--indirect-only); `lighting` is "mis",
    /// "light" (--light-only) or "hemisphere" (-H); `accumulate=False` is
    /// `-o 0`; `roulette=False` is --no-roulette. `cell=(x0, y0, x1, y1)`
    /// renders only those pixels (half-open, y = 0 at the top) and returns a
    /// film of that rectangle; `sample_range=(start, end)` renders only those
    /// sample indices of each pixel (within 0..spp); `passes` cuts the sample
    /// range into that many consecutive parts added in order, as the
    /// distributed renderer does. The GIL is released; Ctrl-C stops the
    /// render and raises KeyboardInterrupt.
    #[pyo3(signature = (
        *, spp=16, max_depth=5, light_samples=1, integrator="path", lighting="mis",
        accumulate=true, roulette=true, sampler="sobol", seed=0, width=800, height=600,
        camera="cs184", bvh="sah", cell=None, sample_range=None, passes=1, adaptive=None,
        threads=0
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
    ) -> PyResult<PyFilm> {
        if adaptive.is_some_and(|a| !a.is_none()) {
            return Err(PyValueError::new_err(
                "adaptive sampling is not available yet: it needs candela-render's adaptive settings",
            ));
        }
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
