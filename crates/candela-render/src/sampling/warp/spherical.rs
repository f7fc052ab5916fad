//! Warps to directions: hemispheres, the sphere and cones around +Z.

use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};

use super::planar::{concentric_disk_to_square, square_to_concentric_disk};
use super::trig::sin_cos_turns;

/// The direction at height `z` and azimuth `2π·v`, given sin²θ directly so
/// callers can compute it without cancellation.
fn direction(z: f32, sin2_theta: f32, v: f32) -> Vec3 {
    let r = sin2_theta.max(0.0).sqrt();
    let (sin, cos) = sin_cos_turns(v);
    Vec3::new(r * cos, r * sin, z)
}

/// The azimuth of `w` as a fraction of a turn, in [0, 1).
fn azimuth_fraction(w: Vec3) -> f32 {
    let f = w.y.atan2(w.x) / (2.0 * PI);
    let f = if f < 0.0 { f + 1.0 } else { f };
    if f >= 1.0 {
        0.0
    } else {
        f
    }
}

/// A uniform direction on the hemisphere z ≥ 0 (z = u0, φ = 2π·u1).
/// Solid-angle density [`uniform_hemisphere_pdf`].
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    direction(u.x, (1.0 - u.x) * (1.0 + u.x), u.y)
}

/// Inverse of [`square_to_uniform_hemisphere`].
pub fn uniform_hemisphere_to_square(w: Vec3) -> Vec2 {
    Vec2::new(w.z.clamp(0.0, 1.0), azimuth_fraction(w))
}

/// 1 / (2π) per steradian on z ≥ 0, zero below.
pub fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 {
        0.5 * FRAC_1_PI
    } else {
        0.0
    }
}

/// A uniform direction on the unit sphere (z = 1 − 2·u0, φ = 2π·u1).
/// Solid-angle density [`uniform_sphere_pdf`].
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    direction(z, 4.0 * u.x * (1.0 - u.x), u.y)
}

/// Inverse of [`square_to_uniform_sphere`].
pub fn uniform_sphere_to_square(w: Vec3) -> Vec2 {
    Vec2::new(((1.0 - w.z) * 0.5).clamp(0.0, 1.0), azimuth_fraction(w))
}

/// 1 / (4π) per steradian.
pub fn uniform_sphere_pdf(_w: Vec3) -> f32 {
    0.25 * FRAC_1_PI
}

/// A cosine-weighted direction on z ≥ 0 (Malley's method): a uniform point
/// of the concentric disk lifted to the hemisphere. Importance sampling for
/// diffuse reflection. Solid-angle density [`cosine_hemisphere_pdf`].
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = square_to_concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    d.extend(z)
}

/// Inverse of [`square_to_cosine_hemisphere`]: project onto the disk.
pub fn cosine_hemisphere_to_square(w: Vec3) -> Vec2 {
    concentric_disk_to_square(w.truncate())
}

/// cos θ / π per steradian on z ≥ 0, zero below.
pub fn cosine_hemisphere_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) * FRAC_1_PI
}

/// A uniform direction in the cone of directions within angle θmax of +Z,
/// given `cos_max = cos θmax`: how a sphere light is sampled by the solid
/// angle it subtends. Solid-angle density [`uniform_cone_pdf`].
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    // 1 − cos θ and sin²θ from it, exact even for tiny cones.
    let one_minus_cos = u.x * (1.0 - cos_max);
    let z = 1.0 - one_minus_cos;
    direction(z, one_minus_cos * (2.0 - one_minus_cos), u.y)
}

/// Inverse of [`square_to_uniform_cone`].
pub fn uniform_cone_to_square(w: Vec3, cos_max: f32) -> Vec2 {
    let u0 = (1.0 - w.z) / (1.0 - cos_max);
    Vec2::new(u0.clamp(0.0, 1.0), azimuth_fraction(w))
}

/// 1 / (2π (1 − cos θmax)) per steradian inside the cone, zero outside.
pub fn uniform_cone_pdf(w: Vec3, cos_max: f32) -> f32 {
    if w.z >= cos_max {
        1.0 / (2.0 * PI * (1.0 - cos_max))
    } else {
        0.0
    }
}
