//! The light tree: choosing which emitter to sample by its importance at
//! the shading point (Conty Estevez and Kulla 2018, "Importance Sampling
//! of Many Lights with Adaptive Tree Splitting"; the same scheme as
//! pbrt-v4's `BVHLightSampler` and Cycles' light tree).
//!
//! Every non-delta light at a finite distance is a leaf of a tree whose
//! nodes bound their lights ([`LightBounds`]: a box, a cone of normals, an
//! emission spread, a power), built binary and walked 4-wide (every other
//! level folded away, so that one pass of 4-lane arithmetic weighs a
//! node's children). To choose a light at a point, the walk from the root
//! takes each child with probability proportional to its importance there
//! (power over squared distance, times bounds on the emitter's and the
//! receiver's cosines); the probability of a light is the product of the
//! branch probabilities down its path, which [`LightTree::pmf`] retraces
//! from the light's stored trail of lanes in O(depth), with the same arithmetic as [`LightTree::choose`], so the
//! two agree exactly. A child whose importance is zero is never taken: its
//! bounds prove that no light below it can reach the point.
//!
//! Lights at infinity stay outside the tree, each chosen with the fixed
//! probability power selection gives it; the tree shares the rest.
//!
//! Files: `bounds.rs` (the bounds), `build.rs` (the cost-driven binary
//! build), `wide.rs` (the 4-wide tree), `importance.rs` (four children's
//! bounds as the walk reads them, and their importance), `sample.rs`
//! (choosing and the pmf), `reference.rs` (tests: the importance written
//! plainly).

mod bounds;
mod build;
mod importance;
#[cfg(test)]
mod reference;
mod sample;
#[cfg(test)]
mod tests;
mod wide;

pub use bounds::LightBounds;

use super::{AreaShape, Light};
use glam::Vec3;

/// Where a light is chosen for: the shading point and what receives light
/// there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightContext {
    /// The receiving point.
    pub p: Vec3,
    /// Unit geometric normal on the side light is received from
    /// (toward the viewer), or zero for a point without one (no cosine
    /// bound).
    pub n: Vec3,
    /// Whether light arrives from both sides of the surface (a BSDF that
    /// transmits); otherwise a light entirely below the horizon of `n`
    /// cannot contribute.
    pub two_sided: bool,
}

impl LightContext {
    /// A point in space with no surface (a medium): no receiver cosine.
    pub fn point(p: Vec3) -> Self {
        Self {
            p,
            n: Vec3::ZERO,
            two_sided: true,
        }
    }

    /// A surface point with geometric normal `ng` facing the viewer;
    /// `transmits` when its BSDF passes light through it.
    pub fn surface(p: Vec3, ng: Vec3, transmits: bool) -> Self {
        Self {
            p,
            n: ng,
            two_sided: transmits,
        }
    }
}

/// A node of the binary tree the build makes: its bounds, and its second
/// child (the first follows it) or, for a leaf, its light.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: LightBounds,
    second_or_light: u32,
    leaf: bool,
}

/// The tree over a scene's finite non-delta lights, with the lights at
/// infinity beside it.
#[derive(Clone, Debug, Default)]
pub struct LightTree {
    /// The 4-wide tree the walk reads (`wide.rs`).
    nodes: Vec<wide::WideNode>,
    /// Per light index: the lanes taken down to it, two bits per level
    /// (`None` for lights not in the tree).
    trails: Vec<Option<u64>>,
    /// Lights at infinity with their probabilities, and the running sum.
    infinite: Vec<(u32, f32)>,
    infinite_cdf: Vec<f32>,
    /// Probability that a light at infinity is chosen (their sum).
    p_infinite: f32,
    /// Levels down to the deepest light (for tolerances in tests).
    depth: u32,
}

impl LightTree {
    /// Builds the tree over `lights`' non-delta lights; `power_pmf` is the
    /// power selection's probability per light: lights at infinity keep
    /// theirs, and the tree's bounds carry it as their power (only ratios
    /// of powers matter).
    pub fn new(lights: &[Light], power_pmf: &[f32]) -> Self {
        let mut leaves = Vec::new();
        let mut infinite = Vec::new();
        for (i, light) in lights.iter().enumerate() {
            if light.is_delta() {
                continue;
            }
            if light.is_infinite() {
                infinite.push((i as u32, power_pmf[i]));
                continue;
            }
            if let Some(b) = light_bounds(light, power_pmf[i]) {
                leaves.push((i as u32, b));
            }
        }
        let p_infinite = if leaves.is_empty() {
            1.0
        } else {
            infinite.iter().map(|&(_, p)| p).sum::<f32>().min(1.0)
        };
        let within: f32 = infinite.iter().map(|&(_, p)| p).sum();
        let mut running = 0.0;
        let infinite_cdf = infinite
            .iter()
            .map(|&(_, p)| {
                running += p / within;
                running
            })
            .collect();
        let wide = if leaves.is_empty() {
            wide::Wide {
                nodes: Vec::new(),
                trails: vec![None; lights.len()],
                depth: 0,
            }
        } else {
            wide::collapse(&build::build(leaves).nodes, lights.len())
        };
        Self {
            nodes: wide.nodes,
            trails: wide.trails,
            infinite,
            infinite_cdf,
            p_infinite,
            depth: wide.depth,
        }
    }

    /// Levels of the walk down to the deepest light (1 for a single
    /// light).
    pub fn depth(&self) -> u32 {
        self.depth
    }
}

/// The bounds of one light, `None` for lights the tree does not hold
/// (delta lights, lights at infinity).
fn light_bounds(light: &Light, phi: f32) -> Option<LightBounds> {
    let Light::Area(area) = light else {
        return None;
    };
    Some(match &area.shape {
        AreaShape::Triangle { v, normal } => LightBounds::flat(v, *normal, phi),
        AreaShape::Rect { shape, normal } => {
            let corners = [
                shape.origin,
                shape.origin + shape.edge0,
                shape.origin + shape.edge1,
                shape.origin + shape.edge0 + shape.edge1,
            ];
            LightBounds::flat(&corners, *normal, phi)
        }
        AreaShape::Sphere { center, radius, .. } => LightBounds::sphere(*center, *radius, phi),
    })
}
