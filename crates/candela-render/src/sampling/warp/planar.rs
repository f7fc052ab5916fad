//! Warps to planar domains: the unit disk, triangles and parallelograms.

use std::f32::consts::{FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

use super::trig::sin_cos_within_quarter_pi;

/// Shirley and Chiu's concentric map from [0, 1)² to the unit disk.
///
/// It maps concentric squares to concentric circles, so strata stay compact
/// and nearly equal in shape (unlike the polar map `r = sqrt(u)`), which
/// keeps stratified samples stratified after warping. Area measure, density
/// [`uniform_disk_pdf`].
pub fn square_to_concentric_disk(u: Vec2) -> Vec2 {
    let a = 2.0 * u - Vec2::ONE;
    if a == Vec2::ZERO {
        return Vec2::ZERO;
    }
    // φ = (π/4)(a_y/a_x) in the first case; π/2 − (π/4)(a_x/a_y) in the
    // second, whose cosine and sine are the sine and cosine of the part
    // within ±π/4 (so the polynomial covers both).
    if a.x.abs() > a.y.abs() {
        let (sin, cos) = sin_cos_within_quarter_pi(FRAC_PI_4 * (a.y / a.x));
        a.x * Vec2::new(cos, sin)
    } else {
        let (sin, cos) = sin_cos_within_quarter_pi(FRAC_PI_4 * (a.x / a.y));
        a.y * Vec2::new(sin, cos)
    }
}

/// Inverse of [`square_to_concentric_disk`] for points of the unit disk.
///
/// In the region |x| ≥ |y| the map has φ = (π/4)·(a_y / a_x) with radius
/// a_x (signed), hence a_y = a_x·(4/π)·atan(y / x); symmetrically otherwise.
pub fn concentric_disk_to_square(p: Vec2) -> Vec2 {
    let r = p.length();
    let a = if r == 0.0 {
        Vec2::ZERO
    } else if p.x.abs() >= p.y.abs() {
        let ax = r.copysign(p.x);
        Vec2::new(ax, ax * (p.y / p.x).atan() / FRAC_PI_4)
    } else {
        let ay = r.copysign(p.y);
        Vec2::new(ay * (p.x / p.y).atan() / FRAC_PI_4, ay)
    };
    ((a + Vec2::ONE) * 0.5).clamp(Vec2::ZERO, Vec2::ONE)
}

/// Density of a uniform point on the unit disk, per unit area (zero outside).
pub fn uniform_disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 {
        1.0 / PI
    } else {
        0.0
    }
}

/// A uniform point on a triangle as barycentrics `(b0, b1)`, `b2 = 1 − b0 − b1`
/// (the square-root map: `b0 = 1 − √u0`, `b1 = u1·√u0`).
///
/// It is chosen over Heitz's lower-distortion map because its inverse is
/// closed-form and cheap. Density [`uniform_triangle_pdf`].
pub fn square_to_uniform_triangle(u: Vec2) -> Vec2 {
    let s = u.x.sqrt();
    Vec2::new(1.0 - s, u.y * s)
}

/// Inverse of [`square_to_uniform_triangle`].
pub fn uniform_triangle_to_square(b: Vec2) -> Vec2 {
    let s = 1.0 - b.x;
    let v = if s > 0.0 {
        (b.y / s).clamp(0.0, 1.0)
    } else {
        0.0
    };
    Vec2::new((s * s).clamp(0.0, 1.0), v)
}

/// Density of [`square_to_uniform_triangle`] per unit area of the
/// barycentric (b0, b1) plane: 2 inside the reference triangle, whose area is
/// 1/2. On a world-space triangle the density per unit area is `1 / area`.
pub fn uniform_triangle_pdf(b: Vec2) -> f32 {
    if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 {
        2.0
    } else {
        0.0
    }
}

/// A parallelogram `origin + s·edge0 + t·edge1`, (s, t) ∈ [0, 1]²: the shape
/// of CS184's area lights and of rectangles in general.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parallelogram {
    /// One corner.
    pub origin: Vec3,
    /// The edge from `origin` along the first parameter.
    pub edge0: Vec3,
    /// The edge from `origin` along the second parameter.
    pub edge1: Vec3,
}

impl Parallelogram {
    /// Its area, |edge0 × edge1|.
    pub fn area(&self) -> f32 {
        self.edge0.cross(self.edge1).length()
    }

    /// A uniformly distributed point: the map is affine, so uniform in, uniform out.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        self.origin + u.x * self.edge0 + u.y * self.edge1
    }

    /// Density of [`Parallelogram::sample`] per unit area (for points on it).
    pub fn pdf(&self) -> f32 {
        1.0 / self.area()
    }

    /// The parameters (s, t) of point `p` (projected onto the plane): the
    /// inverse of [`Parallelogram::sample`], by the dual basis
    /// `(edge1 × n, n × edge0) / |n|²` with `n = edge0 × edge1`.
    pub fn to_square(&self, p: Vec3) -> Vec2 {
        let n = self.edge0.cross(self.edge1);
        let d = p - self.origin;
        Vec2::new(d.dot(self.edge1.cross(n)), d.dot(n.cross(self.edge0))) / n.length_squared()
    }
}
