//! The per-pixel sample stream: (seed, pixel, index, dimension) → [0, 1).

use glam::Vec2;

use super::hash::{combine, pixel_hash, unit_f32};
use super::sobol::{laine_karras, sobol_dim1_reversed_and_reverse};

/// Which point set a [`Sampler`] draws from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum SamplerKind {
    /// Independent uniform values from an integer hash: simple, unbiased,
    /// and the reference the stratified sampler is tested against.
    Independent,
    /// Owen-scrambled, index-shuffled Sobol points padded per dimension
    /// (Burley 2020): lower variance at equal sample counts, best with
    /// power-of-two sample counts.
    #[default]
    Sobol,
}

/// A dimension passed over by [`Sampler::skip_one`], whose value can still
/// be drawn during the same pixel sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SkippedDimension(u32);

/// A deterministic source of sample values.
///
/// Call [`Sampler::start_pixel_sample`] before each pixel sample, then draw
/// with [`Sampler::next_1d`] / [`Sampler::next_2d`]. The `d`-th value after
/// `start_pixel_sample(px, py, i)` depends only on (seed, px, py, i, d) and
/// the kind: no state carries over between pixel samples, so threads and
/// machines can render any subset of samples and agree exactly.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    seed: u64,
    pixel: u64,
    index: u32,
    /// `index` with its bits reversed, the Sobol code's working order.
    index_reversed: u32,
    dimension: u32,
}

impl Sampler {
    /// A sampler of the given kind; `seed` selects one of many independent
    /// renders of the same scene.
    pub fn new(kind: SamplerKind, seed: u64) -> Self {
        Self {
            kind,
            seed,
            pixel: pixel_hash(seed, 0, 0),
            index: 0,
            index_reversed: 0,
            dimension: 0,
        }
    }

    /// The point set this sampler draws from.
    pub fn kind(&self) -> SamplerKind {
        self.kind
    }

    /// Positions the stream at sample `index` of pixel (`px`, `py`),
    /// dimension 0.
    pub fn start_pixel_sample(&mut self, px: u32, py: u32, index: u32) {
        self.pixel = pixel_hash(self.seed, px, py);
        self.index = index;
        self.index_reversed = index.reverse_bits();
        self.dimension = 0;
    }

    /// The number of dimensions consumed since the last
    /// [`Sampler::start_pixel_sample`]; `next_2d` consumes two.
    pub fn dimension(&self) -> u32 {
        self.dimension
    }

    /// The next value in [0, 1).
    pub fn next_1d(&mut self) -> f32 {
        let dim = self.take_dimensions(1);
        self.value_1d(dim)
    }

    /// Passes over the next dimension, as [`Sampler::skip`] does, and
    /// returns it, so that code which needs its value only sometimes (a
    /// light's choice when the point's own number cannot make it, see
    /// `light/select.rs`) draws it with [`Sampler::draw_skipped`] only then.
    pub fn skip_one(&mut self) -> SkippedDimension {
        SkippedDimension(self.take_dimensions(1))
    }

    /// The value [`Sampler::next_1d`] would have given in place of
    /// `skipped` (a dimension of the current pixel sample).
    pub fn draw_skipped(&self, skipped: SkippedDimension) -> f32 {
        self.value_1d(skipped.0)
    }

    /// The one-dimensional value of dimension `dim` of the current pixel
    /// sample.
    fn value_1d(&self, dim: u32) -> f32 {
        match self.kind {
            SamplerKind::Independent => unit_f32(self.independent_bits(dim)),
            SamplerKind::Sobol => {
                // owen(sobol_dim0(j), k2) with j = owen(i, k1), where
                // owen(v, s) = rev(lk(rev(v), s)) and sobol_dim0 = rev:
                // the value is rev(lk(j, k2)).
                let key = combine(self.pixel, dim);
                let j = laine_karras(self.index_reversed, key as u32).reverse_bits();
                unit_f32(laine_karras(j, (key >> 32) as u32).reverse_bits())
            }
        }
    }

    /// The next pair of values in [0, 1)², stratified jointly by the Sobol
    /// sampler (prefer it over two `next_1d` calls for 2-D decisions such as
    /// a direction or a point on a light).
    pub fn next_2d(&mut self) -> Vec2 {
        let dim = self.take_dimensions(2);
        match self.kind {
            SamplerKind::Independent => Vec2::new(
                unit_f32(self.independent_bits(dim)),
                unit_f32(self.independent_bits(dim + 1)),
            ),
            SamplerKind::Sobol => {
                // (owen(sobol_dim0(j), k2), owen(sobol_dim1(j), k3)) with
                // j = owen(i, k1) = rev(t): x = rev(lk(j, k2)) as in
                // next_1d, and rev(sobol_dim1(j)) = sobol_dim1_reversed(t).
                // Both reversals of t come from one table lookup, and the
                // two output reversals are one 64-bit reversal of (y, x):
                // rev64(y << 32 | x) = rev(x) << 32 | rev(y).
                let key = combine(self.pixel, dim);
                let scramble = combine(key, u32::MAX);
                let t = laine_karras(self.index_reversed, key as u32);
                let (t_dim1, t_reversed) = sobol_dim1_reversed_and_reverse(t);
                let x = laine_karras(t_reversed, (key >> 32) as u32);
                let y = laine_karras(t_dim1, scramble as u32);
                let both = ((u64::from(y) << 32) | u64::from(x)).reverse_bits();
                Vec2::new(unit_f32((both >> 32) as u32), unit_f32(both as u32))
            }
        }
    }

    /// Skips `count` dimensions, as if they had been drawn: code that
    /// leaves out a step (a bounce view skipping a vertex's light samples)
    /// keeps every later decision on the dimensions a full render uses.
    pub fn skip(&mut self, count: u32) {
        self.take_dimensions(count);
    }

    fn take_dimensions(&mut self, count: u32) -> u32 {
        let dim = self.dimension;
        self.dimension = self.dimension.wrapping_add(count);
        dim
    }

    fn independent_bits(&self, dim: u32) -> u32 {
        (combine(combine(self.pixel, self.index), dim) >> 32) as u32
    }
}
