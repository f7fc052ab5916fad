//! Uniform sampling of the solid angle a triangle or a rectangle subtends
//! from a point: the light-sampling warps of planar lamps.
//!
//! - Triangles: Arvo, "Stratified sampling of spherical triangles"
//!   (SIGGRAPH 1995). `u0` picks the sub-triangle `A B C'` holding that
//!   fraction of the solid angle (C' slides along the arc A→C), `u1` a point
//!   on the arc B→C' whose cosine to B is uniform.
//! - Rectangles: Ureña, Fajardo, King, "An area-preserving parametrization
//!   for spherical rectangles" (EGSR 2013). `u0` fixes the x of the point by
//!   inverting the solid angle of the strip left of it, `u1` the y by a
//!   uniform height on the great circle through it.
//!
//! Both are evaluated in `f64`: the area of a spherical triangle from its
//! angles, `α + β + γ − π`, cancels catastrophically in `f32` once the
//! triangle is small (pbrt-v4 stops sampling below 3·10⁻⁴ sr for that
//! reason), and `f64` costs little beside the trigonometry. The density
//! (1 / solid angle) uses Van Oosterom and Strackee's formula ("The solid
//! angle of a plane triangle", IEEE TBME 1983), exact for tiny triangles
//! too. Points are given relative to the viewpoint.

use std::f64::consts::PI;

use glam::{DVec3, Vec2, Vec3};

/// The solid angle of the triangle `a b c` (corners relative to the
/// viewpoint) by Van Oosterom and Strackee:
/// `tan(Ω/2) = |a·(b×c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|)`.
/// No cancellation for small triangles; `atan2` handles Ω > π.
pub fn triangle_solid_angle(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c)).abs();
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    (2.0 * numerator.atan2(denominator)) as f32
}

/// The angle between unit vectors, accurate near 0 and π (unlike `acos`).
fn angle_between(v1: DVec3, v2: DVec3) -> f64 {
    if v1.dot(v2) < 0.0 {
        PI - 2.0 * ((v1 + v2).length() / 2.0).min(1.0).asin()
    } else {
        2.0 * ((v2 - v1).length() / 2.0).min(1.0).asin()
    }
}

/// `v` minus its component along unit `axis`, normalised: the tangent at
/// `axis` of the great circle toward `v`.
fn tangent_toward(v: DVec3, axis: DVec3) -> Option<DVec3> {
    (v - v.dot(axis) * axis).try_normalize()
}

/// A direction uniform in the solid angle of the triangle `v` (corners
/// relative to the viewpoint), by Arvo's method; `None` for a triangle
/// seen edge-on or degenerate. Density 1 / [`triangle_solid_angle`].
pub fn square_to_spherical_triangle(v: [Vec3; 3], u: Vec2) -> Option<Vec3> {
    let a = v[0].as_dvec3().try_normalize()?;
    let b = v[1].as_dvec3().try_normalize()?;
    let c = v[2].as_dvec3().try_normalize()?;
    // Normals of the great circles through the edges; the angle at a
    // corner is the one between its two edges' planes.
    let n_ab = a.cross(b).try_normalize()?;
    let n_bc = b.cross(c).try_normalize()?;
    let n_ca = c.cross(a).try_normalize()?;
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - PI;
    if area.is_nan() || area <= 0.0 {
        return None;
    }
    // The sub-triangle A B C' of area u0·Ω: Arvo's closed form for the
    // cosine of the arc A→C'.
    let sub_area = f64::from(u.x) * area;
    let (s, t) = (sub_area - alpha).sin_cos();
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let p = t - cos_alpha;
    let q = s + sin_alpha * a.dot(b);
    let cos_arc = ((q * t - p * s) * cos_alpha - q) / ((q * s + p * t) * sin_alpha);
    let cos_arc = if cos_arc.is_nan() {
        1.0
    } else {
        cos_arc.clamp(-1.0, 1.0)
    };
    let sin_arc = (1.0 - cos_arc * cos_arc).max(0.0).sqrt();
    let c_sub = cos_arc * a + sin_arc * tangent_toward(c, a)?;
    // Along the arc B→C', uniform in 1 − cos of the angle from B.
    let one_minus_z = f64::from(u.y) * (1.0 - c_sub.dot(b));
    let z = 1.0 - one_minus_z;
    let sin_z = (one_minus_z * (2.0 - one_minus_z)).max(0.0).sqrt();
    let w = z * b + sin_z * tangent_toward(c_sub, b)?;
    Some(w.normalize().as_vec3())
}

/// The solid angle of the rectangle `corner + s·edge0 + t·edge1`
/// (corner relative to the viewpoint), as two triangles.
pub fn rectangle_solid_angle(corner: Vec3, edge0: Vec3, edge1: Vec3) -> f32 {
    let far = corner + edge0 + edge1;
    triangle_solid_angle(corner, corner + edge0, far)
        + triangle_solid_angle(corner, far, corner + edge1)
}

/// A point of the rectangle `corner + s·edge0 + t·edge1` (corner relative
/// to the viewpoint, edges orthogonal) whose direction is uniform in the
/// solid angle the rectangle subtends (Ureña et al. 2013); `None` when the
/// viewpoint is in its plane. Density 1 / [`rectangle_solid_angle`] per
/// steradian. Returns the point relative to the viewpoint, so callers get
/// the distance without intersecting.
pub fn square_to_spherical_rectangle(
    corner: Vec3,
    edge0: Vec3,
    edge1: Vec3,
    u: Vec2,
) -> Option<Vec3> {
    let (corner, edge0, edge1) = (corner.as_dvec3(), edge0.as_dvec3(), edge1.as_dvec3());
    let (len0, len1) = (edge0.length(), edge1.length());
    let x = edge0.try_normalize()?;
    let y = tangent_toward(edge1, x)?;
    let mut z = x.cross(y);
    // The local frame of the paper: the rectangle at height z0 < 0.
    let mut z0 = corner.dot(z);
    if z0 > 0.0 {
        z = -z;
        z0 = -z0;
    }
    if z0.is_nan() || z0 >= 0.0 {
        return None;
    }
    let (x0, y0) = (corner.dot(x), corner.dot(y));
    let (x1, y1) = (x0 + len0, y0 + len1);
    // Inner normals of the four planes through the viewpoint and an edge
    // (in closed form), and the rectangle's interior angles between them.
    let n0 = DVec3::new(0.0, z0, -y0) / (z0 * z0 + y0 * y0).sqrt();
    let n1 = DVec3::new(-z0, 0.0, x1) / (z0 * z0 + x1 * x1).sqrt();
    let n2 = DVec3::new(0.0, -z0, y1) / (z0 * z0 + y1 * y1).sqrt();
    let n3 = DVec3::new(z0, 0.0, -x0) / (z0 * z0 + x0 * x0).sqrt();
    let g0 = angle_between(-n0, n1);
    let g1 = angle_between(-n1, n2);
    let g2 = angle_between(-n2, n3);
    let g3 = angle_between(-n3, n0);
    let k = 2.0 * PI - g2 - g3;
    let area = g0 + g1 - k;
    if area.is_nan() || area <= 0.0 {
        return None;
    }
    // x of the point: the strip [x0, xu] holds u0 of the solid angle. The
    // paper's cu = sign(fu) / sqrt(fu² + b0²) with fu = num / den is
    // rewritten without dividing by den = sin(au), which vanishes at au = π.
    let (b0, b1) = (n0.z, n2.z);
    let au = f64::from(u.x) * area + k;
    let (den, cos_au) = au.sin_cos();
    let num = cos_au * b0 - b1;
    let norm = (num * num + b0 * b0 * den * den).sqrt();
    let cu = if norm > 0.0 {
        (num.signum() * den / norm).clamp(-1.0 + 1e-12, 1.0 - 1e-12)
    } else {
        0.0
    };
    let xu = (-(cu * z0) / (1.0 - cu * cu).sqrt()).clamp(x0, x1);
    // y of the point: uniform in the height of its direction along the
    // great circle at that x.
    let d = (xu * xu + z0 * z0).sqrt();
    let h0 = y0 / (d * d + y0 * y0).sqrt();
    let h1 = y1 / (d * d + y1 * y1).sqrt();
    let hv = h0 + f64::from(u.y) * (h1 - h0);
    let hv2 = hv * hv;
    let yv = if hv2 < 1.0 - 1e-12 {
        (hv * d / (1.0 - hv2).sqrt()).clamp(y0, y1)
    } else {
        y1
    };
    Some((xu * x + yv * y + z0 * z).as_vec3())
}
