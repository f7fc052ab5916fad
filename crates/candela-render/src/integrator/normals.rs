//! The normal-shading view: colour = n * 0.5 + 0.5 for the shading normal
//! facing the camera, black where nothing is hit.

use super::ThreadContext;
use crate::geometry::Ray;
use crate::scene::Scene;
use glam::Vec3;

/// The shading normal at the first hit, mapped to [0, 1]³.
pub fn normals(scene: &Scene, ray: &Ray, ctx: &mut ThreadContext) -> Vec3 {
    match scene.intersect(ray, &mut ctx.rays.traversal) {
        Some(hit) => hit.ns_facing() * 0.5 + Vec3::splat(0.5),
        None => Vec3::ZERO,
    }
}
