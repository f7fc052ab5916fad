//! Delta lights: point, spot and directional. They cannot be hit by rays,
//! only sampled; their "pdf" is 1 by convention.

use super::{luminance, LightSample};
use glam::Vec3;
use std::f32::consts::PI;

/// An isotropic point light: radiant intensity `I` (W/sr), irradiance
/// `I / r²` at distance `r` (the CS184 program dropped the falloff; physics
/// keeps it).
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// World position.
    pub position: Vec3,
    /// Radiant intensity per channel.
    pub intensity: Vec3,
}

impl PointLight {
    pub(super) fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        toward_point(self.position, self.intensity, p)
    }

    pub(super) fn power(&self) -> f32 {
        4.0 * PI * luminance(self.intensity)
    }
}

/// Light from an isotropic point of intensity `intensity` arriving at `p`:
/// the inverse-square law every point-like light shares.
fn toward_point(position: Vec3, intensity: Vec3, p: Vec3) -> Option<LightSample> {
    let d = position - p;
    let dist2 = d.length_squared();
    if dist2 == 0.0 {
        return None;
    }
    let distance = dist2.sqrt();
    Some(LightSample {
        wi: d / distance,
        l: intensity / dist2,
        distance,
        pdf: 1.0,
    })
}

/// A point light restricted to a cone around `direction`, with intensity
/// `I · cos(θ)^exponent` inside the cone (COLLADA's falloff exponent).
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    /// World position.
    pub position: Vec3,
    /// Unit cone axis.
    pub direction: Vec3,
    /// Intensity on the axis.
    pub intensity: Vec3,
    /// Cosine of the half cone angle.
    pub cos_cutoff: f32,
    /// Falloff exponent.
    pub exponent: f32,
}

impl SpotLight {
    pub(super) fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        let mut sample = toward_point(self.position, self.intensity, p)?;
        let cos = (-sample.wi).dot(self.direction);
        if cos < self.cos_cutoff {
            return None;
        }
        let falloff = if self.exponent > 0.0 {
            cos.max(0.0).powf(self.exponent)
        } else {
            1.0
        };
        sample.l *= falloff;
        Some(sample)
    }

    pub(super) fn power(&self) -> f32 {
        // Solid angle of the cone; the falloff is ignored (an upper bound is
        // enough to choose among lights).
        2.0 * PI * (1.0 - self.cos_cutoff) * luminance(self.intensity)
    }
}

/// Light arriving from one direction with irradiance `E` on a surface that
/// faces it (sunlight).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: Vec3,
    /// Irradiance on a surface facing the light.
    pub irradiance: Vec3,
}

impl DirectionalLight {
    pub(super) fn sample_li(&self) -> LightSample {
        LightSample {
            wi: -self.direction,
            l: self.irradiance,
            distance: f32::INFINITY,
            pdf: 1.0,
        }
    }

    pub(super) fn power(&self, scene_radius: f32) -> f32 {
        PI * scene_radius * scene_radius * luminance(self.irradiance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_light_falls_off_with_inverse_square() {
        let light = PointLight {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity: Vec3::splat(8.0),
        };
        let s = light.sample_li(Vec3::ZERO).unwrap();
        assert_eq!(s.wi, Vec3::Y);
        assert_eq!(s.distance, 2.0);
        assert_eq!(s.l, Vec3::splat(2.0));
    }

    #[test]
    fn spot_light_is_dark_outside_its_cone() {
        let light = SpotLight {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: -Vec3::Y,
            intensity: Vec3::ONE,
            cos_cutoff: 30f32.to_radians().cos(),
            exponent: 0.0,
        };
        assert!(light.sample_li(Vec3::ZERO).is_some());
        assert!(light.sample_li(Vec3::new(1.0, 0.0, 0.0)).is_none());
    }
}
