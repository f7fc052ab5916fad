//! The render loop: the only module that spawns threads.
//!
//! The image is cut into square tiles rendered in parallel. Every sample is a
//! pure function of (seed, pixel, sample index), so the film is the same for
//! any thread count and any tiling.

use crate::film::{Film, PixelSums};
use crate::integrator::{radiance, IntegratorKind, ThreadContext};
use crate::sampling::{Sampler, SamplerKind};
use crate::scene::Scene;
use crate::stats::{RayCounts, RenderStats};
use glam::Vec2;
use rayon::prelude::*;
use std::time::Instant;

/// Edge length of a render tile in pixels.
const TILE: u32 = 16;

/// What to render.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    /// Samples per pixel.
    pub spp: u32,
    /// Seed of the sample sequence.
    pub seed: u64,
    /// The estimator.
    pub integrator: IntegratorKind,
    /// Sample sequence.
    pub sampler: SamplerKind,
    /// Worker threads; 0 uses every core.
    pub threads: usize,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            spp: 1,
            seed: 0,
            integrator: IntegratorKind::Normals,
            sampler: SamplerKind::default(),
            threads: 0,
        }
    }
}

/// Why a render could not run.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The thread pool could not be created.
    #[error("cannot start render threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
}

/// A finished render.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// Per-pixel sums.
    pub film: Film,
    /// What it cost.
    pub stats: RenderStats,
}

struct TileResult {
    x0: u32,
    y0: u32,
    w: u32,
    pixels: Vec<PixelSums>,
    rays: RayCounts,
    path_segments: u64,
    invalid: u64,
}

/// Renders `scene`. `progress` is called after each tile with the number of
/// samples it took.
pub fn render(
    scene: &Scene,
    settings: &RenderSettings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RenderOutput, RenderError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()?;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let tiles: Vec<(u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let start = Instant::now();
    let results: Vec<TileResult> = pool.install(|| {
        tiles
            .par_iter()
            .map(|&(x0, y0)| {
                let tile = render_tile(scene, settings, x0, y0);
                progress(tile.pixels.len() as u64 * settings.spp as u64);
                tile
            })
            .collect()
    });
    let mut film = Film::new(w, h);
    let mut stats = RenderStats {
        threads: pool.current_num_threads(),
        ..Default::default()
    };
    for tile in results {
        for (i, sums) in tile.pixels.iter().enumerate() {
            let (x, y) = (tile.x0 + i as u32 % tile.w, tile.y0 + i as u32 / tile.w);
            film.pixels[(y * w + x) as usize] = *sums;
        }
        stats.rays += tile.rays;
        stats.invalid_samples += tile.invalid;
        stats.path_segments += tile.path_segments;
    }
    stats.samples = film.pixels.iter().map(|p| p.count as u64).sum();
    stats.render_time = start.elapsed();
    Ok(RenderOutput { film, stats })
}

fn render_tile(scene: &Scene, settings: &RenderSettings, x0: u32, y0: u32) -> TileResult {
    let cam = &scene.camera;
    let (x1, y1) = ((x0 + TILE).min(cam.width), (y0 + TILE).min(cam.height));
    let mut ctx = ThreadContext::default();
    let mut sampler = Sampler::new(settings.sampler, settings.seed);
    let mut pixels = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
    let mut invalid = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let mut sums = PixelSums::default();
            for index in 0..settings.spp {
                sampler.start_pixel_sample(x, y, index);
                let film = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                let lens = sampler.next_2d();
                let ray = cam.generate_ray(film, lens);
                ctx.rays.camera += 1;
                let l = radiance(&settings.integrator, scene, &ray, &mut sampler, &mut ctx);
                if l.is_finite() {
                    sums.add_sample(l);
                } else {
                    // Counted, never hidden: a NaN is a bug to report.
                    invalid += 1;
                    sums.count += 1;
                }
            }
            pixels.push(sums);
        }
    }
    TileResult {
        x0,
        y0,
        w: x1 - x0,
        pixels,
        rays: ctx.rays,
        path_segments: ctx.path_segments,
        invalid,
    }
}
