//! Integrators: estimate the radiance arriving along a camera ray.
//!
//! Each integrator is one small function, chosen per sample from the
//! user's [`IntegratorSettings`] (Yocto/GL's layout); they share the per-thread
//! [`ThreadContext`] for statistics. [`pixel_sample`] is the one definition
//! of a pixel's sample `i` (the render loop and the path inspector both call
//! it); [`sample`] also returns the first hit's albedo, normal and distance
//! and the sample's traversal work (the AOVs). The path integrator tells a
//! [`PathRecorder`] every step it takes ([`record`]); the renderer passes
//! `()`, which records nothing at no cost, and [`inspect`] passes one that
//! builds the path records the viewer shows. [`layers`] fills the film's
//! extra layers (per-bounce light) through the same seam.

pub mod bdpt;
pub mod direct;
pub mod inspect;
pub mod layers;
pub mod light_tracer;
mod medium;
mod normals;
pub mod path;
pub mod record;

pub use bdpt::BidirSettings;
pub use direct::LightingMode;
pub use layers::{layer_names, layered_pixel_sample};
pub use medium::media_ignored;
pub use path::PathSettings;
pub use record::PathRecorder;

use crate::bsdf::Bsdf;
use crate::film::{SampleValue, Splat};
use crate::geometry::Ray;
use crate::material::Material;
use crate::sampling::Sampler;
use crate::scene::Scene;
pub use crate::settings::{Estimator, IntegratorSettings};
use crate::shape::SurfaceHit;
use crate::stats::RayCounts;
use candela_bvh::TraversalStats;
use glam::{Vec2, Vec3};

/// Per-thread mutable state of a render: statistics, and the splats of
/// light subpaths waiting to be added to the film (whose sums are exact
/// and order-free, `film/splat.rs`), so that results never depend on which
/// thread rendered what.
#[derive(Debug, Default)]
pub struct ThreadContext {
    /// Rays traced and traversal work.
    pub rays: RayCounts,
    /// Path segments traced (camera ray included), for the mean path length.
    pub path_segments: u64,
    /// Splats of the light subpaths traced so far.
    pub splats: Vec<Splat>,
    /// Light subpaths traced so far.
    pub light_paths: u64,
}

/// The AOVs of one camera sample, filled in by the integrator at the camera
/// ray's first hit; zero (depth +inf) if the ray escapes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstHitAov {
    /// The BSDF's albedo ([`crate::bsdf::Bsdf::albedo`]); zero for a pure
    /// emitter, which has no BSDF.
    pub albedo: Vec3,
    /// The shading normal flipped toward the camera, in world space.
    pub normal: Vec3,
    /// Distance along the camera ray (a unit direction) to the hit.
    pub depth: f32,
}

impl Default for FirstHitAov {
    fn default() -> Self {
        Self {
            albedo: Vec3::ZERO,
            normal: Vec3::ZERO,
            depth: f32::INFINITY,
        }
    }
}

impl FirstHitAov {
    /// Records the AOVs of the first hit.
    pub fn record(&mut self, hit: &SurfaceHit, material: &Material) {
        self.record_bsdf(hit, material.bsdf_at(hit).as_ref());
    }

    /// [`FirstHitAov::record`] with the hit's BSDF already read (`None`
    /// for a pure emitter).
    pub fn record_bsdf(&mut self, hit: &SurfaceHit, bsdf: Option<&Bsdf>) {
        self.normal = hit.ns_facing();
        self.depth = hit.t;
        self.albedo = bsdf.map_or(Vec3::ZERO, Bsdf::albedo);
    }
}

/// Camera sample `index` of pixel `(x, y)`, exactly as the renderer takes
/// it: the sampler is positioned at (pixel, index), the film and lens
/// points are its first four dimensions, and the integrator draws the rest.
/// Every step of the path goes to `rec` (`&mut ()` records nothing). The
/// radiance carries the reconstruction filter's weight (`camera/filter.rs`;
/// 1 for non-negative filters); the AOVs do not.
pub fn pixel_sample<R: PathRecorder>(
    settings: &IntegratorSettings,
    scene: &Scene,
    pixel: (u32, u32),
    index: u32,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> SampleValue {
    let (mut value, weight) =
        pixel_sample_unweighted(settings, scene, pixel, index, sampler, ctx, rec);
    if weight != 1.0 {
        value.radiance *= weight;
    }
    value
}

/// [`pixel_sample`] before the filter weight, and the weight: what the
/// per-layer sample needs, whose layers take the same weight.
pub(crate) fn pixel_sample_unweighted<R: PathRecorder>(
    settings: &IntegratorSettings,
    scene: &Scene,
    (x, y): (u32, u32),
    index: u32,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> (SampleValue, f32) {
    sampler.start_pixel_sample(x, y, index);
    let filter = &scene.camera.filter;
    // The one-pixel box keeps the old path: the pixel corner plus the
    // sampler's 2-D number, bit for bit.
    let (film, weight) = if filter.is_pixel_box() {
        (Vec2::new(x as f32, y as f32) + sampler.next_2d(), 1.0)
    } else {
        let (offset, weight) = filter.sample(sampler.next_2d());
        (Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + offset, weight)
    };
    // The lens sample's dimensions are taken either way, so later draws
    // keep theirs; a pinhole skips drawing it.
    let lens = if scene.camera.uses_lens_sample() {
        sampler.next_2d()
    } else {
        sampler.skip(2);
        Vec2::ZERO
    };
    let ray = scene.camera.generate_ray(film, lens);
    ctx.rays.camera += 1;
    rec.camera(film, &ray);
    let value = sample_recorded(settings, scene, &ray, sampler, ctx, rec);
    (value, weight)
}

/// One camera sample: radiance (or the colour the integrator shows) along
/// `ray`, with the first hit's AOVs and the traversal work of all its rays
/// (read off the thread's running counts, so counting per sample costs two
/// subtractions).
pub fn sample(
    settings: &IntegratorSettings,
    scene: &Scene,
    ray: &Ray,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> SampleValue {
    sample_recorded(settings, scene, ray, sampler, ctx, &mut ())
}

/// [`sample`], telling `rec` every step of the path (the normals view has
/// no path and records nothing).
pub fn sample_recorded<R: PathRecorder>(
    settings: &IntegratorSettings,
    scene: &Scene,
    ray: &Ray,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> SampleValue {
    let work_before = ctx.rays.traversal;
    let mut aov = FirstHitAov::default();
    let mut radiance = match (settings.estimator, settings.path_settings()) {
        (Estimator::Light, _) => {
            light_tracer::light_trace(scene, &settings.bidir_settings(), sampler, ctx)
        }
        (Estimator::Bdpt, _) => {
            let bidir = settings.bidir_settings();
            bdpt::bdpt_radiance(scene, ray, &bidir, sampler, ctx, &mut aov, rec)
        }
        (_, None) => normals::normals(scene, ray, ctx, &mut aov),
        (_, Some(path)) => path::path_radiance(scene, ray, &path, sampler, ctx, &mut aov, rec),
    };
    if let Some(scale) = clamp_scale(radiance, settings.clamp) {
        radiance *= scale;
    }
    let work = ctx.rays.traversal;
    SampleValue {
        radiance,
        albedo: aov.albedo,
        normal: aov.normal,
        depth: aov.depth,
        cost: TraversalStats {
            nodes_visited: work.nodes_visited - work_before.nodes_visited,
            prims_tested: work.prims_tested - work_before.prims_tested,
        },
    }
}

/// The factor `--clamp` scales a sample of this radiance by, if it is
/// brighter than the clamp: the brightest channel comes down to the clamp,
/// the hue is kept.
fn clamp_scale(radiance: Vec3, clamp: Option<f32>) -> Option<f32> {
    let clamp = clamp?;
    let brightest = radiance.max_element();
    (brightest > clamp).then(|| clamp / brightest)
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
