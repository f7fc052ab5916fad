//! Random walks from the camera and from the lights (Veach 1997 §10.2;
//! pbrt-v4's `GenerateCameraSubpath`, `GenerateLightSubpath`,
//! `RandomWalk`), recording every vertex with its forward and reverse
//! area densities for the MIS weights.
//!
//! Russian roulette runs on both subpaths from bounce
//! [`crate::settings::ROULETTE_FROM`] on, on the throughput relative to
//! the subpath's start (with the η² scale of the path tracer on camera
//! subpaths), survivors divided by the survival probability. The MIS
//! weights ignore it: any weights that sum to one over the strategies keep
//! the estimate unbiased.

use super::vertex::{infinite_light_density, toward_light, Vertex, VertexKind};
use crate::bsdf::{shading_normal_correction, Bsdf, BsdfSample, TransportMode};
use crate::geometry::{Frame, Ray};
use crate::integrator::ThreadContext;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::shading::{scatter_allowed, shading_frame};
use glam::{Vec2, Vec3};

/// A camera subpath of at most `max_vertices` vertices starting with the
/// camera ray `ray`.
pub(crate) fn camera_subpath(
    scene: &Scene,
    ray: &Ray,
    max_vertices: usize,
    roulette_from: Option<u32>,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    path: &mut Vec<Vertex>,
) {
    path.clear();
    if max_vertices == 0 {
        return;
    }
    let camera = &scene.camera;
    let mut v = Vertex::new(
        VertexKind::Camera,
        // The lens, also when clip planes moved the ray's start forward.
        camera.lens_point(ray),
        Vec3::ZERO,
        camera.forward,
        Vec3::ONE,
    );
    v.pdf_fwd = 1.0;
    path.push(v);
    let pdf_dir = camera.pdf_we(ray).1;
    let walk = Walk {
        mode: TransportMode::Radiance,
        max_vertices,
        roulette_from,
    };
    walk.run(scene, *ray, Vec3::ONE, pdf_dir, sampler, ctx, path);
}

/// A light subpath of at most `max_vertices` vertices: a light chosen by
/// power, a ray leaving it, and the walk from there.
pub(crate) fn light_subpath(
    scene: &Scene,
    max_vertices: usize,
    roulette_from: Option<u32>,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    path: &mut Vec<Vertex>,
) {
    path.clear();
    let (u_light, u_pos, u_dir) = (sampler.next_1d(), sampler.next_2d(), sampler.next_2d());
    if max_vertices == 0 {
        return;
    }
    let Some((index, pmf)) = scene.lights.choose_emitter(u_light) else {
        return;
    };
    let light = scene.lights.get(index);
    let bounds = scene.scene_sphere();
    let Some(e) = light.sample_le(u_pos, u_dir, &bounds) else {
        return;
    };
    if e.pdf_pos <= 0.0 || e.pdf_dir <= 0.0 || e.le == Vec3::ZERO {
        return;
    }
    let kind = VertexKind::Light {
        light: index,
        le: e.le,
    };
    let ng = if light.is_infinite() {
        Vec3::ZERO
    } else {
        e.normal
    };
    let mut v = Vertex::new(
        kind,
        e.ray.origin,
        ng,
        e.normal,
        Vec3::splat(1.0 / (pmf * e.pdf_pos)),
    );
    // A delta light's vertex is not a delta *scatterer*: `delta` stays
    // false and the MIS weights ask `is_delta_light` (pbrt's convention).
    v.infinite = light.is_infinite();
    v.pdf_fwd = pmf * e.pdf_pos;
    let infinite = light.is_infinite();
    if infinite {
        v.pdf_fwd = if light.is_delta() {
            pmf
        } else {
            infinite_light_density(scene, e.ray.dir)
        };
    }
    path.push(v);
    let cos = if e.normal == Vec3::ZERO {
        1.0
    } else {
        e.normal.dot(e.ray.dir).abs()
    };
    let beta = e.le * (cos / (pmf * e.pdf_pos * e.pdf_dir));
    let walk = Walk {
        mode: TransportMode::Importance,
        max_vertices,
        roulette_from,
    };
    walk.run(scene, e.ray, beta, e.pdf_dir, sampler, ctx, path);
    if infinite && path.len() > 1 {
        // The first hit's density is the disk's, projected (pbrt-v4).
        let hit = &mut path[1];
        hit.pdf_fwd = e.pdf_pos
            * if hit.on_surface() {
                e.ray.dir.dot(hit.ng).abs()
            } else {
                1.0
            };
    }
}

/// The options of one random walk.
struct Walk {
    mode: TransportMode,
    max_vertices: usize,
    roulette_from: Option<u32>,
}

impl Walk {
    /// Extends `path` (holding its start vertex) along `ray` with
    /// throughput `beta`, `pdf_dir` the solid-angle density of `ray`'s
    /// direction at the start.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        scene: &Scene,
        mut ray: Ray,
        mut beta: Vec3,
        mut pdf_dir: f32,
        sampler: &mut Sampler,
        ctx: &mut ThreadContext,
        path: &mut Vec<Vertex>,
    ) {
        let start = beta.max_element().max(f32::MIN_POSITIVE);
        let mut eta_scale = 1.0f32;
        let mut bounces = 0u32;
        while path.len() < self.max_vertices {
            let Some(hit) = scene.intersect_scattering(&ray, &mut ctx.rays.traversal) else {
                if self.mode == TransportMode::Radiance
                    && scene.lights.infinite_lights().next().is_some()
                {
                    let mut v =
                        Vertex::new(VertexKind::Sky, ray.origin, Vec3::ZERO, -ray.dir, beta);
                    v.pdf_fwd = pdf_dir;
                    path.push(v);
                }
                break;
            };
            ctx.path_segments += 1;
            let material = scene.material(hit.material);
            let frame = shading_frame(scene, &hit, material);
            let bsdf = material.bsdf_at(&hit);
            let kind = VertexKind::Surface {
                hit,
                frame,
                bsdf: bsdf.clone(),
            };
            let mut v = Vertex::new(kind, hit.p, hit.ng, frame.z, beta);
            let prev = path.last().expect("a walk starts from a vertex");
            v.pdf_fwd = prev.area_density(pdf_dir, &v);
            path.push(v);
            if path.len() >= self.max_vertices {
                break;
            }
            let Some(bsdf) = bsdf else {
                break;
            };
            let (u1, u2) = (sampler.next_1d(), sampler.next_2d());
            let wo = hit.wo;
            let Some((wi, s)) = sample_scatter_mode(&bsdf, &frame, hit.ng, wo, (u1, u2), self.mode)
            else {
                break;
            };
            beta *= s.f
                * (s.wi.z.abs() / s.pdf)
                * shading_normal_correction(self.mode, wo, wi, frame.z, hit.ng)
                * frame.shadowing(toward_light(self.mode, wo, wi));
            let specular = s.flags.is_specular();
            let (wo_l, wi_l) = (frame.to_local(wo), s.wi);
            let mut pdf_rev = bsdf.pdf(wi_l, wo_l);
            pdf_dir = s.pdf;
            if specular {
                pdf_dir = 0.0;
                pdf_rev = 0.0;
            }
            if self.mode == TransportMode::Radiance && s.flags.is_transmission() {
                eta_scale *= bsdf.refraction_eta2(wo_l);
            }
            let n = path.len();
            path[n - 1].delta = specular;
            path[n - 2].pdf_rev = path[n - 1].area_density(pdf_rev, &path[n - 2]);
            ray = Ray::new(hit.spawn_origin(wi), wi);
            ctx.rays.bounce += 1;
            bounces += 1;
            if let Some(from) = self.roulette_from {
                if bounces >= from {
                    let survive = ((beta * eta_scale).max_element() / start).min(1.0);
                    if (survive.is_nan() || survive <= 0.0) || sampler.next_1d() >= survive {
                        break;
                    }
                    beta /= survive;
                }
            }
        }
    }
}

/// [`sample_scatter`] in the given transport mode: the same direction
/// and density, `f` of the mode.
fn sample_scatter_mode(
    bsdf: &Bsdf,
    frame: &Frame,
    ng: Vec3,
    wo: Vec3,
    (u1, u2): (f32, Vec2),
    mode: TransportMode,
) -> Option<(Vec3, BsdfSample)> {
    let wo_local = frame.to_local(wo);
    let s = bsdf
        .sample_mode(wo_local, u1, u2, mode)
        .filter(|s| s.pdf > 0.0)?;
    let wi = frame.to_world(s.wi);
    scatter_allowed(ng, wi, wo_local, s.wi).then_some((wi, s))
}
