//! Error metrics between a test image and a reference.
//!
//! The scalar metrics are averaged over every pixel and channel, in `f64`,
//! with no clamping: a NaN anywhere makes the result NaN, which is the
//! honest answer for a broken render. Empty images give 0.
//!
//! [`ztest`] adds a statistical comparison that knows each render's
//! variance, for regression tests that must not flake; [`compare`] puts
//! all of them together for `candela compare` and `candela.compare`.

pub mod compare;
pub mod comparison;
mod normal;
pub mod ztest;

pub use normal::{normal_two_sided_p, two_sided_z_threshold};

use crate::{GrayImage, ImageError, RgbImage};

/// The `ε` of the relative metrics: pbrt-v4's (`Image::MRSE` in
/// `util/image.cpp`, the "MRSE" of its `imgtool diff`), which keeps black
/// reference pixels from dominating the average.
pub const RELATIVE_EPSILON: f64 = 1e-2;

/// The peak of [`psnr`]: display white, 1.0 in linear units.
pub const PSNR_PEAK: f64 = 1.0;

/// Mean squared error: the average of `(test - reference)²`.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn mse(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    mean_over_channels("mse", test, reference, squared_error)
}

/// Relative mean squared error as pbrt-v4 defines it (its MRSE): the
/// average over pixels and channels of `(test - reference)² /
/// (reference + ε)²` with ε = [`RELATIVE_EPSILON`] = 0.01. Unlike MSE it
/// weighs dark and bright regions alike, as the eye does. (pbrt-v4 skips
/// infinite terms; we keep them, and NaN, so a broken render cannot look
/// good.)
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn rel_mse(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    mean_over_channels("rel_mse", test, reference, relative_squared_error)
}

/// Peak signal-to-noise ratio in decibels, `10 log10(peak² / MSE)` with
/// peak [`PSNR_PEAK`] = 1 (display white): +inf for identical images.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn psnr(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    Ok(psnr_of_mse(mse(test, reference)?))
}

/// [`psnr`] from an MSE already computed.
pub fn psnr_of_mse(mse: f64) -> f64 {
    10.0 * (PSNR_PEAK * PSNR_PEAK / mse).log10()
}

/// One term of [`mse`].
fn squared_error(t: f64, r: f64) -> f64 {
    (t - r) * (t - r)
}

/// One term of [`rel_mse`].
fn relative_squared_error(t: f64, r: f64) -> f64 {
    (t - r) * (t - r) / ((r + RELATIVE_EPSILON) * (r + RELATIVE_EPSILON))
}

/// Per-pixel [`rel_mse`] terms averaged over the three channels: the image
/// behind `candela compare --heatmap`.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn rel_mse_image(test: &RgbImage, reference: &RgbImage) -> Result<GrayImage, ImageError> {
    if test.size() != reference.size() {
        let what = "rel_mse_image";
        return Err(ImageError::SizeMismatch {
            what,
            a: test.size(),
            b: reference.size(),
        });
    }
    let values = test
        .pixels()
        .iter()
        .zip(reference.pixels())
        .map(|(t, r)| {
            let sum: f64 = (0..3)
                .map(|c| relative_squared_error(t[c] as f64, r[c] as f64))
                .sum();
            (sum / 3.0) as f32
        })
        .collect();
    GrayImage::from_values(test.width(), test.height(), values)
}

/// Mean absolute relative error: the average of
/// `|test - reference| / (|reference| + ε)` with ε = [`RELATIVE_EPSILON`].
/// Less sensitive to fireflies than the squared metrics.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn mean_abs_rel_error(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    mean_over_channels("mean_abs_rel_error", test, reference, |t, r| {
        (t - r).abs() / (r.abs() + RELATIVE_EPSILON)
    })
}

/// Averages `term(test, reference)` over all channels of all pixels.
fn mean_over_channels(
    what: &'static str,
    test: &RgbImage,
    reference: &RgbImage,
    term: impl Fn(f64, f64) -> f64,
) -> Result<f64, ImageError> {
    if test.size() != reference.size() {
        return Err(ImageError::SizeMismatch {
            what,
            a: test.size(),
            b: reference.size(),
        });
    }
    let count = test.pixels().len() * 3;
    if count == 0 {
        return Ok(0.0);
    }
    let sum: f64 = test
        .pixels()
        .iter()
        .zip(reference.pixels())
        .flat_map(|(t, r)| (0..3).map(move |c| (t[c] as f64, r[c] as f64)))
        .map(|(t, r)| term(t, r))
        .sum();
    Ok(sum / count as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constant(value: f32) -> RgbImage {
        RgbImage::from_fn(4, 3, |_, _| [value; 3]).unwrap()
    }

    #[test]
    fn mse_of_known_differences() {
        let reference = constant(1.0);
        assert_eq!(mse(&reference, &reference).unwrap(), 0.0);
        assert!((mse(&constant(1.5), &reference).unwrap() - 0.25).abs() < 1e-12);
        // One channel of one pixel off by 2 among 4*3*3 = 36 values: 4/36.
        let mut test = reference.clone();
        test.pixels_mut()[5][1] = 3.0;
        assert!((mse(&test, &reference).unwrap() - 4.0 / 36.0).abs() < 1e-12);
    }

    #[test]
    fn relative_metrics_of_known_differences() {
        let reference = constant(2.0);
        let test = constant(3.0);
        // (3-2)^2 / (2 + 0.01)^2
        assert!((rel_mse(&test, &reference).unwrap() - 1.0 / (2.01 * 2.01)).abs() < 1e-12);
        let map = rel_mse_image(&test, &reference).unwrap();
        assert!(map
            .values()
            .iter()
            .all(|&v| (v as f64 - 1.0 / (2.01 * 2.01)).abs() < 1e-7));
        // MSE 1 against a peak of 1: 0 dB; MSE 0.01: 20 dB.
        assert_eq!(psnr(&test, &reference).unwrap(), 0.0);
        assert!((psnr_of_mse(0.01) - 20.0).abs() < 1e-12);
        assert_eq!(psnr(&test, &test).unwrap(), f64::INFINITY);
        // |3-2| / (2 + 0.01)
        assert!((mean_abs_rel_error(&test, &reference).unwrap() - 1.0 / 2.01).abs() < 1e-12);
        // A black reference: the epsilon keeps the error finite, 0.1^2 / 0.01^2 = 100.
        let error = rel_mse(&constant(0.1), &constant(0.0)).unwrap();
        assert!((error - 100.0).abs() < 1e-4, "{error}");
    }

    #[test]
    fn size_mismatch_and_nan_are_reported() {
        let small = RgbImage::new(2, 2).unwrap();
        assert!(matches!(
            mse(&small, &constant(0.0)),
            Err(ImageError::SizeMismatch { .. })
        ));
        let mut test = constant(0.0);
        test.pixels_mut()[0][0] = f32::NAN;
        assert!(mse(&test, &constant(0.0)).unwrap().is_nan());
        let empty = RgbImage::new(0, 0).unwrap();
        assert_eq!(mse(&empty, &empty).unwrap(), 0.0);
    }
}
