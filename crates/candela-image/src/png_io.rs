//! 8-bit sRGB PNG output and PNG texture input.
//!
//! Output is always 8-bit RGB tagged with an sRGB chunk: the format every
//! viewer shows the same way, and the one the CS184 reference images use.
//! Input accepts any PNG colour type and bit depth and treats the values as
//! sRGB-encoded (gAMA and ICC chunks are ignored), which is how textures and
//! environment maps are authored in practice.

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use crate::tonemap::{quantize_u8, srgb_decode};
use crate::{atomic_write, ImageError, RgbImage, ToneMap};

/// The largest decoded PNG we accept, in bytes (a 16k × 16k RGBA image at
/// 8 bits): well above any texture, low enough to refuse a hostile header.
pub(crate) const MAX_DECODED_BYTES: usize = 1 << 30;

/// Writes `image` as an 8-bit sRGB PNG after applying `tone_map`, atomically.
///
/// # Errors
/// [`ImageError::TooLarge`] beyond PNG's 2³¹-pixel side limit, and the
/// errors of [`atomic_write`].
pub fn write_png(
    path: impl AsRef<Path>,
    image: &RgbImage,
    tone_map: &ToneMap,
) -> Result<(), ImageError> {
    write_rgb8(path.as_ref(), image.size(), &tone_map.to_rgb8(image))
}

/// Writes an image whose values are already display values in `[0, 1]`
/// (false-colour maps such as [`crate::rate_image`]): no exposure and no
/// transfer curve, just clamping and rounding to 8 bits.
pub fn write_png_display(path: impl AsRef<Path>, image: &RgbImage) -> Result<(), ImageError> {
    let bytes: Vec<u8> = image
        .pixels()
        .iter()
        .flat_map(|p| p.map(quantize_u8))
        .collect();
    write_rgb8(path.as_ref(), image.size(), &bytes)
}

/// Encodes interleaved 8-bit RGB bytes to `path`.
fn write_rgb8(
    path: &Path,
    (width, height): (usize, usize),
    bytes: &[u8],
) -> Result<(), ImageError> {
    let too_large = || ImageError::TooLarge {
        what: "PNG",
        width,
        height,
    };
    let w = u32::try_from(width).map_err(|_| too_large())?;
    let h = u32::try_from(height).map_err(|_| too_large())?;
    atomic_write(path, |writer| -> Result<(), png::EncodingError> {
        let mut encoder = png::Encoder::new(writer, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut png_writer = encoder.write_header()?;
        png_writer.write_image_data(bytes)?;
        png_writer.finish()
    })
}

/// Reads a PNG and decodes it to linear RGB.
///
/// Grey images are replicated to three channels and alpha is dropped:
/// textures here are colours, not mattes. Values are treated as sRGB.
///
/// # Errors
/// [`ImageError::Io`] if the file cannot be opened, [`ImageError::Read`] if
/// it is not a valid PNG; both name the file.
pub fn read_png(path: impl AsRef<Path>) -> Result<RgbImage, ImageError> {
    read_png_stored(path)?.srgb_decoded()
}

/// An integer image's stored values (PNG, JPEG, TGA, BMP), each scaled to
/// [0, 1] (`v / 255` or `v / 65535`) with no transfer curve applied, as
/// RGBA: grey is replicated to RGB and a missing alpha is 1. Data maps (roughness, normals, alpha) are read
/// from these exactly; colour is decoded by the caller.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major from the top row, RGBA.
    pub pixels: Vec<[f32; 4]>,
    /// Whether the file has an alpha channel.
    pub has_alpha: bool,
}

impl StoredImage {
    /// The colour decoded from sRGB to linear RGB, alpha dropped.
    ///
    /// # Errors
    /// As [`RgbImage::from_pixels`], when `pixels` does not hold
    /// `width × height` entries (never for an image this crate read).
    pub fn srgb_decoded(&self) -> Result<RgbImage, ImageError> {
        let pixels = self
            .pixels
            .iter()
            .map(|p| [srgb_decode(p[0]), srgb_decode(p[1]), srgb_decode(p[2])])
            .collect();
        RgbImage::from_pixels(self.width, self.height, pixels)
    }
}

/// Reads a PNG's stored values (see [`StoredImage`]).
///
/// # Errors
/// As [`read_png`].
pub fn read_png_stored(path: impl AsRef<Path>) -> Result<StoredImage, ImageError> {
    let path = path.as_ref();
    let read_err = |e: png::DecodingError| ImageError::Read {
        path: path.into(),
        source: e.into(),
    };
    let file = File::open(path).map_err(|source| ImageError::Io {
        action: "cannot open",
        path: path.into(),
        source,
    })?;
    let limits = png::Limits {
        bytes: MAX_DECODED_BYTES,
    };
    let mut decoder = png::Decoder::new_with_limits(BufReader::new(file), limits);
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(read_err)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| ImageError::Read {
            path: path.into(),
            source: "decoded image does not fit in memory".into(),
        })?;
    let mut buffer = vec![0u8; size];
    let info = reader.next_frame(&mut buffer).map_err(read_err)?;
    let (width, height) = (info.width as usize, info.height as usize);
    let samples = stored_samples(&buffer[..info.line_size * height], info.line_size, &info);
    let channels = match info.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => {
            return Err(ImageError::Read {
                path: path.into(),
                source: "palette image was not expanded".into(),
            })
        }
    };
    let pixels = samples
        .chunks_exact(channels)
        .map(|s| match channels {
            1 => [s[0], s[0], s[0], 1.0],
            2 => [s[0], s[0], s[0], s[1]],
            3 => [s[0], s[1], s[2], 1.0],
            _ => [s[0], s[1], s[2], s[3]],
        })
        .collect();
    Ok(StoredImage {
        width,
        height,
        pixels,
        has_alpha: channels % 2 == 0,
    })
}

/// Converts the decoder's rows (8 or 16 bits per sample, big-endian) to
/// floats in [0, 1], dropping any row padding.
fn stored_samples(rows: &[u8], line_size: usize, info: &png::OutputInfo) -> Vec<f32> {
    let samples_per_row = info.width as usize * info.color_type.samples();
    match info.bit_depth {
        png::BitDepth::Sixteen => rows
            .chunks_exact(line_size)
            .flat_map(|row| row[..samples_per_row * 2].chunks_exact(2))
            .map(|b| u16::from_be_bytes([b[0], b[1]]) as f32 / 65535.0)
            .collect(),
        _ => rows
            .chunks_exact(line_size)
            .flat_map(|row| &row[..samples_per_row])
            .map(|&v| v as f32 / 255.0)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tonemap::srgb_encode;
    use crate::ToneCurve;
    use candela_testkit::TempDir;

    fn gradient() -> RgbImage {
        RgbImage::from_fn(37, 11, |x, y| {
            [
                x as f32 / 36.0,
                y as f32 / 10.0,
                ((x * 7 + y * 13) % 17) as f32 / 16.0,
            ]
        })
        .unwrap()
    }

    #[test]
    fn png_round_trip_is_within_quantisation() {
        let dir = TempDir::new("png-rt");
        let path = dir.path().join("g.png");
        let image = gradient();
        write_png(&path, &image, &ToneMap::default()).unwrap();
        let back = read_png(&path).unwrap();
        assert_eq!(back.size(), image.size());
        for (a, b) in image.pixels().iter().zip(back.pixels()) {
            for c in 0..3 {
                // Half a code step in the encoded domain, the quantisation bound.
                let error = (srgb_encode(a[c]) - srgb_encode(b[c])).abs();
                assert!(error <= 0.5 / 255.0 + 1e-6, "{a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn written_bytes_are_the_rounded_srgb_codes() {
        let dir = TempDir::new("png-bytes");
        let path = dir.path().join("p.png");
        let image =
            RgbImage::from_pixels(2, 1, vec![[0.5, 0.0, 1.0], [f32::NAN, 0.18, 9.0]]).unwrap();
        write_png(
            &path,
            &image,
            &ToneMap {
                exposure: 0.0,
                curve: ToneCurve::Srgb,
            },
        )
        .unwrap();
        let back = read_png(&path).unwrap();
        let codes: Vec<u8> = back
            .pixels()
            .iter()
            .flat_map(|p| p.map(|v| quantize_u8(srgb_encode(v))))
            .collect();
        assert_eq!(codes, vec![188, 0, 255, 0, 118, 255]);
    }

    #[test]
    fn display_values_are_written_without_a_curve() {
        let dir = TempDir::new("png-display");
        let path = dir.path().join("d.png");
        let image = RgbImage::from_pixels(1, 1, vec![[0.5, 0.25, 1.0]]).unwrap();
        write_png_display(&path, &image).unwrap();
        let p = read_png(&path).unwrap().pixels()[0];
        let codes = p.map(|v| quantize_u8(srgb_encode(v)));
        assert_eq!(codes, [128, 64, 255]);
    }

    #[test]
    fn reading_a_missing_or_corrupt_file_names_it() {
        let dir = TempDir::new("png-bad");
        let missing = dir.path().join("missing.png");
        let err = read_png(&missing).unwrap_err().to_string();
        assert!(err.contains("missing.png"), "{err}");
        let corrupt = dir.path().join("corrupt.png");
        std::fs::write(&corrupt, b"\x89PNG\r\n\x1a\nnot really").unwrap();
        let err = read_png(&corrupt).unwrap_err();
        assert!(matches!(err, ImageError::Read { .. }));
        assert!(err.to_string().contains("corrupt.png"));
    }

    #[test]
    fn sixteen_bit_grey_with_alpha_is_decoded_as_srgb_grey() {
        let dir = TempDir::new("png-16");
        let path = dir.path().join("g16.png");
        // Two pixels: grey 0x8000 with alpha 0x1234, and white, fully opaque.
        let data = [0x80, 0x00, 0x12, 0x34, 0xff, 0xff, 0xff, 0xff];
        atomic_write(&path, |w| -> Result<(), png::EncodingError> {
            let mut encoder = png::Encoder::new(w, 2, 1);
            encoder.set_color(png::ColorType::GrayscaleAlpha);
            encoder.set_depth(png::BitDepth::Sixteen);
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&data)?;
            writer.finish()
        })
        .unwrap();
        let image = read_png(&path).unwrap();
        let grey = srgb_decode(32768.0 / 65535.0);
        assert_eq!(image.pixels(), &[[grey; 3], [1.0; 3]]);
        // 0x8000 / 0xffff is just above one half: linear about 0.2140.
        assert!((grey - 0.214_04).abs() < 1e-4, "{grey}");
    }
}
