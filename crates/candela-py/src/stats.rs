//! Render statistics as plain numbers that add up across merged films.

use candela_render::stats::RenderStats;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// What a film cost. Counters add when films merge; `render_time_s` then
/// becomes the total work time of the parts, while `wall_time_s` is what the
/// user waited (set by whoever ran the parts).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StatsRecord {
    /// Rays from the camera.
    pub camera_rays: u64,
    /// Shadow rays toward lights.
    pub shadow_rays: u64,
    /// Rays scattered after a bounce.
    pub bounce_rays: u64,
    /// BVH nodes visited.
    pub nodes_visited: u64,
    /// Primitive intersection tests.
    pub prims_tested: u64,
    /// Camera paths taken.
    pub samples: u64,
    /// Path segments traced.
    pub path_segments: u64,
    /// NaN or infinite samples dropped.
    pub invalid_samples: u64,
    /// Threads of the largest part.
    pub threads: u64,
    /// Pixels that adaptive sampling stopped early.
    pub converged_pixels: u64,
    /// Sum of the parts' render-loop times, in seconds.
    pub render_time_s: f64,
    /// Elapsed time of the whole render, in seconds.
    pub wall_time_s: f64,
}

impl From<&RenderStats> for StatsRecord {
    fn from(s: &RenderStats) -> Self {
        let t = s.render_time.as_secs_f64();
        Self {
            camera_rays: s.rays.camera,
            shadow_rays: s.rays.shadow,
            bounce_rays: s.rays.bounce,
            nodes_visited: s.rays.traversal.nodes_visited,
            prims_tested: s.rays.traversal.prims_tested,
            samples: s.samples,
            path_segments: s.path_segments,
            invalid_samples: s.invalid_samples,
            threads: s.threads as u64,
            converged_pixels: s.converged_pixels,
            render_time_s: t,
            wall_time_s: t,
        }
    }
}

impl StatsRecord {
    /// All rays traced.
    pub fn rays(&self) -> u64 {
        self.camera_rays + self.shadow_rays + self.bounce_rays
    }

    /// Adds another part's counters and work time; wall times of parts that
    /// ran one after the other add too (callers running parts concurrently
    /// overwrite `wall_time_s`).
    pub fn add(&mut self, o: &StatsRecord) {
        self.camera_rays += o.camera_rays;
        self.shadow_rays += o.shadow_rays;
        self.bounce_rays += o.bounce_rays;
        self.nodes_visited += o.nodes_visited;
        self.prims_tested += o.prims_tested;
        self.samples += o.samples;
        self.path_segments += o.path_segments;
        self.invalid_samples += o.invalid_samples;
        self.threads = self.threads.max(o.threads);
        self.converged_pixels += o.converged_pixels;
        self.render_time_s += o.render_time_s;
        self.wall_time_s += o.wall_time_s;
    }

    /// The counters as fixed-order integers, for serialisation.
    pub fn counters(&self) -> [u64; 10] {
        [
            self.camera_rays,
            self.shadow_rays,
            self.bounce_rays,
            self.nodes_visited,
            self.prims_tested,
            self.samples,
            self.path_segments,
            self.invalid_samples,
            self.threads,
            self.converged_pixels,
        ]
    }

    /// Inverse of [`StatsRecord::counters`] plus the two times.
    pub fn from_parts(c: [u64; 10], render_time_s: f64, wall_time_s: f64) -> Self {
        Self {
            camera_rays: c[0],
            shadow_rays: c[1],
            bounce_rays: c[2],
            nodes_visited: c[3],
            prims_tested: c[4],
            samples: c[5],
            path_segments: c[6],
            invalid_samples: c[7],
            threads: c[8],
            converged_pixels: c[9],
            render_time_s,
            wall_time_s,
        }
    }

    /// A Python dict, with the derived rates users compare between renderers.
    pub fn to_dict<'py>(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let rays = self.rays();
        let per = |n: u64, d: u64| n as f64 / d.max(1) as f64;
        let wall = self.wall_time_s.max(1e-9);
        d.set_item("rays", rays)?;
        d.set_item("camera_rays", self.camera_rays)?;
        d.set_item("shadow_rays", self.shadow_rays)?;
        d.set_item("bounce_rays", self.bounce_rays)?;
        d.set_item("samples", self.samples)?;
        d.set_item("path_segments", self.path_segments)?;
        d.set_item("invalid_samples", self.invalid_samples)?;
        d.set_item("threads", self.threads)?;
        d.set_item("converged_pixels", self.converged_pixels)?;
        d.set_item("render_time_s", self.render_time_s)?;
        d.set_item("wall_time_s", self.wall_time_s)?;
        d.set_item("mrays_per_s", rays as f64 / wall / 1e6)?;
        d.set_item("samples_per_s", self.samples as f64 / wall)?;
        d.set_item("mean_path_length", per(self.path_segments, self.samples))?;
        d.set_item("nodes_per_ray", per(self.nodes_visited, rays))?;
        d.set_item("tests_per_ray", per(self.prims_tested, rays))?;
        Ok(d)
    }
}
