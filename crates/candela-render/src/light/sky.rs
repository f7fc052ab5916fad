//! A procedural sky for environment lighting without image files: a
//! vertical gradient from horizon to zenith, a darker ground and a sun
//! disk, written as an equirectangular image in [`super::EnvironmentMap`]'s
//! mapping.

use candela_image::{ImageError, RgbImage};
use glam::Vec3;
use std::f32::consts::PI;

/// Parameters of the procedural sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProceduralSky {
    /// Radiance straight up.
    pub zenith: Vec3,
    /// Radiance at the horizon (blended toward the zenith with height).
    pub horizon: Vec3,
    /// Radiance of every direction below the horizon.
    pub ground: Vec3,
    /// Unit direction toward the sun's centre.
    pub sun_direction: Vec3,
    /// Angular radius of the sun disk in degrees.
    pub sun_radius_deg: f32,
    /// Radiance of the sun disk.
    pub sun: Vec3,
}

impl Default for ProceduralSky {
    fn default() -> Self {
        Self {
            zenith: Vec3::new(0.25, 0.45, 0.9),
            horizon: Vec3::new(0.9, 0.9, 1.0),
            ground: Vec3::splat(0.1),
            sun_direction: Vec3::new(0.5, 0.7, 0.3).normalize(),
            sun_radius_deg: 6.0,
            sun: Vec3::new(40.0, 36.0, 30.0),
        }
    }
}

impl ProceduralSky {
    /// Radiance from unit direction `w` (world, +Y up).
    pub fn radiance(&self, w: Vec3) -> Vec3 {
        let cos_sun = (self.sun_radius_deg.to_radians()).cos();
        if w.dot(self.sun_direction) >= cos_sun {
            return self.sun;
        }
        if w.y < 0.0 {
            return self.ground;
        }
        self.horizon.lerp(self.zenith, w.y.sqrt())
    }

    /// The sky as a `width` × `height` equirectangular image, each pixel
    /// the radiance at its centre's direction.
    pub fn image(&self, width: usize, height: usize) -> Result<RgbImage, ImageError> {
        RgbImage::from_fn(width, height, |x, y| {
            let phi = 2.0 * PI * (x as f32 + 0.5) / width as f32;
            let theta = PI * (y as f32 + 0.5) / height as f32;
            let w = Vec3::new(
                phi.sin() * theta.sin(),
                theta.cos(),
                -phi.cos() * theta.sin(),
            );
            self.radiance(w).to_array()
        })
    }
}
