//! The bounds of a group of lights (a box, a cone of normals, an emission
//! spread and a power) and the importance they bound at a receiving point
//! (Conty Estevez and Kulla 2018, "Importance Sampling of Many Lights with
//! Adaptive Tree Splitting", §4.1-4.3; pbrt-v4's `LightBounds`).
//!
//! Every bound here is conservative: the importance of a group is zero only
//! when no light of the group can send light to the point (every point of
//! the box is seen outside the emission cone, or below the receiver's
//! horizon), so a light that can contribute always keeps a positive
//! probability and the estimator stays unbiased.

use super::LightContext;
use glam::{Quat, Vec3};
use std::f32::consts::PI;

/// Slack added to the half-angle of a merged cone (radians): the rotation
/// that centres it rounds, and the merged cone must still contain both.
const CONE_SLACK: f32 = 1e-4;

/// What a light, or a group of lights, can do: where it is, which way its
/// surfaces face, how far around their normals they emit, and its power.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    /// Lower corner of the box holding the emitters.
    pub lo: Vec3,
    /// Upper corner.
    pub hi: Vec3,
    /// Unit axis of the cone of emitting normals.
    pub axis: Vec3,
    /// cos θo: every normal lies within θo of `axis` (-1: any direction).
    pub cos_o: f32,
    /// cos θe: each surface emits within θe of its normal (0: a hemisphere).
    pub cos_e: f32,
    /// Emitted power (the figure power selection uses).
    pub phi: f32,
}

/// cos(max(0, a − b)) from the sines and cosines of two angles in [0, π].
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// sin(max(0, a − b)), as [`cos_sub_clamped`].
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

fn sin_of(cos: f32) -> f32 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

impl LightBounds {
    /// Bounds of a one-sided flat emitter with unit normal `normal`
    /// spanning `points`.
    pub fn flat(points: &[Vec3], normal: Vec3, phi: f32) -> Self {
        let (lo, hi) = points
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        Self {
            lo,
            hi,
            axis: normal,
            cos_o: 1.0,
            cos_e: 0.0,
            phi,
        }
    }

    /// Bounds of a sphere emitting outward: normals in every direction.
    pub fn sphere(center: Vec3, radius: f32, phi: f32) -> Self {
        Self {
            lo: center - Vec3::splat(radius),
            hi: center + Vec3::splat(radius),
            axis: Vec3::Z,
            cos_o: -1.0,
            cos_e: 0.0,
            phi,
        }
    }

    /// The bounds of both groups.
    pub fn union(&self, other: &Self) -> Self {
        let (axis, cos_o) = cone_union((self.axis, self.cos_o), (other.axis, other.cos_o));
        Self {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
            axis,
            cos_o,
            cos_e: self.cos_e.min(other.cos_e),
            phi: self.phi + other.phi,
        }
    }

    /// Centre of the box.
    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Surface area of the box.
    pub fn surface_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// The orientation measure M_Ω of the paper (§4.4, eq. 1): the solid
    /// angle the cone of normals widened by the emission spread covers,
    /// weighted by the cosine, which the build's cost multiplies by power
    /// and surface area.
    pub fn orientation_measure(&self) -> f32 {
        let theta_o = self.cos_o.clamp(-1.0, 1.0).acos();
        let theta_e = self.cos_e.clamp(-1.0, 1.0).acos();
        let theta_w = (theta_o + theta_e).min(PI);
        let sin_o = theta_o.sin();
        2.0 * PI * (1.0 - self.cos_o)
            + 0.5
                * PI
                * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                    + self.cos_o)
    }

    /// The importance of the group at `ctx`: power over squared distance
    /// (the distance at least half the box's diagonal, so that a point
    /// inside or near the box does not blow it up), times the cosine of
    /// the smallest angle any emitter in the box can make with the
    /// direction to the point, times the cosine of the smallest angle any
    /// point of the box can make with the receiver's normal (no such term
    /// without a normal). Zero only where no emitter of the group can
    /// reach the point (see the module docs).
    pub fn importance(&self, ctx: &LightContext) -> f32 {
        if self.behind(ctx) {
            return 0.0;
        }
        let center = self.centroid();
        let to_p = ctx.p - center;
        let d2 = to_p.length_squared();
        let half_diagonal2 = 0.25 * (self.hi - self.lo).length_squared();
        // The directions from the point to the box lie within θb of the
        // direction to its centre (the bounding sphere's cone); a point
        // inside that sphere may see the box in any direction.
        let (sin_b, cos_b) = if d2 <= half_diagonal2 {
            (0.0, -1.0)
        } else {
            let sin2 = half_diagonal2 / d2;
            (sin2.sqrt(), (1.0 - sin2).max(0.0).sqrt())
        };
        let wi = if d2 > 0.0 {
            to_p / d2.sqrt()
        } else {
            Vec3::ZERO
        };
        // Smallest angle between an emitter's normal and the direction to
        // the point: θ' = max(0, θw − θo − θb).
        let cos_w = self.axis.dot(wi).clamp(-1.0, 1.0);
        let sin_w = sin_of(cos_w);
        let sin_o = sin_of(self.cos_o);
        let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let cos_emit = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_emit <= self.cos_e {
            return 0.0;
        }
        let mut importance = self.phi * cos_emit / d2.max(half_diagonal2);
        if ctx.n != Vec3::ZERO {
            // Smallest angle between the receiver's normal and a direction
            // toward the box (either side of the surface when it transmits).
            let cos_i = if ctx.two_sided {
                ctx.n.dot(wi).abs()
            } else {
                -ctx.n.dot(wi)
            }
            .clamp(-1.0, 1.0);
            let cos_receive = cos_sub_clamped(sin_of(cos_i), cos_i, sin_b, cos_b);
            if cos_receive <= 0.0 && !ctx.two_sided {
                return 0.0;
            }
            importance *= cos_receive.max(0.0);
        }
        importance.max(0.0)
    }
}

impl LightBounds {
    /// Exact half-space tests on the box, tighter than the cones of its
    /// bounding sphere that [`LightBounds::importance`] uses: the whole box
    /// lies below a one-sided receiver's horizon, or (for emitters that
    /// all share the normal `axis`, such as a grid of lamps) the point lies
    /// behind every emitter's plane. Cutting such groups at the parent
    /// keeps the walk from entering nodes whose children are all dark.
    fn behind(&self, ctx: &LightContext) -> bool {
        let center = self.centroid();
        let half = 0.5 * (self.hi - self.lo);
        // max over the box of v · (q − p) = v · (c − p) + |v| · half.
        let reach = |v: Vec3| v.dot(center - ctx.p) + v.abs().dot(half);
        let below_horizon = !ctx.two_sided && ctx.n != Vec3::ZERO && reach(ctx.n) <= 0.0;
        // Emits toward p from q only if axis · (p − q) > 0.
        let behind_emitters = self.cos_o >= 1.0 && reach(-self.axis) <= 0.0;
        below_horizon || behind_emitters
    }
}

/// The smallest cone (axis, cos of half-angle) holding both cones, widened
/// by [`CONE_SLACK`] (pbrt-v4's `DirectionCone::Union`).
fn cone_union(a: (Vec3, f32), b: (Vec3, f32)) -> (Vec3, f32) {
    let theta_a = a.1.clamp(-1.0, 1.0).acos();
    let theta_b = b.1.clamp(-1.0, 1.0).acos();
    let theta_d = a.0.dot(b.0).clamp(-1.0, 1.0).acos();
    if (theta_d + theta_b).min(PI) <= theta_a {
        return a;
    }
    if (theta_d + theta_a).min(PI) <= theta_b {
        return b;
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b) + CONE_SLACK;
    if theta_o >= PI {
        return (a.0, -1.0);
    }
    // Turn a's axis toward b's by θo − θa.
    let normal = a.0.cross(b.0);
    if normal.length_squared() < 1e-12 {
        return (a.0, -1.0);
    }
    let turn = Quat::from_axis_angle(normal.normalize(), theta_o - CONE_SLACK - theta_a);
    ((turn * a.0).normalize(), theta_o.cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Merged cones hold every direction of both (checked on their rims).
    #[test]
    fn merged_cones_contain_both() {
        let mut rng = candela_testkit::SplitMix64::new(7);
        for _ in 0..2000 {
            let a = (rng.dir(), rng.range(-1.0, 1.0));
            let b = (rng.dir(), rng.range(-1.0, 1.0));
            let (axis, cos) = cone_union(a, b);
            for (w, c) in [a, b] {
                let theta = c.acos();
                let frame = crate::geometry::Frame::from_normal(w);
                for k in 0..16 {
                    let phi = k as f32 * PI / 8.0;
                    let local = Vec3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    );
                    let rim = frame.to_world(local);
                    assert!(axis.dot(rim) >= cos - 1e-5, "{a:?} {b:?} -> {axis:?} {cos}");
                }
            }
        }
    }
}
