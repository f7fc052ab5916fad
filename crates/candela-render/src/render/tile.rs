//! One tile's share of a pass.
//!
//! A tile owns the sums of its pixels between passes. A pass continues each
//! pixel where it left off, one sample index after the other, adding every
//! sample to the pixel's sums in index order: the sums therefore depend
//! only on (seed, pixel, sample range, adaptive rule), never on the tile
//! size, the thread count or how the samples were cut into passes. The
//! extra layers' sums ([`FilmLayers`]) follow the same order.

use super::RenderSettings;
use crate::film::{FilmLayers, PixelRect, PixelSums};
use crate::integrator::{layered_pixel_sample, pixel_sample, ThreadContext};
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::Vec3;
use std::ops::Range;

/// A tile's pixels between passes.
#[derive(Clone, Debug)]
pub(crate) struct TileState {
    /// The pixels, a part of the frame.
    pub rect: PixelRect,
    /// Sums per pixel, row-major within `rect`.
    pub sums: Vec<PixelSums>,
    /// Pixels that stopped early (converged under adaptive sampling).
    pub converged: Vec<bool>,
    /// Sums of the extra layers per pixel (none unless asked for).
    pub layers: FilmLayers,
}

/// What a tile did in one pass.
pub(crate) struct TilePass {
    /// The tile after the pass.
    pub state: TileState,
    /// Statistics of the pass.
    pub ctx: ThreadContext,
    /// Samples taken.
    pub samples: u64,
    /// NaN or infinite samples.
    pub invalid: u64,
}

impl TileState {
    pub fn new(rect: PixelRect, layer_names: &[String]) -> Self {
        let n = rect.area() as usize;
        Self {
            rect,
            sums: vec![PixelSums::default(); n],
            converged: vec![false; n],
            layers: FilmLayers::new(layer_names.to_vec(), n),
        }
    }

    /// Whether pixel `i` still has samples to take.
    fn active(&self, i: usize, range: &Range<u32>) -> bool {
        !self.converged[i] && self.sums[i].count < range.len() as u32
    }

    /// Samples still to take at most, over all pixels.
    pub fn samples_left(&self, range: &Range<u32>) -> u64 {
        (0..self.sums.len())
            .filter(|&i| self.active(i, range))
            .map(|i| (range.len() as u32 - self.sums[i].count) as u64)
            .sum()
    }

    /// Pixels that stopped before the end of their range.
    pub fn converged_count(&self) -> u64 {
        self.converged.iter().filter(|&&c| c).count() as u64
    }

    /// Takes up to `chunk` more samples in every active pixel. Returns
    /// `None` without touching `self` if `cancelled` turns true meanwhile.
    pub fn pass(
        &self,
        scene: &Scene,
        settings: &RenderSettings,
        chunk: u32,
        cancelled: &dyn Fn() -> bool,
    ) -> Option<TilePass> {
        let range = settings.samples();
        let mut out = TilePass {
            state: self.clone(),
            ctx: ThreadContext::default(),
            samples: 0,
            invalid: 0,
        };
        let mut sampler = Sampler::new(settings.sampler, settings.seed);
        // One value per extra layer for the current sample; with none, the
        // samples take the plain path below.
        let mut layer_values = vec![Vec3::ZERO; self.layers.len()];
        for (i, (x, y)) in self.rect.pixels().enumerate() {
            if !self.active(i, &range) {
                continue;
            }
            if cancelled() {
                return None;
            }
            let sums = &mut out.state.sums[i];
            for _ in 0..chunk {
                let index = range.start + sums.count;
                if index >= range.end {
                    break;
                }
                let s = if layer_values.is_empty() {
                    pixel_sample(
                        &settings.integrator,
                        scene,
                        (x, y),
                        index,
                        &mut sampler,
                        &mut out.ctx,
                        &mut (),
                    )
                } else {
                    layered_pixel_sample(
                        &settings.integrator,
                        scene,
                        (x, y),
                        index,
                        &mut sampler,
                        &mut out.ctx,
                        &mut layer_values,
                    )
                };
                if s.radiance.is_finite() {
                    sums.add(&s);
                    if !layer_values.is_empty() {
                        out.state.layers.add(i, &layer_values);
                    }
                } else {
                    // Counted, never hidden: a NaN is a bug to report.
                    out.invalid += 1;
                    sums.add_invalid(&s);
                }
                out.samples += 1;
                let stop = settings
                    .adaptive
                    .is_some_and(|a| a.should_stop(sums.count, sums.lum, sums.lum_sq));
                if stop {
                    out.state.converged[i] = true;
                    break;
                }
            }
        }
        Some(out)
    }
}
