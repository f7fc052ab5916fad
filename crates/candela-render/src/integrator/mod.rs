//! Integrators: estimate the radiance arriving along a camera ray.
//!
//! Each integrator is one small function, chosen per sample from the
//! user's [`IntegratorSettings`] (Yocto/GL's layout); they share the per-thread
//! [`ThreadContext`] for statistics. [`sample`] also returns the first
//! hit's albedo and normal, the auxiliary images denoisers want.

pub mod direct;
mod normals;
pub mod path;

pub use direct::LightingMode;
pub use path::PathSettings;

use crate::film::SampleValue;
use crate::geometry::Ray;
use crate::material::Material;
use crate::sampling::Sampler;
use crate::scene::Scene;
pub use crate::settings::{Estimator, IntegratorSettings};
use crate::shape::SurfaceHit;
use crate::stats::RayCounts;
use glam::Vec3;

/// Per-thread mutable state of a render: statistics only, so that results
/// never depend on which thread rendered what.
#[derive(Debug, Default)]
pub struct ThreadContext {
    /// Rays traced and traversal work.
    pub rays: RayCounts,
    /// Path segments traced (camera ray included), for the mean path length.
    pub path_segments: u64,
}

/// The denoiser AOVs of one camera sample, filled in by the integrator at
/// the camera ray's first hit; zero if the ray escapes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FirstHitAov {
    /// The BSDF's albedo ([`crate::bsdf::Bsdf::albedo`]); zero for a pure
    /// emitter, which has no BSDF.
    pub albedo: Vec3,
    /// The shading normal flipped toward the camera, in world space.
    pub normal: Vec3,
}

impl FirstHitAov {
    /// Records the AOVs of the first hit.
    pub fn record(&mut self, hit: &SurfaceHit, material: &Material) {
        self.normal = hit.ns_facing();
        self.albedo = material
            .bsdf_at(hit)
            .map_or(Vec3::ZERO, |bsdf| bsdf.albedo());
    }
}

/// One camera sample: radiance (or the colour the integrator shows) along
/// `ray`, with the first hit's AOVs.
pub fn sample(
    settings: &IntegratorSettings,
    scene: &Scene,
    ray: &Ray,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> SampleValue {
    let mut aov = FirstHitAov::default();
    let mut radiance = match settings.path_settings() {
        None => normals::normals(scene, ray, ctx, &mut aov),
        Some(path) => path::path_radiance(scene, ray, &path, sampler, ctx, &mut aov),
    };
    if let Some(clamp) = settings.clamp {
        let brightest = radiance.max_element();
        if brightest > clamp {
            radiance *= clamp / brightest;
        }
    }
    SampleValue {
        radiance,
        albedo: aov.albedo,
        normal: aov.normal,
    }
}

/// Radiance (or the colour the integrator shows) along the camera `ray`,
/// without AOVs.
pub fn radiance(
    settings: &IntegratorSettings,
    scene: &Scene,
    ray: &Ray,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Vec3 {
    sample(settings, scene, ray, sampler, ctx).radiance
}
