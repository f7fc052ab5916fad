//! Extra layers: named RGB images an integrator fills beside the beauty
//! image, such as the light of each bounce count (`--bounce-layers`) or,
//! for bidirectional methods, the contribution of each strategy.
//!
//! The integrator declares the layer names when the film is made
//! ([`crate::integrator::layer_names`]); each camera sample then gives one
//! RGB value per layer, and every pixel keeps the f64 sum of each layer's
//! values, like [`PixelSums::radiance`](super::PixelSums::radiance). The
//! sums are added in sample-index order, pixel by pixel, exactly as the
//! beauty's, so they are as deterministic (any thread count, tiling or
//! pass split) and merge the same way (cells, sample ranges, machines: by
//! addition). A layer resolves to the sum divided by the pixel's sample
//! count: the same normalisation as the beauty, so layers that split the
//! beauty's samples add up to the beauty image.
//!
//! A film without extra layers holds an empty `Vec` (no allocation), and
//! the render loop takes its usual path, so a render that asks for none
//! pays nothing for the mechanism.

use super::Film;
use candela_image::RgbImage;
use glam::{DVec3, Vec3};

/// The extra layers of a film (or of a tile): their names and, per pixel,
/// the sum of each layer's sample values.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FilmLayers {
    names: Vec<String>,
    /// Per pixel, one sum per layer: `sums[pixel * names.len() + layer]`.
    sums: Vec<DVec3>,
}

impl FilmLayers {
    /// Zeroed sums of the layers `names` for `pixels` pixels. No names, no
    /// allocation.
    pub fn new(names: Vec<String>, pixels: usize) -> Self {
        let sums = vec![DVec3::ZERO; names.len() * pixels];
        Self { names, sums }
    }

    /// The layers' names, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Number of layers.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether there are no extra layers.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The index of the layer called `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The layer sums of pixel `i` (row-major), one per layer.
    ///
    /// # Panics
    /// If `i` is not a pixel of the film.
    pub fn pixel(&self, i: usize) -> &[DVec3] {
        let n = self.names.len();
        &self.sums[i * n..(i + 1) * n]
    }

    /// Adds one sample's layer values (one per layer) to pixel `i`'s sums.
    ///
    /// # Panics
    /// If `i` is not a pixel of the film or `values` has the wrong length.
    pub fn add(&mut self, i: usize, values: &[Vec3]) {
        let n = self.names.len();
        assert_eq!(values.len(), n, "one value per layer");
        for (sum, v) in self.sums[i * n..(i + 1) * n].iter_mut().zip(values) {
            *sum += v.as_dvec3();
        }
    }

    /// Copies pixel `from` of `other` (same layers) into pixel `to`.
    pub(crate) fn copy_pixel(&mut self, to: usize, other: &FilmLayers, from: usize) {
        let n = self.names.len();
        self.sums[to * n..(to + 1) * n].copy_from_slice(other.pixel(from));
    }

    /// Adds the sums of `other`, which has the same layers and pixels.
    pub(crate) fn merge(&mut self, other: &FilmLayers) {
        debug_assert_eq!(self.names, other.names);
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            *a += *b;
        }
    }
}

impl Film {
    /// An empty film with the extra layers `names` (see [`FilmLayers`]).
    pub fn with_layers(width: u32, height: u32, names: Vec<String>) -> Self {
        let pixels = width as usize * height as usize;
        Self {
            layers: FilmLayers::new(names, pixels),
            ..Self::new(width, height)
        }
    }

    /// An empty film of the same size and extra layers as `self`: what to
    /// merge parts of one render into.
    pub fn empty_like(&self) -> Self {
        Self::with_layers(self.width, self.height, self.layers.names.clone())
    }

    /// Extra layer `index` resolved: per pixel, the sum of its sample
    /// values over the pixel's sample count (black with no samples), plus
    /// the layer's splats over the light-subpath count (as the image).
    ///
    /// # Panics
    /// If there is no layer `index`.
    pub fn layer(&self, index: usize) -> RgbImage {
        assert!(index < self.layers.len(), "no extra layer {index}");
        let pixels = (self.pixels.iter().enumerate())
            .map(|(i, p)| {
                let sum = self.layers.pixel(i)[index];
                let mean = if p.count == 0 {
                    Vec3::ZERO
                } else {
                    (sum / p.count as f64).as_vec3()
                };
                // Light subpaths' splats of this layer (`film/splat.rs`).
                let splats = self.splats.layer_mean(i, index, self.layers.len());
                (mean + splats).to_array()
            })
            .collect();
        RgbImage::from_pixels(self.width as usize, self.height as usize, pixels)
            .expect("a film's pixel count matches its size")
    }

    /// The extra layer called `name`, resolved ([`Film::layer`]).
    pub fn layer_named(&self, name: &str) -> Option<RgbImage> {
        self.layers.index_of(name).map(|i| self.layer(i))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(n: usize) -> Vec<String> {
        (0..n).map(|k| format!("bounce_{k}")).collect()
    }

    #[test]
    fn no_layers_allocate_nothing() {
        let film = Film::new(64, 64);
        assert!(film.layers.is_empty());
        assert_eq!(film.layers.sums.capacity(), 0);
        assert_eq!(Film::with_layers(4, 4, Vec::new()), Film::new(4, 4));
    }

    #[test]
    fn layers_resolve_to_means_and_merge_by_addition() {
        let mut a = Film::with_layers(2, 1, names(2));
        let mut b = a.empty_like();
        let samples = [
            [Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO],
            [Vec3::ZERO, Vec3::splat(4.0)],
            [Vec3::splat(2.0), Vec3::splat(1.0)],
        ];
        for (i, s) in samples.iter().enumerate() {
            let film = if i == 0 { &mut a } else { &mut b };
            film.pixels[1].add_sample(s[0] + s[1]);
            film.layers.add(1, s);
        }
        a.merge(&b).expect("same size and layers");
        assert_eq!(a.pixels[1].count, 3);
        let l0 = a.layer_named("bounce_0").expect("layer 0");
        let l1 = a.layer(1);
        let close = |got: [f32; 3], want: [f32; 3]| (0..3).all(|c| (got[c] - want[c]).abs() < 1e-6);
        assert!(close(l0.pixels()[1], [1.0, 4.0 / 3.0, 5.0 / 3.0]));
        assert!(close(l1.pixels()[1], [5.0 / 3.0; 3]));
        // Pixel 0 took no samples: black, not NaN.
        assert_eq!(l0.pixels()[0], [0.0; 3]);
        // The layers split every sample, so they add up to the beauty.
        let sum = [0, 1, 2].map(|c| l0.pixels()[1][c] + l1.pixels()[1][c]);
        assert!(close(sum, a.resolve().pixels()[1]));
        assert!(a.layer_named("bounce_2").is_none());
    }

    #[test]
    fn films_with_other_layers_do_not_merge() {
        let mut a = Film::with_layers(2, 2, names(2));
        let err = a.merge(&Film::with_layers(2, 2, names(3))).unwrap_err();
        assert_eq!(
            err.to_string(),
            "cannot merge a film with layers [bounce_0, bounce_1, bounce_2] \
             into one with layers [bounce_0, bounce_1]"
        );
        assert!(a.merge(&Film::new(2, 2)).is_err());
        assert!(Film::new(2, 2).merge(&a).is_err());
    }
}
