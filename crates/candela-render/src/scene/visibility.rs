//! Visibility through opacity cut-outs and invisible (null) surfaces: the
//! closest hit a ray really meets and whether a segment is really blocked,
//! for camera, bounce and shadow rays alike (see `shading/opacity.rs`). The
//! BVH knows nothing of materials: a ray that meets a cut-out point is
//! continued from just beyond it, here, with as many traversals as
//! cut-outs it crosses.
//!
//! An invisible surface that emits is the one exception: it blocks no
//! shadow ray, but the closest-hit query [`Scene::intersect_visible`] stops
//! there, so that an integrator adds its emission (with the MIS weight of
//! any emitter its path finds) and then goes on along the same ray with
//! [`continue_past`], its throughput, bounce count and previous vertex
//! unchanged: as if the ray had passed, which is what the shadow rays of
//! light sampling see. [`Scene::intersect_scattering`] passes these too,
//! for the integrators that do not add such emission.

use super::Scene;
use crate::geometry::Ray;
use crate::shading::opacity::passes_through;
use crate::shape::SurfaceHit;
use candela_bvh::TraversalStats;
use glam::Vec3;

/// Cut-outs (or emitting invisible surfaces, for a path) crossed before a
/// ray gives up and takes the surface it is on (a guard against
/// pathological stacks, never reached by real scenes).
pub const MAX_CUTOUTS: u32 = 1024;

impl Scene {
    /// The closest surface along `ray` that is not cut out at the hit.
    /// Inlined so that the hit is built where the caller keeps it rather
    /// than copied out through an `Option` (callgrind: 57 instructions per
    /// closest-hit query).
    #[inline]
    pub fn intersect_visible(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        if !self.has_cutouts {
            return self.intersect(ray, stats);
        }
        self.intersect_past_cutouts(ray, stats)
    }

    /// [`Scene::intersect_visible`] in a scene with cut-outs.
    #[inline(never)]
    fn intersect_past_cutouts(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        self.intersect_past(ray, stats, false)
    }

    /// The closest hit along `ray` that does not let it through, or is an
    /// emitting invisible surface, or (`boundaries`) bounds a medium.
    #[inline(always)]
    fn intersect_past(
        &self,
        ray: &Ray,
        stats: &mut TraversalStats,
        boundaries: bool,
    ) -> Option<SurfaceHit> {
        let mut hit = self.intersect(ray, stats)?;
        let mut segment = *ray;
        for _ in 0..MAX_CUTOUTS {
            let material = self.material(hit.material);
            let seen_emitting = material.invisible && material.emission.is_some();
            let boundary = boundaries && self.media.interface(hit.material).is_some();
            if seen_emitting || boundary || !passes_through(material, &hit, &segment) {
                return Some(hit);
            }
            segment = continue_past(&segment, &hit);
            hit = self.intersect(&segment, stats)?;
        }
        Some(hit)
    }

    /// The closest surface along `ray` that scatters: past cut-outs and
    /// every invisible surface, emitting or not (for integrators that do
    /// not add an invisible surface's emission; the scene reports them).
    pub fn intersect_scattering(
        &self,
        ray: &Ray,
        stats: &mut TraversalStats,
    ) -> Option<SurfaceHit> {
        let mut hit = self.intersect_visible(ray, stats)?;
        let mut segment = *ray;
        for _ in 0..MAX_CUTOUTS {
            if !self.material(hit.material).invisible {
                return Some(hit);
            }
            segment = continue_past(&segment, &hit);
            hit = self.intersect_visible(&segment, stats)?;
        }
        Some(hit)
    }

    /// In a scene with media, the closest surface along `ray` the path
    /// tracer stops at: what [`Scene::intersect_visible`] finds, and also
    /// every surface that bounds a medium (an invisible one included), where
    /// the path changes medium. Surfaces that bound nothing and let the ray
    /// through are passed here, as there.
    #[inline(never)]
    pub fn intersect_in_media(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        self.intersect_past(ray, stats, true)
    }

    /// The fraction of light per channel that travels along `ray` up to its
    /// `t_max`, starting in `medium`: zero if a surface that does not let
    /// it through is in the way, else the product of the media's
    /// transmittances over the pieces between the surfaces it passes
    /// (invisible ones and cut-outs), changing medium at their boundaries.
    pub fn transmittance(
        &self,
        ray: &Ray,
        mut medium: Option<u32>,
        stats: &mut TraversalStats,
    ) -> Vec3 {
        let mut tr = Vec3::ONE;
        let mut segment = *ray;
        for _ in 0..MAX_CUTOUTS {
            let hit = self.intersect(&segment, stats);
            if let Some(m) = medium {
                let t = hit.as_ref().map_or(segment.t_max, |h| h.t);
                tr *= self.media.get(m).transmittance(t * segment.dir.length());
                if tr == Vec3::ZERO {
                    return tr;
                }
            }
            let Some(hit) = hit else {
                return tr;
            };
            if !passes_through(self.material(hit.material), &hit, &segment) {
                return Vec3::ZERO;
            }
            medium = self.media.after(hit.material, hit.front_face, true, medium);
            segment = continue_past(&segment, &hit);
            if segment.t_max <= 0.0 {
                return tr;
            }
        }
        Vec3::ZERO
    }

    /// Whether something that is not cut out blocks `ray` before its `t_max`.
    pub fn occluded_visible(&self, ray: &Ray, stats: &mut TraversalStats) -> bool {
        if !self.occluded(ray, stats) {
            return false;
        }
        if !self.has_cutouts {
            return true;
        }
        let mut segment = *ray;
        for _ in 0..MAX_CUTOUTS {
            let Some(hit) = self.intersect(&segment, stats) else {
                return false;
            };
            if !passes_through(self.material(hit.material), &hit, &segment) {
                return true;
            }
            segment = continue_past(&segment, &hit);
            if segment.t_max <= 0.0 {
                return false;
            }
        }
        true
    }
}

/// The rest of `ray` beyond `hit`, from just past the surface.
pub fn continue_past(ray: &Ray, hit: &SurfaceHit) -> Ray {
    let origin = hit.spawn_origin(ray.dir);
    let mut next = Ray::new(origin, ray.dir);
    if ray.t_max.is_finite() {
        // Parameters are in units of |dir|; the offset origin is a few ulps
        // past the hit.
        let travelled = (origin - ray.origin).length() / ray.dir.length();
        next.t_max = ray.t_max - travelled;
    }
    next
}
