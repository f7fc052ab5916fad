//! The recorder seam: what the path integrator tells an observer, step by
//! step, so that the path inspector ([`super::inspect`]) shows the very
//! computation the renderer does rather than a second copy of it.
//!
//! The integrator is generic over `R: PathRecorder` and calls the recorder
//! at each event with values it has computed anyway. Every method has an
//! empty default body and `()` implements the trait with those, so the
//! render path (which passes `&mut ()`) compiles to the same code as
//! without the seam.
//!
//! Conventions: `value` fields are what the event adds to the path's
//! radiance *before* the path throughput `beta` of the current vertex
//! (given by [`PathRecorder::vertex`]) and the event's `scale` (the
//! `1/n` of an average over `n` light samples or hemisphere rays): the
//! contribution is `beta * value * scale`.

use crate::bsdf::BsdfSample;
use crate::geometry::Ray;
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use glam::{Vec2, Vec3};

/// Why a path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PathEnd {
    /// The ray left the scene.
    Escaped,
    /// The maximum depth (or the end of the bounce range) was reached.
    MaxDepth,
    /// The surface has no BSDF (a pure emitter absorbs).
    Absorbed,
    /// The BSDF returned no direction (or one of zero density).
    NoScatter,
    /// The sampled direction lay on the wrong side of the geometric surface
    /// (shading normals bend, geometry does not).
    WrongSide,
    /// Russian roulette ended it.
    Roulette,
}

/// Light the path finds itself: an emitting surface it hits, or a light at
/// infinity seen by the ray that escapes.
#[derive(Clone, Copy, Debug)]
pub struct EmissionEvent {
    /// The light (index into the scene's light set), if the emitter is one.
    pub light: Option<u32>,
    /// Emitted radiance toward the path.
    pub radiance: Vec3,
    /// MIS weight against the light sampling of the previous vertex
    /// (1 when only this path can find it, 0 when the previous vertex's
    /// direct estimate counted it instead).
    pub mis_weight: f32,
    /// `radiance * mis_weight`.
    pub value: Vec3,
}

/// One light sample (or the one sample of a delta light) at a vertex.
#[derive(Clone, Copy, Debug)]
pub struct LightSampleEvent {
    /// The light (index into the scene's light set).
    pub light: u32,
    /// Unit direction from the vertex toward the light.
    pub wi: Vec3,
    /// Distance to the sampled point (infinite for lights at infinity).
    pub distance: f32,
    /// Radiance arriving along `wi` if unoccluded.
    pub radiance: Vec3,
    /// Density of the sample per solid angle, including the probability of
    /// choosing the light (1 for delta lights).
    pub pdf: f32,
    /// BSDF value for (wo, wi), without the cosine; zero if not evaluated.
    pub f: Vec3,
    /// The BSDF's density of `wi`, when MIS needed it.
    pub bsdf_pdf: Option<f32>,
    /// MIS weight of this sample (1 without MIS).
    pub mis_weight: f32,
    /// Whether the shadow ray found the light unoccluded; `None` when no
    /// shadow ray was traced because the sample could not contribute.
    pub visible: Option<bool>,
    /// `f · L · |cos| · mis_weight / pdf` if visible, else zero.
    pub value: Vec3,
    /// `1/n` for one of `n` light samples, 1 for a delta light.
    pub scale: f32,
}

/// One uniform hemisphere ray of CS184's `-H` direct lighting.
#[derive(Clone, Copy, Debug)]
pub struct HemisphereEvent {
    /// Unit direction of the ray.
    pub wi: Vec3,
    /// Its density per solid angle.
    pub pdf: f32,
    /// BSDF value for (wo, wi), without the cosine.
    pub f: Vec3,
    /// Whether a ray was traced (not when `f` is zero or `wi` points into
    /// the surface).
    pub traced: bool,
    /// Where the ray hit, if it was traced and hit something.
    pub hit: Option<Vec3>,
    /// Emitted radiance it found.
    pub radiance: Vec3,
    /// `f · L · |cos| / pdf`.
    pub value: Vec3,
    /// `1/n` for one of `n` rays.
    pub scale: f32,
}

/// The BSDF sample that continues the path.
#[derive(Clone, Copy, Debug)]
pub struct ScatterEvent<'a> {
    /// The sample, in the local shading frame.
    pub sample: &'a BsdfSample,
    /// Its direction in world space.
    pub wi: Vec3,
    /// The throughput after the bounce (before Russian roulette).
    pub beta: Vec3,
}

/// Receives the path integrator's events; see the module docs. All methods
/// do nothing by default.
#[allow(unused_variables)]
pub trait PathRecorder {
    /// The camera ray, through the film point `film` (pixel units).
    #[inline(always)]
    fn camera(&mut self, film: Vec2, ray: &Ray) {}

    /// The path reached a surface after `depth` bounces along `ray`, with
    /// throughput `beta`.
    #[inline(always)]
    fn vertex(&mut self, scene: &Scene, depth: u32, ray: &Ray, hit: &SurfaceHit, beta: Vec3) {}

    /// The ray after `depth` bounces left the scene, with throughput `beta`.
    #[inline(always)]
    fn escape(&mut self, depth: u32, ray: &Ray, beta: Vec3) {}

    /// Light found by the path itself, added to the image (its bounce count
    /// lies in the rendered range).
    #[inline(always)]
    fn emission(&mut self, event: &EmissionEvent) {}

    /// One light sample at the current vertex, added to the image.
    #[inline(always)]
    fn light_sample(&mut self, event: &LightSampleEvent) {}

    /// One hemisphere ray at the current vertex, added to the image.
    #[inline(always)]
    fn hemisphere_ray(&mut self, event: &HemisphereEvent) {}

    /// The path continues by this BSDF sample.
    #[inline(always)]
    fn scatter(&mut self, event: &ScatterEvent) {}

    /// Russian roulette: survival probability, the decision, and the
    /// throughput after it (divided by the probability if it survived).
    #[inline(always)]
    fn roulette(&mut self, survive: f32, survived: bool, beta: Vec3) {}

    /// The path adds `value` (throughput and weights included) to its
    /// radiance: light that reached the camera after `bounces` bounces.
    /// Called beside each `l +=` with the very value added, so that a
    /// recorder can split the radiance by bounce count exactly
    /// ([`super::layers`]).
    #[inline(always)]
    fn radiance_term(&mut self, bounces: u32, value: Vec3) {}

    /// A bidirectional strategy's contribution to the sample's own pixel,
    /// for extra layer `layer` (`bdpt/techniques.rs`).
    #[inline(always)]
    fn technique(&mut self, layer: usize, value: Vec3) {}

    /// The path ended; `radiance` is what it carries to the camera
    /// (before the firefly clamp).
    #[inline(always)]
    fn end(&mut self, end: PathEnd, radiance: Vec3) {}
}

/// Records nothing: the renderer's recorder.
impl PathRecorder for () {}
