//! Statistical image comparison: are two renders the same image up to noise?
//!
//! Comparing a Monte Carlo render with a reference by hash or by an MSE
//! bound either flakes or misses bias. Instead, following Mitsuba 3's
//! render regression tests, we compare means with their known uncertainty:
//! pixels are grouped in square blocks (8 × 8 by default), each block's mean
//! and the variance of that mean are computed for both renders, and
//!
//! ```text
//! z = (mean_a - mean_b) / sqrt(var_a + var_b)
//! ```
//!
//! per block and channel. Blocks average away the heavy per-pixel noise so
//! the normal approximation holds, and still localise a bias. A global z of
//! the whole-image means catches a small bias spread everywhere (e.g. a few
//! percent of lost energy) that no single block reveals.
//!
//! # Assumptions
//! - The two renders are independent (different seeds, or one is a
//!   reference made separately).
//! - Block means are close to normal. With 64 pixels per block this holds
//!   unless the image has rare, huge fireflies (heavy-tailed samples); then
//!   the test over-rejects.
//! - The variances are right. From per-pixel standard errors
//!   ([`BlockStats::from_pixel_errors`]) we also assume pixel estimates are
//!   independent of each other (true when each pixel draws its own samples)
//!   and that each pixel's standard error came from enough samples (≥ 16 or
//!   so). From independent batches ([`BlockStats::from_batches`]) the
//!   variance is estimated from their spread, which needs no such assumption
//!   but enough batches (≥ 16) for the normal threshold to be accurate.
//!   From the pixels alone ([`BlockStats::from_block_spread`], for images
//!   without a variance layer) the variance comes from the spread of each
//!   block's pixels: conservative where a block holds image structure.
//! - The threshold is Bonferroni-corrected over all tests (every block and
//!   channel, plus the three global ones), so an unbiased pair fails with
//!   probability at most the chosen false-alarm rate.
//!
//! A block where both variances are zero (e.g. background) passes only if
//! the means are equal; its z is then 0 or infinite. A NaN mean fails.

use std::path::Path;

use super::two_sided_z_threshold;
use crate::{write_png_display, ImageError, RgbImage};

/// Per-block means of one render and the variance of each block mean.
#[derive(Clone, Debug, PartialEq)]
pub struct BlockStats {
    width: usize,
    height: usize,
    block_size: usize,
    blocks_x: usize,
    blocks_y: usize,
    /// Per block: mean of its pixels' means.
    mean: Vec<[f64; 3]>,
    /// Per block: variance of `mean`.
    variance: Vec<[f64; 3]>,
    /// Whole image: mean and its variance.
    global: ([f64; 3], [f64; 3]),
}

impl BlockStats {
    /// Block statistics from a render's per-pixel means and per-pixel
    /// standard errors of those means (the standard deviation of the
    /// samples divided by √n). Partial blocks at the right and bottom edges
    /// use the pixels they have.
    ///
    /// # Errors
    /// [`ImageError::SizeMismatch`] if the images differ in size,
    /// [`ImageError::InvalidArgument`] for a zero block size.
    pub fn from_pixel_errors(
        mean: &RgbImage,
        std_error: &RgbImage,
        block_size: usize,
    ) -> Result<Self, ImageError> {
        if mean.size() != std_error.size() {
            let what = "z-test mean and standard error";
            return Err(ImageError::SizeMismatch {
                what,
                a: mean.size(),
                b: std_error.size(),
            });
        }
        let mut stats = Self::empty(mean.size(), block_size)?;
        // Sum means and squared standard errors per block, then normalise:
        // the mean of n independent estimates has variance sum(se²) / n².
        let mut counts = vec![0usize; stats.mean.len()];
        let mut global_var = [0.0; 3];
        for (i, (m, se)) in mean.pixels().iter().zip(std_error.pixels()).enumerate() {
            let block = stats.block_of(i);
            counts[block] += 1;
            for c in 0..3 {
                let var = se[c] as f64 * se[c] as f64;
                stats.mean[block][c] += m[c] as f64;
                stats.variance[block][c] += var;
                stats.global.0[c] += m[c] as f64;
                global_var[c] += var;
            }
        }
        for ((m, v), &n) in stats.mean.iter_mut().zip(&mut stats.variance).zip(&counts) {
            let n = n as f64;
            *m = m.map(|s| s / n);
            *v = v.map(|s| s / (n * n));
        }
        let n = mean.pixels().len().max(1) as f64;
        stats.global = (
            stats.global.0.map(|s| s / n),
            global_var.map(|s| s / (n * n)),
        );
        Ok(stats)
    }

    /// Block statistics from independent renders of the same image (batches
    /// with different seeds): the block mean is averaged over batches and
    /// its variance estimated from their spread, `s² / K` for `K` batches.
    ///
    /// # Errors
    /// [`ImageError::InvalidArgument`] for fewer than two batches or a zero
    /// block size, [`ImageError::SizeMismatch`] if the batches differ in size.
    pub fn from_batches(batches: &[RgbImage], block_size: usize) -> Result<Self, ImageError> {
        if batches.len() < 2 {
            return Err(ImageError::InvalidArgument(
                "z-test needs at least two batches".into(),
            ));
        }
        let first = &batches[0];
        let mut stats = Self::empty(first.size(), block_size)?;
        // A batch's plain block means: from_pixel_errors with zero errors.
        let zero = RgbImage::new(first.width(), first.height())?;
        let mut per_batch = Vec::with_capacity(batches.len());
        for batch in batches {
            if batch.size() != first.size() {
                let what = "z-test batches";
                return Err(ImageError::SizeMismatch {
                    what,
                    a: first.size(),
                    b: batch.size(),
                });
            }
            per_batch.push(Self::from_pixel_errors(batch, &zero, block_size)?);
        }
        let k = batches.len() as f64;
        let spread = |values: &mut dyn Iterator<Item = f64>| {
            let v: Vec<f64> = values.collect();
            let mean = v.iter().sum::<f64>() / k;
            let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (k - 1.0);
            (mean, var / k)
        };
        for block in 0..stats.mean.len() {
            for c in 0..3 {
                let (m, v) = spread(&mut per_batch.iter().map(|s| s.mean[block][c]));
                stats.mean[block][c] = m;
                stats.variance[block][c] = v;
            }
        }
        for c in 0..3 {
            let (m, v) = spread(&mut per_batch.iter().map(|s| s.global.0[c]));
            stats.global.0[c] = m;
            stats.global.1[c] = v;
        }
        Ok(stats)
    }

    /// Zeroed statistics for an image of `size` in blocks of `block_size`.
    fn empty((width, height): (usize, usize), block_size: usize) -> Result<Self, ImageError> {
        if block_size == 0 {
            return Err(ImageError::InvalidArgument(
                "z-test block size must be positive".into(),
            ));
        }
        let blocks_x = width.div_ceil(block_size);
        let blocks_y = height.div_ceil(block_size);
        let n = blocks_x * blocks_y;
        let zeros = vec![[0.0; 3]; n];
        let global = ([0.0; 3], [0.0; 3]);
        Ok(Self {
            width,
            height,
            block_size,
            blocks_x,
            blocks_y,
            mean: zeros.clone(),
            variance: zeros,
            global,
        })
    }

    /// The block holding pixel number `i` (row-major).
    fn block_of(&self, i: usize) -> usize {
        let (x, y) = (i % self.width, i / self.width);
        (y / self.block_size) * self.blocks_x + x / self.block_size
    }
}

/// Per-block z-scores of two renders, with the threshold they are judged by.
#[derive(Clone, Debug, PartialEq)]
pub struct ZTest {
    width: usize,
    height: usize,
    block_size: usize,
    blocks_x: usize,
    blocks_y: usize,
    z: Vec<[f64; 3]>,
    global_z: [f64; 3],
    threshold: f64,
}

/// The verdict of a [`ZTest`] in a few numbers, for test assertions and logs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZSummary {
    /// Number of blocks compared.
    pub blocks: usize,
    /// Largest block `|z|` over all blocks and channels (infinite if a block
    /// has a NaN mean or differs with zero variance).
    pub max_abs_z: f64,
    /// Block and channel of `max_abs_z`: `(block x, block y, channel)`.
    pub worst: (usize, usize, usize),
    /// Largest `|z|` of the whole-image means over the channels.
    pub global_abs_z: f64,
    /// The Bonferroni-corrected `|z|` threshold used.
    pub threshold: f64,
    /// Block-channel tests with `|z|` above the threshold.
    pub count_over: usize,
    /// `count_over` divided by the number of block-channel tests.
    pub fraction_over: f64,
}

impl ZSummary {
    /// True if no block and no global mean exceeds the threshold.
    pub fn passed(&self) -> bool {
        self.count_over == 0 && self.global_abs_z <= self.threshold
    }
}

/// Compares two renders block by block. `false_alarm_rate` is the
/// probability that two unbiased renders fail (e.g. 0.01).
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the two were computed for different
/// image or block sizes.
pub fn z_test(a: &BlockStats, b: &BlockStats, false_alarm_rate: f64) -> Result<ZTest, ImageError> {
    if (a.width, a.height, a.block_size) != (b.width, b.height, b.block_size) {
        let what = "z-test block statistics (image or block size)";
        return Err(ImageError::SizeMismatch {
            what,
            a: (a.width, a.height),
            b: (b.width, b.height),
        });
    }
    let z = (0..a.mean.len())
        .map(|i| {
            [0, 1, 2].map(|c| {
                z_score(
                    a.mean[i][c],
                    a.variance[i][c],
                    b.mean[i][c],
                    b.variance[i][c],
                )
            })
        })
        .collect::<Vec<_>>();
    let global_z =
        [0, 1, 2].map(|c| z_score(a.global.0[c], a.global.1[c], b.global.0[c], b.global.1[c]));
    let threshold = two_sided_z_threshold(false_alarm_rate, 3 * z.len() + 3);
    Ok(ZTest {
        width: a.width,
        height: a.height,
        block_size: a.block_size,
        blocks_x: a.blocks_x,
        blocks_y: a.blocks_y,
        z,
        global_z,
        threshold,
    })
}

/// The z-score of a difference of means; NaN becomes infinite so it fails.
fn z_score(mean_a: f64, var_a: f64, mean_b: f64, var_b: f64) -> f64 {
    let difference = mean_a - mean_b;
    let z = if difference == 0.0 {
        0.0
    } else {
        difference / (var_a + var_b).sqrt()
    };
    if z.is_nan() {
        f64::INFINITY
    } else {
        z
    }
}

impl ZTest {
    /// Signed z-scores per block (row-major over blocks) and channel;
    /// positive where the first render is brighter.
    pub fn block_z(&self) -> &[[f64; 3]] {
        &self.z
    }

    /// Number of blocks across and down.
    pub fn blocks(&self) -> (usize, usize) {
        (self.blocks_x, self.blocks_y)
    }

    /// Signed z-scores of the whole-image means per channel.
    pub fn global_z(&self) -> [f64; 3] {
        self.global_z
    }

    /// The threshold, max |z|, failures and their fraction.
    pub fn summary(&self) -> ZSummary {
        let (mut max_abs_z, mut worst, mut count_over) = (0.0, (0, 0, 0), 0);
        let blocks_x = self.blocks_x.max(1);
        for (i, z) in self.z.iter().enumerate() {
            for (c, z) in z.iter().enumerate() {
                if z.abs() > max_abs_z {
                    max_abs_z = z.abs();
                    worst = (i % blocks_x, i / blocks_x, c);
                }
                count_over += usize::from(z.abs() > self.threshold);
            }
        }
        let tests = 3 * self.z.len();
        ZSummary {
            blocks: self.z.len(),
            max_abs_z,
            worst,
            global_abs_z: self.global_z.iter().fold(0.0, |m, z| z.abs().max(m)),
            threshold: self.threshold,
            count_over,
            fraction_over: if tests == 0 {
                0.0
            } else {
                count_over as f64 / tests as f64
            },
        }
    }

    /// A false-colour picture of the comparison at the image's resolution:
    /// each block shows its channel of largest `|z|`, red where the first
    /// render is brighter and blue where it is darker, with brightness
    /// `|z| / threshold`; blocks over the threshold are yellow (brighter)
    /// or cyan (darker) so failures stand out.
    pub fn difference_image(&self) -> Result<RgbImage, ImageError> {
        RgbImage::from_fn(self.width, self.height, |x, y| {
            let block = &self.z[(y / self.block_size) * self.blocks_x + x / self.block_size];
            let z = block
                .iter()
                .fold(0.0_f64, |m, &z| if z.abs() > m.abs() { z } else { m });
            let level = (z.abs() / self.threshold).min(1.0) as f32;
            match (z > 0.0, z.abs() > self.threshold) {
                (true, false) => [level, 0.0, 0.0],
                (false, false) => [0.0, 0.0, level],
                (true, true) => [1.0, 1.0, 0.0],
                (false, true) => [0.0, 1.0, 1.0],
            }
        })
    }

    /// Writes [`Self::difference_image`] as a PNG (display values, no tone
    /// curve), for a failing regression test to leave behind.
    pub fn write_difference_png(&self, path: impl AsRef<Path>) -> Result<(), ImageError> {
        write_png_display(path, &self.difference_image()?)
    }
}

#[path = "ztest_spread.rs"]
mod spread;

#[cfg(test)]
#[path = "ztest_tests.rs"]
mod tests;
