//! The Beckmann distribution of microfacet normals: D, Smith's Λ, and
//! sampling of the normals visible from a direction (Heitz & d'Eon 2014,
//! "Importance Sampling Microfacet-Based BSDFs using the Distribution of
//! Visible Normals").
//!
//! Slopes (−m.x/m.z, −m.y/m.z) are independent Gaussians of variances
//! α_x²/2 and α_y²/2. Sampling stretches the configuration to α = 1, where
//! seen from a direction at angle θ in the xz-plane the visible slope density
//! is proportional to (cot θ − x)·exp(−x²)/√π for x < cot θ, times the
//! unchanged density of y; both marginals are inverted numerically, rotated
//! to the azimuth of `wo`, and unstretched.

use std::f32::consts::PI;

use glam::{DVec3, Vec2, Vec3};

use super::special::{erf, erf_inv, erfc, solve_increasing};

/// Beyond this many standard deviations slopes are treated as impossible.
const SLOPE_LIMIT: f64 = 6.0;

/// D(m) for roughness (α_x, α_y); zero below the horizon.
pub(super) fn d(alpha_x: f32, alpha_y: f32, m: Vec3) -> f32 {
    let cos2 = m.z * m.z;
    if m.z <= 0.0 || cos2 == 0.0 {
        return 0.0;
    }
    let exponent = ((m.x / alpha_x).powi(2) + (m.y / alpha_y).powi(2)) / cos2;
    // Beyond e^-80 the density is zero in f32 anyway, and cos⁴ may have
    // underflowed, which would turn 0/0 into NaN.
    if exponent > 80.0 {
        return 0.0;
    }
    (-exponent).exp() / (PI * alpha_x * alpha_y * cos2 * cos2)
}

/// Smith's Λ given α(φ)·tan θ of the direction: with a = 1 / (α tan θ),
/// Λ = (exp(−a²) / (a√π) − erfc(a)) / 2, written with erfc so that it stays
/// accurate as both terms vanish for steep slopes.
pub(super) fn lambda(alpha_tan: f64) -> f32 {
    if alpha_tan == 0.0 {
        return 0.0;
    }
    if alpha_tan.is_infinite() {
        return f32::INFINITY;
    }
    let a = 1.0 / alpha_tan;
    if a > 30.0 {
        return 0.0;
    }
    let value = ((-a * a).exp() / (a * std::f64::consts::PI.sqrt()) - erfc(a)) / 2.0;
    value.max(0.0) as f32
}

/// A normal visible from `wo` (`wo.z > 0`), distributed as
/// G1(wo)·max(0, wo·m)·D(m) / cos θo.
pub(super) fn sample_visible_normal(alpha_x: f32, alpha_y: f32, wo: Vec3, u: Vec2) -> Vec3 {
    let (ax, ay) = (f64::from(alpha_x), f64::from(alpha_y));
    let stretched =
        DVec3::new(ax * f64::from(wo.x), ay * f64::from(wo.y), f64::from(wo.z)).normalize();
    let sin_theta = (1.0 - stretched.z * stretched.z).max(0.0).sqrt();
    let (cos_phi, sin_phi) = if sin_theta > 1e-9 {
        (stretched.x / sin_theta, stretched.y / sin_theta)
    } else {
        (1.0, 0.0)
    };
    let x = visible_slope_x(stretched.z, sin_theta, f64::from(u.x));
    let y = erf_inv((2.0 * f64::from(u.y) - 1.0).clamp(-1.0 + 1e-15, 1.0 - 1e-15));
    let (sx, sy) = (cos_phi * x - sin_phi * y, sin_phi * x + cos_phi * y);
    Vec3::new((-ax * sx) as f32, (-ay * sy) as f32, 1.0).normalize()
}

/// Inverts the CDF of the x slope seen from angle θ (α = 1):
/// C(x) = μ(1 + erf x)/2 + exp(−x²)/(2√π), μ = cot θ, for x ≤ μ.
fn visible_slope_x(cos_theta: f64, sin_theta: f64, u: f64) -> f64 {
    if sin_theta < 1e-6 {
        // Seen from straight above every normal is equally visible per
        // projected area: the plain slope distribution.
        return erf_inv((2.0 * u - 1.0).clamp(-1.0 + 1e-15, 1.0 - 1e-15));
    }
    let mu = cos_theta / sin_theta;
    let inv_sqrt_pi = 1.0 / std::f64::consts::PI.sqrt();
    let cdf = |x: f64| 0.5 * mu * (1.0 + erf(x)) + 0.5 * inv_sqrt_pi * (-x * x).exp();
    let density = |x: f64| ((mu - x) * inv_sqrt_pi * (-x * x).exp()).max(1e-300);
    let hi = mu.min(SLOPE_LIMIT);
    solve_increasing(cdf, density, u * cdf(hi), -SLOPE_LIMIT, hi)
}
