//! Comparing renders: what `candela compare` and Python's `candela.compare`
//! report, computed here once.
//!
//! For a test image against a reference:
//! - [`mse`](super::mse), [`rel_mse`](super::rel_mse) (pbrt-v4's MRSE,
//!   ε = 0.01) and [`psnr`](super::psnr_of_mse) (peak 1);
//! - the block z-test of [`super::ztest`] (8 × 8 blocks, 1 % family-wise
//!   false-alarm rate by default). When both images carry a variance layer
//!   (Candela's EXRs) the block variances come from the per-pixel variances
//!   of the mean; otherwise from the spread of each block's pixels
//!   ([`BlockStats::from_block_spread`], conservative where blocks hold
//!   edges);
//! - with render time and sample counts in the test image's header, its
//!   efficiency `1 / (relMSE × time)` (the inverse of the time to reach
//!   unit relMSE if error falls as 1/time, as Monte Carlo variance does).
//!   Two renders' efficiencies against the same reference give the
//!   equal-error speed-up of one over the other. The reference's own noise
//!   adds to both relMSEs, so use a reference far more converged than
//!   either.
//!
//! Inputs are Candela's EXRs, any plain RGB EXR (pbrt-v4, Mitsuba 3: bare
//! `R`, `G`, `B`; layer-prefixed files by [`crate::read_exr_layers`]'s
//! rules) and PNGs (decoded from sRGB to linear values).

use std::path::{Path, PathBuf};

use super::ztest::{z_test, BlockStats, ZSummary};
use super::{mse, psnr_of_mse, rel_mse, rel_mse_image};
use crate::{
    finite_percentile, heat_image, read_exr_layers, read_png, ImageError, RenderInfo, RgbImage,
};

/// One image to compare, with what its file says about it.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareImage {
    /// The file (or a name for an in-memory image), for messages.
    pub path: PathBuf,
    /// Linear RGB.
    pub beauty: RgbImage,
    /// Per-pixel variance of the mean, if the file has a variance layer.
    pub variance: Option<RgbImage>,
    /// Header metadata (empty for PNGs).
    pub info: RenderInfo,
}

impl CompareImage {
    /// Reads an `.exr` or `.png` file (by extension, case-insensitive).
    ///
    /// # Errors
    /// [`ImageError::Io`]/[`ImageError::Read`] naming the file if it is
    /// missing or not a readable image, [`ImageError::Incompatible`] for
    /// another extension.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ImageError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("exr") => {
                let layers = read_exr_layers(path)?;
                Ok(Self {
                    path: path.into(),
                    variance: layers.variance().cloned(),
                    beauty: layers.beauty,
                    info: layers.info,
                })
            }
            Some("png") => Ok(Self::plain(path, read_png(path)?)),
            _ => Err(ImageError::Incompatible(format!(
                "{}: not an image candela reads (.exr or .png)",
                path.display()
            ))),
        }
    }

    /// An image with no variance and no metadata.
    pub fn plain(name: impl Into<PathBuf>, beauty: RgbImage) -> Self {
        Self {
            path: name.into(),
            beauty,
            variance: None,
            info: RenderInfo::default(),
        }
    }

    /// `1 / (relMSE × time)` if the header carries the render time and
    /// sample counts.
    pub fn efficiency(&self, rel_mse: f64) -> Option<f64> {
        let time = self.info.time_seconds?;
        self.info.spp?;
        Some(1.0 / (rel_mse * time))
    }
}

/// Where the z-test's variances came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarianceSource {
    /// Both images' variance layers (per-pixel variance of the mean).
    PixelVariance,
    /// The spread of each block's pixels.
    BlockSpread,
}

impl VarianceSource {
    /// A short name for reports: `pixel variance` or `block spread`.
    pub fn name(self) -> &'static str {
        match self {
            Self::PixelVariance => "pixel variance",
            Self::BlockSpread => "block spread",
        }
    }
}

/// Settings of a comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompareOptions {
    /// Edge of the z-test's square blocks, in pixels.
    pub block_size: usize,
    /// Probability that two unbiased renders fail the z-test.
    pub false_alarm_rate: f64,
}

impl Default for CompareOptions {
    /// 8 × 8 blocks, 1 % false alarms: the test suite's choice.
    fn default() -> Self {
        Self {
            block_size: 8,
            false_alarm_rate: 0.01,
        }
    }
}

/// A test image measured against a reference.
#[derive(Clone, Debug, PartialEq)]
pub struct PairReport {
    /// Mean squared error.
    pub mse: f64,
    /// pbrt-v4's relative MSE (ε = 0.01).
    pub rel_mse: f64,
    /// PSNR in dB, peak 1.
    pub psnr: f64,
    /// The block z-test's verdict.
    pub z: ZSummary,
    /// Where the z-test's variances came from.
    pub variance_source: VarianceSource,
}

/// Measures `test` against `reference`.
///
/// # Errors
/// [`ImageError::Incompatible`] naming both files if their sizes differ;
/// [`ImageError::InvalidArgument`] for a zero block size.
pub fn compare_pair(
    test: &CompareImage,
    reference: &CompareImage,
    opts: &CompareOptions,
) -> Result<PairReport, ImageError> {
    if test.beauty.size() != reference.beauty.size() {
        let ((tw, th), (rw, rh)) = (test.beauty.size(), reference.beauty.size());
        return Err(ImageError::Incompatible(format!(
            "{} is {tw}x{th} but {} is {rw}x{rh}: images must have the same size",
            test.path.display(),
            reference.path.display()
        )));
    }
    let (a, b, variance_source) = match (&test.variance, &reference.variance) {
        (Some(va), Some(vb)) => (
            BlockStats::from_pixel_errors(&test.beauty, &std_error(va)?, opts.block_size)?,
            BlockStats::from_pixel_errors(&reference.beauty, &std_error(vb)?, opts.block_size)?,
            VarianceSource::PixelVariance,
        ),
        _ => (
            BlockStats::from_block_spread(&test.beauty, opts.block_size)?,
            BlockStats::from_block_spread(&reference.beauty, opts.block_size)?,
            VarianceSource::BlockSpread,
        ),
    };
    let mse = mse(&test.beauty, &reference.beauty)?;
    Ok(PairReport {
        mse,
        rel_mse: rel_mse(&test.beauty, &reference.beauty)?,
        psnr: psnr_of_mse(mse),
        z: z_test(&a, &b, opts.false_alarm_rate)?.summary(),
        variance_source,
    })
}

/// The standard error image `sqrt(variance)` (+inf stays +inf).
fn std_error(variance: &RgbImage) -> Result<RgbImage, ImageError> {
    let pixels = variance
        .pixels()
        .iter()
        .map(|p| p.map(|v| v.max(0.0).sqrt()))
        .collect();
    RgbImage::from_pixels(variance.width(), variance.height(), pixels)
}

/// The heat map of the per-pixel relative squared error of `test` against
/// `reference` (channel mean of the [`rel_mse`](super::rel_mse) terms),
/// scaled so that the 99th percentile is the hottest colour (one firefly
/// does not darken the rest); display values for
/// [`crate::write_png_display`].
///
/// # Errors
/// As [`compare_pair`] for sizes.
pub fn error_heatmap(
    test: &CompareImage,
    reference: &CompareImage,
) -> Result<RgbImage, ImageError> {
    let errors = rel_mse_image(&test.beauty, &reference.beauty).map_err(|_| {
        ImageError::Incompatible(format!(
            "{} and {} differ in size",
            test.path.display(),
            reference.path.display()
        ))
    })?;
    let max = finite_percentile(errors.values(), 0.99)
        .filter(|&m| m > 0.0)
        .unwrap_or(1.0);
    heat_image(&errors, max)
}

#[cfg(test)]
#[path = "compare_tests.rs"]
mod tests;
