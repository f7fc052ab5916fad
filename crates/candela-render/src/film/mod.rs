//! The film: per-pixel sums that merge by addition.
//!
//! Each pixel keeps the sums of its radiance samples and of their squares,
//! the sums of their illuminance (luminance) and of its square, the sums of
//! the first-hit albedo and shading normal (denoiser AOVs), of the first-hit
//! distance (depth) with the number of samples that hit, of the traversal
//! work (BVH nodes visited, primitive tests: the cost AOV), and the sample
//! count. Tiles, threads, cells, sample ranges and machines merge by adding
//! these sums, and the adaptive sampler's confidence test
//! ([`adaptive::converged`]) reads the same numbers (Tungsten's
//! `SampleRecord`). The image is resolved only at the end. A film may also
//! carry extra named RGB layers ([`layers`]) that merge the same way.
//!
//! Light tracing and BDPT also add *splats* to pixels other than the
//! sample's own; they are kept apart, in exact fixed-point sums
//! ([`splat`]), and added to the camera samples' mean when resolving.

pub mod adaptive;
pub mod denoised;
pub mod layers;
pub mod output;
mod rect;
pub mod splat;
mod sums;
pub mod wire;

pub use adaptive::Adaptive;
pub use denoised::{denoise_film, denoised_path, write_denoised};
pub use layers::FilmLayers;
pub use output::{write_film, OutputError, OutputFormat, OutputOptions};
pub use rect::PixelRect;
pub use splat::{Splat, SplatLayer};
pub use sums::{luminance, CostMeasure, PixelSums, SampleValue};

use candela_image::{GrayImage, RgbImage};
use glam::Vec3;

/// A `width` × `height` grid of [`PixelSums`], row-major, y = 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per-pixel sums.
    pub pixels: Vec<PixelSums>,
    /// Light subpaths' splats (empty for unidirectional renders).
    pub splats: SplatLayer,
    /// Extra named layers (none unless the integrator declared some).
    pub layers: FilmLayers,
}

/// Why two films cannot be merged.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FilmMismatch {
    /// The films differ in size.
    #[error("cannot merge a {b_w}x{b_h} film into a {a_w}x{a_h} film")]
    Size {
        /// Width of the film merged into.
        a_w: u32,
        /// Its height.
        a_h: u32,
        /// Width of the film merged.
        b_w: u32,
        /// Its height.
        b_h: u32,
    },
    /// The films carry different extra layers.
    #[error("cannot merge a film with layers [{}] into one with layers [{}]", .b.join(", "), .a.join(", "))]
    Layers {
        /// Layers of the film merged into.
        a: Vec<String>,
        /// Layers of the film merged.
        b: Vec<String>,
    },
}

/// The smallest, mean and largest sample count over some pixels: what a
/// time-budgeted or adaptive render reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleSpread {
    /// Fewest samples of any pixel.
    pub min: u32,
    /// Mean samples per pixel.
    pub mean: f64,
    /// Most samples of any pixel.
    pub max: u32,
}

impl Film {
    /// An empty film: every pixel black with no samples.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSums::default(); width as usize * height as usize],
            splats: SplatLayer::default(),
            layers: FilmLayers::default(),
        }
    }

    /// The whole frame as a rectangle.
    pub fn rect(&self) -> PixelRect {
        PixelRect::full(self.width, self.height)
    }

    /// The sums of pixel (x, y).
    ///
    /// # Panics
    /// If (x, y) lies outside the film.
    pub fn pixel(&self, x: u32, y: u32) -> &PixelSums {
        &self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Adds another film of the same size and extra layers, pixel by
    /// pixel. Merging is how cells, sample ranges or machines combine: the
    /// sums of disjoint cells give the full frame exactly (adding zero is
    /// exact); two sample ranges give the union up to f64 rounding
    /// (addition is not associative). Splats merge exactly in every case
    /// (fixed point, see [`splat`]).
    pub fn merge(&mut self, other: &Film) -> Result<(), FilmMismatch> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(FilmMismatch::Size {
                a_w: self.width,
                a_h: self.height,
                b_w: other.width,
                b_h: other.height,
            });
        }
        if self.layers.names() != other.layers.names() {
            return Err(FilmMismatch::Layers {
                a: self.layers.names().to_vec(),
                b: other.layers.names().to_vec(),
            });
        }
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
        self.splats.merge(&other.splats);
        self.layers.merge(&other.layers);
        Ok(())
    }

    /// The image: mean radiance per pixel, plus the pixel's splats over
    /// all light subpaths ([`splat`]).
    pub fn resolve(&self) -> RgbImage {
        if self.splats.light_paths == 0 {
            return self.rgb(PixelSums::mean);
        }
        let pixels = (self.pixels.iter().enumerate())
            .map(|(i, p)| (p.mean() + self.splats.mean(i)).to_array())
            .collect();
        RgbImage::from_pixels(self.width as usize, self.height as usize, pixels)
            .expect("a film's pixel count matches its size")
    }

    /// Mean first-hit albedo per pixel (black where nothing was hit).
    pub fn albedo(&self) -> RgbImage {
        self.rgb(PixelSums::mean_albedo)
    }

    /// Mean first-hit shading normal per pixel, facing the camera, in world
    /// space; not renormalised, as denoisers expect (zero where nothing was
    /// hit).
    pub fn normal(&self) -> RgbImage {
        self.rgb(PixelSums::mean_normal)
    }

    /// Mean distance along the camera rays to the first hit, per pixel, over
    /// the samples whose camera ray hit something; +inf where none did
    /// (nothing there, not "at the camera").
    pub fn depth(&self) -> GrayImage {
        self.gray(PixelSums::mean_depth)
    }

    /// Traversal work per sample of each pixel: BVH nodes visited and/or
    /// primitive tests of all the rays of a sample (camera, bounce and
    /// shadow rays), averaged over the pixel's samples. See
    /// [`candela_image::heat_image`] to show it.
    pub fn cost(&self, measure: CostMeasure) -> GrayImage {
        self.gray(|p| p.mean_cost(measure))
    }

    /// Standard error of each pixel's mean radiance, per channel (of the
    /// camera samples only: splats keep no squares).
    pub fn std_error(&self) -> RgbImage {
        self.rgb(PixelSums::std_error)
    }

    /// Variance of each pixel's mean radiance, per channel (+inf below two
    /// samples): the EXR `variance` layer.
    pub fn variance(&self) -> RgbImage {
        self.rgb(|p| p.variance_of_mean().as_vec3())
    }

    /// Samples taken per pixel, as an image.
    pub fn sample_count_image(&self) -> GrayImage {
        self.gray(|p| p.count as f32)
    }

    fn gray(&self, f: impl Fn(&PixelSums) -> f32) -> GrayImage {
        let values = self.pixels.iter().map(f).collect();
        GrayImage::from_values(self.width as usize, self.height as usize, values)
            .expect("a film's pixel count matches its size")
    }

    fn rgb(&self, f: impl Fn(&PixelSums) -> Vec3) -> RgbImage {
        let pixels = self.pixels.iter().map(|p| f(p).to_array()).collect();
        RgbImage::from_pixels(self.width as usize, self.height as usize, pixels)
            .expect("a film's pixel count matches its size")
    }

    /// Samples taken per pixel.
    pub fn sample_counts(&self) -> Vec<u32> {
        self.pixels.iter().map(|p| p.count).collect()
    }

    /// Sample-count spread over the pixels of `rect` (all zero if `rect` is
    /// empty or outside the film).
    pub fn sample_spread(&self, rect: PixelRect) -> SampleSpread {
        let rect = rect.clamped(self.width, self.height);
        let (mut min, mut max, mut total) = (u32::MAX, 0, 0u64);
        for (x, y) in rect.pixels() {
            let n = self.pixel(x, y).count;
            min = min.min(n);
            max = max.max(n);
            total += n as u64;
        }
        if rect.area() == 0 {
            return SampleSpread::default();
        }
        SampleSpread {
            min,
            mean: total as f64 / rect.area() as f64,
            max,
        }
    }
}

#[cfg(test)]
mod tests;
