//! What the walk needs of a node's four children, precomputed once at
//! build time and laid out lane by lane ([`Bounds4`]), and the importance
//! each child's bounds allow at a receiving point, evaluated for the four
//! at once with 4-lane arithmetic (Conty Estevez and Kulla 2018, "Importance Sampling
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
//! The weight the walk uses is not the bound itself but an estimate that
//! is positive exactly where the bound is: the same cosines taken toward a
//! sphere of a quarter of the bounding radius ([`ESTIMATE_RADIUS`]), at
//! least [`BOUND_FLOOR`] of the bound's. The bound's cosines are the worst
//! case over the whole box, so a large group far to the side (a half of a
//! hall's ceiling seen from the floor) gets cosines near 1 where most of
//! its lamps make steep angles, and takes samples from the lamps overhead;
//! a sample proportional to the bound is unbiased but wastes them. At the
//! points the camera sees, this lowers the one-sample variance of direct
//! light (shadows included) by 32 % in the many-lights hall and by 42 % in
//! the city (BENCHMARKS.md; the two constants were chosen there among six
//! pairs, and a radius fraction from 0.15 to 0.35 does about as well); the
//! floor keeps every group the bound lets through at a share of at least
//! 0.3 of what the bound alone would give it, so choices stay unbiased and
//! the variance bounded. Inside a group's bounding sphere the weight stays
//! the bound's (power over radius², no cosines).
//!
//! The walk evaluates one such pass per level for every light sample and
//! for the MIS pmf of every emitter a BSDF sample finds, so this is the
//! tree's inner loop: the boxes' centres, their bounding spheres' radii and
//! sin θo are stored, the distance costs one square root and one
//! reciprocal, and the branches of the bound become lane selects.
use super::{LightBounds, LightContext};
use glam::{BVec4A, Vec3, Vec4};

/// The estimate's cosines are taken toward a sphere of this fraction of
/// each box's bounding radius (the bound takes the whole sphere).
pub(super) const ESTIMATE_RADIUS: f32 = 0.25;

/// The estimate is at least this fraction of the bound (where the bound is
/// positive).
pub(super) const BOUND_FLOOR: f32 = 0.3;

/// Up to four groups' bounds, one per lane (unused lanes: zero power).
#[derive(Clone, Copy, Debug)]
pub(super) struct Bounds4 {
    /// Centres of the boxes.
    center: [Vec4; 3],
    /// Half the boxes' extents per axis (for the half-space tests).
    half: [Vec4; 3],
    /// Unit axes of the cones of normals.
    axis: [Vec4; 3],
    /// Radius² and radius of the boxes' bounding spheres.
    radius2: Vec4,
    radius: Vec4,
    /// cos θo and sin θo of the cones of normals.
    cos_o: Vec4,
    sin_o: Vec4,
    /// 2 sin(θo/2) = |m − axis| for a normal m at θo from the axis: how
    /// far the emitters' planes may tilt from the axis's (the half-space
    /// test).
    chord: Vec4,
    /// cos θe, the emission spread.
    cos_e: Vec4,
    /// Powers.
    phi: Vec4,
}

fn sin_of(cos: Vec4) -> Vec4 {
    (Vec4::ONE - cos * cos).max(Vec4::ZERO).sqrt()
}

/// cos(max(0, a − b)) lane by lane, from the angles' cosines and sines.
fn cos_sub_clamped(cos_a: Vec4, sin_a: Vec4, cos_b: Vec4, sin_b: Vec4) -> Vec4 {
    Vec4::select(cos_a.cmpgt(cos_b), Vec4::ONE, cos_a * cos_b + sin_a * sin_b)
}

fn dot3(a: &[Vec4; 3], b: &[Vec4; 3]) -> Vec4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Bounds4 {
    /// The lanes of `groups` (at most four).
    pub(super) fn new(groups: &[LightBounds]) -> Self {
        assert!(groups.len() <= 4, "a wide node holds at most four children");
        let lane = |f: &dyn Fn(&LightBounds) -> f32, unused: f32| {
            let mut v = [unused; 4];
            for (slot, g) in v.iter_mut().zip(groups) {
                *slot = f(g);
            }
            Vec4::from_array(v)
        };
        let vec = |f: &dyn Fn(&LightBounds) -> Vec3| [0, 1, 2].map(|k| lane(&|g| f(g)[k], 0.0));
        let half = |g: &LightBounds| 0.5 * (g.hi - g.lo);
        let radius2 = lane(&|g| half(g).length_squared(), 1.0);
        let cos_o = lane(&|g| g.cos_o, 1.0);
        Self {
            center: vec(&|g| g.centroid()),
            half: vec(&half),
            axis: vec(&|g| g.axis),
            radius2,
            radius: radius2.sqrt(),
            cos_o,
            sin_o: sin_of(cos_o),
            chord: (2.0 * (Vec4::ONE - cos_o)).max(Vec4::ZERO).sqrt(),
            cos_e: lane(&|g| g.cos_e, 0.0),
            phi: lane(&|g| g.phi, 0.0),
        }
    }

    /// The importance of each lane's group at `ctx`: the estimate, zero
    /// exactly where the bound is (the module docs).
    #[inline]
    pub(super) fn importance(&self, ctx: &LightContext) -> [f32; 4] {
        let to_p = [
            Vec4::splat(ctx.p.x) - self.center[0],
            Vec4::splat(ctx.p.y) - self.center[1],
            Vec4::splat(ctx.p.z) - self.center[2],
        ];
        let has_normal = ctx.n != Vec3::ZERO;
        let n = [ctx.n.x, ctx.n.y, ctx.n.z].map(Vec4::splat);
        let n_abs = [ctx.n.x.abs(), ctx.n.y.abs(), ctx.n.z.abs()].map(Vec4::splat);
        let axis_abs = self.axis.map(Vec4::abs);
        let d2 = dot3(&to_p, &to_p);
        let d = d2.sqrt();
        // Exact half-space tests on the boxes, tighter than the cones of
        // their bounding spheres: the box lies wholly below a one-sided
        // receiver's horizon, or the point lies behind every emitter's
        // plane. max over the box of v · (q − p) = |v| · half − v · (p − c);
        // a normal m within θo of the axis a adds at most
        // |m − a| · |q − p| ≤ 2 sin(θo/2) · (d + r), so that a group of
        // nearly parallel emitters (a wall of lamps, slightly bent) is
        // still cut at a point just behind it (emitters send light only to
        // the front of their plane: cos θe ≥ 0).
        let n_dot = dot3(&n, &to_p);
        let mut dark = if !ctx.two_sided && has_normal {
            (dot3(&n_abs, &self.half) - n_dot).cmple(Vec4::ZERO)
        } else {
            BVec4A::FALSE
        };
        let axis_dot = dot3(&self.axis, &to_p);
        dark |= self.cos_e.cmpge(Vec4::ZERO)
            & (dot3(&axis_abs, &self.half) + axis_dot + self.chord * (d + self.radius))
                .cmple(Vec4::ZERO);

        // Inside the bounding sphere every direction is possible: both
        // cosine bounds are 1 and the distance is clamped to the radius.
        let inside = d2.cmple(self.radius2);
        let inside_value = Vec4::select(
            self.cos_e.cmplt(Vec4::ONE),
            self.phi / self.radius2,
            Vec4::ZERO,
        );

        let inv_d = d.recip();
        // The directions to the box lie within θb of the direction from
        // its centre to the point.
        let sin_b = (self.radius * inv_d).min(Vec4::ONE);
        let cos_b = sin_of(sin_b);
        // θx = max(0, θw − θo), then θ' = max(0, θx − θb).
        let cos_w = (axis_dot * inv_d).clamp(-Vec4::ONE, Vec4::ONE);
        let sin_w = sin_of(cos_w);
        let within = cos_w.cmpgt(self.cos_o);
        let cos_x = Vec4::select(within, Vec4::ONE, cos_w * self.cos_o + sin_w * self.sin_o);
        let sin_x = Vec4::select(within, Vec4::ZERO, sin_w * self.cos_o - cos_w * self.sin_o);
        let cos_emit = cos_sub_clamped(cos_x, sin_x, cos_b, sin_b);
        let mut outside_dark = cos_emit.cmple(self.cos_e);
        // The estimate's cone toward the box (the module docs).
        let sin_near = sin_b * ESTIMATE_RADIUS;
        let cos_near = sin_of(sin_near);
        let mut bound = cos_emit;
        let mut estimate = cos_sub_clamped(cos_x, sin_x, cos_near, sin_near).max(Vec4::ZERO);
        if has_normal {
            let cos_n = n_dot * inv_d;
            let cos_i =
                if ctx.two_sided { cos_n.abs() } else { -cos_n }.clamp(-Vec4::ONE, Vec4::ONE);
            let sin_i = sin_of(cos_i);
            let cos_receive = cos_sub_clamped(cos_i, sin_i, cos_b, sin_b);
            if !ctx.two_sided {
                outside_dark |= cos_receive.cmple(Vec4::ZERO);
            }
            bound *= cos_receive.max(Vec4::ZERO);
            estimate *= cos_sub_clamped(cos_i, sin_i, cos_near, sin_near).max(Vec4::ZERO);
        }
        let value = self.phi / d2 * estimate.max(BOUND_FLOOR * bound);
        let value = Vec4::select(outside_dark, Vec4::ZERO, value);
        let value = Vec4::select(inside, inside_value, value);
        Vec4::select(dark, Vec4::ZERO, value)
            .max(Vec4::ZERO)
            .to_array()
    }
}
