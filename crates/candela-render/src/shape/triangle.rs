//! Watertight ray–triangle intersection (Woop, Benthin, Wald, "Watertight
//! Ray/Triangle Intersection", JCGT 2013; as in pbrt).
//!
//! Möller–Trumbore computes each barycentric from a different rounding of a
//! shared edge, so rays through an edge or a vertex can slip between two
//! triangles. Here the vertices are moved into a ray space where the ray is
//! the +z axis through the origin (translate, permute so z is the largest
//! direction component, shear), and each barycentric weight becomes a 2D
//! edge function `x_a y_b - y_a x_b` of one edge alone. Its computed sign is
//! either the true sign or zero (rounding is monotone), and a neighbour
//! sharing the edge gets exactly the negated value, so with inclusive tests
//! (all `>= 0` or all `<= 0`: no back-face culling) a ray through an edge or
//! a vertex hits at least one of the triangles around it.
//!
//! Hits at `t` near zero. pbrt rejects any hit whose computed `t` lies
//! within its rounding-error bound `δt` (a true `t` that may be `<= 0`).
//! That bound grows with the triangle's extent as seen from the origin, so a
//! ray starting a few microns above a large ground quad (`δt` of a 6-unit
//! quad at 45° is about 5e-5) was wrongly rejected. Hits with `0 < t <= δt`
//! are therefore decided again in f64 ([`near_hit_t`]): the sign of `t` is
//! the sign of `n·(v0 - o) / n·d`, which f64 gets right with its own error
//! bound some 1e9 times tighter. A hit is accepted only when its true `t`
//! is provably positive, and spawned rays start strictly on their side of
//! the surface ([`super::offset_ray_origin`]), so they still never re-hit it.
//! A `t` that rounds to `<= 0` is rejected before the bound is computed:
//! that early exit is what keeps shadow and bounce rays (whose leaves are
//! mostly behind them) fast, at the price that an origin closer to a plane
//! than the f32 rounding of `t` (about 1e-4 on a 1000-unit triangle) may
//! miss it.

use super::surface::{gamma, SurfacePoint};
use glam::{DVec3, Vec3};

/// A triangle hit: distance and the barycentric weights of `v1` and `v2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Weight of `v1`.
    pub b1: f32,
    /// Weight of `v2`.
    pub b2: f32,
}

/// Per-ray set-up shared by every triangle the ray meets: the permuted
/// origin and the shear that maps the direction onto +z.
#[derive(Clone, Copy, Debug)]
pub struct TriangleRay {
    pub(super) origin: Vec3,
    pub(super) kz: u8,
    pub(super) shear: Vec3,
    /// The permuted direction, for [`near_hit_t`].
    pub(super) dir: Vec3,
}

impl TriangleRay {
    /// Prepares the ray `o + t d` (`d` need not be unit length).
    pub fn new(o: Vec3, d: Vec3) -> Self {
        let a = d.abs();
        let kz = if a.x > a.y && a.x > a.z {
            0
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let d = permute(d, kz);
        let shear = Vec3::new(-d.x / d.z, -d.y / d.z, 1.0 / d.z);
        Self {
            origin: permute(o, kz),
            kz,
            shear,
            dir: d,
        }
    }
}

/// Rotates coordinates so that axis `kz` comes last (an even permutation,
/// which keeps the handedness).
#[inline(always)]
fn permute(v: Vec3, kz: u8) -> Vec3 {
    match kz {
        0 => Vec3::new(v.y, v.z, v.x),
        1 => Vec3::new(v.z, v.x, v.y),
        _ => v,
    }
}

/// The vertices translated, permuted and sheared into ray space (z not yet
/// scaled), and the edge functions, whose signs decide the hit.
#[inline(always)]
fn ray_space(ray: &TriangleRay, v: &[Vec3; 3]) -> ([Vec3; 3], [f32; 3]) {
    let s = ray.shear;
    let p = v.map(|p| {
        let a = permute(p, ray.kz) - ray.origin;
        Vec3::new(a.x + s.x * a.z, a.y + s.y * a.z, a.z)
    });
    let e0 = p[1].x * p[2].y - p[1].y * p[2].x;
    let e1 = p[2].x * p[0].y - p[2].y * p[0].x;
    let e2 = p[0].x * p[1].y - p[0].y * p[1].x;
    (p, [e0, e1, e2])
}

/// The error bound on the f32 `t` of the ray's crossing of triangle `v`'s
/// plane, for tests that check a hit's accuracy.
#[cfg(test)]
pub(super) fn t_error_bound_of(ray: &TriangleRay, v: &[Vec3; 3]) -> f32 {
    let (p, e) = ray_space(ray, v);
    let z = Vec3::new(p[0].z, p[1].z, p[2].z) * ray.shear.z;
    t_error_bound(&p, z, e, 1.0 / (e[0] + e[1] + e[2]))
}

/// Intersects the prepared ray with triangle `v` for `t` in `(0, t_max)`.
#[inline(always)]
pub fn intersect_triangle(ray: &TriangleRay, v: &[Vec3; 3], t_max: f32) -> Option<TriangleHit> {
    let (p, [e0, e1, e2]) = ray_space(ray, v);
    let s = ray.shear;
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return None; // ray in the triangle's plane, or a degenerate triangle
    }
    let z = Vec3::new(p[0].z, p[1].z, p[2].z) * s.z;
    let t_scaled = e0 * z.x + e1 * z.y + e2 * z.z;
    // Range test without dividing: t = t_scaled / det must lie in (0, t_max).
    // Rejecting t <= 0 here keeps the common case (triangles behind the
    // origin) cheap; a positive t within its error bound is decided below.
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det)
        || det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det)
    {
        return None;
    }
    let inv_det = 1.0 / det;
    let mut t = t_scaled * inv_det;
    // A NaN (from a determinant that underflows) rejects here.
    if t.is_nan() || t >= t_max {
        return None;
    }
    let bound = t_error_bound(&p, z, [e0, e1, e2], inv_det);
    let trusted = t > bound; // false for a NaN bound too
    if !trusted {
        let near_zero = t.abs() <= bound && inv_det.is_finite();
        if !near_zero {
            return None;
        }
        t = near_hit_t(ray, v, t_max)?;
    }
    Some(TriangleHit {
        t,
        b1: e1 * inv_det,
        b2: e2 * inv_det,
    })
}

/// The `t` of a hit whose f32 `t` lies within its error bound of zero,
/// recomputed in f64 as `n·(v0 - o) / n·d` with `n = (v1 - v0) x (v2 - v0)`;
/// `None` unless `t` is provably in `(0, t_max)` (the edge tests have
/// already passed in f32, watertight).
///
/// Error bound: every input is an f32, so the edge vectors and `v0 - o` are
/// exact or within one f64 rounding; each component of `n` is then within
/// `γ(4)` of the sum of its two products' magnitudes (`n_abs`), and each dot
/// product within `γ(8) n_abs·|w|`. We use `γ(16)` in f64 (about 2e-15
/// relative) for margin and require both signs to be certain.
#[cold]
#[inline(never)]
pub(super) fn near_hit_t(ray: &TriangleRay, v: &[Vec3; 3], t_max: f32) -> Option<f32> {
    let [a, b, c] = v.map(|p| permute(p, ray.kz).as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let n = e1.cross(e2);
    let n_abs = DVec3::new(
        (e1.y * e2.z).abs() + (e1.z * e2.y).abs(),
        (e1.z * e2.x).abs() + (e1.x * e2.z).abs(),
        (e1.x * e2.y).abs() + (e1.y * e2.x).abs(),
    );
    let w = a - ray.origin.as_dvec3();
    let d = ray.dir.as_dvec3();
    let g = gamma_f64(16);
    let (num, den) = (n.dot(w), n.dot(d));
    if num.abs() <= g * n_abs.dot(w.abs()) || den.abs() <= g * n_abs.dot(d.abs()) {
        return None;
    }
    let t = (num / den) as f32;
    (t > 0.0 && t < t_max).then_some(t)
}

/// [`gamma`] for f64 arithmetic.
fn gamma_f64(n: u32) -> f64 {
    let u = f64::EPSILON * 0.5;
    n as f64 * u / (1.0 - n as f64 * u)
}

/// pbrt's bound on the rounding error of `t` (Pharr et al., 3rd ed. 3.9.6):
/// a hit closer than this may lie behind the origin. Only rays that cross
/// the triangle's interior below `t_max` pay for it.
#[inline(never)]
pub(super) fn t_error_bound(p: &[Vec3; 3], z: Vec3, e: [f32; 3], inv_det: f32) -> f32 {
    let max_z = z.abs().max_element();
    let max_x = p[0].x.abs().max(p[1].x.abs()).max(p[2].x.abs());
    let max_y = p[0].y.abs().max(p[1].y.abs()).max(p[2].y.abs());
    let delta_x = gamma(5) * (max_x + max_z);
    let delta_y = gamma(5) * (max_y + max_z);
    let delta_z = gamma(3) * max_z;
    let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    let max_e = e[0].abs().max(e[1].abs()).max(e[2].abs());
    3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv_det.abs()
}

/// The hit point rebuilt from barycentrics (more accurate than `o + t d`),
/// its error bound, and the unit normal `normalize((v1 - v0) x (v2 - v0))`.
pub fn triangle_surface_point(v: &[Vec3; 3], b1: f32, b2: f32) -> SurfacePoint {
    triangle_surface_point_with_normal(v, b1, b2, triangle_normal(v))
}

/// The unit normal of triangle `v` by its winding, `(v1 − v0) × (v2 − v0)`
/// normalised; zero for a degenerate triangle.
#[inline]
pub fn triangle_normal(v: &[Vec3; 3]) -> Vec3 {
    (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero()
}

/// [`triangle_surface_point`] given the triangle's [`triangle_normal`] `n`
/// (a scene keeps one per triangle: a hit then reads it rather than
/// computing a cross product and a square root).
#[inline]
pub fn triangle_surface_point_with_normal(
    v: &[Vec3; 3],
    b1: f32,
    b2: f32,
    n: Vec3,
) -> SurfacePoint {
    let b0 = 1.0 - b1 - b2;
    let p = b0 * v[0] + b1 * v[1] + b2 * v[2];
    let p_error = gamma(7) * ((b0 * v[0]).abs() + (b1 * v[1]).abs() + (b2 * v[2]).abs());
    SurfacePoint { p, p_error, n }
}
