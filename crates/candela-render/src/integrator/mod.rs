//! Integrators: estimate the radiance arriving along a camera ray.
//!
//! Each integrator is one small function, chosen once per render by
//! [`IntegratorKind`] (Yocto/GL's layout); they share the per-thread
//! [`ThreadContext`] for statistics.

pub mod direct;
mod normals;
pub mod path;

pub use direct::LightingMode;
pub use path::PathSettings;

use crate::geometry::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::stats::RayCounts;
use glam::Vec3;

/// Which estimator renders the image.
#[derive(Clone, Debug, PartialEq)]
pub enum IntegratorKind {
    /// Shading normals as colours (n * 0.5 + 0.5): the CS184 Part 1 view.
    Normals,
    /// Path tracing (which, with its bounce range, also gives the zero-bounce,
    /// direct-only and indirect-only views).
    Path(PathSettings),
}

/// Per-thread mutable state of a render: statistics only, so that results
/// never depend on which thread rendered what.
#[derive(Debug, Default)]
pub struct ThreadContext {
    /// Rays traced and traversal work.
    pub rays: RayCounts,
    /// Path segments traced (camera ray included), for the mean path length.
    pub path_segments: u64,
}

/// Radiance (or the AOV the integrator shows) along the camera `ray`.
pub fn radiance(
    kind: &IntegratorKind,
    scene: &Scene,
    ray: &Ray,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Vec3 {
    match kind {
        IntegratorKind::Normals => normals::normals(scene, ray, ctx),
        IntegratorKind::Path(settings) => path::path_radiance(scene, ray, settings, sampler, ctx),
    }
}
