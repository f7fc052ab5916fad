//! The render loop: the only module that spawns threads.
//!
//! The frame (or the cell [`RenderSettings::cell`]) is cut into square
//! tiles, and rendered in progressive passes over all tiles: each pass adds
//! a few more samples to every pixel that still needs them
//! ([`schedule`] sizes the passes). Stopping between passes — on
//! [`Cancel`], or when [`RenderSettings::time_budget`] is spent — leaves a
//! uniformly sampled image. Every sample is a pure function of (seed,
//! pixel, sample index), and each pixel adds its samples in index order, so
//! the film is bit-identical for any thread count, tiling and pass
//! schedule, with or without adaptive sampling. Light subpaths (light
//! tracing, BDPT) belong to the camera sample that traced them; their
//! splats are added to the film after each pass in exact fixed-point sums
//! (`film/splat.rs`), so they keep that property.
//!
//! Library users call [`render`] (or [`render_with`] for cancellation and
//! rich progress, [`render_from`] to continue a film and checkpoint it) and get a [`Film`] of mergeable sums: films of disjoint
//! cells, or of disjoint sample ranges of the same pixels, merge with
//! [`Film::merge`] into the film of the whole job.

mod control;
mod info;
mod resume;
pub mod schedule;
mod tile;

pub use control::{Cancel, Progress, RenderControl};
pub use info::integrator_name;
pub use resume::{Continuation, PassEnd};

use crate::film::{Adaptive, Film, PixelRect};
use crate::integrator::{layer_names, IntegratorSettings};
use crate::sampling::SamplerKind;
use crate::scene::Scene;
use crate::stats::RenderStats;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};
use tile::{TilePass, TileState};

pub use crate::settings::DEFAULT_TILE;

/// What to render.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    /// Samples per pixel: the sample indices `0..spp`, unless
    /// [`RenderSettings::sample_range`] says otherwise. With adaptive
    /// sampling or a time budget, the most a pixel takes.
    pub spp: u32,
    /// Seed of the sample sequence; another seed gives other noise around
    /// the same mean.
    pub seed: u64,
    /// The estimator.
    pub integrator: IntegratorSettings,
    /// Sample sequence.
    pub sampler: SamplerKind,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
    /// Render only this rectangle of the frame (CS184's `-p`). The film is
    /// still the full frame, with no samples outside the cell, so the films
    /// of disjoint cells merge into the full render bit for bit.
    pub cell: Option<PixelRect>,
    /// Render only these sample indices of each pixel (`None`: `0..spp`), so
    /// that workers can split a render by samples and merge their films.
    /// The merged sums equal those of one render of the union up to f64
    /// rounding (addition in another order), i.e. within a few ulps.
    pub sample_range: Option<Range<u32>>,
    /// Stop each pixel once its mean is known well enough (CS184 `-a`).
    /// The rule sees only the samples of this render (and of the film it
    /// continues, see [`render_from`]).
    pub adaptive: Option<Adaptive>,
    /// Stop starting passes once this much time has passed; the last pass
    /// may overrun by about [`schedule::PASS_TARGET`].
    pub time_budget: Option<Duration>,
    /// Tile edge in pixels; it changes only the speed, never the image.
    pub tile: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            spp: 1,
            seed: 0,
            integrator: IntegratorSettings {
                estimator: crate::integrator::Estimator::Normals,
                ..IntegratorSettings::default()
            },
            sampler: SamplerKind::default(),
            threads: 0,
            cell: None,
            sample_range: None,
            adaptive: None,
            time_budget: None,
            tile: DEFAULT_TILE,
        }
    }
}

impl RenderSettings {
    /// The sample indices each pixel takes (at most).
    pub fn samples(&self) -> Range<u32> {
        self.sample_range.clone().unwrap_or(0..self.spp)
    }
}

/// Why a render could not run.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The thread pool could not be created.
    #[error("cannot start render threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
    /// The settings ask for something impossible.
    #[error("invalid render settings: {0}")]
    Settings(String),
}

/// How a render ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// Every pixel took all its samples or converged.
    Complete,
    /// The time budget was spent first.
    TimeBudget,
    /// [`Cancel::cancel`] was called; the film holds the passes finished
    /// before.
    Cancelled,
}

/// A finished (or stopped) render.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// Per-pixel sums over the full frame.
    pub film: Film,
    /// What it cost.
    pub stats: RenderStats,
    /// Whether it ran to the end.
    pub stop: StopReason,
}

/// Renders `scene`. `progress` is called after each tile with the number of
/// samples it took. See [`render_with`] for cancellation.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RenderOutput, RenderError> {
    let report = |p: &Progress| progress(p.tile_samples);
    let control = RenderControl {
        cancel: None,
        progress: Some(&report),
    };
    render_with(scene, settings, &control)
}

/// Renders `scene` in progressive passes, reporting to and stopping on
/// `control`.
pub fn render_with(
    scene: &Scene,
    settings: &RenderSettings,
    control: &RenderControl,
) -> Result<RenderOutput, RenderError> {
    render_from(scene, settings, control, &Continuation::default())
}

/// [`render_with`], continuing the film `from.start` (a stopped render of
/// the same scene and settings: the result equals the uninterrupted render
/// bit for bit) and showing every finished pass to `from.after_pass`.
pub fn render_from(
    scene: &Scene,
    settings: &RenderSettings,
    control: &RenderControl,
    from: &Continuation,
) -> Result<RenderOutput, RenderError> {
    let region = region(scene, settings)?;
    let size = (scene.camera.width, scene.camera.height);
    if let Some(film) = from.start {
        resume::check_start(film, settings, size)?;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()?;
    let range = settings.samples();
    let start = Instant::now();
    let names = layer_names(&settings.integrator);
    if let Some(film) = from.start {
        if film.layers.names() != names.as_slice() {
            return Err(RenderError::Settings(format!(
                "cannot continue a film with layers {:?} in a render with layers {names:?}",
                film.layers.names()
            )));
        }
    }
    let mut tiles: Vec<TileState> = region
        .tiles(settings.tile)
        .into_iter()
        .map(|rect| match from.start {
            Some(film) => TileState::from_film(rect, film, settings, &names),
            None => TileState::new(rect, &names),
        })
        .collect();
    let mut stats = RenderStats {
        threads: pool.current_num_threads(),
        ..Default::default()
    };
    let mut chunk = 1;
    // A continued film brings its splats: integer sums, so adding the rest
    // to them gives the uninterrupted render's sums exactly.
    let mut splats = from.start.map(|f| f.splats.clone()).unwrap_or_default();
    let (width, height) = (scene.camera.width, scene.camera.height);
    let rays = AtomicU64::new(0);
    let stop = loop {
        let left: u64 = tiles.iter().map(|t| t.samples_left(&range)).sum();
        if left == 0 {
            break StopReason::Complete;
        }
        if control.cancelled() {
            break StopReason::Cancelled;
        }
        let pass_start = Instant::now();
        let pass = PassContext {
            scene,
            settings,
            control,
            chunk,
            index: stats.passes,
            samples_before: stats.samples,
            samples_bound: stats.samples + left,
            start,
            rays: &rays,
        };
        let results = pool.install(|| pass.run(&tiles));
        let complete = results.iter().all(Option::is_some);
        for (tile, result) in tiles
            .iter_mut()
            .zip(results)
            .filter_map(|(t, r)| Some((t, r?)))
        {
            stats.rays += result.ctx.rays;
            if complete {
                // Exact integer sums: the order of tiles does not matter.
                splats.add(width, height, names.len(), &result.ctx.splats);
                splats.light_paths += result.ctx.light_paths;
                stats.path_segments += result.ctx.path_segments;
                stats.invalid_samples += result.invalid;
                stats.samples += result.samples;
                *tile = result.state;
            }
        }
        if !complete {
            break StopReason::Cancelled;
        }
        stats.passes += 1;
        if let Some(after_pass) = from.after_pass {
            after_pass(&PassEnd {
                tiles: &tiles,
                size,
                layer_names: &names,
                splats: &splats,
                stats: &stats,
                elapsed: start.elapsed(),
            });
        }
        let remaining = settings
            .time_budget
            .map(|b| b.saturating_sub(start.elapsed()));
        match schedule::next_pass_size(chunk, pass_start.elapsed(), remaining) {
            Some(next) => chunk = next,
            None => break StopReason::TimeBudget,
        }
    };
    let mut film = assemble(&tiles, width, height, names);
    stats.invalid_samples += splats.invalid;
    film.splats = splats;
    stats.converged_pixels = tiles.iter().map(TileState::converged_count).sum();
    stats.render_time = start.elapsed();
    Ok(RenderOutput { film, stats, stop })
}

/// What every tile of one pass shares.
struct PassContext<'a> {
    scene: &'a Scene,
    settings: &'a RenderSettings,
    control: &'a RenderControl<'a>,
    /// Samples per pixel this pass takes at most.
    chunk: u32,
    /// The pass number, for progress reports.
    index: u32,
    samples_before: u64,
    samples_bound: u64,
    start: Instant,
    /// Rays traced by the whole render so far.
    rays: &'a AtomicU64,
}

impl PassContext<'_> {
    /// Runs the pass over all tiles in parallel; a tile is `None` if the
    /// render was cancelled before it finished.
    fn run(&self, tiles: &[TileState]) -> Vec<Option<TilePass>> {
        let done = AtomicU64::new(self.samples_before);
        let cancelled = || self.control.cancelled();
        tiles
            .par_iter()
            .map(|t| {
                let out = t.pass(self.scene, self.settings, self.chunk, &cancelled)?;
                if let Some(progress) = self.control.progress {
                    let rays = out.ctx.rays.total();
                    progress(&Progress {
                        tile_samples: out.samples,
                        samples_done: done.fetch_add(out.samples, Ordering::Relaxed) + out.samples,
                        rays_done: self.rays.fetch_add(rays, Ordering::Relaxed) + rays,
                        samples_bound: self.samples_bound,
                        pass: self.index,
                        elapsed: self.start.elapsed(),
                    });
                }
                Some(out)
            })
            .collect()
    }
}

/// The full-frame film from the tiles' sums; pixels outside every tile
/// (outside the cell) stay empty.
fn assemble(tiles: &[TileState], width: u32, height: u32, layer_names: Vec<String>) -> Film {
    let mut film = Film::with_layers(width, height, layer_names);
    for tile in tiles {
        for (i, ((x, y), sums)) in tile.rect.pixels().zip(&tile.sums).enumerate() {
            let pixel = y as usize * width as usize + x as usize;
            film.pixels[pixel] = *sums;
            if !film.layers.is_empty() {
                film.layers.copy_pixel(pixel, &tile.layers, i);
            }
        }
    }
    film
}

/// The pixels to render: the cell, checked against the frame, or the frame.
fn region(scene: &Scene, settings: &RenderSettings) -> Result<PixelRect, RenderError> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    if settings.tile == 0 {
        return Err(RenderError::Settings(
            "the tile size must be positive".into(),
        ));
    }
    let range = settings.samples();
    if range.is_empty() {
        return Err(RenderError::Settings(format!(
            "the sample range {}..{} is empty",
            range.start, range.end
        )));
    }
    if let Some(a) = settings.adaptive {
        if a.batch == 0 || a.tolerance.is_nan() || a.tolerance < 0.0 {
            return Err(RenderError::Settings(format!(
                "adaptive sampling needs a positive batch and a tolerance >= 0 (got {} and {})",
                a.batch, a.tolerance
            )));
        }
    }
    match settings.cell {
        None => Ok(PixelRect::full(w, h)),
        Some(cell) if cell.fits_in(w, h) => Ok(cell),
        Some(c) => Err(RenderError::Settings(format!(
            "the cell {}x{} at ({}, {}) is empty or leaves the {w}x{h} frame",
            c.width, c.height, c.x, c.y
        ))),
    }
}
