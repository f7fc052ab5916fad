//! The CS184 sample-rate false-colour image.
//!
//! Adaptive sampling stops early in easy pixels; the course program shows
//! where it spent effort as a colour ramp from blue (few samples) through
//! green to red (the maximum). The colours are display values: write them
//! with [`crate::write_png_display`], not through a tone curve.

use crate::{GrayImage, ImageError, RgbImage};

/// Maps a fraction in `[0, 1]` to blue → green → red, linearly in each half:
/// 0 is blue, 0.5 green, 1 red. Out-of-range values clamp; NaN maps to blue.
pub fn rate_colormap(fraction: f32) -> [f32; 3] {
    let f = if fraction.is_nan() {
        0.0
    } else {
        fraction.clamp(0.0, 1.0)
    };
    if f < 0.5 {
        let t = 2.0 * f;
        [0.0, t, 1.0 - t]
    } else {
        let t = 2.0 * f - 1.0;
        [t, 1.0 - t, 0.0]
    }
}

/// The sample-rate image: each pixel's sample count divided by
/// `max_samples`, through [`rate_colormap`].
///
/// # Errors
/// [`ImageError::InvalidArgument`] if `max_samples` is zero.
pub fn rate_image(sample_counts: &GrayImage, max_samples: u32) -> Result<RgbImage, ImageError> {
    if max_samples == 0 {
        return Err(ImageError::InvalidArgument(
            "rate image needs max_samples > 0".into(),
        ));
    }
    let scale = 1.0 / max_samples as f32;
    let pixels = sample_counts
        .values()
        .iter()
        .map(|&n| rate_colormap(n * scale))
        .collect();
    RgbImage::from_pixels(sample_counts.width(), sample_counts.height(), pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_endpoints_and_midpoints() {
        assert_eq!(rate_colormap(0.0), [0.0, 0.0, 1.0]);
        assert_eq!(rate_colormap(0.25), [0.0, 0.5, 0.5]);
        assert_eq!(rate_colormap(0.5), [0.0, 1.0, 0.0]);
        assert_eq!(rate_colormap(0.75), [0.5, 0.5, 0.0]);
        assert_eq!(rate_colormap(1.0), [1.0, 0.0, 0.0]);
        assert_eq!(rate_colormap(f32::NAN), [0.0, 0.0, 1.0]);
        assert_eq!(rate_colormap(7.0), [1.0, 0.0, 0.0]);
        assert_eq!(rate_colormap(-1.0), [0.0, 0.0, 1.0]);
    }

    #[test]
    fn ramp_is_continuous_and_sums_to_one() {
        for i in 0..=1000 {
            let c = rate_colormap(i as f32 / 1000.0);
            assert!((c.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        }
        let below = rate_colormap(0.5 - 1e-6);
        assert!((below[1] - 1.0).abs() < 1e-5 && below[2] < 1e-5);
    }

    #[test]
    fn rate_image_divides_by_the_maximum() {
        let counts = GrayImage::from_values(3, 1, vec![0.0, 64.0, 128.0]).unwrap();
        let image = rate_image(&counts, 128).unwrap();
        assert_eq!(
            image.pixels(),
            &[[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
        );
        assert!(rate_image(&counts, 0).is_err());
    }
}
