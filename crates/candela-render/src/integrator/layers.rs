//! What each camera sample gives the film's extra layers
//! ([`crate::film::FilmLayers`]).
//!
//! An estimator that fills extra layers declares their names here
//! ([`layer_names`], read when the film is made) and fills one value per
//! layer for each sample ([`layered_pixel_sample`], called by the render
//! loop only when there are layers, so a render without them runs the
//! plain [`super::pixel_sample`]).
//!
//! The path tracer's per-bounce layers (`--bounce-layers K`): layer `k`
//! holds the light that reached the camera after exactly `k` bounces, with
//! the bounce count of the `--bounce k` view. The path tells its recorder
//! every term it adds to its radiance with the term's bounce count
//! ([`PathRecorder::radiance_term`]); [`BounceLayers`] adds each term to
//! its layer. Layer `k` therefore receives the very f32 values, in the same
//! order, that a `--bounce k` render of the same seed adds (that view
//! traces the same paths and skips, rather than draws, the dimensions of
//! the light it leaves out): the two agree sample for sample, bit for bit.
//! With `-m K` the layers split every term of the beauty, so they add up to
//! it up to f32 rounding. A `--clamp` scales a sample's layers by the
//! factor it scaled the sample's radiance by, so that they still add up to
//! the (clamped) beauty.

use super::record::{PathEnd, PathRecorder};
use super::{clamp_scale, pixel_sample_unweighted, IntegratorSettings, ThreadContext};
use crate::film::SampleValue;
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::Vec3;

/// The name of the layer of light after `k` bounces.
pub fn bounce_layer_name(k: u32) -> String {
    format!("bounce_{k}")
}

/// The extra layers these settings fill, in order (none by default).
pub fn layer_names(settings: &IntegratorSettings) -> Vec<String> {
    // Estimators with layers of their own (e.g. per-strategy layers of
    // bidirectional methods) add their names here.
    if settings.technique_layers {
        return super::bdpt::techniques::layer_names(settings.max_depth);
    }
    match settings.bounce_layers {
        Some(k) => (0..=k).map(bounce_layer_name).collect(),
        None => Vec::new(),
    }
}

/// [`super::pixel_sample`] that also fills `layers`, one value per name of
/// [`layer_names`] (the settings were validated: the layers belong to the
/// path tracer).
pub fn layered_pixel_sample(
    settings: &IntegratorSettings,
    scene: &Scene,
    pixel: (u32, u32),
    index: u32,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    layers: &mut [Vec3],
) -> SampleValue {
    layers.fill(Vec3::ZERO);
    let mut rec = BounceLayers {
        layers,
        unclamped: Vec3::ZERO,
    };
    let (mut sample, weight) =
        pixel_sample_unweighted(settings, scene, pixel, index, sampler, ctx, &mut rec);
    if let Some(scale) = clamp_scale(rec.unclamped, settings.clamp) {
        rec.layers.iter_mut().for_each(|l| *l *= scale);
    }
    // The reconstruction filter's weight, as `pixel_sample` gives the beauty.
    if weight != 1.0 {
        sample.radiance *= weight;
        rec.layers.iter_mut().for_each(|l| *l *= weight);
    }
    sample
}

/// Splits a path's radiance by bounce count: term `k` goes to layer `k`
/// (terms beyond the last layer only to the beauty).
pub struct BounceLayers<'a> {
    /// One sum per bounce count.
    pub layers: &'a mut [Vec3],
    /// The path's radiance before the clamp.
    pub unclamped: Vec3,
}

impl PathRecorder for BounceLayers<'_> {
    #[inline(always)]
    fn radiance_term(&mut self, bounces: u32, value: Vec3) {
        if let Some(layer) = self.layers.get_mut(bounces as usize) {
            *layer += value;
        }
    }

    #[inline(always)]
    fn technique(&mut self, layer: usize, value: Vec3) {
        if let Some(l) = self.layers.get_mut(layer) {
            *l += value;
        }
    }

    #[inline(always)]
    fn end(&mut self, _end: PathEnd, radiance: Vec3) {
        self.unclamped = radiance;
    }
}
