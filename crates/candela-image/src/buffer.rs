//! Plain image buffers: linear RGB and single-channel float images.
//!
//! Both are row-major with `y = 0` at the top (the order PNG and EXR store
//! rows in), so writers stream rows without flipping. Colours are `[f32; 3]`
//! rather than a vector type so this crate stays independent of the math
//! library the renderer uses.

use crate::ImageError;

/// Number of pixels in a `width × height` image, or an error if it overflows.
fn pixel_count(width: usize, height: usize) -> Result<usize, ImageError> {
    width.checked_mul(height).ok_or(ImageError::TooLarge {
        what: "memory",
        width,
        height,
    })
}

/// A linear-light RGB image with `f32` channels.
///
/// The renderer's film resolves into this; writers apply tone mapping only at
/// output so the buffer keeps the full dynamic range.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbImage {
    width: usize,
    height: usize,
    pixels: Vec<[f32; 3]>,
}

impl RgbImage {
    /// A black image of the given size.
    pub fn new(width: usize, height: usize) -> Result<Self, ImageError> {
        let n = pixel_count(width, height)?;
        Ok(Self {
            width,
            height,
            pixels: vec![[0.0; 3]; n],
        })
    }

    /// Wraps existing row-major pixels; fails if their number is not
    /// `width * height`, so a wrong buffer is caught where it is made.
    pub fn from_pixels(
        width: usize,
        height: usize,
        pixels: Vec<[f32; 3]>,
    ) -> Result<Self, ImageError> {
        let expected = pixel_count(width, height)?;
        if pixels.len() != expected {
            return Err(ImageError::BadLength {
                what: "RGB pixels",
                expected,
                actual: pixels.len(),
            });
        }
        Ok(Self {
            width,
            height,
            pixels,
        })
    }

    /// An image whose pixel `(x, y)` is `f(x, y)`; handy for tests and maps.
    pub fn from_fn(
        width: usize,
        height: usize,
        mut f: impl FnMut(usize, usize) -> [f32; 3],
    ) -> Result<Self, ImageError> {
        pixel_count(width, height)?;
        let pixels = (0..height).flat_map(|y| (0..width).map(move |x| (x, y)));
        let pixels = pixels.map(|(x, y)| f(x, y)).collect();
        Ok(Self {
            width,
            height,
            pixels,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// `(width, height)`, for size comparisons and error messages.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// All pixels, row-major from the top-left.
    pub fn pixels(&self) -> &[[f32; 3]] {
        &self.pixels
    }

    /// All pixels, mutable, row-major from the top-left.
    pub fn pixels_mut(&mut self) -> &mut [[f32; 3]] {
        &mut self.pixels
    }

    /// Gives the pixel buffer back, e.g. to reuse its allocation.
    pub fn into_pixels(self) -> Vec<[f32; 3]> {
        self.pixels
    }

    /// The pixel at `(x, y)`, or `None` outside the image.
    pub fn get(&self, x: usize, y: usize) -> Option<[f32; 3]> {
        (x < self.width && y < self.height).then(|| self.pixels[y * self.width + x])
    }

    /// Mutable access to the pixel at `(x, y)`, or `None` outside the image.
    pub fn get_mut(&mut self, x: usize, y: usize) -> Option<&mut [f32; 3]> {
        if x < self.width && y < self.height {
            Some(&mut self.pixels[y * self.width + x])
        } else {
            None
        }
    }
}

/// A single-channel `f32` image: sample counts, variances, standard errors,
/// depth or any other per-pixel scalar that travels beside the beauty image.
#[derive(Clone, Debug, PartialEq)]
pub struct GrayImage {
    width: usize,
    height: usize,
    values: Vec<f32>,
}

impl GrayImage {
    /// An image of zeros of the given size.
    pub fn new(width: usize, height: usize) -> Result<Self, ImageError> {
        let n = pixel_count(width, height)?;
        Ok(Self {
            width,
            height,
            values: vec![0.0; n],
        })
    }

    /// Wraps existing row-major values; fails if their number is not
    /// `width * height`.
    pub fn from_values(width: usize, height: usize, values: Vec<f32>) -> Result<Self, ImageError> {
        let expected = pixel_count(width, height)?;
        if values.len() != expected {
            return Err(ImageError::BadLength {
                what: "values",
                expected,
                actual: values.len(),
            });
        }
        Ok(Self {
            width,
            height,
            values,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// `(width, height)`, for size comparisons and error messages.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// All values, row-major from the top-left.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// All values, mutable, row-major from the top-left.
    pub fn values_mut(&mut self) -> &mut [f32] {
        &mut self.values
    }

    /// The value at `(x, y)`, or `None` outside the image.
    pub fn get(&self, x: usize, y: usize) -> Option<f32> {
        (x < self.width && y < self.height).then(|| self.values[y * self.width + x])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_major_with_top_row_first() {
        let img = RgbImage::from_fn(3, 2, |x, y| [x as f32, y as f32, 0.0]).unwrap();
        assert_eq!(img.pixels()[0], [0.0, 0.0, 0.0]);
        assert_eq!(img.pixels()[4], [1.0, 1.0, 0.0]);
        assert_eq!(img.get(2, 1), Some([2.0, 1.0, 0.0]));
        assert_eq!(img.get(3, 0), None);
        assert_eq!(img.get(0, 2), None);
    }

    #[test]
    fn wrong_lengths_and_overflow_are_errors() {
        assert!(matches!(
            RgbImage::from_pixels(2, 2, vec![[0.0; 3]; 3]),
            Err(ImageError::BadLength {
                expected: 4,
                actual: 3,
                ..
            })
        ));
        assert!(GrayImage::from_values(2, 3, vec![0.0; 7]).is_err());
        assert!(matches!(
            RgbImage::new(usize::MAX, 2),
            Err(ImageError::TooLarge { .. })
        ));
    }
}
