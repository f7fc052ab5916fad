//! The path records: plain, serialisable data (vectors as `[x, y, z]`).

use crate::integrator::record::PathEnd;
use serde::Serialize;

/// A vector as JSON writes it.
pub type V3 = [f32; 3];

/// One camera sample's path, step by step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathRecord {
    /// The pixel.
    pub pixel: (u32, u32),
    /// The sample index within the pixel.
    pub sample: u32,
    /// The film point the camera ray goes through, in pixel units.
    pub film: [f32; 2],
    /// The camera ray.
    pub camera_ray: RayRecord,
    /// The surfaces the path reached, in order (index = bounce count).
    pub vertices: Vec<VertexRecord>,
    /// The ray that left the scene, if the path ended that way.
    pub escape: Option<EscapeRecord>,
    /// Every non-zero term the path added to the image, in order.
    pub contributions: Vec<Contribution>,
    /// Why the path ended.
    pub end: PathEnd,
    /// The radiance the integrator returned: the sum of `contributions`
    /// (up to f32 rounding in the order of addition).
    pub radiance: V3,
    /// What the film adds for this sample: `radiance` after the firefly
    /// clamp, or zero if it is not finite (counted as invalid).
    pub value: V3,
}

/// A ray: origin and unit direction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RayRecord {
    /// Start point.
    pub origin: V3,
    /// Unit direction.
    pub direction: V3,
}

/// One surface interaction.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VertexRecord {
    /// Bounces before this vertex (0: the camera ray's hit).
    pub depth: u32,
    /// Hit point.
    pub position: V3,
    /// Distance along the incoming ray.
    pub distance: f32,
    /// Geometric normal, flipped toward the incoming ray's origin.
    pub geometric_normal: V3,
    /// Shading normal as authored (not flipped).
    pub shading_normal: V3,
    /// Whether the ray arrived on the side the shading normal points to
    /// (emitters emit on that side only).
    pub front_face: bool,
    /// The primitive: `mesh 'name' triangle i` or `sphere 'name'`.
    pub shape: String,
    /// The material's name.
    pub material: String,
    /// The BSDF model (`diffuse`, `glass`, ...), or `emitter` for a
    /// material without one.
    pub surface: String,
    /// Path throughput arriving at the vertex.
    pub throughput: V3,
    /// Emission found here by the path, if counted.
    pub emission: Option<EmissionRecord>,
    /// Light samples (and delta lights) taken here for direct lighting.
    pub light_samples: Vec<LightSampleRecord>,
    /// Uniform hemisphere rays taken here (CS184's `-H`).
    pub hemisphere_rays: Vec<HemisphereRecord>,
    /// The BSDF sample that continued the path.
    pub scatter: Option<ScatterRecord>,
    /// Russian roulette after the bounce, if it was played.
    pub roulette: Option<RouletteRecord>,
}

/// Light the path found itself.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EmissionRecord {
    /// The light's name (an emitting surface that is no light of the set,
    /// e.g. one of zero area, has none).
    pub light: Option<String>,
    /// Emitted radiance toward the path.
    pub radiance: V3,
    /// MIS weight against the previous vertex's light samples.
    pub mis_weight: f32,
    /// Its contribution (throughput included).
    pub contribution: V3,
}

/// The ray that left the scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EscapeRecord {
    /// Bounces before it.
    pub depth: u32,
    /// The ray.
    pub ray: RayRecord,
    /// Path throughput along it.
    pub throughput: V3,
    /// The lights at infinity it sees (if their bounce count is rendered).
    pub environment: Vec<EmissionRecord>,
}

/// One light sample at a vertex.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightSampleRecord {
    /// The light's name.
    pub light: String,
    /// Whether it is a delta light (point, spot, directional), sampled once
    /// per vertex without randomness.
    pub delta: bool,
    /// Unit direction toward the light.
    pub direction: V3,
    /// The sampled point on the light (`None` for lights at infinity).
    pub point: Option<V3>,
    /// Radiance arriving if unoccluded.
    pub radiance: V3,
    /// Density per solid angle, including the choice of the light.
    pub pdf: f32,
    /// BSDF value for this direction (cosine excluded).
    pub bsdf: V3,
    /// BSDF density of this direction, when MIS used it.
    pub bsdf_pdf: Option<f32>,
    /// MIS weight (1 without MIS).
    pub mis_weight: f32,
    /// Shadow-ray result: `Some(true)` unoccluded, `Some(false)` occluded,
    /// `None` not traced (the sample could not contribute).
    pub visible: Option<bool>,
    /// Its contribution (throughput and the 1/n average included).
    pub contribution: V3,
}

/// One uniform hemisphere ray at a vertex.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HemisphereRecord {
    /// Unit direction.
    pub direction: V3,
    /// Density per solid angle.
    pub pdf: f32,
    /// BSDF value (cosine excluded).
    pub bsdf: V3,
    /// Whether the ray was traced.
    pub traced: bool,
    /// Where it hit, if it hit something.
    pub hit: Option<V3>,
    /// Emitted radiance found.
    pub radiance: V3,
    /// Its contribution (throughput and the 1/n average included).
    pub contribution: V3,
}

/// The BSDF sample that continued the path.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScatterRecord {
    /// The lobe sampled, e.g. `specular transmission`.
    pub lobe: String,
    /// Unit direction of the next ray.
    pub direction: V3,
    /// BSDF value (cosine excluded).
    pub bsdf: V3,
    /// Density (for a delta lobe: the probability of choosing it).
    pub pdf: f32,
    /// `|cos θ|` with the shading normal.
    pub cos: f32,
    /// Throughput after the bounce (before roulette).
    pub throughput: V3,
}

/// Russian roulette after a bounce.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RouletteRecord {
    /// Probability of going on.
    pub survival_probability: f32,
    /// Whether the path went on.
    pub survived: bool,
    /// Throughput afterwards (divided by the probability if it survived).
    pub throughput: V3,
}

/// How a contribution's light was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Strategy {
    /// The path hit an emitting surface (BSDF sampling).
    Emission,
    /// The path escaped and saw a light at infinity (BSDF sampling).
    Environment,
    /// A light sample at a vertex (next-event estimation).
    LightSample,
    /// A delta light (point, spot, directional) at a vertex.
    DeltaLight,
    /// A uniform hemisphere ray at a vertex (`-H`).
    Hemisphere,
}

/// One term of the path's radiance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contribution {
    /// The vertex it was gathered at (index into `vertices`); `None` for
    /// light seen by the escaping ray.
    pub vertex: Option<usize>,
    /// Bounces of the light it carries: the `k` of `--bounce k`.
    pub bounces: u32,
    /// How it was found.
    pub strategy: Strategy,
    /// The light's name, when there is one.
    pub light: Option<String>,
    /// Its value, throughput included.
    pub value: V3,
}
