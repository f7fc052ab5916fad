//! Light tracing (particle tracing; Veach 1997 §10.3.4, Arvo & Kirk 1990):
//! paths start at the lights and every vertex is joined to a fresh point
//! on the lens (`Camera::sample_wi`), landing anywhere on the film. It is
//! BDPT's t = 1 family alone, each unweighted: strategy (s, 1) for every
//! light-subpath prefix, (1, 1) included (emitting surfaces seen directly;
//! not point and spot lights, which the path tracer never shows either).
//!
//! Each camera sample (pixel, index) traces one light subpath from the
//! sampler positioned there and adds nothing to its own pixel: all light
//! arrives as splats (`film/splat.rs`), so the image is deterministic for
//! any thread count and tiling. Light paths that would hit the lens are
//! impossible for a pinhole (a point) and are not used for the thin lens,
//! and surfaces seen by the camera only through delta BSDFs (a mirror's
//! reflection, objects behind glass) stay black: no connection can end at
//! a delta vertex. `-m` counts bounces as for the path tracer: (s, 1)
//! carries light after s − 1 bounces, s − 1 ≤ m.

use super::bdpt::{connect, splat_at, subpath, vertex::Vertex, BidirSettings};
use super::ThreadContext;
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::Vec3;

/// Traces one light subpath and splats every connection to the camera;
/// the camera sample itself carries zero radiance.
pub fn light_trace(
    scene: &Scene,
    settings: &BidirSettings,
    sampler: &mut Sampler,
    ctx: &mut ThreadContext,
) -> Vec3 {
    let m = settings.max_depth as usize;
    let mut light: Vec<Vertex> = Vec::with_capacity(m + 1);
    ctx.light_paths += 1;
    subpath::light_subpath(
        scene,
        m + 1,
        settings.roulette_from,
        sampler,
        ctx,
        &mut light,
    );
    // A point or spot light seen directly is a point of zero area that the
    // path tracer never shows (no ray hits it): (1, 1) is left out for
    // delta lights so that both render the same image.
    let first = if light.first().is_some_and(|v| v.is_delta_light(scene)) {
        2
    } else {
        1
    };
    for s in first..=light.len() {
        if let Some(c) = connect::connect_to_camera(scene, &light, s, sampler, ctx) {
            if let Some(film) = c.film {
                splat_at(scene, film, c.l, 0, &mut ctx.splats);
            }
        }
    }
    Vec3::ZERO
}
