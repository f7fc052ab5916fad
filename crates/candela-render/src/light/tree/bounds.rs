//! The bounds of a group of lights (a box, a cone of normals, an emission
//! spread and a power), built and merged here (Conty Estevez and Kulla
//! 2018, "Importance Sampling of Many Lights with Adaptive Tree
//! Splitting", §4.1-4.4; pbrt-v4's `LightBounds`). The importance they
//! bound at a receiving point is in `importance.rs`, evaluated from the
//! precomputed form the walk reads.

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
}

/// The smallest cone (axis, cos of half-angle) holding both cones, widened
/// by [`CONE_SLACK`] (pbrt-v4's `DirectionCone::Union`).
fn cone_union(a: (Vec3, f32), b: (Vec3, f32)) -> (Vec3, f32) {
    let theta_a = a.1.clamp(-1.0, 1.0).acos();
    let theta_b = b.1.clamp(-1.0, 1.0).acos();
    // The angle between the axes as 2 atan(|a − b| / |a + b|), exact near
    // 0 where acos(a · b) is not: two normals of one plane whose lengths
    // differ by an ulp have a · b one ulp below 1, whose acos is 3.5e-4.
    let theta_d = 2.0 * (a.0 - b.0).length().atan2((a.0 + b.0).length());
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
        // (Anti)parallel axes: no rotation to make, so no rounding to
        // allow for. Axes that differ by rounding (the normals of a grid of
        // lamps) keep a's axis, widened to hold b: a cone of one direction
        // stays one (cos θo = 1, which the exact half-space test of the
        // importance needs); opposite axes take the whole sphere.
        if a.0.dot(b.0) < 0.0 {
            return (a.0, -1.0);
        }
        return (a.0, theta_a.max(theta_d + theta_b).min(PI).cos());
    }
    let turn = Quat::from_axis_angle(normal.normalize(), theta_o - CONE_SLACK - theta_a);
    ((turn * a.0).normalize(), theta_o.cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Normals of one plane computed from triangles of different sizes
    /// differ by an ulp; merged, they stay a cone of one direction (cos θo
    /// = 1, which the importance's exact half-space test needs), and
    /// opposite normals make the whole sphere.
    #[test]
    fn parallel_cones_stay_a_single_direction() {
        let down = Vec3::new(0.0, -1.0, 0.0);
        let rounded = Vec3::new(0.0, -0.99999994, 0.0);
        assert_eq!(cone_union((down, 1.0), (rounded, 1.0)), (down, 1.0));
        assert_eq!(cone_union((rounded, 1.0), (down, 1.0)), (rounded, 1.0));
        let (_, cos) = cone_union((down, 0.5), (rounded, 1.0));
        assert_eq!(cos, 0.5);
        assert_eq!(cone_union((down, 1.0), (-rounded, 1.0)).1, -1.0);
    }

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
