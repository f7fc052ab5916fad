//! Checkpoints from Python: the file format and the matching rules are the
//! renderer's (`candela_render::checkpoint`); this only converts.
//! `candela.distributed` writes them as finished units come back;
//! `Scene.render(checkpoint=PATH)` renders through the renderer's
//! `CheckpointWriter`, as the CLI does.

use crate::film::PyFilm;
use crate::settings::kwargs_json;
use crate::settings::RenderRequest;
use crate::stats::StatsRecord;
use crate::unit::crop;
use crate::watch::run_interruptible;
use crate::wire::PlacedFilm;
use candela_render::checkpoint::{Checkpoint, CheckpointWriter, ContentHash};
use candela_render::film::PixelRect;
use candela_render::render::{render_from, Cancel, Continuation, PassEnd, RenderControl};
use candela_render::scene::Scene;
use candela_render::settings::Settings;
use candela_scene::SceneDesc;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

fn json_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (v.to_string(),))
}

fn parse_hash(text: &str) -> PyResult<ContentHash> {
    ContentHash::parse(text).ok_or_else(|| {
        PyValueError::new_err(format!("scene_hash {text:?}: expected 32 hex digits"))
    })
}

/// Writes a checkpoint atomically: `film` (of the whole image), the full
/// `settings` (`Scene.settings(...)`), the scene's `scene_hash`
/// (`Scene.content_hash(...)`), the front end's `front` record and the
/// render time so far.
#[pyfunction]
#[pyo3(signature = (path, film, *, settings, scene_hash, front, elapsed_s))]
pub fn write_checkpoint(
    py: Python<'_>,
    path: PathBuf,
    film: PyRef<'_, PyFilm>,
    settings: &Bound<'_, PyDict>,
    scene_hash: &str,
    front: &Bound<'_, PyDict>,
    elapsed_s: f64,
) -> PyResult<()> {
    let placed = &film.inner;
    if placed.origin != (0, 0) || placed.full != (placed.film.width, placed.film.height) {
        return Err(PyValueError::new_err(
            "a checkpoint holds a film of the whole image",
        ));
    }
    let settings = Settings::from_json(&kwargs_json(Some(settings))?)
        .map_err(|e| PyValueError::new_err(format!("checkpoint settings: {e}")))?;
    let checkpoint = Checkpoint {
        settings,
        scene_hash: parse_hash(scene_hash)?,
        front: kwargs_json(Some(front))?,
        elapsed: Duration::try_from_secs_f64(elapsed_s)
            .map_err(|e| PyValueError::new_err(format!("elapsed_s {elapsed_s}: {e}")))?,
        film: placed.film.clone(),
    };
    py.detach(|| checkpoint.save(&path))
        .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// Reads a checkpoint: a dict of `settings`, `front`, `elapsed_s`,
/// `scene_hash` and `film` (a `candela.Film` of the whole image). Given
/// `scene_hash` and `settings`, also checks that the checkpoint is of that
/// scene and those settings, and raises ValueError naming what differs.
/// A missing, truncated or corrupt file raises ValueError with one line.
#[pyfunction]
#[pyo3(signature = (path, *, scene_hash=None, settings=None))]
pub fn read_checkpoint<'py>(
    py: Python<'py>,
    path: PathBuf,
    scene_hash: Option<&str>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let checkpoint = py
        .detach(|| Checkpoint::load(&path))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    if let (Some(hash), Some(settings)) = (scene_hash, settings) {
        let settings = Settings::from_json(&kwargs_json(Some(settings))?)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        checkpoint
            .check_matches(parse_hash(hash)?, &settings)
            .map_err(|e| PyValueError::new_err(format!("{}: {e}", path.display())))?;
    }
    let d = PyDict::new(py);
    let settings = Value::Object(checkpoint.settings.to_json());
    d.set_item("settings", json_py(py, &settings)?)?;
    d.set_item("front", json_py(py, &Value::Object(checkpoint.front))?)?;
    d.set_item("elapsed_s", checkpoint.elapsed.as_secs_f64())?;
    d.set_item("scene_hash", checkpoint.scene_hash.to_string())?;
    let (w, h) = (checkpoint.film.width, checkpoint.film.height);
    let film = PyFilm {
        inner: PlacedFilm {
            film: checkpoint.film,
            origin: (0, 0),
            full: (w, h),
            stats: StatsRecord::default(),
        },
    };
    d.set_item("film", Py::new(py, film)?)?;
    Ok(d)
}

/// `Scene.render(checkpoint=PATH, ...)`: one render of the whole sample
/// range that saves checkpoints as the CLI does (and continues the one at
/// PATH if it is of this scene and these settings).
pub fn render_checkpointed(
    py: Python<'_>,
    desc: &Arc<SceneDesc>,
    scene: &Scene,
    req: &RenderRequest,
) -> PyResult<PyFilm> {
    let spp = req.settings.sampling.spp();
    if req.passes != 1 || req.samples != (0..spp) {
        return Err(PyValueError::new_err(
            "checkpoint= renders every sample of each pixel in one go: \
             give no sample_range or passes with it",
        ));
    }
    let mut front = serde_json::Map::new();
    front.insert("front".into(), "python".into());
    front.insert("scene".into(), desc.source.display().to_string().into());
    let started = py
        .detach(|| CheckpointWriter::start(&req.settings, desc, front))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let Some((writer, resumed)) = started else {
        return Err(PyValueError::new_err("no checkpoint path"));
    };
    let mut settings = req.settings.render_settings();
    settings.time_budget = writer.budget_left(settings.time_budget);
    let cancel = Cancel::new();
    let result = run_interruptible(py, &cancel, || {
        let after_pass = |p: &PassEnd<'_>| writer.after_pass(p);
        let from = Continuation {
            start: resumed.as_ref().map(|r| &r.film),
            after_pass: Some(&after_pass),
        };
        let control = RenderControl {
            cancel: Some(cancel.clone()),
            progress: None,
        };
        let out = render_from(scene, &settings, &control, &from).map_err(|e| e.to_string())?;
        // Saved on Ctrl-C too: the film holds the passes that finished.
        writer
            .save(out.film.clone(), out.stats.render_time)
            .map_err(|e| e.to_string())?;
        Ok::<_, String>(out)
    })?;
    let out = result.map_err(PyValueError::new_err)?;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let cell = settings.cell.unwrap_or(PixelRect::full(w, h));
    Ok(PyFilm {
        inner: PlacedFilm {
            film: crop(&out.film, cell),
            origin: (cell.x, cell.y),
            full: (w, h),
            stats: StatsRecord::from(&out.stats),
        },
    })
}
