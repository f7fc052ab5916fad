//! The render settings: every option a user can give, defined once.
//!
//! [`Settings`] is the one description of a render's options: each field
//! carries its documentation (the CLI's `--help`, the Python docstring and
//! the viewer's labels all come from here), its default, and its checks
//! ([`Settings::validate`]). Front ends map onto it in one place each:
//! - the CLI derives its flags from it (`clap`, feature `cli`), adding only
//!   the CS184 spellings that set several fields at once (`-r W H`, `-H`,
//!   `--normals`, ...);
//! - Python's `Scene.render(**kwargs)`, the Dask wire format and any JSON
//!   client give the same names as JSON keys ([`Settings::overlay`]), so a
//!   new field reaches them with no further code.
//!
//! The groups ([`SamplingSettings`], [`IntegratorSettings`],
//! [`ImageSettings`], [`OutputSettings`], [`RunSettings`]) are flattened:
//! every front end sees one flat list of names. The library's own
//! per-render types ([`RenderSettings`], [`SceneOptions`]) are derived from
//! a validated `Settings` here and nowhere else.

#[cfg(feature = "cli")]
mod help;
mod image;
mod integrator;
mod output;
mod run;
mod sampling;
#[cfg(test)]
mod tests;

pub use candela_image::{ExrCompression, ToneCurve};
#[cfg(feature = "cli")]
pub use help::{flags, help, SettingFlag};
pub use image::{ImageSettings, BUILT_IN_SKY, CELL_HELP};
pub use integrator::{Estimator, IntegratorSettings, ROULETTE_FROM, ROULETTE_THRESHOLD};
pub use output::OutputSettings;
pub use run::{Bvh, RunSettings, DEFAULT_CHECKPOINT_EVERY, DEFAULT_MEMORY_LIMIT_GIB, DEFAULT_TILE};
pub use sampling::{SamplingSettings, ADAPTIVE_HELP, DEFAULT_SPP};

use crate::camera::PixelFilter;
use crate::film::PixelSums;
use crate::render::RenderSettings;
use crate::scene::SceneOptions;
use candela_scene::{FilterHint, RenderHints};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::fmt::Display;

/// Every option of a render, as every front end names it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Settings {
    /// Samples per pixel, seed, sampler, adaptive sampling, time budget.
    #[serde(flatten)]
    #[cfg_attr(feature = "cli", command(flatten, next_help_heading = "Sampling"))]
    pub sampling: SamplingSettings,
    /// Estimator, lighting, depth, roulette.
    #[serde(flatten)]
    #[cfg_attr(feature = "cli", command(flatten, next_help_heading = "Integrator"))]
    pub integrator: IntegratorSettings,
    /// Size, cell, camera, environment.
    #[serde(flatten)]
    #[cfg_attr(
        feature = "cli",
        command(flatten, next_help_heading = "Image and camera")
    )]
    pub image: ImageSettings,
    /// Tone mapping.
    #[serde(flatten)]
    #[cfg_attr(feature = "cli", command(flatten, next_help_heading = "Output"))]
    pub output: OutputSettings,
    /// Threads, tiles, BVH, memory limit.
    #[serde(flatten)]
    #[cfg_attr(feature = "cli", command(flatten, next_help_heading = "Execution"))]
    pub run: RunSettings,
}

/// Settings that cannot be honoured, with a one-line message naming the
/// setting (by its key and its CLI flag), the value and what is expected.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct SettingsError(String);

impl SettingsError {
    /// An error with this message.
    pub fn new(message: impl Into<String>) -> Self {
        Self(message.into())
    }
}

/// `Ok` if `ok`, else the error "`key` (`flag`) `value`: expected `what`".
fn check(
    ok: bool,
    key: &str,
    flag: &str,
    value: impl Display,
    what: impl Display,
) -> Result<(), SettingsError> {
    if ok {
        Ok(())
    } else {
        Err(SettingsError(format!("{key} ({flag}) {value}: {what}")))
    }
}

/// A scene's suggestions as settings changes.
fn hints_json(h: &RenderHints) -> Map<String, Value> {
    let mut m = Map::new();
    if let Some(spp) = h.spp {
        m.insert("spp".into(), spp.into());
    }
    if let Some(d) = h.max_depth {
        m.insert("max_depth".into(), d.into());
    }
    if let Some((w, h)) = h.resolution {
        m.insert("width".into(), w.into());
        m.insert("height".into(), h.into());
    }
    if h.file_camera {
        m.insert("camera".into(), "file".into());
    }
    if let Some(c) = h.clamp {
        m.insert("clamp".into(), c.into());
    }
    if let Some(f) = h.filter {
        m.insert("filter".into(), String::from(filter_of_hint(f)).into());
    }
    if h.hide_emitters {
        m.insert("hide_emitters".into(), true.into());
    }
    m
}

/// The settings' filter for a scene's: Mitsuba's Gaussian has radius 4σ.
fn filter_of_hint(hint: FilterHint) -> PixelFilter {
    match hint {
        FilterHint::Box => PixelFilter::default(),
        FilterHint::Tent { radius } => PixelFilter::Tent { radius },
        FilterHint::Gaussian { stddev } => PixelFilter::Gaussian {
            stddev,
            radius: 4.0 * stddev,
        },
        FilterHint::Mitchell { b, c } => PixelFilter::Mitchell { b, c },
        FilterHint::CatmullRom => PixelFilter::CatmullRom,
        FilterHint::Lanczos { lobes } => PixelFilter::Lanczos { lobes },
    }
}

/// Memory a render of `width` × `height` pixels with `layers` extra layers
/// claims beyond the scene: the film's sums twice (the tiles' working
/// copies and the merged film) and the images written from it (beauty,
/// albedo, normal, counts, depth, cost, and each extra layer).
pub fn film_bytes(width: u32, height: u32, layers: usize) -> u64 {
    let sums = std::mem::size_of::<PixelSums>() as u64 + layers as u64 * 24;
    let images = 4 * 12 + 8 + 3 * 4 + layers as u64 * 12;
    width as u64 * height as u64 * (2 * sums + images)
}

impl Settings {
    /// Checks every setting; the first problem is the error.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.sampling.validate()?;
        self.integrator.validate()?;
        self.image.validate()?;
        self.output.validate()?;
        self.run.validate()?;
        use crate::integrator::Estimator;
        check(
            self.run.checkpoint.is_none()
                || !matches!(
                    self.integrator.estimator,
                    Estimator::Light | Estimator::Bdpt
                ),
            "checkpoint",
            "--checkpoint",
            "",
            "checkpoints do not carry the light-subpath splats of --integrator light/bdpt yet",
        )?;
        let (w, h) = (self.image.width, self.image.height);
        let layers = crate::integrator::layer_names(&self.integrator).len();
        let need = film_bytes(w, h, layers) as f64 / (1u64 << 30) as f64;
        check(
            need <= self.run.memory_limit,
            "width, height",
            "-r",
            format_args!("{w} {h}"),
            format_args!(
                "the film would need {need:.1} GiB of memory, more than the limit of {} GiB \
                 (raise it with --memory-limit / memory_limit)",
                self.run.memory_limit
            ),
        )
    }

    /// The settings as a flat JSON object: the wire format of every front
    /// end (Python keywords, Dask units, the viewer).
    pub fn to_json(&self) -> Map<String, Value> {
        match serde_json::to_value(self) {
            Ok(Value::Object(map)) => map,
            _ => unreachable!("Settings serialise to a JSON object"),
        }
    }

    /// These settings with some of them replaced by `changes` (a flat JSON
    /// object of keys and values), validated. An unknown key or a value of
    /// the wrong type is an error naming the key.
    pub fn overlay(&self, changes: &Map<String, Value>) -> Result<Settings, SettingsError> {
        let mut map = self.to_json();
        for (key, value) in changes {
            if !map.contains_key(key) {
                let known: Vec<&str> = map.keys().map(String::as_str).collect();
                return Err(SettingsError(format!(
                    "unknown setting `{key}` (the settings are: {})",
                    known.join(", ")
                )));
            }
            map.insert(key.clone(), value.clone());
        }
        let settings: Settings =
            serde_json::from_value(Value::Object(map.clone())).map_err(|err| {
                // Name the first key whose value alone does not parse.
                let culprit = changes.iter().find(|(k, v)| {
                    let one = Map::from_iter([((*k).clone(), (*v).clone())]);
                    serde_json::from_value::<Settings>(Value::Object(one)).is_err()
                });
                match culprit {
                    Some((k, v)) => SettingsError(format!("setting `{k}` = {v}: {err}")),
                    None => SettingsError(format!("settings: {err}")),
                }
            })?;
        settings.validate()?;
        Ok(settings)
    }

    /// The settings of a render: the defaults, under what the scene suggests
    /// (`hints`), under what the user gave explicitly (`explicit`, as JSON).
    ///
    /// A time budget given without a sample count means "no limit but
    /// time", so a scene's suggested sample count does not cap it.
    pub fn resolve(
        hints: &RenderHints,
        explicit: &Map<String, Value>,
    ) -> Result<Settings, SettingsError> {
        let mut suggested = hints_json(hints);
        let timed = explicit.get("time").is_some_and(|t| !t.is_null());
        if timed && !explicit.contains_key("spp") {
            suggested.remove("spp");
        }
        Settings::default().overlay(&suggested)?.overlay(explicit)
    }

    /// Settings from a JSON object of changes to the defaults.
    pub fn from_json(changes: &Map<String, Value>) -> Result<Settings, SettingsError> {
        Settings::default().overlay(changes)
    }

    /// What the render loop needs (sample range: all of `0..spp`).
    pub fn render_settings(&self) -> RenderSettings {
        RenderSettings {
            spp: self.sampling.spp(),
            seed: self.sampling.seed,
            integrator: self.integrator.clone(),
            sampler: self.sampling.sampler,
            threads: self.run.threads,
            cell: self.image.cell,
            sample_range: None,
            adaptive: self.sampling.adaptive,
            time_budget: self.sampling.time_budget(),
            tile: self.run.tile,
        }
    }

    /// What the scene build needs; loads the environment map, if any.
    pub fn scene_options(&self) -> Result<SceneOptions, SettingsError> {
        Ok(SceneOptions {
            environment: self.image.environment()?,
            ..self.camera_options()
        })
    }

    /// The scene options without loading the environment map (`None`):
    /// all that [`Scene::camera_for`](crate::scene::Scene::camera_for)
    /// reads, so a viewer can move the camera of a built scene cheaply.
    pub fn camera_options(&self) -> SceneOptions {
        SceneOptions {
            width: self.image.width,
            height: self.image.height,
            camera_mode: self.image.camera,
            bvh: self.run.bvh.into(),
            lens_radius: self.image.aperture,
            focal_distance: self.image.focal_distance,
            environment: None,
            view: self.image.view(),
            filter: self.image.filter,
        }
    }

    /// Runs `f` (a scene build) on `threads` threads, so that `-t` bounds
    /// the BVH build as it bounds the render.
    pub fn with_threads<R: Send>(&self, f: impl FnOnce() -> R + Send) -> Result<R, SettingsError> {
        if self.run.threads == 0 {
            return Ok(f());
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.run.threads)
            .build()
            .map_err(|e| SettingsError(format!("threads (-t) {}: {e}", self.run.threads)))?;
        Ok(pool.install(f))
    }
}
