//! Environment light: radiance arriving from infinitely far away, given by
//! an equirectangular (latitude-longitude) HDR image, importance sampled.
//!
//! # Mapping (Mitsuba 3's `envmap`, +Y up)
//! In the map's own frame, a unit direction `d` has polar angle
//! `θ = acos(d.y)` from +Y and azimuth `φ = atan2(d.x, −d.z)` in [0, 2π):
//!
//! ```text
//! u = φ / 2π      (image column, left to right)
//! v = θ / π       (image row, top to bottom: row 0 is the zenith +Y)
//! d(u, v) = (sin φ sin θ, cos θ, −cos φ sin θ)
//! ```
//!
//! so the image's left edge (`u = 0`) and its centre (`u = ½`) look toward
//! −Z and +Z, `u = ¼` toward +X and `u = ¾` toward −X: seen from inside the
//! sphere the panorama reads left to right as the viewer turns right. An
//! optional rotation about +Y ([`EnvironmentOptions::rotate_y_deg`], right
//! handed) turns the map in the world; a scale multiplies its radiance.
//!
//! # Radiance and sampling
//! How radiance between pixel centres is read is the description's choice
//! ([`EnvironmentLookup`]). `Nearest`: each pixel is constant radiance
//! over its patch of the sphere, and directions are drawn from a 2-D
//! piecewise-constant distribution ([`Distribution2D`]) over the pixels
//! with weights luminance × the row's mean `sin θ` (the Jacobian of the
//! mapping), `p(ω) = p(u, v) / (2π² sin θ)` (pbrt-v3's
//! `InfiniteAreaLight`). The two bilinear lookups sample a bilinear
//! density on the same vertex grid as the radiance
//! (`envmap_bilinear.rs`). Either way radiance and density share one
//! structure, so wherever light arrives the density is positive, and light
//! sampling alone stays unbiased.

use super::envmap_bilinear::BilinearGrid;
use super::{luminance, LightSample};
use crate::sampling::piecewise::Distribution2D;
use crate::texture::{read_linear_image, TextureError};
use candela_image::RgbImage;
pub use candela_scene::EnvironmentLookup;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;
use std::sync::Arc;

/// How an environment image is placed and scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentOptions {
    /// Multiplies every pixel's radiance.
    pub scale: f32,
    /// Rotation of the map about world +Y, in degrees (right-handed: a
    /// positive angle turns the map's −Z column toward −X).
    pub rotate_y_deg: f32,
    /// How radiance between pixel centres is read (nearest by default).
    pub lookup: EnvironmentLookup,
    /// The map's own orientation in the world (the scene's `to_world`, a
    /// rotation), applied before [`EnvironmentOptions::rotate_y_deg`].
    pub to_world: Mat3,
}

impl Default for EnvironmentOptions {
    fn default() -> Self {
        Self {
            scale: 1.0,
            rotate_y_deg: 0.0,
            lookup: EnvironmentLookup::Nearest,
            to_world: Mat3::IDENTITY,
        }
    }
}

/// An equirectangular environment map ready for shading and sampling.
#[derive(Clone, PartialEq)]
pub struct EnvironmentMap {
    width: usize,
    height: usize,
    /// Scaled linear radiance, row-major, row 0 at the zenith.
    pixels: Vec<Vec3>,
    distribution: Distribution2D,
    /// The vertex grid of a bilinear lookup; `None` reads pixels nearest.
    bilinear: Option<BilinearGrid>,
    /// World direction to map direction, and back.
    to_map: Mat3,
    to_world: Mat3,
    /// ∫ luminance(L(ω)) dω over the sphere.
    luminance_integral: f32,
}

impl std::fmt::Debug for EnvironmentMap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // Pixels and tables would flood any debug print of the light set.
        write!(f, "EnvironmentMap({}x{})", self.width, self.height)
    }
}

impl EnvironmentMap {
    /// Builds the map of `image` (negative and non-finite values count as
    /// black).
    pub fn from_image(image: &RgbImage, opts: &EnvironmentOptions) -> Result<Self, TextureError> {
        let (width, height) = image.size();
        if width == 0 || height == 0 {
            return Err(TextureError::Empty);
        }
        let scale = if opts.scale.is_finite() {
            opts.scale.max(0.0)
        } else {
            0.0
        };
        let pixels: Vec<Vec3> = image
            .pixels()
            .iter()
            .map(|p| {
                let c = Vec3::from_array(p.map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 }));
                c * scale
            })
            .collect();
        let rotation = Mat3::from_rotation_y(opts.rotate_y_deg.to_radians()) * opts.to_world;
        let (distribution, bilinear, luminance_integral) = match opts.lookup {
            EnvironmentLookup::Nearest => {
                let (distribution, integral) = pixel_distribution(&pixels, width, height);
                (distribution, None, integral)
            }
            lookup => {
                let grid = BilinearGrid::new(&pixels, width, height, lookup);
                let integral = grid.luminance_integral();
                // Unused: the grid samples itself.
                (Distribution2D::new(&[], 1), Some(grid), integral)
            }
        };
        Ok(Self {
            width,
            height,
            pixels,
            distribution,
            bilinear,
            to_map: rotation.transpose(),
            to_world: rotation,
            luminance_integral,
        })
    }

    /// Reads an equirectangular EXR (linear) or PNG (sRGB) file.
    pub fn load(path: &Path, opts: &EnvironmentOptions) -> Result<Self, TextureError> {
        Self::from_image(&read_linear_image(path)?, opts)
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// ∫ luminance(L(ω)) dω over the whole sphere (exact for the
    /// piecewise-constant map, each cell's corner mean for a bilinear one).
    pub fn luminance_integral(&self) -> f32 {
        self.luminance_integral
    }

    /// Map coordinates `(u, v)` of the world direction `w` (see the module
    /// docs).
    pub fn direction_to_uv(&self, w: Vec3) -> Vec2 {
        let d = self.to_map * w;
        let mut phi = d.x.atan2(-d.z);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let u = (phi / (2.0 * PI)).min(1.0 - f32::EPSILON / 2.0);
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        Vec2::new(u, v.min(1.0 - f32::EPSILON / 2.0))
    }

    /// The unit world direction at map coordinates `uv`.
    pub fn uv_to_direction(&self, uv: Vec2) -> Vec3 {
        let (sin_p, cos_p) = (2.0 * PI * uv.x).sin_cos();
        let (sin_t, cos_t) = (PI * uv.y).sin_cos();
        self.to_world * Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t)
    }

    /// Radiance arriving from world direction `w` (pointing away from the
    /// scene, toward the sky).
    pub fn le(&self, w: Vec3) -> Vec3 {
        let uv = self.direction_to_uv(w);
        if let Some(grid) = &self.bilinear {
            return grid.radiance(uv);
        }
        let col = ((uv.x * self.width as f32) as usize).min(self.width - 1);
        let row = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        self.pixels[row * self.width + col]
    }

    /// Density per unit solid angle with which [`EnvironmentMap::sample`]
    /// picks world direction `w`.
    pub fn pdf(&self, w: Vec3) -> f32 {
        let d = self.to_map * w;
        let sin_theta = (1.0 - d.y * d.y).max(0.0).sqrt();
        if sin_theta <= 0.0 {
            return 0.0;
        }
        let uv = self.direction_to_uv(w);
        let pdf_uv = match &self.bilinear {
            Some(grid) => grid.pdf(uv),
            None => self.distribution.pdf(uv),
        };
        pdf_uv / (2.0 * PI * PI * sin_theta)
    }

    /// Draws a direction in proportion to luminance. The density reported
    /// is [`EnvironmentMap::pdf`] of the direction returned, so the two
    /// agree to the last bit.
    pub fn sample(&self, u: Vec2) -> Option<LightSample> {
        let uv = match &self.bilinear {
            Some(grid) => grid.sample(u)?,
            None => {
                let (uv, pdf_uv) = self.distribution.sample(u);
                if pdf_uv <= 0.0 {
                    return None;
                }
                uv
            }
        };
        let wi = self.uv_to_direction(uv);
        let pdf = self.pdf(wi);
        (pdf > 0.0).then(|| LightSample {
            wi,
            l: self.le(wi),
            distance: f32::INFINITY,
            pdf,
        })
    }
}

/// The piecewise-constant sampling distribution of a nearest lookup
/// (weights luminance × the row's mean `sin θ`) and ∫ luminance dω.
fn pixel_distribution(pixels: &[Vec3], width: usize, height: usize) -> (Distribution2D, f32) {
    let mut weights = Vec::with_capacity(pixels.len());
    let mut luminance_integral = 0.0f64;
    let d_phi = 2.0 * std::f64::consts::PI / width as f64;
    for row in 0..height {
        let (cos0, cos1) = row_cosines(row, height);
        // Mean of sin θ over the row: its solid angle per unit θ.
        let d_theta = std::f64::consts::PI / height as f64;
        let mean_sin = (cos0 - cos1) / d_theta;
        for p in &pixels[row * width..(row + 1) * width] {
            let y = f64::from(luminance(*p));
            weights.push((y * mean_sin) as f32);
            luminance_integral += y * d_phi * (cos0 - cos1);
        }
    }
    (
        Distribution2D::new(&weights, width),
        luminance_integral as f32,
    )
}

/// cos θ at the top and bottom edges of image row `row` of `height`.
fn row_cosines(row: usize, height: usize) -> (f64, f64) {
    let d_theta = std::f64::consts::PI / height as f64;
    (
        (row as f64 * d_theta).cos(),
        ((row + 1) as f64 * d_theta).cos(),
    )
}

/// The environment as a light of the scene; shares its (large) map.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentLight {
    /// The map.
    pub map: Arc<EnvironmentMap>,
}

impl EnvironmentLight {
    /// Radiance arriving from direction `wi` (pointing toward the sky).
    pub fn le(&self, wi: Vec3) -> Vec3 {
        self.map.le(wi)
    }

    pub(super) fn sample_li(&self, u: Vec2) -> Option<LightSample> {
        self.map.sample(u)
    }

    pub(super) fn pdf_li(&self, wi: Vec3) -> f32 {
        self.map.pdf(wi)
    }

    /// Half the flux through a disk of the scene's radius: for a sky
    /// uniform over the upper hemisphere this is exactly the ambient
    /// light's figure, so the two compare fairly when both are present.
    pub(super) fn power(&self, scene_radius: f32) -> f32 {
        PI * scene_radius * scene_radius * 0.5 * self.map.luminance_integral
    }
}
