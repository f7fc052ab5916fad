//! Splats: what light subpaths add to pixels other than the one whose
//! sample traced them, kept so that the film stays bit-for-bit
//! deterministic for any thread count, tiling, pass schedule, cell split
//! and sample split.
//!
//! # Design
//!
//! - **Ownership.** Every light subpath belongs to one camera-film sample
//!   (pixel, index): the light tracer and BDPT trace exactly one light
//!   subpath per camera sample, from the sampler positioned at that
//!   (pixel, index). The work split is therefore the one the render loop
//!   already has, and a light subpath is a pure function of (seed, pixel,
//!   index), like every camera path.
//! - **Exact, order-free sums.** A splat may land on any pixel, so two
//!   threads (or two machines) add into the same pixel in an order nobody
//!   controls. Floating-point addition would then depend on the schedule.
//!   Instead each splat is rounded *once* to fixed point, an integer
//!   number of [`SPLAT_QUANTUM`] = 2⁻⁴⁰ radiance units per channel, and
//!   the per-pixel sums are `i128`: integer addition is associative and
//!   commutative, so the sums are exactly the same whatever the order,
//!   and [`SplatLayer::merge`] (cells, sample ranges, Dask workers) is
//!   exact too. A splat of magnitude at least [`MAX_SPLAT`] (2⁶⁰ per
//!   channel, never met by a finite render) or non-finite is not added but
//!   counted in [`SplatLayer::invalid`], like the film's invalid samples.
//!   Range: the sum of a pixel can reach 2⁸⁷ ≈ 1.5·10²⁶, i.e. 2²⁷ splats of
//!   the largest size, or ~10¹⁸ splats of a million; resolution 9·10⁻¹³,
//!   far below f32 noise.
//! - **Resolving.** A pixel's value is the mean of its camera samples
//!   (the film's [`super::PixelSums`]) plus its splat sum divided by the
//!   total number of light subpaths of the whole film
//!   ([`SplatLayer::light_paths`]): every light subpath is an independent
//!   estimate of the whole image (Veach 1997 §10.3.4, pbrt-v4's
//!   `RGBFilm::AddSplat` with the division by the sample count at the end).
//!   Candela's film is the filtered mean per pixel, so the integrators
//!   splat importance-weighted values already multiplied by the pixel
//!   count (see the camera's importance docs), one splat per pixel the
//!   reconstruction filter covers, weighted by it (`bdpt::splat_at`; one
//!   splat for the default one-pixel box).
//!
//! A film without splats (every unidirectional render) keeps an empty
//! buffer and costs nothing.

use glam::{DVec3, Vec3};

/// Bits after the binary point of the fixed-point splat sums.
pub const SPLAT_FRACTION_BITS: u32 = 40;
/// The value of one unit of the fixed-point sums: 2⁻⁴⁰.
pub const SPLAT_QUANTUM: f64 = 1.0 / (1u64 << SPLAT_FRACTION_BITS) as f64;
/// Splats whose magnitude reaches this (per channel) are counted invalid.
pub const MAX_SPLAT: f32 = (1u64 << 60) as f32;

/// One contribution of a light subpath to a pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Splat {
    /// Pixel column.
    pub x: u32,
    /// Pixel row (0 at the top).
    pub y: u32,
    /// Radiance times the pixel count (see the module docs).
    pub value: Vec3,
    /// Which sums it goes to: 0 the image, k ≥ 1 the film's extra layer
    /// k − 1 (per-strategy layers of BDPT).
    pub layer: u32,
}

/// Per-pixel fixed-point splat sums and the light-subpath count.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SplatLayer {
    /// Fixed-point sums per pixel (row-major), in units of
    /// [`SPLAT_QUANTUM`]; empty until the first splat or merge.
    pub sums: Vec<[i128; 3]>,
    /// Light subpaths traced into this film (splatting or not).
    pub light_paths: u64,
    /// Splats dropped as non-finite or too large.
    pub invalid: u64,
    /// Fixed-point sums of the extra layers, `layer_sums[pixel · n + k]`
    /// for the film's n extra layers; empty until a layer splat arrives.
    pub layer_sums: Vec<[i128; 3]>,
}

/// The fixed-point value of one channel, or `None` if it cannot be added.
fn to_fixed(v: f32) -> Option<i128> {
    (v.is_finite() && v.abs() < MAX_SPLAT)
        .then(|| (v as f64 * (1u64 << SPLAT_FRACTION_BITS) as f64).round() as i128)
}

impl SplatLayer {
    /// Whether nothing was ever splatted or counted here.
    pub fn is_empty(&self) -> bool {
        self.sums.is_empty() && self.light_paths == 0 && self.invalid == 0
    }

    /// Adds `splats` to a film of `width` × `height` pixels with `layers`
    /// extra layers; splats outside it (never produced by a camera) or for
    /// a layer it does not have are counted invalid.
    pub fn add(&mut self, width: u32, height: u32, layers: usize, splats: &[Splat]) {
        if splats.is_empty() {
            return;
        }
        let n = width as usize * height as usize;
        if self.sums.len() != n {
            self.sums = vec![[0; 3]; n];
        }
        for s in splats {
            let fixed = [
                to_fixed(s.value.x),
                to_fixed(s.value.y),
                to_fixed(s.value.z),
            ];
            let inside = s.x < width && s.y < height && (s.layer as usize) <= layers;
            let ([Some(r), Some(g), Some(b)], true) = (fixed, inside) else {
                self.invalid += 1;
                continue;
            };
            let pixel = s.y as usize * width as usize + s.x as usize;
            let sum = if s.layer == 0 {
                &mut self.sums[pixel]
            } else {
                if self.layer_sums.len() != n * layers {
                    self.layer_sums = vec![[0; 3]; n * layers];
                }
                &mut self.layer_sums[pixel * layers + s.layer as usize - 1]
            };
            sum[0] += r;
            sum[1] += g;
            sum[2] += b;
        }
    }

    /// Adds another film's splats (same pixel count): exact.
    pub fn merge(&mut self, other: &SplatLayer) {
        if !other.sums.is_empty() {
            if self.sums.is_empty() {
                self.sums = vec![[0; 3]; other.sums.len()];
            }
            for (a, b) in self.sums.iter_mut().zip(&other.sums) {
                for c in 0..3 {
                    a[c] += b[c];
                }
            }
        }
        if !other.layer_sums.is_empty() {
            if self.layer_sums.is_empty() {
                self.layer_sums = vec![[0; 3]; other.layer_sums.len()];
            }
            for (a, b) in self.layer_sums.iter_mut().zip(&other.layer_sums) {
                for c in 0..3 {
                    a[c] += b[c];
                }
            }
        }
        self.light_paths += other.light_paths;
        self.invalid += other.invalid;
    }

    /// What extra layer `k` (of `layers`) of pixel `i` gets from splats:
    /// their sum over all light subpaths (zero with none).
    pub fn layer_mean(&self, i: usize, k: usize, layers: usize) -> Vec3 {
        match self.layer_sums.get(i * layers + k) {
            Some(s) if self.light_paths > 0 => {
                let sum = DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64) * SPLAT_QUANTUM;
                (sum / self.light_paths as f64).as_vec3()
            }
            _ => Vec3::ZERO,
        }
    }

    /// The splat sum of pixel `i` in radiance units (f64).
    pub fn sum(&self, i: usize) -> DVec3 {
        self.sums.get(i).map_or(DVec3::ZERO, |s| {
            DVec3::new(s[0] as f64, s[1] as f64, s[2] as f64) * SPLAT_QUANTUM
        })
    }

    /// What pixel `i`'s splats add to its value: the sum over all light
    /// subpaths (zero with none).
    pub fn mean(&self, i: usize) -> Vec3 {
        if self.light_paths == 0 {
            return Vec3::ZERO;
        }
        (self.sum(i) / self.light_paths as f64).as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn splat(x: u32, y: u32, v: f32) -> Splat {
        Splat {
            x,
            y,
            value: Vec3::splat(v),
            layer: 0,
        }
    }

    #[test]
    fn sums_do_not_depend_on_order_or_grouping() {
        // Values whose f32/f64 sums depend on the order.
        let splats: Vec<Splat> = (0..1000)
            .map(|i| splat(i % 3, 0, (1.0 + i as f32 * 0.37).powi(3) * 1e-3))
            .collect();
        let mut forward = SplatLayer::default();
        forward.add(3, 1, 0, &splats);
        let mut reversed = SplatLayer::default();
        let mut rev = splats.clone();
        rev.reverse();
        reversed.add(3, 1, 0, &rev);
        let (mut a, mut b) = (SplatLayer::default(), SplatLayer::default());
        a.add(3, 1, 0, &splats[..333]);
        b.add(3, 1, 0, &splats[333..]);
        b.merge(&a);
        assert_eq!(forward, reversed);
        assert_eq!(forward.sums, b.sums);
        let exact: f64 = splats.iter().step_by(3).map(|s| s.value.x as f64).sum();
        assert!((forward.sum(0).x - exact).abs() < 1e-9 * exact);
    }

    #[test]
    fn bad_splats_are_counted_not_added() {
        let mut layer = SplatLayer::default();
        layer.add(
            2,
            2,
            0,
            &[
                splat(0, 0, f32::NAN),
                splat(1, 1, 1e30),
                splat(2, 0, 1.0),
                splat(1, 0, 2.0),
            ],
        );
        assert_eq!(layer.invalid, 3);
        assert_eq!(layer.sum(1), DVec3::splat(2.0));
        layer.light_paths = 4;
        assert_eq!(layer.mean(1), Vec3::splat(0.5));
    }
}
