//! The path tracer: one flat loop with the throughput `beta`, the bounce
//! count, the previous BSDF pdf and a specular flag (pbrt-v4's
//! `PathIntegrator::Li`), next-event estimation at every non-specular vertex
//! and Russian roulette on throughput.
//!
//! Roulette ends paths whose throughput fell below
//! [`ROULETTE_THRESHOLD`], with probability 1 − throughput / threshold.
//! It looks at `beta · η²-scale` rather than `beta` (pbrt-v4's
//! `etaScale`): refraction into glass scales radiance by `1/η²`, which
//! leaving undoes, so the bare throughput of a path inside glass understates
//! what it will carry out and roulette would end it needlessly often. The
//! survival probability may be anything in (0, 1]: dividing the survivors
//! by it keeps the estimate unbiased either way.
//!
//! Bounce counting follows CS184: light that reaches the camera after `k`
//! scattering events has "k bounces" — `k = 0` is an emitter seen directly,
//! `k = 1` direct lighting. [`PathSettings::bounces`] selects which `k` are
//! added to the image: `0..=m` normally, `m..=m` for CS184's `-o 0`, `0..=1`
//! for the direct-only view, `2..=m` for the indirect-only view and `k..=k`
//! for `--bounce k`. A vertex whose light samples fall outside the range
//! skips their sampler dimensions rather than drawing them, so every view
//! traces the same paths as the full render: the views of disjoint ranges
//! add up to it sample for sample.

use super::direct::{
    bsdf_hit_weight, direct_dimensions, estimate_direct, light_context, LightingMode, SpawnOrigins,
};
use super::medium::MediumVertex;
use super::record::{EmissionEvent, PathEnd, PathRecorder, ScatterEvent};
use super::{FirstHitAov, ThreadContext};
use crate::bsdf::Bsdf;
use crate::geometry::Ray;
use crate::light::{LightContext, LightSelection, LightSelector};
use crate::medium::FreeFlight;
use crate::sampling::Sampler;
use crate::scene::{continue_past, Scene, MAX_CUTOUTS};
use crate::settings::ROULETTE_THRESHOLD;
use crate::shading::opacity::passes_through;
use crate::shading::{sample_scatter, shading_frame, NoScatter, ShadingFrame};
use crate::shape::SurfaceHit;
use glam::Vec3;
use std::ops::RangeInclusive;

/// Settings of the path tracer.
#[derive(Clone, Debug, PartialEq)]
pub struct PathSettings {
    /// Bounce counts whose light is added to the image; the path is traced
    /// up to the end of this range.
    pub bounces: RangeInclusive<u32>,
    /// How direct light is gathered at each vertex.
    pub lighting: LightingMode,
    /// Light samples per vertex for non-delta lights (`-l`).
    pub light_samples: u32,
    /// Russian roulette from this bounce count on (`None`: never).
    pub roulette_from: Option<u32>,
    /// How each light sample chooses its light.
    pub light_selection: LightSelection,
    /// Camera rays pass through emitting surfaces (Mitsuba's
    /// `hide_emitters`; `bounces` then starts at 1, which hides the
    /// environment seen directly).
    pub hide_emitters: bool,
}

impl Default for PathSettings {
    fn default() -> Self {
        Self {
            bounces: 0..=5,
            lighting: LightingMode::Mis,
            light_samples: 1,
            roulette_from: Some(3),
            light_selection: LightSelection::default(),
            hide_emitters: false,
        }
    }
}

/// Russian roulette after the bounce that made the path `depth` bounces
/// long: ends it with probability 1 − throughput / threshold (see the
/// module docs) or divides the survivor's throughput by its chance; false
/// when the path ends.
#[inline(always)]
fn survives_roulette<R: PathRecorder>(
    settings: &PathSettings,
    depth: u32,
    beta: &mut Vec3,
    eta_scale: f32,
    sampler: &mut Sampler,
    rec: &mut R,
) -> bool {
    if let Some(from) = settings.roulette_from {
        if depth >= from {
            let survive = ((*beta * eta_scale).max_element() / ROULETTE_THRESHOLD).min(1.0);
            if survive <= 0.0 || sampler.next_1d() >= survive {
                rec.roulette(survive, false, *beta);
                return false;
            }
            *beta /= survive;
            rec.roulette(survive, true, *beta);
        }
    }
    true
}

/// Where the previous scattering event was, for MIS at the next emitter.
#[derive(Clone, Copy)]
struct PrevVertex {
    /// Where its light samples chose their lights (its point among them).
    receiver: LightContext,
    bsdf_pdf: f32,
    specular: bool,
}

/// Radiance along the camera ray `ray`; the first hit's albedo and normal
/// go to `aov`, and every step to `rec` (`&mut ()` records nothing and
/// costs nothing).
pub fn path_radiance<R: PathRecorder>(
    scene: &Scene,
    camera_ray: &Ray,
    settings: &PathSettings,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    aov: &mut FirstHitAov,
    rec: &mut R,
) -> Vec3 {
    let max_depth = *settings.bounces.end();
    let mut l = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    // Product of η² over the refractions so far (see the module docs).
    let mut eta_scale = 1.0f32;
    let mut ray = *camera_ray;
    let mut prev: Option<PrevVertex> = None;
    let mut depth = 0u32;
    // Emitting invisible surfaces the path has gone through.
    let mut crossed = 0u32;
    let selector = scene.lights.selector(settings.light_selection);
    // Participating media (`crate::medium`): the medium the path is in.
    let media = scene.media.any();
    let mut medium = scene.media.camera;
    let end = loop {
        let found = if media {
            scene.intersect_in_media(&ray, &mut ctx.rays.traversal)
        } else {
            scene.intersect_visible(&ray, &mut ctx.rays.traversal)
        };
        if let Some(m) = medium.filter(|_| media) {
            let length = found
                .as_ref()
                .map_or(f32::INFINITY, |h| (h.p - ray.origin).length());
            match scene
                .media
                .get(m)
                .sample_distance(length, sampler.next_2d())
            {
                FreeFlight::Passed { weight } => beta *= weight,
                FreeFlight::Scattered { distance, weight } => {
                    beta *= weight;
                    if depth >= max_depth {
                        break PathEnd::MaxDepth;
                    }
                    let dir = ray.dir.normalize();
                    let vertex = MediumVertex {
                        scene,
                        p: ray.origin + dir * distance,
                        wo: -dir,
                        phase: &scene.media.get(m).phase,
                        medium: m,
                    };
                    if settings.bounces.contains(&(depth + 1)) {
                        let term = beta
                            * vertex.direct(
                                settings.lighting,
                                settings.light_samples,
                                &selector,
                                sampler,
                                ctx,
                            );
                        l += term;
                        rec.radiance_term(depth + 1, term);
                    } else {
                        // A medium point takes light samples in every mode.
                        let light = LightingMode::Light;
                        sampler.skip(direct_dimensions(scene, light, settings.light_samples));
                    }
                    // Sampled in proportion to its value: the weight is one.
                    let (wi, phase_pdf) = vertex.phase.sample(vertex.wo, sampler.next_2d());
                    prev = Some(PrevVertex {
                        receiver: LightContext::point(vertex.p),
                        bsdf_pdf: phase_pdf,
                        specular: false,
                    });
                    ray = Ray::new(vertex.p, wi);
                    ctx.rays.bounce += 1;
                    depth += 1;
                    if !survives_roulette(settings, depth, &mut beta, eta_scale, sampler, rec) {
                        break PathEnd::Roulette;
                    }
                    continue;
                }
            }
        }
        let Some(hit) = found else {
            rec.escape(depth, &ray, beta);
            if settings.bounces.contains(&depth) {
                let term = beta * escaped_radiance(scene, &selector, &ray, prev, settings, rec);
                l += term;
                rec.radiance_term(depth, term);
            }
            break PathEnd::Escaped;
        };
        rec.vertex(scene, depth, &ray, &hit, beta);
        let material = scene.material(hit.material);
        if settings.bounces.contains(&depth) && hit.front_face {
            if let Some(le) = material.emission_at(hit.texture_point()) {
                let mis_weight = emitter_weight(scene, &selector, &ray, &hit, prev, settings);
                let term = beta * le * mis_weight;
                l += term;
                rec.radiance_term(depth, term);
                rec.emission(&EmissionEvent {
                    light: scene.lights.light_of_prim(hit.prim),
                    radiance: le,
                    mis_weight,
                    value: le * mis_weight,
                });
            }
        }
        // Emitters hidden from the camera are not there for camera rays.
        let hidden = depth == 0 && settings.hide_emitters && material.emission.is_some();
        // A medium's boundary that lets the ray through where it met it (a
        // cut-out; invisible surfaces are the common case).
        let passed_boundary = media
            && !material.invisible
            && scene.media.interface(hit.material).is_some()
            && passes_through(material, &hit, &ray);
        if material.invisible || hidden || passed_boundary {
            if media {
                medium = scene
                    .media
                    .after(hit.material, hit.front_face, true, medium);
            }
            // An emitting null surface: its emission is in, and the path goes
            // on as if it were not there (`scene/visibility.rs`).
            crossed += 1;
            if crossed > MAX_CUTOUTS {
                break PathEnd::Absorbed;
            }
            ray = continue_past(&ray, &hit);
            continue;
        }
        // The first vertex's BSDF serves the AOVs and the path alike; past
        // the last bounce it is not read. A BSDF made for this hit (textured,
        // a blend) lives in `made`; an untextured one is borrowed.
        let mut made = None;
        let bsdf = if depth == 0 || depth < max_depth {
            material.bsdf_in(&hit, &mut made)
        } else {
            None
        };
        if depth == 0 {
            aov.record_bsdf(&hit, bsdf);
        }
        if depth >= max_depth {
            break PathEnd::MaxDepth;
        }
        let Some(bsdf) = bsdf else {
            break PathEnd::Absorbed; // a pure emitter absorbs
        };
        let frame = shading_frame(scene, &hit, material);
        let wo = frame.to_local(hit.wo);
        // Where lights are chosen for at this vertex: its light samples,
        // and the MIS weight of an emitter its bounce finds.
        let receiver = light_context(&hit, bsdf);
        // Offset origins of the shadow rays, which the bounce reuses.
        let mut origins = SpawnOrigins::default();
        if media {
            origins.set_media([
                scene
                    .media
                    .after(hit.material, hit.front_face, false, medium),
                scene
                    .media
                    .after(hit.material, hit.front_face, true, medium),
            ]);
        }
        if !bsdf.flags().is_specular() {
            let term = beta
                * direct_at_vertex(
                    scene,
                    &hit,
                    &frame,
                    wo,
                    bsdf,
                    &receiver,
                    depth,
                    settings,
                    &selector,
                    sampler,
                    &mut origins,
                    ctx,
                    rec,
                );
            l += term;
            rec.radiance_term(depth + 1, term);
        }
        // A direction on the wrong side of the true surface would leak
        // through it (shading normals bend, geometry does not): the
        // sample is rejected (`shading::scatter_allowed`).
        // A one-lobe BSDF ignores `u1`: its dimension is skipped, not drawn.
        let u1 = if bsdf.samples_a_lobe() {
            sampler.next_1d()
        } else {
            sampler.skip(1);
            0.0
        };
        let u2 = sampler.next_2d();
        let (wi, s) = match sample_scatter(bsdf, &frame, hit.ng, wo, u1, u2) {
            Ok(scattered) => scattered,
            Err(NoScatter::NoSample) => break PathEnd::NoScatter,
            Err(NoScatter::WrongSide) => break PathEnd::WrongSide,
        };
        let transmits = s.flags.is_transmission();
        beta *= s.f * (frame.shadowing(wi) * s.wi.z.abs() / s.pdf);
        rec.scatter(&ScatterEvent {
            sample: &s,
            wi,
            beta,
        });
        if transmits {
            eta_scale *= bsdf.refraction_eta2(wo);
        }
        prev = Some(PrevVertex {
            receiver,
            bsdf_pdf: s.pdf,
            specular: s.flags.is_specular(),
        });
        if media {
            medium = scene
                .media
                .after(hit.material, hit.front_face, wi.dot(hit.ng) < 0.0, medium);
        }
        ray = Ray::new(origins.origin_toward(&hit, wi), wi);
        ctx.rays.bounce += 1;
        depth += 1;
        if !survives_roulette(settings, depth, &mut beta, eta_scale, sampler, rec) {
            break PathEnd::Roulette;
        }
    };
    rec.end(end, l);
    ctx.path_segments += depth as u64 + 1;
    l
}

/// The direct-lighting estimate at a non-specular vertex after `depth`
/// bounces, if light after `depth + 1` bounces is in the rendered range;
/// otherwise zero, with the estimate's sampler dimensions skipped so that
/// the rest of the path draws what a full render draws (bounce views then
/// add up to it sample for sample).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn direct_at_vertex<R: PathRecorder>(
    scene: &Scene,
    hit: &SurfaceHit,
    frame: &ShadingFrame,
    wo: Vec3,
    bsdf: &Bsdf,
    receiver: &LightContext,
    depth: u32,
    settings: &PathSettings,
    selector: &LightSelector,
    sampler: &mut Sampler,
    origins: &mut SpawnOrigins,
    ctx: &mut ThreadContext,
    rec: &mut R,
) -> Vec3 {
    let dimensions = || direct_dimensions(scene, settings.lighting, settings.light_samples);
    if !settings.bounces.contains(&(depth + 1)) {
        sampler.skip(dimensions());
        return Vec3::ZERO;
    }
    let first_dimension = sampler.dimension();
    let direct = estimate_direct(
        scene,
        hit,
        frame,
        wo,
        bsdf,
        receiver,
        settings.lighting,
        settings.light_samples,
        selector,
        sampler,
        origins,
        ctx,
        rec,
    );
    debug_assert_eq!(
        sampler.dimension() - first_dimension,
        dimensions(),
        "direct_dimensions must count what estimate_direct draws"
    );
    direct
}

/// MIS weight of emission found by the path itself (not by light sampling).
fn emitter_weight(
    scene: &Scene,
    selector: &LightSelector,
    ray: &Ray,
    hit: &SurfaceHit,
    prev: Option<PrevVertex>,
    settings: &PathSettings,
) -> f32 {
    let Some(prev) = prev.filter(|p| !p.specular) else {
        return 1.0; // seen by the camera or through a mirror: only this path finds it
    };
    match settings.lighting {
        // The vertex's direct-lighting estimate (hemisphere rays or light
        // samples) already counted this emitter.
        LightingMode::Hemisphere | LightingMode::Light => 0.0,
        LightingMode::Mis => {
            let Some(index) = scene.lights.light_of_prim(hit.prim) else {
                return 1.0;
            };
            let from = prev.receiver.p;
            let light_pdf = selector.pmf(&prev.receiver, index)
                * scene.lights.pdf_li(index, from, ray.dir, hit.p);
            bsdf_hit_weight(prev.bsdf_pdf, light_pdf, settings.light_samples)
        }
    }
}

/// Radiance of the lights at infinity (ambient sky, environment map) seen
/// along an escaping ray, each weighted for MIS like emission found by
/// the path: full weight when only this path could find it (camera rays,
/// specular bounces), none in the hemisphere and light-only modes (the
/// vertex's direct estimate counted it), the power heuristic under MIS.
fn escaped_radiance<R: PathRecorder>(
    scene: &Scene,
    selector: &LightSelector,
    ray: &Ray,
    prev: Option<PrevVertex>,
    settings: &PathSettings,
    rec: &mut R,
) -> Vec3 {
    let mut l = Vec3::ZERO;
    for index in scene.lights.infinite_lights() {
        let light = scene.lights.get(index);
        let le = light.le(ray.dir);
        if le == Vec3::ZERO {
            continue;
        }
        let weight = match prev.filter(|p| !p.specular) {
            None => 1.0,
            Some(prev) => match settings.lighting {
                LightingMode::Hemisphere | LightingMode::Light => 0.0,
                LightingMode::Mis => {
                    let light_pdf = selector.pmf(&prev.receiver, index)
                        * light.pdf_li(prev.receiver.p, ray.dir, Vec3::ZERO);
                    bsdf_hit_weight(prev.bsdf_pdf, light_pdf, settings.light_samples)
                }
            },
        };
        l += le * weight;
        rec.emission(&EmissionEvent {
            light: Some(index),
            radiance: le,
            mis_weight: weight,
            value: le * weight,
        });
    }
    l
}
