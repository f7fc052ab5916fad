//! Block statistics of an image that carries no variance: the variance of
//! each block mean is estimated from the spread of the block's pixels.

use super::BlockStats;
use crate::{ImageError, RgbImage};

impl BlockStats {
    /// Block statistics from the pixels alone (a plain EXR or a PNG). Each
    /// block's `k` pixel values are treated as independent draws around the
    /// block mean, so the variance of the block mean is `s² / k` with `s²`
    /// the sample variance of the block's pixels (`k − 1` denominator);
    /// the whole-image mean has variance `Σ k_b s_b² / N²` over the blocks.
    ///
    /// Image structure inside a block (an edge, a gradient) adds to `s²`,
    /// so this over-estimates the noise: the test stays valid (false alarms
    /// at most at the chosen rate, if the pixel noise is independent) but
    /// loses power where blocks are not flat. Prefer
    /// [`BlockStats::from_pixel_errors`] when the render's own variance is
    /// known. A block of one pixel has unknown variance (+inf) and passes;
    /// its pixel counts in the whole-image variance with the mean spread of
    /// the other blocks.
    ///
    /// # Errors
    /// [`ImageError::InvalidArgument`] for a zero block size.
    pub fn from_block_spread(mean: &RgbImage, block_size: usize) -> Result<Self, ImageError> {
        let zero = RgbImage::new(mean.width(), mean.height())?;
        let mut stats = Self::from_pixel_errors(mean, &zero, block_size)?;
        let blocks = stats.mean.len();
        let mut squares = vec![[0.0_f64; 3]; blocks];
        let mut counts = vec![0usize; blocks];
        for (i, p) in mean.pixels().iter().enumerate() {
            let block = stats.block_of(i);
            counts[block] += 1;
            for c in 0..3 {
                let d = p[c] as f64 - stats.mean[block][c];
                squares[block][c] += d * d;
            }
        }
        // Pixels of one-pixel blocks borrow the mean spread of the others
        // for the whole-image variance.
        let measured = || counts.iter().zip(&squares).filter(|(&k, _)| k >= 2);
        let blocks_measured = measured().count() as f64;
        let typical = [0, 1, 2].map(|c| {
            let total: f64 = measured().map(|(&k, s)| s[c] / (k as f64 - 1.0)).sum();
            if blocks_measured > 0.0 {
                total / blocks_measured
            } else {
                f64::INFINITY
            }
        });
        let mut global = [0.0; 3];
        for ((variance, square), &k) in stats.variance.iter_mut().zip(&squares).zip(&counts) {
            let k = k as f64;
            for c in 0..3 {
                let spread = if k < 2.0 {
                    typical[c]
                } else {
                    square[c] / (k - 1.0)
                };
                variance[c] = if k < 2.0 { f64::INFINITY } else { spread / k };
                global[c] += k * spread;
            }
        }
        let n = mean.pixels().len().max(1) as f64;
        stats.global.1 = global.map(|g| g / (n * n));
        Ok(stats)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_of_a_known_block() {
        // One 2x2 block with values 1, 2, 3, 4 in every channel: mean 2.5,
        // s² = 5/3, variance of the mean 5/12.
        let image = RgbImage::from_fn(2, 2, |x, y| [(1 + x + 2 * y) as f32; 3]).unwrap();
        let stats = BlockStats::from_block_spread(&image, 2).unwrap();
        assert_eq!(stats.mean, vec![[2.5; 3]]);
        assert!((stats.variance[0][0] - 5.0 / 12.0).abs() < 1e-12);
        assert!((stats.global.1[0] - 5.0 / 12.0).abs() < 1e-12);
        // A 1-pixel block (3x3 image in 2x2 blocks has one corner block).
        let odd = RgbImage::from_fn(3, 3, |x, _| [x as f32; 3]).unwrap();
        let stats = BlockStats::from_block_spread(&odd, 2).unwrap();
        assert_eq!(stats.variance[3][0], f64::INFINITY);
    }
}
