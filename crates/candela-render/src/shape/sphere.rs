//! Analytic ray–sphere intersection.
//!
//! The discriminant is computed as `r^2 - |f - (f.d / d.d) d|^2` (Haines et
//! al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
//! Gems, 2019), which keeps its precision when the sphere is small and far
//! away, and the roots use the cancellation-free `q` form.

use super::surface::{gamma, SurfacePoint};
use crate::geometry::Ray;
use glam::{Mat3, Vec3};

/// Nearest root of `|o + t d - center| = radius` in `(0, t_max)`: the near
/// one from outside, the far one from inside.
#[inline]
pub fn intersect_sphere(o: Vec3, d: Vec3, center: Vec3, radius: f32, t_max: f32) -> Option<f32> {
    let f = o - center;
    let a = d.length_squared();
    if a.is_nan() || a <= 0.0 {
        return None;
    }
    let half_b = f.dot(d);
    let l = f - (half_b / a) * d;
    let disc = a * (radius - l.length()) * (radius + l.length());
    if disc < 0.0 {
        return None;
    }
    let c = f.length_squared() - radius * radius;
    let q = -half_b - disc.sqrt().copysign(half_b);
    let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { 0.0 });
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    if t0 > 0.0 && t0 < t_max {
        Some(t0)
    } else if t1 > 0.0 && t1 < t_max {
        Some(t1)
    } else {
        None
    }
}

/// Surface point at `t`: reprojected onto the sphere (which tightens the
/// error to a few ulps of the radius), with its bound and outward normal.
pub fn sphere_surface_point(center: Vec3, radius: f32, ray: &Ray, t: f32) -> SurfacePoint {
    let mut local = ray.at(t) - center;
    let len = local.length();
    if len > 0.0 {
        local *= radius / len;
    }
    let p = center + local;
    // Reprojection error (pbrt: gamma(5) |p|) plus the final addition.
    let p_error = gamma(5) * local.abs() + gamma(1) * p.abs();
    let n = (local / radius).normalize_or(Vec3::Y);
    SurfacePoint { p, p_error, n }
}

/// Spherical texture coordinates of a point on the sphere, in `[0, 1]^2`:
/// `u = phi / 2pi` around +Y (world up), `v = theta / pi` from +Y.
pub fn sphere_uv(center: Vec3, p: Vec3) -> (f32, f32) {
    let q = (p - center).normalize_or(Vec3::Y);
    let phi = q.z.atan2(q.x);
    let u = if phi < 0.0 {
        phi + std::f32::consts::TAU
    } else {
        phi
    } / std::f32::consts::TAU;
    let v = q.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
    (u, v)
}

/// [`sphere_uv`] in the parameterisation of `axes` (orthonormal columns
/// x, y, z in world space; [`candela_scene::SphereDesc::axes`]): `v = θ/π`
/// from +z, `u = φ/2π` around it from +x toward +y. With
/// [`candela_scene::SphereDesc::Y_POLE`] it is [`sphere_uv`].
pub fn sphere_uv_in(axes: Mat3, center: Vec3, p: Vec3) -> (f32, f32) {
    let q = axes.transpose() * (p - center).normalize_or(axes.z_axis);
    let phi = q.y.atan2(q.x);
    let u = if phi < 0.0 {
        phi + std::f32::consts::TAU
    } else {
        phi
    } / std::f32::consts::TAU;
    let v = q.z.clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
    (u, v)
}
