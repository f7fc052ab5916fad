//! The film: per-pixel sums that merge by addition.
//!
//! Each pixel keeps the sum of its radiance samples, the sum of their
//! illuminance (luminance) and of its square, and the sample count. Tiles,
//! threads, sample ranges and machines merge by adding these sums, and the
//! adaptive sampler's confidence test reads the same numbers (Tungsten's
//! `SampleRecord`). The image is resolved only at the end.

use glam::{DVec3, Vec3};

/// Rec. 709 luminance of a linear RGB colour.
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The sums kept for one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSums {
    /// Sum of radiance samples.
    pub radiance: DVec3,
    /// Sum of the samples' luminance.
    pub lum: f64,
    /// Sum of the squared luminance.
    pub lum_sq: f64,
    /// Number of samples.
    pub count: u32,
}

impl PixelSums {
    /// Adds one radiance sample.
    pub fn add_sample(&mut self, l: Vec3) {
        let y = luminance(l) as f64;
        self.radiance += l.as_dvec3();
        self.lum += y;
        self.lum_sq += y * y;
        self.count += 1;
    }

    /// Adds another pixel's sums (merging sample sets).
    pub fn merge(&mut self, other: &PixelSums) {
        self.radiance += other.radiance;
        self.lum += other.lum;
        self.lum_sq += other.lum_sq;
        self.count += other.count;
    }

    /// The pixel's estimate: the mean radiance (black with no samples).
    pub fn mean(&self) -> Vec3 {
        if self.count == 0 {
            Vec3::ZERO
        } else {
            (self.radiance / self.count as f64).as_vec3()
        }
    }
}

/// A `width` × `height` grid of [`PixelSums`], row-major, y = 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per-pixel sums.
    pub pixels: Vec<PixelSums>,
}

impl Film {
    /// An empty film.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSums::default(); width as usize * height as usize],
        }
    }

    /// The sums of pixel (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> &PixelSums {
        &self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Adds another film of the same size, pixel by pixel.
    ///
    /// # Panics
    /// If the sizes differ: merging films of different renders is a bug.
    pub fn merge(&mut self, other: &Film) {
        assert_eq!(
            (self.width, self.height),
            (other.width, other.height),
            "films of different sizes"
        );
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
    }

    /// The image: mean radiance per pixel, row-major.
    pub fn resolve(&self) -> Vec<Vec3> {
        self.pixels.iter().map(PixelSums::mean).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_sums_equals_adding_all_samples_to_one_pixel() {
        let samples = [
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(0.5, 0.0, 0.25),
            Vec3::new(4.0, 4.0, 4.0),
        ];
        let mut all = PixelSums::default();
        samples.iter().for_each(|&s| all.add_sample(s));
        let mut a = PixelSums::default();
        a.add_sample(samples[0]);
        let mut b = PixelSums::default();
        b.add_sample(samples[1]);
        b.add_sample(samples[2]);
        a.merge(&b);
        assert_eq!(a.count, 3);
        assert!((a.radiance - all.radiance).length() < 1e-12);
        assert!((a.lum_sq - all.lum_sq).abs() < 1e-12);
        let mean = a.mean();
        assert!((mean - Vec3::new(5.5, 6.0, 7.25) / 3.0).length() < 1e-6);
    }

    #[test]
    fn empty_pixel_resolves_to_black() {
        assert_eq!(PixelSums::default().mean(), Vec3::ZERO);
        assert!((luminance(Vec3::ONE) - 1.0).abs() < 1e-6);
    }
}
