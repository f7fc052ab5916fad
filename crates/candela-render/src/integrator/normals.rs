//! The normal-shading view: colour = n * 0.5 + 0.5 for the shading normal
//! facing the camera, black where nothing is hit.

use super::{FirstHitAov, ThreadContext};
use crate::geometry::Ray;
use crate::scene::Scene;
use glam::Vec3;

/// The shading normal at the first hit, mapped to [0, 1]³; the hit's AOVs
/// go to `aov`.
pub fn normals(scene: &Scene, ray: &Ray, ctx: &mut ThreadContext, aov: &mut FirstHitAov) -> Vec3 {
    match scene.intersect_scattering(ray, &mut ctx.rays.traversal) {
        Some(hit) => {
            aov.record(&hit, scene.material(hit.material));
            hit.ns_facing() * 0.5 + Vec3::splat(0.5)
        }
        None => Vec3::ZERO,
    }
}
