//! A heat map for scalar images (per-pixel cost, depth): a ramp from black
//! through violet, red and orange to pale yellow whose luminance rises
//! monotonically, so brighter always means more, also in grey print. The
//! colours are display values: write them with [`crate::write_png_display`].

use crate::{GrayImage, ImageError, RgbImage};

/// The ramp's control colours at 0, 1/4, 1/2, 3/4 and 1 (Rec. 709
/// luminance 0, 0.11, 0.29, 0.61, 0.94).
const STOPS: [[f32; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [0.2, 0.05, 0.45],
    [0.75, 0.15, 0.35],
    [0.98, 0.55, 0.1],
    [1.0, 0.95, 0.6],
];

/// Maps a fraction in `[0, 1]` to the heat ramp, linearly between its
/// control colours. Out-of-range values clamp; NaN maps to black.
pub fn heat_colormap(fraction: f32) -> [f32; 3] {
    let f = if fraction.is_nan() {
        0.0
    } else {
        fraction.clamp(0.0, 1.0)
    };
    let x = f * (STOPS.len() - 1) as f32;
    let i = (x as usize).min(STOPS.len() - 2);
    let t = x - i as f32;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    // This form gives each stop exactly at t = 0 and t = 1.
    [0, 1, 2].map(|c| a[c] * (1.0 - t) + b[c] * t)
}

/// The heat map of `values`: each value divided by `max`, through
/// [`heat_colormap`] (values above `max`, and +inf, are the hottest colour;
/// NaN is black). Pick `max` as the largest value of interest, e.g.
/// [`finite_percentile`] 0.99, so that one hot pixel does not darken the
/// rest.
///
/// # Errors
/// [`ImageError::InvalidArgument`] unless `max` is finite and positive.
pub fn heat_image(values: &GrayImage, max: f32) -> Result<RgbImage, ImageError> {
    if !(max.is_finite() && max > 0.0) {
        return Err(ImageError::InvalidArgument(format!(
            "heat map needs a finite maximum > 0, got {max}"
        )));
    }
    let pixels = values
        .values()
        .iter()
        .map(|&v| heat_colormap(v / max))
        .collect();
    RgbImage::from_pixels(values.width(), values.height(), pixels)
}

/// The `q`-quantile (`q` in `[0, 1]`, clamped) of the finite values, by the
/// nearest rank; `None` if no value is finite.
pub fn finite_percentile(values: &[f32], q: f32) -> Option<f32> {
    let mut finite: Vec<f32> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        return None;
    }
    finite.sort_by(f32::total_cmp);
    let q = if q.is_nan() { 1.0 } else { q.clamp(0.0, 1.0) };
    let rank = (q * (finite.len() - 1) as f32).round() as usize;
    Some(finite[rank])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luminance(c: [f32; 3]) -> f32 {
        0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    }

    #[test]
    fn ramp_hits_its_stops_and_brightens_monotonically() {
        for (i, stop) in STOPS.iter().enumerate() {
            assert_eq!(heat_colormap(i as f32 / 4.0), *stop);
        }
        let mut last = -1.0;
        for i in 0..=1000 {
            let y = luminance(heat_colormap(i as f32 / 1000.0));
            assert!(y > last, "luminance falls at {i}: {y} after {last}");
            last = y;
        }
        assert_eq!(heat_colormap(f32::NAN), [0.0; 3]);
        assert_eq!(heat_colormap(-3.0), STOPS[0]);
        assert_eq!(heat_colormap(f32::INFINITY), STOPS[4]);
    }

    #[test]
    fn heat_image_divides_by_the_maximum() {
        let v = GrayImage::from_values(4, 1, vec![0.0, 50.0, 100.0, f32::INFINITY]).unwrap();
        let image = heat_image(&v, 100.0).unwrap();
        assert_eq!(image.pixels(), &[STOPS[0], STOPS[2], STOPS[4], STOPS[4]]);
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(heat_image(&v, bad).is_err(), "max {bad} accepted");
        }
    }

    #[test]
    fn percentiles_ignore_non_finite_values() {
        let v = [f32::INFINITY, 3.0, 1.0, f32::NAN, 2.0, 4.0, 5.0];
        assert_eq!(finite_percentile(&v, 0.0), Some(1.0));
        assert_eq!(finite_percentile(&v, 0.5), Some(3.0));
        assert_eq!(finite_percentile(&v, 1.0), Some(5.0));
        assert_eq!(finite_percentile(&v, 7.0), Some(5.0));
        assert_eq!(finite_percentile(&[f32::NAN], 0.5), None);
    }
}
