//! Error metrics between a test image and a reference.
//!
//! The scalar metrics are averaged over every pixel and channel, in `f64`,
//! with no clamping: a NaN anywhere makes the result NaN, which is the
//! honest answer for a broken render. Empty images give 0.
//!
//! [`ztest`] adds a statistical comparison that knows each render's
//! variance, for regression tests that must not flake.

mod normal;
pub mod ztest;

pub use normal::{normal_two_sided_p, two_sided_z_threshold};

use crate::{ImageError, RgbImage};

/// The `ε` of relative errors, as in the denoising literature (e.g.
/// Rousselle, Knaus and Zwicker, "Adaptive sampling and reconstruction using
/// greedy error minimization", 2011): it keeps black reference pixels from
/// dominating the average.
pub const RELATIVE_EPSILON: f64 = 1e-2;

/// Mean squared error: the average of `(test - reference)²`.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn mse(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    mean_over_channels("mse", test, reference, |t, r| (t - r) * (t - r))
}

/// Relative mean squared error: the average of
/// `(test - reference)² / (reference² + ε)` with ε = [`RELATIVE_EPSILON`].
/// Unlike MSE it weighs dark and bright regions alike, as the eye does.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if the sizes differ.
pub fn rel_mse(test: &RgbImage, reference: &RgbImage) -> Result<f64, ImageError> {
    mean_over_channels("rel_mse", test, reference, |t, r| {
        (t - r) * (t - r) / (r * r + RELATIVE_EPSILON)
    })
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
        // (3-2)^2 / (4 + 0.01)
        assert!((rel_mse(&test, &reference).unwrap() - 1.0 / 4.01).abs() < 1e-12);
        // |3-2| / (2 + 0.01)
        assert!((mean_abs_rel_error(&test, &reference).unwrap() - 1.0 / 2.01).abs() < 1e-12);
        // A black reference: the epsilon keeps the error finite, 0.1^2 / 0.01 = 1.
        let error = rel_mse(&constant(0.1), &constant(0.0)).unwrap();
        assert!((error - 1.0).abs() < 1e-6, "{error}");
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
