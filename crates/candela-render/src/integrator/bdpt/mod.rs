//! Bidirectional path tracing (Veach 1997, ch. 10; Veach & Guibas 1995;
//! pbrt-v4's chapter "Bidirectional Methods" as a guide).
//!
//! Each camera sample traces one camera subpath (from its camera ray) and
//! one light subpath (from a light chosen by power), then joins every
//! prefix of one to every prefix of the other ([`connect`]) and weights
//! each strategy (s, t) — s light vertices, t camera vertices — by the
//! power heuristic over all strategies that could have made the same path
//! ([`mis`]). Strategies with t ≥ 2 add to the sample's own pixel;
//! t = 1 strategies land anywhere on the film and go to the film's exact
//! splat sums (`film/splat.rs`), the light subpath being owned by this
//! camera sample. t = 0 (light subpaths that hit the lens) is impossible
//! for the pinhole and not used for the thin lens; (1, 1) is left to
//! (0, 2) as in pbrt.
//!
//! **Path length.** `-m` counts bounces as the path tracer does: light that
//! reaches the camera after k scattering events has k bounces, i.e. k + 2
//! vertices (camera and light included) and k + 1 segments, so strategy
//! (s, t) is used when s + t − 2 ≤ m. The same `-m` gives the same image
//! expectation as `--integrator path`. Russian roulette runs on both
//! subpaths ([`subpath`]).

pub(crate) mod connect;
pub(crate) mod mis;
pub(crate) mod subpath;
pub mod techniques;
pub(crate) mod vertex;

use super::{FirstHitAov, PathRecorder, ThreadContext};
use crate::film::Splat;
use crate::geometry::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use vertex::{Vertex, VertexKind};

/// Settings of the bidirectional estimators.
#[derive(Clone, Debug, PartialEq)]
pub struct BidirSettings {
    /// Most bounces (the path tracer's `-m`).
    pub max_depth: u32,
    /// Russian roulette from this bounce on (`None`: never).
    pub roulette_from: Option<u32>,
    /// Fill the per-strategy layers ([`techniques`]).
    pub technique_layers: bool,
}

/// Splats a t = 1 contribution `l` landing at film position `film`
/// (pixels) into `splats`: scaled by the pixel count, since the film
/// divides splat sums by the number of light subpaths (see `film/splat.rs`
/// and the camera's importance docs), for film layer `layer` (0 the image,
/// k the extra layer k − 1). The one-pixel box gives one splat, to the
/// pixel `film` lies in; a wider reconstruction filter one to every pixel
/// whose filter covers `film`, weighted by the normalised filter there
/// (`camera/filter.rs`), so that light paths estimate the same filtered
/// image as camera paths.
pub(crate) fn splat_at(scene: &Scene, film: Vec2, l: Vec3, layer: u32, splats: &mut Vec<Splat>) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let value = l * (w as f32 * h as f32);
    let filter = &scene.camera.filter;
    if filter.is_pixel_box() {
        splats.push(Splat {
            x: (film.x.max(0.0) as u32).min(w - 1),
            y: (film.y.max(0.0) as u32).min(h - 1),
            value,
            layer,
        });
        return;
    }
    for (x, y, weight) in filter.pixels_covering(film, w, h) {
        splats.push(Splat {
            x,
            y,
            value: value * weight,
            layer,
        });
    }
}

/// Radiance of one BDPT camera sample along `camera_ray` (strategies with
/// t ≥ 2); the t = 1 strategies go to `ctx.splats`. With
/// `settings.technique_layers`, every strategy's contribution also goes to
/// its layers ([`techniques`]): t ≥ 2 to `rec`, t = 1 as tagged splats.
#[allow(clippy::too_many_arguments)]
pub fn bdpt_radiance<R: PathRecorder>(
    scene: &Scene,
    camera_ray: &Ray,
    settings: &BidirSettings,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
    aov: &mut FirstHitAov,
    rec: &mut R,
) -> Vec3 {
    let m = settings.max_depth as usize;
    let mut light: Vec<Vertex> = Vec::with_capacity(m + 1);
    let mut camera: Vec<Vertex> = Vec::with_capacity(m + 2);
    ctx.light_paths += 1;
    ctx.path_segments += 1;
    subpath::camera_subpath(
        scene,
        camera_ray,
        m + 2,
        settings.roulette_from,
        sampler,
        ctx,
        &mut camera,
    );
    subpath::light_subpath(
        scene,
        m + 1,
        settings.roulette_from,
        sampler,
        ctx,
        &mut light,
    );
    if let Some(VertexKind::Surface { hit, .. }) = camera.get(1).map(|v| &v.kind) {
        aov.record(hit, scene.material(hit.material));
    }
    let mut l = Vec3::ZERO;
    for t in 1..=camera.len() {
        for s in 0..=light.len() {
            if s + t < 2 || s + t - 2 > m || (s == 1 && t == 1) {
                continue;
            }
            let Some((c, w)) = strategy(scene, &light, &camera, s, t, sampler, ctx) else {
                continue;
            };
            let layer = settings
                .technique_layers
                .then(|| techniques::layer_index(s, t));
            match c.film {
                Some(film) => {
                    splat_at(scene, film, c.l * w, 0, &mut ctx.splats);
                    if let Some(i) = layer {
                        splat_at(scene, film, c.l * w, i as u32 + 1, &mut ctx.splats);
                        splat_at(scene, film, c.l, i as u32 + 2, &mut ctx.splats);
                    }
                }
                None => {
                    l += c.l * w;
                    if let Some(i) = layer {
                        rec.technique(i, c.l * w);
                        rec.technique(i + 1, c.l);
                    }
                }
            }
        }
    }
    l
}

/// Strategy (s, t)'s unweighted connection and its MIS weight.
fn strategy(
    scene: &Scene,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Option<(connect::Connection, f32)> {
    let c = if t == 1 {
        connect::connect_to_camera(scene, light, s, sampler, ctx)?
    } else {
        connect::connect(scene, light, camera, s, t, sampler, ctx)?
    };
    let w = mis::mis_weight(scene, light, camera, c.sampled.clone(), s, t);
    Some((c, w))
}
