//! The path inspector: re-traces chosen camera samples of one pixel and
//! records every step of their paths, for the viewer's table and 3D lines.
//!
//! It cannot drift from the renderer because it *is* the renderer: it calls
//! [`super::pixel_sample`], the function the render loop calls, with a
//! [`Recording`] in the [`PathRecorder`] seam instead of `()`. Samples are a
//! pure function of (seed, pixel, sample index, dimension), so sample `i`
//! traced here is sample `i` of the render with the same settings.
//!
//! Each [`PathRecord`] lists its vertices (surface, material, throughput,
//! light samples with their MIS weights and shadow-ray results, the BSDF
//! sample that continued the path, Russian roulette), its contributions
//! (which bounce count, which strategy, how much), their sum and the value
//! the film adds for the sample. Vectors are `[x, y, z]` in world space;
//! non-finite numbers serialise as JSON `null`.

use super::record::{
    EmissionEvent, HemisphereEvent, LightSampleEvent, PathEnd, PathRecorder, ScatterEvent,
};
use super::{pixel_sample, Estimator, ThreadContext};
use crate::bsdf::BsdfFlags;
use crate::geometry::Ray;
use crate::render::RenderSettings;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use glam::{Vec2, Vec3};
use serde::Serialize;
use std::ops::Range;

/// Most samples one call traces (each record holds a whole path).
pub const MAX_TRACED_SAMPLES: u32 = 4096;

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

/// Why paths cannot be traced.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InspectError {
    /// The pixel lies outside the image.
    #[error("pixel ({x}, {y}) lies outside the {width}x{height} image")]
    Pixel {
        /// Column asked for.
        x: u32,
        /// Row asked for.
        y: u32,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// The sample range is empty or too long.
    #[error("sample range {start}..{end}: expected 1 to {MAX_TRACED_SAMPLES} samples")]
    Samples {
        /// First index.
        start: u32,
        /// One past the last index.
        end: u32,
    },
    /// The normals view traces no paths.
    #[error("the normals view traces no light paths; choose the path integrator")]
    Normals,
}

/// Traces samples `samples` of `pixel` exactly as [`crate::render::render`]
/// with `settings` takes them (same seed, sampler and integrator options;
/// the thread count, tiling and cell do not matter) and records their
/// paths. Adaptive sampling may stop a pixel before a given index; the
/// record shows what that sample would have added.
pub fn trace_paths(
    scene: &Scene,
    settings: &RenderSettings,
    pixel: (u32, u32),
    samples: Range<u32>,
) -> Result<Vec<PathRecord>, InspectError> {
    let (width, height) = (scene.camera.width, scene.camera.height);
    if pixel.0 >= width || pixel.1 >= height {
        return Err(InspectError::Pixel {
            x: pixel.0,
            y: pixel.1,
            width,
            height,
        });
    }
    if samples.is_empty() || samples.len() > MAX_TRACED_SAMPLES as usize {
        return Err(InspectError::Samples {
            start: samples.start,
            end: samples.end,
        });
    }
    if settings.integrator.estimator == Estimator::Normals {
        return Err(InspectError::Normals);
    }
    let mut sampler = Sampler::new(settings.sampler, settings.seed);
    let mut ctx = ThreadContext::default();
    Ok(samples
        .map(|index| {
            let mut rec = Recording::new(scene, pixel, index);
            let s = pixel_sample(
                &settings.integrator,
                scene,
                pixel,
                index,
                &mut sampler,
                &mut ctx,
                &mut rec,
            );
            // The film's rule (render/tile.rs): a non-finite sample counts
            // as black.
            let value = if s.radiance.is_finite() {
                s.radiance
            } else {
                Vec3::ZERO
            };
            rec.record.value = value.to_array();
            rec.record
        })
        .collect())
}

/// The lobe a BSDF sample chose, in words.
fn lobe_name(flags: BsdfFlags) -> String {
    let kind = if flags.is_specular() {
        "specular"
    } else if flags.intersects(BsdfFlags::GLOSSY) {
        "glossy"
    } else {
        "diffuse"
    };
    let side = if flags.is_transmission() {
        "transmission"
    } else {
        "reflection"
    };
    format!("{kind} {side}")
}

fn ray_record(ray: &Ray) -> RayRecord {
    RayRecord {
        origin: ray.origin.to_array(),
        direction: ray.dir.to_array(),
    }
}

/// The recorder that builds a [`PathRecord`].
struct Recording<'a> {
    scene: &'a Scene,
    record: PathRecord,
    /// Throughput of the current vertex (or of the escaping ray).
    beta: Vec3,
}

impl<'a> Recording<'a> {
    fn new(scene: &'a Scene, pixel: (u32, u32), sample: u32) -> Self {
        Self {
            scene,
            record: PathRecord {
                pixel,
                sample,
                film: [0.0; 2],
                camera_ray: RayRecord::default(),
                vertices: Vec::new(),
                escape: None,
                contributions: Vec::new(),
                end: PathEnd::Escaped,
                radiance: [0.0; 3],
                value: [0.0; 3],
            },
            beta: Vec3::ONE,
        }
    }

    fn light_name(&self, index: u32) -> String {
        self.scene.names.light(index)
    }

    /// Adds a contribution if it is non-zero; `at_vertex` false for light
    /// seen by the escaping ray.
    fn contribute(
        &mut self,
        at_vertex: bool,
        bounces: u32,
        strategy: Strategy,
        light: Option<String>,
        value: Vec3,
    ) {
        if value == Vec3::ZERO {
            return;
        }
        let vertex = at_vertex.then(|| self.record.vertices.len() - 1);
        self.record.contributions.push(Contribution {
            vertex,
            bounces,
            strategy,
            light,
            value: value.to_array(),
        });
    }

    fn last_vertex(&mut self) -> Option<&mut VertexRecord> {
        self.record.vertices.last_mut()
    }
}

impl PathRecorder for Recording<'_> {
    fn camera(&mut self, film: Vec2, ray: &Ray) {
        self.record.film = film.to_array();
        self.record.camera_ray = ray_record(ray);
    }

    fn vertex(&mut self, scene: &Scene, depth: u32, _ray: &Ray, hit: &SurfaceHit, beta: Vec3) {
        self.beta = beta;
        let material = scene.material(hit.material);
        let surface = material
            .bsdf_at(hit)
            .map_or("emitter", |bsdf| bsdf.name())
            .to_string();
        self.record.vertices.push(VertexRecord {
            depth,
            position: hit.p.to_array(),
            distance: hit.t,
            geometric_normal: hit.ng.to_array(),
            shading_normal: hit.ns.to_array(),
            front_face: hit.front_face,
            shape: scene.names.shape(hit.prim),
            material: scene.names.material(hit.material),
            surface,
            throughput: beta.to_array(),
            emission: None,
            light_samples: Vec::new(),
            hemisphere_rays: Vec::new(),
            scatter: None,
            roulette: None,
        });
    }

    fn escape(&mut self, depth: u32, ray: &Ray, beta: Vec3) {
        self.beta = beta;
        self.record.escape = Some(EscapeRecord {
            depth,
            ray: ray_record(ray),
            throughput: beta.to_array(),
            environment: Vec::new(),
        });
    }

    fn emission(&mut self, e: &EmissionEvent) {
        let contribution = self.beta * e.value;
        let light = e.light.map(|i| self.light_name(i));
        let record = EmissionRecord {
            light: light.clone(),
            radiance: e.radiance.to_array(),
            mis_weight: e.mis_weight,
            contribution: contribution.to_array(),
        };
        if let Some(escape) = &mut self.record.escape {
            let bounces = escape.depth;
            escape.environment.push(record);
            self.contribute(false, bounces, Strategy::Environment, light, contribution);
        } else if let Some(vertex) = self.last_vertex() {
            let bounces = vertex.depth;
            vertex.emission = Some(record);
            self.contribute(true, bounces, Strategy::Emission, light, contribution);
        }
    }

    fn light_sample(&mut self, e: &LightSampleEvent) {
        let contribution = self.beta * e.value * e.scale;
        let light = self.light_name(e.light);
        let delta = self.scene.lights.get(e.light).is_delta();
        let Some(vertex) = self.last_vertex() else {
            return;
        };
        let origin = Vec3::from_array(vertex.position);
        let bounces = vertex.depth + 1;
        vertex.light_samples.push(LightSampleRecord {
            light: light.clone(),
            delta,
            direction: e.wi.to_array(),
            point: e
                .distance
                .is_finite()
                .then(|| (origin + e.wi * e.distance).to_array()),
            radiance: e.radiance.to_array(),
            pdf: e.pdf,
            bsdf: e.f.to_array(),
            bsdf_pdf: e.bsdf_pdf,
            mis_weight: e.mis_weight,
            visible: e.visible,
            contribution: contribution.to_array(),
        });
        let strategy = if delta {
            Strategy::DeltaLight
        } else {
            Strategy::LightSample
        };
        self.contribute(true, bounces, strategy, Some(light), contribution);
    }

    fn hemisphere_ray(&mut self, e: &HemisphereEvent) {
        let contribution = self.beta * e.value * e.scale;
        let Some(vertex) = self.last_vertex() else {
            return;
        };
        let bounces = vertex.depth + 1;
        vertex.hemisphere_rays.push(HemisphereRecord {
            direction: e.wi.to_array(),
            pdf: e.pdf,
            bsdf: e.f.to_array(),
            traced: e.traced,
            hit: e.hit.map(|p| p.to_array()),
            radiance: e.radiance.to_array(),
            contribution: contribution.to_array(),
        });
        self.contribute(true, bounces, Strategy::Hemisphere, None, contribution);
    }

    fn scatter(&mut self, e: &ScatterEvent) {
        if let Some(vertex) = self.last_vertex() {
            vertex.scatter = Some(ScatterRecord {
                lobe: lobe_name(e.sample.flags),
                direction: e.wi.to_array(),
                bsdf: e.sample.f.to_array(),
                pdf: e.sample.pdf,
                cos: e.sample.wi.z.abs(),
                throughput: e.beta.to_array(),
            });
        }
    }

    fn roulette(&mut self, survive: f32, survived: bool, beta: Vec3) {
        if let Some(vertex) = self.last_vertex() {
            vertex.roulette = Some(RouletteRecord {
                survival_probability: survive,
                survived,
                throughput: beta.to_array(),
            });
        }
    }

    fn end(&mut self, end: PathEnd, radiance: Vec3) {
        self.record.end = end;
        self.record.radiance = radiance.to_array();
    }
}
