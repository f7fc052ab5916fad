//! Render statistics: what users compare between renderers.

use candela_bvh::TraversalStats;
use std::time::Duration;

/// Rays traced by kind, and the traversal work they cost. One per thread,
/// added up at the end.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Rays from the camera.
    pub camera: u64,
    /// Shadow (visibility) rays toward lights.
    pub shadow: u64,
    /// Scattered rays after a bounce.
    pub bounce: u64,
    /// Node visits and primitive tests.
    pub traversal: TraversalStats,
}

impl RayCounts {
    /// All rays traced.
    pub fn total(&self) -> u64 {
        self.camera + self.shadow + self.bounce
    }
}

impl std::ops::AddAssign for RayCounts {
    fn add_assign(&mut self, o: Self) {
        self.camera += o.camera;
        self.shadow += o.shadow;
        self.bounce += o.bounce;
        self.traversal += o.traversal;
    }
}

/// Everything measured during one render.
#[derive(Clone, Debug, Default)]
pub struct RenderStats {
    /// Rays by kind and traversal work.
    pub rays: RayCounts,
    /// Samples (camera paths) taken.
    pub samples: u64,
    /// Path segments traced (camera rays included).
    pub path_segments: u64,
    /// Samples that were NaN or infinite and were dropped.
    pub invalid_samples: u64,
    /// Wall-clock time of the render loop.
    pub render_time: Duration,
    /// Threads used.
    pub threads: usize,
    /// Progressive passes completed.
    pub passes: u32,
    /// Pixels that adaptive sampling stopped because they converged.
    pub converged_pixels: u64,
}

impl RenderStats {
    /// Millions of rays per second of wall-clock time.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.render_time.as_secs_f64().max(1e-9) / 1e6
    }

    /// Samples per second of wall-clock time.
    pub fn samples_per_second(&self) -> f64 {
        self.samples as f64 / self.render_time.as_secs_f64().max(1e-9)
    }

    /// Mean number of segments per camera path.
    pub fn mean_path_length(&self) -> f64 {
        self.path_segments as f64 / self.samples.max(1) as f64
    }

    /// Average BVH nodes visited per ray.
    pub fn nodes_per_ray(&self) -> f64 {
        self.rays.traversal.nodes_visited as f64 / self.rays.total().max(1) as f64
    }

    /// Average primitive intersection tests per ray.
    pub fn tests_per_ray(&self) -> f64 {
        self.rays.traversal.prims_tested as f64 / self.rays.total().max(1) as f64
    }
}
