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

use super::surface::{gamma, SurfacePoint};
use glam::Vec3;

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

/// Intersects the prepared ray with triangle `v` for `t` in `(0, t_max)`.
#[inline(always)]
pub fn intersect_triangle(ray: &TriangleRay, v: &[Vec3; 3], t_max: f32) -> Option<TriangleHit> {
    let s = ray.shear;
    let p = v.map(|p| {
        let a = permute(p, ray.kz) - ray.origin;
        Vec3::new(a.x + s.x * a.z, a.y + s.y * a.z, a.z)
    });
    let e0 = p[1].x * p[2].y - p[1].y * p[2].x;
    let e1 = p[2].x * p[0].y - p[2].y * p[0].x;
    let e2 = p[0].x * p[1].y - p[0].y * p[1].x;
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
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
        return None;
    }
    if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
        return None;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    // Written so that a NaN (from a determinant that underflows) rejects.
    if !(t < t_max && t > t_error_bound(&p, z, [e0, e1, e2], inv_det)) {
        return None;
    }
    Some(TriangleHit {
        t,
        b1: e1 * inv_det,
        b2: e2 * inv_det,
    })
}

/// pbrt's bound on the rounding error of `t` (Pharr et al., 3rd ed. 3.9.6):
/// a hit closer than this may lie behind the origin. Only hits pay for it.
#[cold]
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
    let b0 = 1.0 - b1 - b2;
    let p = b0 * v[0] + b1 * v[1] + b2 * v[2];
    let p_error = gamma(7) * ((b0 * v[0]).abs() + (b1 * v[1]).abs() + (b2 * v[2]).abs());
    let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
    SurfacePoint { p, p_error, n }
}
