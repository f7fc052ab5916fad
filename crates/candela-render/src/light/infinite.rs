//! Lights at infinity that rays can escape to: the ambient sky.

use super::{luminance, LightSample};
use crate::sampling::warp::{square_to_uniform_hemisphere, uniform_hemisphere_pdf};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Uniform radiance from every direction of the upper (+Y) hemisphere: the
/// COLLADA ambient light, treated as an infinite area light.
#[derive(Clone, Debug, PartialEq)]
pub struct AmbientLight {
    /// Sky radiance.
    pub radiance: Vec3,
}

/// Y-up world to the warps' Z-up pole.
fn from_pole(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.z, w.y)
}

impl AmbientLight {
    /// Radiance arriving from direction `wi` (pointing toward the sky).
    pub fn le(&self, wi: Vec3) -> Vec3 {
        if wi.y > 0.0 {
            self.radiance
        } else {
            Vec3::ZERO
        }
    }

    /// Directions are drawn uniformly over the upper hemisphere: the light
    /// is uniform, so this is its exact importance sampling.
    pub(super) fn sample_li(&self, u: Vec2) -> Option<LightSample> {
        let local = square_to_uniform_hemisphere(u);
        let wi = from_pole(local);
        Some(LightSample {
            wi,
            l: self.radiance,
            distance: f32::INFINITY,
            pdf: uniform_hemisphere_pdf(local),
        })
    }

    pub(super) fn pdf_li(&self, wi: Vec3) -> f32 {
        uniform_hemisphere_pdf(from_pole(wi))
    }

    pub(super) fn power(&self, scene_radius: f32) -> f32 {
        // Flux through a disk of the scene's radius from a hemisphere.
        PI * PI * scene_radius * scene_radius * luminance(self.radiance)
    }
}
