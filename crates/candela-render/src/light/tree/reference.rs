//! A reference for the importance: the bound of Conty Estevez and Kulla
//! (2018, §4.1-4.3) and the estimate the walk weighs by, written plainly
//! from [`LightBounds`], against which the precomputed form of
//! `importance.rs` is checked.

use super::importance::{BOUND_FLOOR, ESTIMATE_RADIUS};
use super::{LightBounds, LightContext};
use glam::Vec3;

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
    /// The importance of the group at `ctx`: power over squared distance
    /// (the distance at least half the box's diagonal, so that a point
    /// inside or near the box does not blow it up), times the cosine of
    /// the smallest angle any emitter in the box can make with the
    /// direction to the point, times the cosine of the smallest angle any
    /// point of the box can make with the receiver's normal (no such term
    /// without a normal): the bound. The importance the walk uses is an
    /// estimate, the same cosines toward a sphere of a quarter of the
    /// radius, at least 0.3 of the bound's; zero exactly where the bound
    /// is, that is only where no emitter of the group can reach the point
    /// (see `importance.rs`).
    pub(super) fn importance(&self, ctx: &LightContext) -> f32 {
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
        if d2 <= half_diagonal2 {
            return self.phi / half_diagonal2;
        }
        // The estimate: the same cosines toward a sphere of a quarter of
        // the radius, at least 0.3 of the bound's.
        let sin_near = ESTIMATE_RADIUS * sin_b;
        let cos_near = sin_of(sin_near);
        let mut estimate = cos_sub_clamped(sin_x, cos_x, sin_near, cos_near).max(0.0);
        let mut bound = cos_emit;
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
            bound *= cos_receive.max(0.0);
            estimate *= cos_sub_clamped(sin_of(cos_i), cos_i, sin_near, cos_near).max(0.0);
        }
        (self.phi / d2 * estimate.max(BOUND_FLOOR * bound)).max(0.0)
    }
}

impl LightBounds {
    /// Exact half-space tests on the box, tighter than the cones of its
    /// bounding sphere that [`LightBounds::importance`] uses: the whole box
    /// lies below a one-sided receiver's horizon, or the point lies behind
    /// every emitter's plane (emitters whose normals are all within θo of
    /// `axis`, such as a grid of lamps). Cutting such groups at the parent
    /// keeps the walk from entering nodes whose children are all dark.
    fn behind(&self, ctx: &LightContext) -> bool {
        let center = self.centroid();
        let half = 0.5 * (self.hi - self.lo);
        // max over the box of v · (q − p) = v · (c − p) + |v| · half.
        let reach = |v: Vec3| v.dot(center - ctx.p) + v.abs().dot(half);
        let below_horizon = !ctx.two_sided && ctx.n != Vec3::ZERO && reach(ctx.n) <= 0.0;
        // Emits toward p from q only if m · (p − q) > 0 for its normal m,
        // and m · (p − q) ≤ axis · (p − q) + |m − axis| · |p − q|, with
        // |m − axis| ≤ 2 sin(θo / 2) and |p − q| ≤ d + r.
        let tilt = (2.0 * (1.0 - self.cos_o)).max(0.0).sqrt()
            * ((ctx.p - center).length() + half.length());
        let behind_emitters = self.cos_e >= 0.0 && reach(-self.axis) + tilt <= 0.0;
        below_horizon || behind_emitters
    }
}

/// The 4-lane importance equals the plain one lane by lane up to rounding,
/// and is zero exactly where it is, at receivers of every kind around
/// groups of every kind: single flat lights, spheres, and unions (cones of
/// normals from a point to any direction).
#[test]
fn precomputed_importance_agrees_with_the_plain_bound() {
    use super::importance::Bounds4;
    let mut rng = candela_testkit::SplitMix64::new(11);
    let group = |rng: &mut candela_testkit::SplitMix64| {
        let c = rng.vec(-3.0, 3.0);
        let phi = rng.log(-1.0, 1.0);
        if rng.range(0.0, 1.0) < 0.2 {
            return LightBounds::sphere(c, rng.range(0.01, 0.5), phi);
        }
        let size = rng.range(0.01, 1.0);
        let v = [c, c + size * rng.dir(), c + size * rng.dir()];
        let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        LightBounds::flat(&v, normal, phi)
    };
    let (mut compared, mut zeros) = (0, 0);
    for k in 0..400 {
        // One to four lanes, each a union of up to 8 lights, some sharing
        // one orientation.
        let lanes: Vec<LightBounds> = (0..=k % 4)
            .map(|lane| {
                let mut b = group(&mut rng);
                for _ in 0..((k + lane) % 8) {
                    let mut other = group(&mut rng);
                    if k % 3 == 0 && b.cos_o >= 1.0 && other.cos_o >= 1.0 {
                        other.axis = b.axis;
                    }
                    b = b.union(&other);
                }
                b
            })
            .collect();
        let wide = Bounds4::new(&lanes);
        for j in 0..40 {
            let p = rng.vec(-5.0, 5.0);
            let ctx = match j % 3 {
                0 => LightContext::surface(p, rng.dir(), false),
                1 => LightContext::surface(p, rng.dir(), true),
                _ => LightContext::point(p),
            };
            let got = wide.importance(&ctx);
            for (lane, b) in lanes.iter().enumerate() {
                let (want, got) = (b.importance(&ctx), got[lane]);
                assert_eq!(want == 0.0, got == 0.0, "{b:?} at {ctx:?}: {want} vs {got}");
                zeros += usize::from(want == 0.0);
                assert!(
                    (got - want).abs() <= 1e-4 * want,
                    "{b:?} at {ctx:?}: {want} vs {got}"
                );
                compared += 1;
            }
            // Unused lanes are never taken.
            assert!(got[lanes.len()..].iter().all(|&w| w == 0.0), "{got:?}");
        }
    }
    // Both outcomes were exercised.
    assert!(
        zeros > compared / 20 && zeros < compared / 2,
        "{zeros} of {compared}"
    );
}
