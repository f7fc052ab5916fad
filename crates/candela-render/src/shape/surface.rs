//! Surface points with rounding-error bounds, and ray-origin offsets.
//!
//! After pbrt (Pharr, Jakob, Humphreys, 3rd ed., section 3.9): an
//! intersection point is only known up to a box of half-widths `p_error`.
//! A ray leaving the surface starts from that point pushed along the normal
//! just past the box, so it cannot land on the wrong side of its own surface
//! — no fixed epsilon, correct at any scale and distance from the origin.

use crate::geometry::Ray;
use glam::Vec3;

/// Bound on the relative error of `n` chained f32 operations:
/// `n u / (1 - n u)` with `u` the unit roundoff (pbrt's `gamma`).
#[inline]
pub const fn gamma(n: u32) -> f32 {
    let u = f32::EPSILON * 0.5;
    n as f32 * u / (1.0 - n as f32 * u)
}

/// A point on a surface with its error bound and geometric normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Computed position.
    pub p: Vec3,
    /// Per-axis bound on `|p - true position|`.
    pub p_error: Vec3,
    /// Unit geometric normal (the side is the shape's convention).
    pub n: Vec3,
}

/// Moves `p` along `n` (toward the side `w` points to) by just more than the
/// error box's extent along `n`, rounding each coordinate away from `p`.
/// Forced inline: once per bounce and per shadow-ray side, and the calls
/// cost a quarter of its instructions (callgrind).
#[inline(always)]
pub fn offset_ray_origin(p: Vec3, p_error: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let d = n.abs().dot(p_error);
    let mut offset = d * n;
    if w.dot(n) < 0.0 {
        offset = -offset;
    }
    let po = p + offset;
    Vec3::new(
        away(po.x, offset.x),
        away(po.y, offset.y),
        away(po.z, offset.z),
    )
}

/// A ray from `sp` in direction `w`, offset so it cannot re-hit the surface.
pub fn spawn_ray(sp: &SurfacePoint, w: Vec3) -> Ray {
    Ray::new(offset_ray_origin(sp.p, sp.p_error, sp.n, w), w)
}

/// Rounds `x` one float further in the direction of `sign` (the addition
/// that produced it may have rounded back toward the surface).
fn away(x: f32, sign: f32) -> f32 {
    if sign > 0.0 {
        next_up(x)
    } else if sign < 0.0 {
        -next_up(-x)
    } else {
        x
    }
}

/// The next representable float above `x`.
fn next_up(x: f32) -> f32 {
    if x.is_infinite() && x > 0.0 || x.is_nan() {
        return x;
    }
    if x == 0.0 {
        return f32::from_bits(1);
    }
    let bits = x.to_bits();
    f32::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_up_steps_one_ulp() {
        for x in [1.0f32, -1.0, 0.0, -0.0, 3.5e-40, 1e30, -2.0] {
            let y = next_up(x);
            assert!(y > x, "{x} -> {y}");
            // Nothing lies strictly between x and y.
            assert!(
                ((x as f64 + y as f64) * 0.5) as f32 == x
                    || ((x as f64 + y as f64) * 0.5) as f32 == y
            );
        }
        assert_eq!(next_up(1.0), 1.0 + f32::EPSILON);
        assert_eq!(next_up(-1.0), -1.0 + f32::EPSILON / 2.0);
    }

    #[test]
    fn offset_moves_to_the_side_of_w() {
        let (p, e, n) = (Vec3::new(5.0, 1.0, -3.0), Vec3::splat(1e-3), Vec3::Z);
        assert!(offset_ray_origin(p, e, n, Vec3::Z).z > p.z + 1e-3);
        assert!(offset_ray_origin(p, e, n, -Vec3::Z).z < p.z - 1e-3);
        assert_eq!(offset_ray_origin(p, e, n, Vec3::Z).x, p.x);
    }

    #[test]
    fn offset_depends_on_w_only_through_its_side() {
        // Next-event estimation computes one origin per side of a vertex
        // and reuses it for every shadow ray leaving on that side.
        let (p, e) = (Vec3::new(0.3, -2.0, 7.5), Vec3::new(2e-6, 3e-6, 5e-6));
        let n = Vec3::new(0.2, 0.9, -0.3).normalize();
        let above = offset_ray_origin(p, e, n, n);
        let below = offset_ray_origin(p, e, n, -n);
        assert_ne!(above, below);
        for w in [
            Vec3::X,
            -Vec3::X,
            Vec3::Y,
            -Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::ONE,
        ] {
            let want = if w.dot(n) < 0.0 { below } else { above };
            assert_eq!(offset_ray_origin(p, e, n, w), want, "{w}");
        }
    }
}
