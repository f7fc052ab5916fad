//! The sums one pixel keeps.

use candela_bvh::TraversalStats;
use candela_image::variance::variance_of_mean;
use glam::{DVec3, Vec3};

/// Rec. 709 luminance of a linear RGB colour: the "illuminance" whose
/// spread CS184's adaptive sampling watches.
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// What one camera sample contributes: its radiance and, for denoisers, the
/// albedo and camera-facing shading normal at its first hit (zero where the
/// camera ray escapes), the distance to that hit and the traversal work the
/// sample cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleValue {
    /// Radiance (or the colour the integrator shows).
    pub radiance: Vec3,
    /// Albedo of the first surface hit.
    pub albedo: Vec3,
    /// Shading normal at the first hit, flipped toward the camera.
    pub normal: Vec3,
    /// Distance along the camera ray to the first hit; +inf if it escapes.
    pub depth: f32,
    /// BVH nodes visited and primitive tests of every ray of the sample
    /// (camera, bounce and shadow rays).
    pub cost: TraversalStats,
}

impl Default for SampleValue {
    /// Black, nothing hit (depth +inf), no work.
    fn default() -> Self {
        Self {
            radiance: Vec3::ZERO,
            albedo: Vec3::ZERO,
            normal: Vec3::ZERO,
            depth: f32::INFINITY,
            cost: TraversalStats::default(),
        }
    }
}

/// What a cost image counts, per sample of a pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CostMeasure {
    /// BVH nodes visited.
    Nodes,
    /// Primitive intersection tests.
    PrimTests,
    /// Both: the traversal work.
    #[default]
    Total,
}

/// The sums kept for one pixel. Every field is a sum over samples, so two
/// pixels' sums [`merge`](PixelSums::merge) into the sums of both sample sets.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSums {
    /// Sum of radiance samples.
    pub radiance: DVec3,
    /// Sum of squared radiance samples, per channel (for standard errors
    /// and image z-tests).
    pub radiance_sq: DVec3,
    /// Sum of the samples' luminance.
    pub lum: f64,
    /// Sum of the squared luminance.
    pub lum_sq: f64,
    /// Sum of first-hit albedos.
    pub albedo: DVec3,
    /// Sum of first-hit shading normals.
    pub normal: DVec3,
    /// Sum of the first-hit distances of the samples whose camera ray hit
    /// something.
    pub depth: f64,
    /// Number of samples whose camera ray hit something.
    pub depth_count: u32,
    /// Number of samples, including invalid (NaN or infinite) ones, which
    /// count as black.
    pub count: u32,
    /// BVH nodes visited by all rays of all samples.
    pub nodes: u64,
    /// Primitive intersection tests of all rays of all samples.
    pub prim_tests: u64,
}

impl PixelSums {
    /// Adds one radiance sample with no AOVs.
    pub fn add_sample(&mut self, l: Vec3) {
        self.add(&SampleValue {
            radiance: l,
            ..Default::default()
        });
    }

    /// Adds one sample. The caller decides what to do with non-finite
    /// radiance (see [`PixelSums::add_invalid`]).
    pub fn add(&mut self, s: &SampleValue) {
        let l = s.radiance.as_dvec3();
        let y = luminance(s.radiance) as f64;
        self.radiance += l;
        self.radiance_sq += l * l;
        self.lum += y;
        self.lum_sq += y * y;
        self.albedo += s.albedo.as_dvec3();
        self.normal += s.normal.as_dvec3();
        if s.depth.is_finite() {
            self.depth += s.depth as f64;
            self.depth_count += 1;
        }
        self.count += 1;
        self.nodes += s.cost.nodes_visited;
        self.prim_tests += s.cost.prims_tested;
    }

    /// Counts a sample whose radiance was NaN or infinite as black, keeping
    /// its AOVs: a NaN is a bug to report, not to hide in a dimmer mean.
    pub fn add_invalid(&mut self, s: &SampleValue) {
        self.add(&SampleValue {
            radiance: Vec3::ZERO,
            ..*s
        });
    }

    /// Adds another pixel's sums (merging sample sets).
    pub fn merge(&mut self, other: &PixelSums) {
        self.radiance += other.radiance;
        self.radiance_sq += other.radiance_sq;
        self.lum += other.lum;
        self.lum_sq += other.lum_sq;
        self.albedo += other.albedo;
        self.normal += other.normal;
        self.depth += other.depth;
        self.depth_count += other.depth_count;
        self.count += other.count;
        self.nodes += other.nodes;
        self.prim_tests += other.prim_tests;
    }

    /// The pixel's estimate: the mean radiance (black with no samples).
    pub fn mean(&self) -> Vec3 {
        self.average(self.radiance)
    }

    /// Mean first-hit albedo.
    pub fn mean_albedo(&self) -> Vec3 {
        self.average(self.albedo)
    }

    /// Mean first-hit shading normal (not renormalised).
    pub fn mean_normal(&self) -> Vec3 {
        self.average(self.normal)
    }

    /// Mean distance to the first hit over the samples that hit something;
    /// +inf if none did.
    pub fn mean_depth(&self) -> f32 {
        if self.depth_count == 0 {
            f32::INFINITY
        } else {
            (self.depth / self.depth_count as f64) as f32
        }
    }

    /// Mean traversal work per sample, by measure (0 with no samples).
    pub fn mean_cost(&self, measure: CostMeasure) -> f32 {
        let work = match measure {
            CostMeasure::Nodes => self.nodes,
            CostMeasure::PrimTests => self.prim_tests,
            CostMeasure::Total => self.nodes + self.prim_tests,
        };
        if self.count == 0 {
            0.0
        } else {
            (work as f64 / self.count as f64) as f32
        }
    }

    /// Variance of the mean radiance per channel, `s² / n` with the
    /// `n − 1` sample variance ([`candela_image::variance`]); +inf with
    /// fewer than two samples.
    pub fn variance_of_mean(&self) -> DVec3 {
        let n = self.count as f64;
        let v = |c: usize| variance_of_mean(n, self.radiance[c], self.radiance_sq[c]);
        DVec3::new(v(0), v(1), v(2))
    }

    /// Standard error of the mean radiance per channel,
    /// `sqrt(sample variance / n)`; zero with fewer than two samples.
    pub fn std_error(&self) -> Vec3 {
        if self.count < 2 {
            return Vec3::ZERO;
        }
        self.variance_of_mean().sqrt().as_vec3()
    }

    fn average(&self, sum: DVec3) -> Vec3 {
        if self.count == 0 {
            Vec3::ZERO
        } else {
            (sum / self.count as f64).as_vec3()
        }
    }
}
