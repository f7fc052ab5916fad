//! The GGX (Trowbridge-Reitz) distribution of microfacet normals: D, Smith's
//! Λ, and sampling of the visible normals by Heitz 2018, "Sampling the GGX
//! Distribution of Visible Normals" (JCGT 7(4)).
//!
//! GGX is the distribution of normals of a stretched ellipsoid; stretching
//! the view by (α_x, α_y) turns the visible normals into those of a
//! hemisphere, whose projection is a disk cut by the horizon: sample that
//! disk area uniformly, lift back onto the hemisphere, unstretch. No
//! equation is solved, so it is much cheaper than Beckmann's sampler.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::sampling::warp::sin_cos_turns;

/// D(m) = 1 / (π α_x α_y (m.x²/α_x² + m.y²/α_y² + m.z²)²); zero below the
/// horizon.
pub(super) fn d(alpha_x: f32, alpha_y: f32, m: Vec3) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let s = (m.x / alpha_x).powi(2) + (m.y / alpha_y).powi(2) + m.z * m.z;
    1.0 / (PI * alpha_x * alpha_y * s * s)
}

/// Smith's Λ = (√(1 + α² tan²θ) − 1) / 2 given α(φ)·tan θ, written as
/// t / (2 (1 + √(1 + t))) with t = α² tan²θ, free of cancellation for
/// directions near the normal.
pub(super) fn lambda(alpha_tan: f64) -> f32 {
    if alpha_tan.is_infinite() {
        return f32::INFINITY;
    }
    let t = alpha_tan * alpha_tan;
    (t / (2.0 * (1.0 + (1.0 + t).sqrt()))) as f32
}

/// A normal visible from `wo` (`wo.z > 0`), distributed as
/// G1(wo)·max(0, wo·m)·D(m) / cos θo.
pub(super) fn sample_visible_normal(alpha_x: f32, alpha_y: f32, wo: Vec3, u: Vec2) -> Vec3 {
    // The view in the stretched (hemisphere) configuration, and a basis
    // around it.
    let v = Vec3::new(alpha_x * wo.x, alpha_y * wo.y, wo.z).normalize();
    let len2 = v.x * v.x + v.y * v.y;
    let t1 = if len2 > 0.0 {
        Vec3::new(-v.y, v.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2 = v.cross(t1);
    // A uniform point of the projected visible area: the unit disk whose
    // half on the far side of the horizon is squeezed by s = (1 + v.z)/2
    // (the part of the hemisphere's projection the horizon hides).
    let r = u.x.sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    let p1 = r * cos_phi;
    let s = 0.5 * (1.0 + v.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * sin_phi;
    let lift = (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    let n = p1 * t1 + p2 * t2 + lift * v;
    Vec3::new(alpha_x * n.x, alpha_y * n.y, n.z.max(1e-7)).normalize()
}
