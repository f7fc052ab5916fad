//! Uniform directions in the solid angle a triangle subtends from a point:
//! Arvo, "Stratified sampling of spherical triangles", SIGGRAPH 1995.
//!
//! Area sampling a light and converting to solid angle gives directions
//! with density `d² / (A cos θ_l)`, which varies wildly across a light that
//! is near or seen at a slant; uniform solid-angle sampling has the constant
//! density `1 / Ω`, so the light-sampling estimator's variance is only that
//! of the BSDF and cosine.
//!
//! Arvo's construction: pick the sub-triangle `A B C'` (with `C'` on the arc
//! `AC`) whose area is `u0 · Ω`, then a point on the arc `B C'` with `1 -
//! cos` linear in `u1`; both steps are inverse CDFs, so the map is a
//! bijection with an inverse ([`SphericalTriangle::to_square`]).
//!
//! Everything is computed in f64: the angles and areas involve differences
//! of nearly equal numbers for small or thin triangles, and the cost is
//! dominated by the few trigonometric calls anyway. Callers should still
//! fall back to area sampling for very small solid angles (see
//! `crate::light::AreaLight`), where nothing is gained and digits are lost.

use glam::{DVec3, Vec2, Vec3};

/// The triangle `v` seen from a point, set up for sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphericalTriangle {
    /// Unit directions to the vertices.
    a: DVec3,
    b: DVec3,
    c: DVec3,
    /// Solid angle (the spherical triangle's area).
    solid_angle: f64,
    /// The angle at vertex `a`, and `cos` of the arc `ab`.
    alpha: f64,
    cos_c: f64,
}

/// The area of the spherical triangle with unit vertices `a`, `b`, `c`, by
/// Van Oosterom and Strackee's formula `tan(Ω/2) = |a·(b×c)| / (1 + a·b +
/// b·c + c·a)` (no cancellation between the angles, unlike Girard's
/// `α + β + γ − π`).
fn spherical_area(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let det = a.dot(b.cross(c)).abs();
    2.0 * det.atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a))
}

/// `v` minus its component along the unit vector `axis`, normalised.
fn orthogonal_part(v: DVec3, axis: DVec3) -> DVec3 {
    (v - v.dot(axis) * axis).normalize_or_zero()
}

impl SphericalTriangle {
    /// The triangle with corners `v` seen from `p`; `None` when `p` is one
    /// of the corners.
    pub fn new(p: Vec3, v: &[Vec3; 3]) -> Option<Self> {
        let p = p.as_dvec3();
        let [a, b, c] = v.map(|q| (q.as_dvec3() - p).normalize_or_zero());
        if a == DVec3::ZERO || b == DVec3::ZERO || c == DVec3::ZERO {
            return None;
        }
        // The angle at `a` between the arcs to `b` and `c`: its cosine and
        // sine times |a×b||a×c| are b·c − (a·b)(a·c) and |a·(b×c)|.
        let det = a.dot(b.cross(c)).abs();
        let alpha = det.atan2(b.dot(c) - a.dot(b) * a.dot(c));
        Some(Self {
            a,
            b,
            c,
            solid_angle: spherical_area(a, b, c),
            alpha,
            cos_c: a.dot(b),
        })
    }

    /// The solid angle the triangle subtends, in steradians.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// Density of [`SphericalTriangle::sample`] per steradian, inside the
    /// triangle: `1 / Ω`.
    pub fn pdf(&self) -> f32 {
        (1.0 / self.solid_angle) as f32
    }

    /// A uniformly distributed unit direction inside the triangle.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let (a, b) = (self.a, self.b);
        let (u0, u1) = (f64::from(u.x), f64::from(u.y));
        // Arvo's step 1: the cosine of the arc from `a` to `c'` for which
        // the sub-triangle `a b c'` has area u0·Ω (spherical trigonometry).
        let (sin_alpha, cos_alpha) = self.alpha.sin_cos();
        let (s, t) = (u0 * self.solid_angle - self.alpha).sin_cos();
        let (du, dv) = (t - cos_alpha, s + sin_alpha * self.cos_c);
        let q = (((dv * t - du * s) * cos_alpha - dv) / ((dv * s + du * t) * sin_alpha))
            .clamp(-1.0, 1.0);
        let c1 = q * a + (1.0 - q * q).max(0.0).sqrt() * orthogonal_part(self.c, a);
        // Step 2: along the arc from `b` toward `c'`, uniform in 1 − cos.
        let z = 1.0 - u1 * (1.0 - c1.dot(b));
        let w = z * b + (1.0 - z * z).max(0.0).sqrt() * orthogonal_part(c1, b);
        w.normalize().as_vec3()
    }

    /// The square point [`SphericalTriangle::sample`] maps to direction `w`
    /// (inside the triangle): `c'` is where the great circle through `b`
    /// and `w` meets the arc `ac`.
    pub fn to_square(&self, w: Vec3) -> Vec2 {
        let (a, b, c) = (self.a, self.b, self.c);
        let w = w.as_dvec3().normalize();
        let mut c1 = b.cross(w).cross(a.cross(c)).normalize_or_zero();
        if c1 == DVec3::ZERO {
            return Vec2::ZERO; // w is b itself (or a): every u0 maps there
        }
        if c1.dot(a + c) < 0.0 {
            c1 = -c1;
        }
        let u0 = spherical_area(a, b, c1) / self.solid_angle;
        let u1 = (1.0 - w.dot(b)) / (1.0 - c1.dot(b));
        Vec2::new(u0 as f32, u1 as f32).clamp(Vec2::ZERO, Vec2::ONE)
    }

    /// Whether direction `w` from the point lies inside the triangle (on
    /// the inner side of the three great circles of its edges).
    pub fn contains(&self, w: Vec3) -> bool {
        let (a, b, c) = (self.a, self.b, self.c);
        let w = w.as_dvec3();
        let orient = a.dot(b.cross(c)).signum();
        [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(p, q)| orient * w.dot(p.cross(*q)) >= 0.0)
    }
}
