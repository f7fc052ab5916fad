//! Direct lighting at one shading point: light sampling with optional MIS
//! against BSDF sampling (Veach 1997, ch. 9; the multi-sample model with
//! `n` light samples and one BSDF sample, power heuristic β = 2).
//!
//! The functions here are the small pieces of Tungsten's `TraceBase`:
//! [`estimate_direct`] sums the light samples at a vertex, and
//! [`bsdf_hit_weight`] is the matching MIS weight for the BSDF sample that
//! finds an emitter on its own.

use super::record::{HemisphereEvent, LightSampleEvent, PathRecorder};
use super::ThreadContext;
use crate::bsdf::Bsdf;
use crate::geometry::Ray;
use crate::light::{LightContext, LightSample, LightSelector};
use crate::sampling::warp::{
    square_to_uniform_hemisphere, square_to_uniform_sphere, uniform_hemisphere_pdf,
    uniform_sphere_pdf,
};
use crate::sampling::Sampler;
use crate::scene::{continue_past, Scene, MAX_CUTOUTS};
use crate::shading::{scatter_allowed, scatter_allowed_given, ShadingFrame};
use crate::shape::SurfaceHit;
use glam::{Vec2, Vec3};

/// Fraction of a shadow ray's length left unchecked at the light's end, so
/// that the light's own surface does not shadow it (pbrt's ShadowEpsilon).
const SHADOW_EPSILON: f32 = 1e-4;

/// The power heuristic for `nf` samples of density `f` against `ng` of `g`.
pub fn power_heuristic(nf: f32, f_pdf: f32, ng: f32, g_pdf: f32) -> f32 {
    let f = nf * f_pdf;
    let g = ng * g_pdf;
    if f.is_infinite() {
        return 1.0;
    }
    if f == 0.0 && g == 0.0 {
        return 0.0;
    }
    (f * f) / (f * f + g * g)
}

/// How a vertex gathers direct light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum LightingMode {
    /// CS184's `-H`: direct light from `n` rays in uniformly sampled
    /// hemisphere directions at each vertex (the emitters they hit, and
    /// the sky); no light sampling, so point and directional lights stay
    /// dark.
    Hemisphere,
    /// Light sampling only; BSDF rays do not count the emitters they hit.
    Light,
    /// Both, weighted by the power heuristic.
    Mis,
}

/// Sampler dimensions of one light sample: the light's choice and a point
/// on it (the choice's own dimension is drawn only when the point's number
/// cannot also make the choice).
const LIGHT_SAMPLE_DIMENSIONS: u32 = 3;

/// Sampler dimensions one [`estimate_direct`] call draws in `scene`: two per
/// hemisphere ray, [`LIGHT_SAMPLE_DIMENSIONS`] per light sample, none for
/// delta lights. A caller that skips the estimate skips these, so that the
/// rest of the path keeps its random numbers.
pub fn direct_dimensions(scene: &Scene, mode: LightingMode, light_samples: u32) -> u32 {
    match mode {
        LightingMode::Hemisphere => 2 * light_samples,
        LightingMode::Light | LightingMode::Mis if scene.lights.has_sampled_lights() => {
            LIGHT_SAMPLE_DIMENSIONS * light_samples
        }
        LightingMode::Light | LightingMode::Mis => 0,
    }
}

/// Where lights are chosen for at `hit` (the choice and the MIS weight of an
/// emitter found from there both read it): the point and its geometric
/// normal on the viewer's side, two-sided when `bsdf` transmits (a BSDF
/// without transmission reflects nothing from below that side, see
/// `shading::scatter_allowed`).
pub fn light_context(hit: &SurfaceHit, bsdf: &Bsdf) -> LightContext {
    LightContext::surface(hit.p, hit.ng, bsdf.flags().is_transmission())
}

/// Direct radiance reflected toward `hit.wo`. Light sampling: `light_samples`
/// samples of the non-delta lights (chosen by `selector` for `receiver`,
/// the vertex's [`light_context`]) plus one sample of each
/// delta light, each weighted for MIS when `mode` is [`LightingMode::Mis`].
/// Hemisphere mode: `light_samples` uniform hemisphere rays (CS184's `-H`
/// with `-l`). Each sample goes to `rec`. The shadow rays' origins are kept
/// in `origins`, for the vertex's bounce. `wo` is `hit.wo` in `frame`
/// (the vertex's BSDF sample needs it too).
#[allow(clippy::too_many_arguments)]
pub fn estimate_direct<R: PathRecorder>(
    scene: &Scene,
    hit: &SurfaceHit,
    frame: &ShadingFrame,
    wo: Vec3,
    bsdf: &Bsdf,
    receiver: &LightContext,
    mode: LightingMode,
    light_samples: u32,
    selector: &LightSelector,
    sampler: &mut Sampler,
    origins: &mut SpawnOrigins,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> Vec3 {
    if mode == LightingMode::Hemisphere {
        return estimate_hemisphere(
            scene,
            hit,
            frame,
            wo,
            bsdf,
            light_samples,
            sampler,
            ctx,
            rec,
        );
    }
    let lights = &scene.lights;
    let mut vertex = Vertex {
        scene,
        hit,
        frame,
        bsdf,
        wo,
        origins,
    };
    let mut total = Vec3::ZERO;
    for (index, light) in lights.delta_lights() {
        // Delta lights take no random numbers, so the sampler's dimensions
        // stay aligned whatever the scene holds.
        if let Some(s) = light.sample_li(hit.p, Vec2::ZERO) {
            total += vertex.light_sample(index, s, None, 1.0, ctx, rec);
        }
    }
    if !lights.has_sampled_lights() || light_samples == 0 {
        return total;
    }
    if lights.behind_every_lamp(hit.p) {
        // Every light sample would land on a lamp's back and be rejected
        // (the ceiling above a Cornell box's lamp): pass over their numbers.
        sampler.skip(LIGHT_SAMPLE_DIMENSIONS * light_samples);
        return total;
    }
    let mut sum = Vec3::ZERO;
    let scale = 1.0 / light_samples as f32;
    for _ in 0..light_samples {
        // The choice's own number, drawn only when the point's cannot be
        // reused for it (`LightSelector::choose_with_point`).
        let choice_dimension = sampler.skip_one();
        let u = sampler.next_2d();
        // None: no light can reach this point (the tree's bounds say so).
        let Some((index, pmf, u)) =
            selector.choose_with_point(receiver, u, || sampler.draw_skipped(choice_dimension))
        else {
            continue;
        };
        let mis = (mode == LightingMode::Mis && lights.is_hittable(index))
            .then_some(light_samples as f32);
        if let Some(sample) = lights.sample_li(index, hit.p, u) {
            let mut s = sample;
            s.pdf *= pmf;
            sum += vertex.light_sample(index, s, mis, scale, ctx, rec);
        }
    }
    total + sum / light_samples as f32
}

/// CS184's uniform hemisphere estimate of direct light: `samples` rays in
/// uniform directions over the hemisphere on the viewer's side, each adding
/// the emission it finds (an emitter's front face, or the lights at
/// infinity when it escapes) times `f · |cos| / pdf`. A BSDF that transmits
/// (rough glass) also receives direct light from the other side, which no
/// other strategy of this mode counts (emitters found by BSDF rays weigh 0
/// here): its rays cover the whole sphere instead.
#[allow(clippy::too_many_arguments)]
fn estimate_hemisphere<R: PathRecorder>(
    scene: &Scene,
    hit: &SurfaceHit,
    frame: &ShadingFrame,
    wo: Vec3,
    bsdf: &Bsdf,
    samples: u32,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> Vec3 {
    if samples == 0 {
        return Vec3::ZERO;
    }
    let scale = 1.0 / samples as f32;
    let whole_sphere = bsdf.flags().is_transmission();
    let mut sum = Vec3::ZERO;
    for _ in 0..samples {
        let (wi_local, pdf) = if whole_sphere {
            let w = square_to_uniform_sphere(sampler.next_2d());
            (w, uniform_sphere_pdf(w))
        } else {
            let local = square_to_uniform_hemisphere(sampler.next_2d());
            // The frame is not flipped toward the viewer (dielectrics need
            // its side), so take the hemisphere wo lies in.
            let w = if wo.z < 0.0 { -local } else { local };
            (w, uniform_hemisphere_pdf(local))
        };
        let wi = frame.to_world(wi_local);
        let f = bsdf.f(wo, wi_local) * frame.shadowing(wi);
        let mut event = HemisphereEvent {
            wi,
            pdf,
            f,
            traced: false,
            hit: None,
            radiance: Vec3::ZERO,
            value: Vec3::ZERO,
            scale,
        };
        if f == Vec3::ZERO || !scatter_allowed(hit.ng, wi, wo, wi_local) {
            rec.hemisphere_ray(&event);
            continue;
        }
        let ray = Ray::new(hit.spawn_origin(wi), wi);
        ctx.rays.shadow += 1;
        let (found, crossed) = emission_crossed(scene, &ray, ctx);
        let le = crossed
            + match &found {
                Some(h) if h.front_face => scene
                    .material(h.material)
                    .emission_at(h.texture_point())
                    .unwrap_or(Vec3::ZERO),
                Some(_) => Vec3::ZERO,
                None => scene
                    .lights
                    .infinite_lights()
                    .map(|i| scene.lights.get(i).le(wi))
                    .sum(),
            };
        let value = f * le * (wi_local.z.abs() / pdf);
        sum += value;
        event.traced = true;
        event.hit = found.map(|h| h.p);
        event.radiance = le;
        event.value = value;
        rec.hemisphere_ray(&event);
    }
    sum / samples as f32
}

/// The closest surface that scatters along `ray`, and the emission of the
/// invisible (null) emitting surfaces it passes on the way (each on its
/// front side), which the hemisphere estimate adds like any other.
fn emission_crossed(
    scene: &Scene,
    ray: &Ray,
    ctx: &mut ThreadContext,
) -> (Option<SurfaceHit>, Vec3) {
    let mut le = Vec3::ZERO;
    let mut segment = *ray;
    let mut found = scene.intersect_visible(&segment, &mut ctx.rays.traversal);
    for _ in 0..MAX_CUTOUTS {
        let Some(h) = found.filter(|h| scene.material(h.material).invisible) else {
            break;
        };
        if h.front_face {
            le += scene
                .material(h.material)
                .emission_at(h.uv)
                .unwrap_or(Vec3::ZERO);
        }
        segment = continue_past(&segment, &h);
        found = scene.intersect_visible(&segment, &mut ctx.rays.traversal);
    }
    (found, le)
}

/// Ray origins offset from a vertex ([`SurfaceHit::spawn_origin`]), one per
/// side of its geometric normal, each with its distance from the hit point,
/// kept as they are computed: the offset depends on a direction only through
/// its side, so the vertex's `-l` light samples and its bounce mostly share
/// one (the bounce's offset was about 70 instructions, 1% of the render loop).
///
/// In a scene with media it also holds the medium a ray leaving the vertex
/// starts in, by the same side (the path sets it: it knows the medium it
/// arrived in and the surface's interface); shadow rays then carry the
/// media's transmittance instead of a yes or no.
#[derive(Clone, Copy, Debug, Default)]
pub struct SpawnOrigins([Option<(Vec3, f32)>; 2], Option<[Option<u32>; 2]>);

impl SpawnOrigins {
    /// The slot of `w`'s side of the geometric normal (1: below).
    #[inline(always)]
    fn side(hit: &SurfaceHit, w: Vec3) -> usize {
        usize::from(w.dot(hit.ng) < 0.0)
    }

    /// The origin for a ray from `hit` toward `w` and its distance from
    /// `hit.p`, computed and kept if this side has none yet; `below` is
    /// `w.dot(hit.ng) < 0.0` (the caller has the dot product).
    #[inline(always)]
    fn toward(&mut self, hit: &SurfaceHit, w: Vec3, below: bool) -> (Vec3, f32) {
        debug_assert_eq!(usize::from(below), Self::side(hit, w));
        *self.0[usize::from(below)].get_or_insert_with(|| {
            let origin = hit.spawn_origin(w);
            (origin, (origin - hit.p).length())
        })
    }

    /// Sets the media a ray toward each side of the vertex starts in
    /// (`[the arriving ray's side, the other side]`).
    pub fn set_media(&mut self, sides: [Option<u32>; 2]) {
        self.1 = Some(sides);
    }

    /// `hit.spawn_origin(w)`: the kept origin of `w`'s side, else computed
    /// (and not kept: the bounce is the vertex's last ray).
    #[inline(always)]
    pub fn origin_toward(&self, hit: &SurfaceHit, w: Vec3) -> Vec3 {
        match self.0[Self::side(hit, w)] {
            Some((origin, _)) => origin,
            None => hit.spawn_origin(w),
        }
    }
}

/// A shading point, as light samples see it.
struct Vertex<'a> {
    scene: &'a Scene,
    hit: &'a SurfaceHit,
    frame: &'a ShadingFrame,
    bsdf: &'a Bsdf,
    /// Toward the viewer, in the local frame.
    wo: Vec3,
    /// Shadow-ray origins already computed.
    origins: &'a mut SpawnOrigins,
}

impl Vertex<'_> {
    /// `f · L · |cos| / pdf` for one sample `s` of light `index`, times its
    /// MIS weight when `mis_count` (the number of light samples) is given,
    /// if unoccluded; the sample goes to `rec` with its `scale`. Left to the
    /// compiler's inlining (forcing it saved nothing: callgrind counted 0.1%
    /// more instructions per render).
    fn light_sample<R: PathRecorder>(
        &mut self,
        index: u32,
        s: LightSample,
        mis_count: Option<f32>,
        scale: f32,
        ctx: &mut ThreadContext,
        rec: &mut R,
    ) -> Vec3 {
        let mut event = LightSampleEvent {
            light: index,
            wi: s.wi,
            distance: s.distance,
            radiance: s.l,
            pdf: s.pdf,
            f: Vec3::ZERO,
            bsdf_pdf: None,
            mis_weight: 1.0,
            visible: None,
            value: Vec3::ZERO,
            scale,
        };
        let value = self.contribution(&s, mis_count, ctx, &mut event);
        event.value = value;
        rec.light_sample(&event);
        value
    }

    /// The value of [`Vertex::light_sample`], filling in `event` as it goes.
    #[inline(always)]
    fn contribution(
        &mut self,
        s: &LightSample,
        mis_count: Option<f32>,
        ctx: &mut ThreadContext,
        event: &mut LightSampleEvent,
    ) -> Vec3 {
        let (hit, bsdf) = (self.hit, self.bsdf);
        if s.pdf <= 0.0 || s.l == Vec3::ZERO {
            return Vec3::ZERO;
        }
        // The geometric surface decides reflection vs transmission (no leaks
        // through walls whose shading normals bend: `shading/normal_map.rs`).
        let wi = self.frame.to_local(s.wi);
        let wi_dot_ng = s.wi.dot(hit.ng);
        if !scatter_allowed_given(wi_dot_ng, self.wo, wi) {
            return Vec3::ZERO;
        }
        let f = bsdf.f(self.wo, wi) * self.frame.shadowing(s.wi);
        event.f = f;
        if f == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let below = wi_dot_ng < 0.0;
        let transmitted = match self.origins.1 {
            None => {
                let visible = self.unoccluded(s.wi, below, s.distance, ctx);
                event.visible = Some(visible);
                if !visible {
                    return Vec3::ZERO;
                }
                Vec3::ONE
            }
            Some(media) => {
                let tr = self.transmitted(s.wi, below, s.distance, media[usize::from(below)], ctx);
                event.visible = Some(tr != Vec3::ZERO);
                if tr == Vec3::ZERO {
                    return Vec3::ZERO;
                }
                tr
            }
        };
        let weight = match mis_count {
            Some(n) => {
                let bsdf_pdf = bsdf.pdf(self.wo, wi);
                event.bsdf_pdf = Some(bsdf_pdf);
                power_heuristic(n, s.pdf, 1.0, bsdf_pdf)
            }
            None => 1.0,
        };
        event.mis_weight = weight;
        f * s.l * wi.z.abs() * (weight / s.pdf) * transmitted
    }

    /// The media's transmittance along the shadow ray of
    /// [`Vertex::unoccluded`], which starts in `medium`; zero if blocked.
    fn transmitted(
        &mut self,
        wi: Vec3,
        below: bool,
        distance: f32,
        medium: Option<u32>,
        ctx: &mut ThreadContext,
    ) -> Vec3 {
        let (origin, offset) = self.origins.toward(self.hit, wi, below);
        let mut ray = Ray::new(origin, wi);
        ray.t_max = shadow_t_max(distance, offset);
        if ray.t_max <= 0.0 {
            return Vec3::ONE;
        }
        ctx.rays.shadow += 1;
        self.scene
            .transmittance(&ray, medium, &mut ctx.rays.traversal)
    }

    /// Whether the segment from the vertex toward `wi` (`below` the
    /// geometric surface or not) is free up to `distance` (short of the
    /// light's surface by [`SHADOW_EPSILON`]).
    fn unoccluded(
        &mut self,
        wi: Vec3,
        below: bool,
        distance: f32,
        ctx: &mut ThreadContext,
    ) -> bool {
        let (origin, offset) = self.origins.toward(self.hit, wi, below);
        let t_max = shadow_t_max(distance, offset);
        if t_max <= 0.0 {
            return true;
        }
        let mut ray = Ray::new(origin, wi);
        ray.t_max = t_max;
        ctx.rays.shadow += 1;
        !self.scene.occluded_visible(&ray, &mut ctx.rays.traversal)
    }
}

/// The end of a shadow ray toward a light sample `distance` from the point,
/// from an origin `offset` from it: short of the light's surface by
/// [`SHADOW_EPSILON`] (unbounded for lights at infinity).
#[inline(always)]
pub(super) fn shadow_t_max(distance: f32, offset: f32) -> f32 {
    if distance.is_finite() {
        (distance - offset) * (1.0 - SHADOW_EPSILON)
    } else {
        f32::INFINITY
    }
}

/// MIS weight of an emitter found by a BSDF sample of density `bsdf_pdf`
/// when `light_samples` light samples would have found it with density
/// `light_pdf` (already including the light's selection probability).
pub fn bsdf_hit_weight(bsdf_pdf: f32, light_pdf: f32, light_samples: u32) -> f32 {
    power_heuristic(1.0, bsdf_pdf, light_samples as f32, light_pdf)
}
