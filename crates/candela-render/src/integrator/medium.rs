//! The path tracer's vertices inside participating media (`crate::medium`):
//! next-event estimation with the phase function in place of a BSDF, MIS
//! against phase sampling as at surfaces (the emitter a phase-sampled ray
//! finds is weighted by `path.rs`'s `emitter_weight`, which reads the
//! phase density as the previous vertex's "BSDF" density).
//!
//! The light-sample loop of [`MediumVertex::direct`] repeats the one of
//! `direct::estimate_direct` (delta lights, choice, MIS count) rather than
//! sharing it through a closure: shared, the CS184 render loop ran 0.55%
//! more instructions (callgrind) for the same images.

use super::direct::{power_heuristic, shadow_t_max, LightingMode};
use super::ThreadContext;
use crate::geometry::Ray;
use crate::light::{LightContext, LightSample, LightSelector};
use crate::medium::HenyeyGreenstein;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::settings::{Estimator, IntegratorSettings};
use glam::{Vec2, Vec3};

/// What of `scene`'s media the integrator `settings` leaves out, if
/// anything, for the front ends to report: only the path tracer (and its
/// direct and indirect views) traces media, and CS184's hemisphere rays
/// (`-H`) do not see them.
pub fn media_ignored(scene: &Scene, settings: &IntegratorSettings) -> Option<&'static str> {
    if !scene.media.any() {
        return None;
    }
    match settings.estimator {
        Estimator::Light | Estimator::Bdpt => {
            Some("participating media: the light and bidirectional tracers ignore them (the path tracer traces them)")
        }
        Estimator::Path | Estimator::Direct | Estimator::Indirect
            if settings.lighting == LightingMode::Hemisphere =>
        {
            Some("participating media: the hemisphere rays of -H do not see them (light sampling does)")
        }
        _ => None,
    }
}

/// A scattering point inside medium `medium`, as light samples see it.
pub(super) struct MediumVertex<'a> {
    pub scene: &'a Scene,
    pub p: Vec3,
    /// Toward the previous vertex.
    pub wo: Vec3,
    pub phase: &'a HenyeyGreenstein,
    pub medium: u32,
}

impl MediumVertex<'_> {
    /// Direct light scattered toward `wo`: `light_samples` samples of the
    /// sampled lights (weighted against phase sampling under MIS) and one
    /// of each delta light, each times the transmittance of its shadow ray.
    /// The CS184 hemisphere mode has no hemisphere here: a medium point
    /// takes light samples with weight one (its phase-sampled ray then
    /// counts no emitter, as `emitter_weight` says for that mode).
    pub fn direct(
        &self,
        mode: LightingMode,
        light_samples: u32,
        selector: &LightSelector,
        sampler: &mut Sampler,
        ctx: &mut ThreadContext,
    ) -> Vec3 {
        let lights = &self.scene.lights;
        let mut total = Vec3::ZERO;
        for (_, light) in lights.delta_lights() {
            if let Some(s) = light.sample_li(self.p, Vec2::ZERO) {
                total += self.light_sample(&s, None, ctx);
            }
        }
        if !lights.has_sampled_lights() || light_samples == 0 {
            return total;
        }
        let receiver = LightContext::point(self.p);
        let mut sum = Vec3::ZERO;
        for _ in 0..light_samples {
            let choice_dimension = sampler.skip_one();
            let u = sampler.next_2d();
            let Some((index, pmf, u)) =
                selector.choose_with_point(&receiver, u, || sampler.draw_skipped(choice_dimension))
            else {
                continue;
            };
            let mis = (mode == LightingMode::Mis && lights.is_hittable(index))
                .then_some(light_samples as f32);
            if let Some(mut s) = lights.sample_li(index, self.p, u) {
                s.pdf *= pmf;
                sum += self.light_sample(&s, mis, ctx);
            }
        }
        total + sum / light_samples as f32
    }

    /// `phase · L · T / pdf` of one light sample, MIS-weighted when
    /// `mis_count` (the number of light samples) is given.
    fn light_sample(
        &self,
        s: &LightSample,
        mis_count: Option<f32>,
        ctx: &mut ThreadContext,
    ) -> Vec3 {
        if s.pdf <= 0.0 || s.l == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let phase = self.phase.eval(self.wo, s.wi);
        if phase <= 0.0 {
            return Vec3::ZERO;
        }
        let mut ray = Ray::new(self.p, s.wi);
        ray.t_max = shadow_t_max(s.distance, 0.0);
        ctx.rays.shadow += 1;
        let tr = self
            .scene
            .transmittance(&ray, Some(self.medium), &mut ctx.rays.traversal);
        if tr == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let weight = mis_count.map_or(1.0, |n| power_heuristic(n, s.pdf, 1.0, phase));
        s.l * tr * (phase * weight / s.pdf)
    }
}
