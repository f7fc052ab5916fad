//! Rendering one pixel rectangle × sample range, with cancellation.
//!
//! Interim: `candela_render::render::render` renders the whole image and all
//! samples and cannot be stopped. Branch `film` adds `RenderSettings::cell`,
//! `sample_range` and a cancellation flag; once merged, this module shrinks to
//! a call to `render` with those fields. Until then it repeats the library's
//! per-sample loop exactly (same sampler calls, same order of additions per
//! pixel), which the Python tests check against the CLI bit for bit.

use candela_render::film::{Film, PixelSums};
use candela_render::integrator::{radiance, ThreadContext};
use candela_render::render::RenderSettings;
use candela_render::sampling::Sampler;
use candela_render::scene::Scene;
use candela_render::stats::{RayCounts, RenderStats};
use glam::Vec2;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Edge of the square tiles a unit is cut into for the thread pool; also how
/// often (in pixels) a cancelled render notices.
const TILE: u32 = 16;

/// A rectangle of pixels, `x0..x1` × `y0..y1`, in image coordinates
/// (y = 0 at the top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    /// Left column (inclusive).
    pub x0: u32,
    /// Top row (inclusive).
    pub y0: u32,
    /// Right column (exclusive).
    pub x1: u32,
    /// Bottom row (exclusive).
    pub y1: u32,
}

impl PixelRect {
    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }
}

/// Why a unit produced no film.
#[derive(Debug, thiserror::Error)]
pub enum UnitError {
    /// The thread pool could not be created.
    #[error("cannot start render threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
    /// The cancellation flag was raised (Ctrl-C).
    #[error("render cancelled")]
    Cancelled,
}

struct TileResult {
    rect: PixelRect,
    pixels: Vec<PixelSums>,
    rays: RayCounts,
    path_segments: u64,
    invalid: u64,
}

/// Renders samples `samples` of every pixel in `rect`, on `settings.threads`
/// threads. The film covers `rect` only. Returns [`UnitError::Cancelled`] soon
/// after `cancel` becomes true.
pub fn render_unit(
    scene: &Scene,
    settings: &RenderSettings,
    rect: PixelRect,
    samples: Range<u32>,
    cancel: &AtomicBool,
) -> Result<(Film, RenderStats), UnitError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()?;
    let tiles: Vec<PixelRect> = (rect.y0..rect.y1)
        .step_by(TILE as usize)
        .flat_map(|y0| {
            (rect.x0..rect.x1)
                .step_by(TILE as usize)
                .map(move |x0| PixelRect {
                    x0,
                    y0,
                    x1: (x0 + TILE).min(rect.x1),
                    y1: (y0 + TILE).min(rect.y1),
                })
        })
        .collect();
    let start = Instant::now();
    let results: Vec<Option<TileResult>> = pool.install(|| {
        tiles
            .par_iter()
            .map(|&tile| {
                (!cancel.load(Ordering::Relaxed))
                    .then(|| render_tile(scene, settings, tile, samples.clone()))
            })
            .collect()
    });
    let mut film = Film::new(rect.width(), rect.height());
    let mut stats = RenderStats {
        threads: pool.current_num_threads(),
        ..Default::default()
    };
    for tile in results {
        let tile = tile.ok_or(UnitError::Cancelled)?;
        for (i, sums) in tile.pixels.iter().enumerate() {
            let (x, y) = (
                tile.rect.x0 - rect.x0 + i as u32 % tile.rect.width(),
                tile.rect.y0 - rect.y0 + i as u32 / tile.rect.width(),
            );
            film.pixels[(y * rect.width() + x) as usize] = *sums;
        }
        stats.rays += tile.rays;
        stats.invalid_samples += tile.invalid;
        stats.path_segments += tile.path_segments;
    }
    stats.samples = film.pixels.iter().map(|p| p.count as u64).sum();
    stats.render_time = start.elapsed();
    Ok((film, stats))
}

/// The library's per-pixel loop (`render::render_tile`), over a sample range.
fn render_tile(
    scene: &Scene,
    settings: &RenderSettings,
    rect: PixelRect,
    samples: Range<u32>,
) -> TileResult {
    let cam = &scene.camera;
    let mut ctx = ThreadContext::default();
    let mut sampler = Sampler::new(settings.sampler, settings.seed);
    let mut pixels = Vec::with_capacity((rect.width() * rect.height()) as usize);
    let mut invalid = 0;
    for y in rect.y0..rect.y1 {
        for x in rect.x0..rect.x1 {
            let mut sums = PixelSums::default();
            for index in samples.clone() {
                sampler.start_pixel_sample(x, y, index);
                let film = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                let lens = sampler.next_2d();
                let ray = cam.generate_ray(film, lens);
                ctx.rays.camera += 1;
                let l = radiance(&settings.integrator, scene, &ray, &mut sampler, &mut ctx);
                if l.is_finite() {
                    sums.add_sample(l);
                } else {
                    invalid += 1;
                    sums.count += 1;
                }
            }
            pixels.push(sums);
        }
    }
    TileResult {
        rect,
        pixels,
        rays: ctx.rays,
        path_segments: ctx.path_segments,
        invalid,
    }
}
