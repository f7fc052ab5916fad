//! Sampling the Beckmann distribution of *visible* normals (Heitz & d'Eon
//! 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution
//! of Visible Normals").
//!
//! Sampling only normals that `wo` can see avoids the wasted and
//! high-weight samples of plain D(h)·cos θh sampling at grazing angles: the
//! weight f·cos/pdf becomes F·G2/G1, at most 1 with F = 1.
//!
//! Method: stretch the configuration so that α = 1; there the slopes (x, y)
//! are independent normals of variance 1/2, and seen from a direction at
//! angle θ in the xz-plane, the visible slope density is proportional to
//! (cot θ − x)·exp(−x²)/√π for x < cot θ, times the unchanged density of y.
//! Invert both marginals numerically, rotate to the azimuth of `wo`, and
//! unstretch.

use std::f64::consts::PI;

use glam::{Vec2, Vec3};

use super::special::{erf, erf_inv, solve_increasing};

/// Beyond this many standard deviations slopes are treated as impossible.
const SLOPE_LIMIT: f64 = 6.0;

/// A microfacet normal visible from `wo` (`wo.z > 0`), distributed as
/// G1(wo)·max(0, wo·h)·D(h) / cos θo, for Beckmann roughness `alpha`.
pub(crate) fn sample_visible_normal(alpha: f32, wo: Vec3, u: Vec2) -> Vec3 {
    let alpha = f64::from(alpha);
    let stretched = glam::DVec3::new(
        alpha * f64::from(wo.x),
        alpha * f64::from(wo.y),
        f64::from(wo.z),
    )
    .normalize();
    let sin_theta = (1.0 - stretched.z * stretched.z).max(0.0).sqrt();
    let (cos_phi, sin_phi) = if sin_theta > 1e-9 {
        (stretched.x / sin_theta, stretched.y / sin_theta)
    } else {
        (1.0, 0.0)
    };
    let x = visible_slope_x(stretched.z, sin_theta, f64::from(u.x));
    let y = erf_inv((2.0 * f64::from(u.y) - 1.0).clamp(-1.0 + 1e-15, 1.0 - 1e-15));
    let (sx, sy) = (cos_phi * x - sin_phi * y, sin_phi * x + cos_phi * y);
    Vec3::new((-alpha * sx) as f32, (-alpha * sy) as f32, 1.0).normalize()
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
    let inv_sqrt_pi = 1.0 / PI.sqrt();
    let cdf = |x: f64| 0.5 * mu * (1.0 + erf(x)) + 0.5 * inv_sqrt_pi * (-x * x).exp();
    let density = |x: f64| ((mu - x) * inv_sqrt_pi * (-x * x).exp()).max(1e-300);
    let hi = mu.min(SLOPE_LIMIT);
    solve_increasing(cdf, density, u * cdf(hi), -SLOPE_LIMIT, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::microfacet::Beckmann;
    use crate::sampling::chi2::Chi2Test;

    #[test]
    fn visible_normals_match_their_density() {
        // The density of visible normals, D_wo(h) = G1(wo) max(0, wo·h) D(h) / cos θo.
        for alpha in [0.1f32, 0.5, 1.0] {
            let dist = Beckmann::new(alpha);
            for theta in [0.0f32, 0.8, 1.4, 1.56] {
                let wo = Vec3::new(theta.sin() * 0.6, theta.sin() * 0.8, theta.cos());
                let g1 = 1.0 / (1.0 + dist.lambda(wo));
                let pdf = move |h: Vec3| g1 * wo.dot(h).max(0.0) * dist.d(h) / wo.z;
                Chi2Test::sphere(&format!("visible normals α = {alpha} θ = {theta}"))
                    .run(
                        |u| {
                            let h = sample_visible_normal(alpha, wo, Vec2::new(u[0], u[1]));
                            Some((h, pdf(h)))
                        },
                        pdf,
                    )
                    .assert_ok();
            }
        }
    }
}
