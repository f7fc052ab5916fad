//! When a triangle or rectangle light is sampled by solid angle instead of
//! by area, seen from a shading point.
//!
//! Area sampling converted to solid angle has the density `d² / (A cos θ_l)`,
//! which varies across the light as much as distance and slant do: worst for
//! lights that are near or seen at a slant, where it makes the light samples
//! noisy. Uniform solid-angle sampling (Arvo's spherical triangles, Ureña et
//! al.'s spherical rectangles, [`crate::sampling::warp`]) has the constant
//! density `1 / Ω` instead.
//!
//! The rule, a function of the point and the light alone, so that
//! [`super::AreaLight::sample_li`] and [`super::AreaLight::pdf_li`] (the MIS
//! density of a direction found by the BSDF) always agree:
//! - the point must be on the emitting side (else the light is dark there);
//! - a rectangle's edges must be perpendicular (a general parallelogram is
//!   sampled by area);
//! - the solid angle must lie in [`SOLID_ANGLE_RANGE`]. Below it the light
//!   is small or far, its area density is already nearly constant in solid
//!   angle (the relative variation is about the light's angular size) and
//!   the trigonometry would cost for nothing; above it the point is almost
//!   on the light, which fills nearly the whole hemisphere, and the
//!   spherical constructions lose their conditioning (angles near π).

use crate::sampling::warp::{Parallelogram, SphericalRectangle, SphericalTriangle};
use glam::{Vec2, Vec3};
use std::ops::RangeInclusive;

/// Solid angles (steradians) sampled by solid angle; pbrt-v4 uses the
/// same bounds for its triangles (3e-4 and 2π − 0.06).
pub const SOLID_ANGLE_RANGE: RangeInclusive<f32> = 3e-4..=6.22;

/// Relative tolerance on `|e0·e1| / (|e0||e1|)` for a parallelogram to count
/// as a rectangle.
const PERPENDICULAR: f32 = 1e-4;

/// A planar light as seen from a point, when the rule says to sample it by
/// solid angle.
pub(super) enum SolidAngleSampler {
    Triangle(SphericalTriangle),
    Rectangle(SphericalRectangle),
}

impl SolidAngleSampler {
    /// The triangle `v` emitting toward `normal`, seen from `p`.
    pub(super) fn triangle(p: Vec3, v: &[Vec3; 3], normal: Vec3) -> Option<Self> {
        if normal.dot(p - v[0]) <= 0.0 {
            return None;
        }
        let st = SphericalTriangle::new(p, v)?;
        SOLID_ANGLE_RANGE
            .contains(&st.solid_angle())
            .then_some(Self::Triangle(st))
    }

    /// The parallelogram `shape` emitting toward `normal`, seen from `p`.
    pub(super) fn rectangle(p: Vec3, shape: &Parallelogram, normal: Vec3) -> Option<Self> {
        let (e0, e1) = (shape.edge0, shape.edge1);
        if normal.dot(p - shape.origin) <= 0.0
            || e0.dot(e1).abs() > PERPENDICULAR * e0.length() * e1.length()
        {
            return None;
        }
        let sr = SphericalRectangle::new(p, shape.origin, e0, e1)?;
        SOLID_ANGLE_RANGE
            .contains(&sr.solid_angle())
            .then_some(Self::Rectangle(sr))
    }

    /// A direction toward the light and the distance to it (`None` when
    /// rounding put the direction on the light's plane's wrong side).
    pub(super) fn sample(
        &self,
        p: Vec3,
        plane_point: Vec3,
        normal: Vec3,
        u: Vec2,
    ) -> Option<(Vec3, f32)> {
        match self {
            Self::Triangle(st) => {
                let wi = st.sample(u);
                let cos_light = -normal.dot(wi);
                let distance = normal.dot(p - plane_point) / cos_light;
                (cos_light > 0.0 && distance.is_finite()).then_some((wi, distance))
            }
            Self::Rectangle(sr) => Some(sr.sample(u)),
        }
    }

    /// The density of [`SolidAngleSampler::sample`] per steradian.
    pub(super) fn pdf(&self) -> f32 {
        match self {
            Self::Triangle(st) => st.pdf(),
            Self::Rectangle(sr) => sr.pdf(),
        }
    }
}
