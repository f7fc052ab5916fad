//! What the walk needs of a node, precomputed once at build time
//! ([`NodeBounds`]), and the importance the group's bounds allow at a
//! receiving point, evaluated with as few square roots and divisions as
//! the bound permits (Conty Estevez and Kulla 2018, "Importance Sampling
//! of Many Lights with Adaptive Tree Splitting", §4.1-4.3; pbrt-v4's
//! `LightBounds::Importance`).
//!
//! The bound: power over squared distance (the distance at least the
//! radius of the box's bounding sphere, so that a point inside or near
//! the box does not blow it up), times the cosine of the smallest angle
//! any emitter in the box can make with the direction to the point, times
//! the cosine of the smallest angle any point of the box can make with the
//! receiver's normal (no such term without a normal). Every bound is
//! conservative: zero only where no light of the group can send light to
//! the point (every point of the box is seen outside the emission cone or
//! below a one-sided receiver's horizon, which exact half-space tests on
//! the box check first), so a light that can contribute always keeps a
//! positive probability and the estimator stays unbiased. `reference.rs`
//! (tests only) holds the bound written plainly, which this must match.
//!
//! The walk evaluates two importances per level for every light sample and
//! for the MIS pmf of every emitter a BSDF sample finds, so this is the
//! tree's inner loop. The bound is the same as the paper's; only the
//! arithmetic is arranged to skip work: the box's centre, its bounding
//! sphere's radius and sin θo are stored; the distance costs one reciprocal
//! square root; sin θb is that radius times it; and the sines of the
//! emitter and receiver angles (a square root each) are computed only when
//! the angle subtraction needs them (the angle is wider than θb).

use super::{LightBounds, LightContext};
use glam::Vec3;

/// A node's bounds as the importance reads them.
#[derive(Clone, Copy, Debug)]
pub(super) struct NodeBounds {
    /// Centre of the box.
    center: Vec3,
    /// Radius² of the box's bounding sphere (half the diagonal, squared).
    radius2: f32,
    /// Half the box's extent per axis (for the half-space tests).
    half: Vec3,
    /// Radius of the bounding sphere.
    radius: f32,
    /// Unit axis of the cone of normals.
    axis: Vec3,
    /// cos θo and sin θo of the cone of normals.
    cos_o: f32,
    sin_o: f32,
    /// cos θe, the emission spread.
    cos_e: f32,
    /// Power.
    phi: f32,
}

/// cos(max(0, a − b)) from the cosines of two angles in [0, π] and their
/// sines, the sine of `a` computed only when needed.
#[inline(always)]
fn cos_sub_clamped(cos_a: f32, sin_a: impl FnOnce() -> f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a() * sin_b
    }
}

#[inline(always)]
fn sin_of(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

impl NodeBounds {
    /// The precomputed form of `b`.
    pub(super) fn new(b: &LightBounds) -> Self {
        let half = 0.5 * (b.hi - b.lo);
        let radius2 = half.length_squared();
        Self {
            center: b.centroid(),
            radius2,
            half,
            radius: radius2.sqrt(),
            axis: b.axis,
            cos_o: b.cos_o,
            sin_o: sin_of(b.cos_o),
            cos_e: b.cos_e,
            phi: b.phi,
        }
    }

    /// The importance of the group at `ctx` (the module docs).
    #[inline]
    pub(super) fn importance(&self, ctx: &LightContext) -> f32 {
        let to_p = ctx.p - self.center;
        if self.behind(ctx, to_p) {
            return 0.0;
        }
        let d2 = to_p.length_squared();
        if d2 <= self.radius2 {
            // Inside the bounding sphere every direction is possible: both
            // cosine bounds are 1 and the distance is clamped to the radius.
            return if self.cos_e < 1.0 {
                self.phi / self.radius2
            } else {
                0.0
            };
        }
        let inv_d = d2.sqrt().recip();
        let wi = to_p * inv_d;
        // The directions to the box lie within θb of -wi.
        let sin_b = (self.radius * inv_d).min(1.0);
        let cos_b = (1.0 - sin_b * sin_b).max(0.0).sqrt();
        // θx = max(0, θw − θo), then θ' = max(0, θx − θb).
        let cos_w = self.axis.dot(wi).clamp(-1.0, 1.0);
        let cos_emit = if cos_w > self.cos_o {
            1.0
        } else if self.cos_o >= 1.0 {
            // One orientation (a flat group): θx = θw.
            cos_sub_clamped(cos_w, || sin_of(cos_w), sin_b, cos_b)
        } else {
            let sin_w = sin_of(cos_w);
            let cos_x = cos_w * self.cos_o + sin_w * self.sin_o;
            let sin_x = sin_w * self.cos_o - cos_w * self.sin_o;
            cos_sub_clamped(cos_x, || sin_x, sin_b, cos_b)
        };
        if cos_emit <= self.cos_e {
            return 0.0;
        }
        let mut importance = self.phi * cos_emit / d2;
        if ctx.n != Vec3::ZERO {
            let cos_i = if ctx.two_sided {
                ctx.n.dot(wi).abs()
            } else {
                -ctx.n.dot(wi)
            }
            .clamp(-1.0, 1.0);
            let cos_receive = cos_sub_clamped(cos_i, || sin_of(cos_i), sin_b, cos_b);
            if cos_receive <= 0.0 && !ctx.two_sided {
                return 0.0;
            }
            importance *= cos_receive.max(0.0);
        }
        importance.max(0.0)
    }

    /// Exact half-space tests on the box, tighter than the cones of its
    /// bounding sphere: the box lies wholly
    /// below a one-sided receiver's horizon, or the point lies behind every
    /// emitter's plane of a group with one orientation. `to_p` is the point
    /// minus the centre.
    #[inline(always)]
    fn behind(&self, ctx: &LightContext, to_p: Vec3) -> bool {
        // max over the box of v · (q − p) = −v · (p − c) + |v| · half.
        let reach = |v: Vec3| v.abs().dot(self.half) - v.dot(to_p);
        let below_horizon = !ctx.two_sided && ctx.n != Vec3::ZERO && reach(ctx.n) <= 0.0;
        let behind_emitters = self.cos_o >= 1.0 && reach(-self.axis) <= 0.0;
        below_horizon || behind_emitters
    }
}
