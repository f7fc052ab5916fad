//! The Henyey–Greenstein phase function (Henyey and Greenstein 1941), the
//! one lobe pbrt-v4 and Mitsuba 3 give homogeneous media.
//!
//! Directions follow the BSDFs' convention: `wo` points back toward where
//! the light goes (the previous vertex), `wi` toward where it comes from,
//! so forward scattering (`g > 0`) puts `wi` near `-wo`, and the phase
//! function reads `cos θ = -wo · wi` between the propagation directions.

use crate::geometry::Frame;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Below this |g| the lobe is sampled as the isotropic one (the inverse
/// CDF divides by g).
const ISOTROPIC_BELOW: f32 = 1e-3;

/// A Henyey–Greenstein lobe of asymmetry `g` in (-1, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f32,
}

impl HenyeyGreenstein {
    /// The lobe of asymmetry `g`, clamped into (-1, 1) where it is a density.
    pub fn new(g: f32) -> Self {
        Self {
            g: g.clamp(-0.999, 0.999),
        }
    }

    /// Its asymmetry: the mean cosine between the propagation directions.
    pub fn g(&self) -> f32 {
        self.g
    }

    /// The density over solid angle of scattering from propagation
    /// direction `-wo` into `-wi`; also the value (the phase function is
    /// normalised and sampled exactly).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        let g = self.g;
        let denom = 1.0 + g * g + 2.0 * g * wo.dot(wi);
        (1.0 - g * g) / (4.0 * PI * denom * denom.max(0.0).sqrt())
    }

    /// A direction `wi` drawn in proportion to [`HenyeyGreenstein::eval`],
    /// and its density.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> (Vec3, f32) {
        let g = self.g;
        // cos of the angle to the propagation direction -wo, by inverting
        // the lobe's CDF in that cosine.
        let cos_theta = if g.abs() < ISOTROPIC_BELOW {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
            ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
        };
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let forward = Frame::from_normal(-wo);
        let local = Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
        // The path goes on along wi, at angle θ from where it was going.
        let wi = forward.to_world(local);
        (wi, self.eval(wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::Chi2Test;

    /// Every lobe's sampling against its density, from a tilted `wo`.
    #[test]
    fn sampling_matches_the_density() {
        let wo = Vec3::new(0.3, -0.5, 0.81).normalize();
        for g in [-0.7, 0.0, 0.3, 0.9] {
            let hg = HenyeyGreenstein::new(g);
            Chi2Test::sphere(&format!("Henyey-Greenstein g = {g}"))
                .run(
                    |u| {
                        let (wi, pdf) = hg.sample(wo, Vec2::new(u[0], u[1]));
                        Some((wi, pdf))
                    },
                    |wi| hg.eval(wo, wi),
                )
                .assert_ok();
        }
    }

    /// The lobe integrates to one and its mean cosine between propagation
    /// directions is g (by quadrature over the cosine, independent of the
    /// sampling code).
    #[test]
    fn density_is_normalised_with_mean_cosine_g() {
        for g in [-0.8f32, -0.2, 0.0, 0.5, 0.95] {
            let hg = HenyeyGreenstein::new(g);
            let wo = Vec3::Z;
            let n = 200_000;
            let (mut total, mut mean_cos) = (0.0f64, 0.0f64);
            for i in 0..n {
                // Midpoint rule in μ = -wo · wi, the cosine between the
                // directions before and after scattering.
                let mu = -1.0 + (2.0 * (i as f64 + 0.5)) / n as f64;
                let wi = Vec3::new((1.0 - mu * mu).sqrt() as f32, 0.0, -mu as f32);
                let p = f64::from(hg.eval(wo, wi)) * 2.0 * std::f64::consts::PI * (2.0 / n as f64);
                total += p;
                mean_cos += p * mu;
            }
            assert!((total - 1.0).abs() < 2e-3, "g = {g}: ∫p = {total}");
            assert!(
                (mean_cos - f64::from(g)).abs() < 2e-3,
                "g = {g}: mean cos {mean_cos}"
            );
        }
    }
}
