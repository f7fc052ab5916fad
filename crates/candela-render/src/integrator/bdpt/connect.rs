//! Joining a light subpath's first `s` vertices to a camera subpath's
//! first `t`: the unweighted contribution of strategy (s, t) (Veach 1997
//! §10.2.1; pbrt-v4's `ConnectBDPT`). `s = 0` uses the camera subpath
//! alone (it hit a light), `t = 1` samples a fresh point on the lens and
//! lands anywhere on the film, `s = 1` samples a fresh point on a light.
//! `t = 0` (a light subpath that hits the lens) is impossible for the
//! pinhole and not used for the thin lens.

use super::vertex::{Vertex, VertexKind};
use crate::bsdf::TransportMode;
use crate::geometry::Ray;
use crate::integrator::ThreadContext;
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// Shadow rays leave this fraction of the segment unchecked at the far
/// end, so the target's own surface does not block them.
const SHADOW_EPSILON: f32 = 1e-4;

/// What one strategy gives before its MIS weight.
pub(crate) struct Connection {
    /// The path's contribution `f / p` (zero if occluded or not connectible).
    pub l: Vec3,
    /// The vertex sampled afresh (lens point for `t = 1`, light point for
    /// `s = 1`), which replaces the subpath's own in the MIS weight.
    pub sampled: Option<Vertex>,
    /// Film position (pixels) for `t = 1`.
    pub film: Option<Vec2>,
}

/// The geometry term between two vertices with shading-normal cosines
/// (none at points and at infinity), without visibility.
fn geometry(a: &Vertex, b: &Vertex) -> f32 {
    if a.infinite || b.infinite {
        let w = if a.infinite { a.ns } else { -b.ns };
        let cos = |v: &Vertex| {
            if v.on_surface() {
                v.ns.dot(w).abs()
            } else {
                1.0
            }
        };
        return cos(a) * cos(b);
    }
    let d = b.p - a.p;
    let dist2 = d.length_squared();
    if dist2 == 0.0 {
        return 0.0;
    }
    let w = d / dist2.sqrt();
    let cos = |v: &Vertex| {
        if v.on_surface() {
            v.ns.dot(w).abs()
        } else {
            1.0
        }
    };
    cos(a) * cos(b) / dist2
}

/// Where a segment leaves `v` toward `target`: off the surface by its
/// error bound, or the point itself.
fn spawn(v: &Vertex, toward: Vec3) -> Vec3 {
    match v.kind {
        VertexKind::Surface { hit, .. } => hit.spawn_origin(toward),
        _ => v.p,
    }
}

/// Whether nothing blocks the segment between `a` and `b` (`b` may be at
/// infinity).
fn visible(scene: &Scene, a: &Vertex, b: &Vertex, ctx: &mut ThreadContext) -> bool {
    ctx.rays.shadow += 1;
    if b.infinite {
        let dir = -b.ns;
        let ray = Ray::new(spawn(a, dir), dir);
        return !scene.occluded_visible(&ray, &mut ctx.rays.traversal);
    }
    let dir = (b.p - a.p).normalize_or_zero();
    let from = spawn(a, dir);
    let to = spawn(b, -dir);
    let d = to - from;
    let dist = d.length();
    if dist == 0.0 || !dist.is_finite() {
        return true;
    }
    let mut ray = Ray::new(from, d / dist);
    ray.t_max = dist * (1.0 - SHADOW_EPSILON);
    !scene.occluded_visible(&ray, &mut ctx.rays.traversal)
}

/// `wo` of a subpath vertex: toward its predecessor (zero for endpoints).
fn wo(path: &[Vertex], i: usize) -> Vec3 {
    match path[i].kind {
        VertexKind::Surface { hit, .. } => hit.wo,
        _ => Vec3::ZERO,
    }
}

/// Strategy (s, t) for `s ≥ 1`, `t = 1`: light vertex `s − 1` seen through
/// a fresh lens point. Draws 2 dimensions.
pub(crate) fn connect_to_camera(
    scene: &Scene,
    light: &[Vertex],
    s: usize,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Option<Connection> {
    let u_lens = sampler.next_2d();
    let qs = &light[s - 1];
    if !qs.connectible(scene) || qs.infinite {
        return None;
    }
    let cs = scene.camera.sample_wi(qs.p, u_lens)?;
    if (cs.pdf.is_nan() || cs.pdf <= 0.0) || cs.we == Vec3::ZERO {
        return None;
    }
    let mut camera = Vertex::new(
        VertexKind::Camera,
        cs.p_lens,
        Vec3::ZERO,
        scene.camera.forward,
        cs.we / cs.pdf,
    );
    camera.pdf_fwd = 1.0;
    let mut l =
        qs.beta * qs.f(scene, wo(light, s - 1), camera.p, TransportMode::Importance) * camera.beta;
    if qs.on_surface() {
        l *= cs.wi.dot(qs.ns).abs();
    }
    // Behind clip planes the camera sees only what lies past the near
    // plane: the shadow ray ends there, not at the lens.
    let near_end = Vertex {
        p: scene.camera.clipped(Ray::new(cs.p_lens, -cs.wi)).origin,
        ..camera.clone()
    };
    if l == Vec3::ZERO || !visible(scene, qs, &near_end, ctx) {
        return None;
    }
    Some(Connection {
        l,
        sampled: Some(camera),
        film: Some(cs.film),
    })
}

/// Strategy (s, t) for `t ≥ 2`. Draws 3 dimensions when `s = 1`.
pub(crate) fn connect(
    scene: &Scene,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Option<Connection> {
    let pt = &camera[t - 1];
    if s == 0 {
        let l = pt.beta * pt.le(scene, camera[t - 2].p);
        return (l != Vec3::ZERO).then_some(Connection {
            l,
            sampled: None,
            film: None,
        });
    }
    if s == 1 {
        let (u_light, u_pos) = (sampler.next_1d(), sampler.next_2d());
        if !pt.connectible(scene) {
            return None;
        }
        let light_vertex = sample_light_vertex(scene, pt, u_light, u_pos)?;
        let emitted = light_vertex.f(scene, Vec3::ZERO, pt.p, TransportMode::Importance);
        let l = pt.beta
            * pt.f(
                scene,
                wo(camera, t - 1),
                light_point(&light_vertex, pt),
                TransportMode::Radiance,
            )
            * emitted
            * light_vertex.beta
            * geometry(pt, &light_vertex);
        if l == Vec3::ZERO || !visible(scene, pt, &light_vertex, ctx) {
            return None;
        }
        return Some(Connection {
            l,
            sampled: Some(light_vertex),
            film: None,
        });
    }
    let qs = &light[s - 1];
    if !qs.connectible(scene) || !pt.connectible(scene) || qs.infinite {
        return None;
    }
    let l = qs.beta
        * qs.f(scene, wo(light, s - 1), pt.p, TransportMode::Importance)
        * pt.f(scene, wo(camera, t - 1), qs.p, TransportMode::Radiance)
        * pt.beta
        * geometry(qs, pt);
    if l == Vec3::ZERO || !visible(scene, pt, qs, ctx) {
        return None;
    }
    Some(Connection {
        l,
        sampled: None,
        film: None,
    })
}

/// A point standing for `v` as seen from `from`: its position, or far along
/// its direction for a vertex at infinity.
fn light_point(v: &Vertex, from: &Vertex) -> Vec3 {
    if v.infinite {
        from.p - v.ns
    } else {
        v.p
    }
}

/// A fresh light vertex for strategy s = 1: a light chosen as light
/// subpaths choose theirs, a point on it by its emission sampling (lights
/// at infinity: a direction by their light sampling as seen from `pt`).
fn sample_light_vertex(scene: &Scene, pt: &Vertex, u_light: f32, u_pos: Vec2) -> Option<Vertex> {
    let (index, pmf) = scene.lights.choose_emitter(u_light)?;
    let light = scene.lights.get(index);
    let mut v = if light.is_infinite() {
        let ls = light.sample_li(pt.p, u_pos)?;
        if ls.pdf.is_nan() || ls.pdf <= 0.0 {
            return None;
        }
        let kind = VertexKind::Light {
            light: index,
            le: ls.l,
        };
        let mut v = Vertex::new(
            kind,
            pt.p + ls.wi,
            Vec3::ZERO,
            -ls.wi,
            Vec3::splat(1.0 / (pmf * ls.pdf)),
        );
        v.infinite = true;
        v
    } else {
        let e = light.sample_le(u_pos, Vec2::splat(0.5), &scene.scene_sphere())?;
        if e.pdf_pos.is_nan() || e.pdf_pos <= 0.0 {
            return None;
        }
        let kind = VertexKind::Light {
            light: index,
            le: e.le,
        };
        Vertex::new(
            kind,
            e.ray.origin,
            e.normal,
            e.normal,
            Vec3::splat(1.0 / (pmf * e.pdf_pos)),
        )
    };
    v.pdf_fwd = v.pdf_light_origin(scene, pt);
    Some(v)
}
