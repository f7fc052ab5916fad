//! Uniform directions in the solid angle a rectangle subtends from a point:
//! Ureña, Fajardo, King, "An Area-Preserving Parametrization for Spherical
//! Rectangles", EGSR 2013.
//!
//! In the rectangle's frame (`x`, `y` along its edges, `z` toward the point
//! side, the point at the origin) the rectangle spans `[x0, x1] × [y0, y1]`
//! at height `z0 < 0`. The spherical rectangle's area is `Ω = γ0 + γ1 − k`
//! with `γ_i` its inner angles and `k = 2π − γ2 − γ3`. The first uniform
//! number picks the abscissa `xu` at which the part left of `xu` has area
//! `u0 · Ω` (closed form); the second places the point on that vertical
//! line uniformly in the sine of its elevation `h = y / sqrt(xu² + z0² +
//! y²)`, which is uniform in solid angle along the line. As for
//! [`super::SphericalTriangle`], the arithmetic is in f64, and callers fall
//! back to area sampling for tiny solid angles.

use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::TAU;

/// A rectangle seen from a point, set up for sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphericalRectangle {
    /// World axes of the rectangle's frame (`z` toward the point's side).
    x: DVec3,
    y: DVec3,
    z: DVec3,
    /// Local extents (the point at the origin) and the height `z0 < 0`.
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    /// `n0.z` and `n2.z` of the edge-plane normals, and `k`.
    b0: f64,
    b1: f64,
    k: f64,
    solid_angle: f64,
}

impl SphericalRectangle {
    /// The rectangle `corner + s·edge0 + t·edge1`, `(s, t) ∈ [0, 1]²`,
    /// with perpendicular edges, seen from `p`; `None` when `p` lies in its
    /// plane or an edge is degenerate.
    pub fn new(p: Vec3, corner: Vec3, edge0: Vec3, edge1: Vec3) -> Option<Self> {
        let (e0, e1) = (edge0.as_dvec3(), edge1.as_dvec3());
        let (len0, len1) = (e0.length(), e1.length());
        if len0 == 0.0 || len1 == 0.0 {
            return None;
        }
        let (x, y) = (e0 / len0, e1 / len1);
        let mut z = x.cross(y);
        let d = corner.as_dvec3() - p.as_dvec3();
        let mut z0 = d.dot(z);
        if z0 == 0.0 {
            return None;
        }
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let (x1, y1) = (x0 + len0, y0 + len1);
        let corner_at = |cx: f64, cy: f64| DVec3::new(cx, cy, z0);
        let (v00, v01, v10, v11) = (
            corner_at(x0, y0),
            corner_at(x0, y1),
            corner_at(x1, y0),
            corner_at(x1, y1),
        );
        // Unit normals of the planes through the point and each edge.
        let n0 = v00.cross(v10).normalize();
        let n1 = v10.cross(v11).normalize();
        let n2 = v11.cross(v01).normalize();
        let n3 = v01.cross(v00).normalize();
        let angle = |m: DVec3, n: DVec3| (-m.dot(n)).clamp(-1.0, 1.0).acos();
        let (g0, g1, g2, g3) = (angle(n0, n1), angle(n1, n2), angle(n2, n3), angle(n3, n0));
        let k = TAU - g2 - g3;
        Some(Self {
            x,
            y,
            z,
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: n0.z,
            b1: n2.z,
            k,
            solid_angle: g0 + g1 - k,
        })
    }

    /// The solid angle the rectangle subtends, in steradians.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// Density of [`SphericalRectangle::sample`] per steradian, inside the
    /// rectangle: `1 / Ω`.
    pub fn pdf(&self) -> f32 {
        (1.0 / self.solid_angle) as f32
    }

    /// A uniformly distributed unit direction inside the rectangle, and the
    /// distance along it to the rectangle.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (u0, u1) = (f64::from(u.x), f64::from(u.y));
        let z0 = self.z0;
        // The abscissa splitting off area u0·Ω.
        let au = u0 * self.solid_angle + self.k;
        let fu = (au.cos() * self.b0 - self.b1) / au.sin();
        let cu = (1.0 / (fu * fu + self.b0 * self.b0).sqrt())
            .copysign(fu)
            .clamp(-1.0, 1.0);
        let xu = (-(cu * z0) / (1.0 - cu * cu).sqrt()).clamp(self.x0, self.x1);
        // Uniform in the sine of the elevation along the line x = xu.
        let d2 = xu * xu + z0 * z0;
        let h0 = self.y0 / (d2 + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d2 + self.y1 * self.y1).sqrt();
        let hv = h0 + u1 * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 {
            (hv * d2.sqrt() / (1.0 - hv2).sqrt()).clamp(self.y0, self.y1)
        } else {
            self.y1
        };
        let local = DVec3::new(xu, yv, z0);
        let distance = local.length();
        let w = (local.x * self.x + local.y * self.y + local.z * self.z) / distance;
        (w.as_vec3(), distance as f32)
    }
}
