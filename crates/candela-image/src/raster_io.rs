//! Reading the image formats scenes use for textures besides PNG and EXR:
//! JPEG, TGA, BMP and WebP (8-bit stored values, sRGB-encoded colour unless the
//! scene says the data is linear) and Radiance HDR (`.hdr`, linear), through
//! the `image` crate with a cap on the decoded size; and the Portable Float
//! Map (`.pfm`, linear, pbrt's and Mitsuba's plain float format), read here.

use crate::png_io::MAX_DECODED_BYTES;
use crate::{ImageError, RgbImage, StoredImage};
use image::{DynamicImage, ImageReader, Limits};
use std::path::Path;

/// The 8-bit formats read as stored values, by lower-case extension.
pub const STORED_EXTENSIONS: [&str; 5] = ["jpg", "jpeg", "tga", "bmp", "webp"];

/// Reads a JPEG, TGA, BMP or WebP file's stored values, each scaled to [0, 1]
/// (`v / 255`, or `v / 65535` for 16-bit data), as RGBA with grey
/// replicated to RGB and a missing alpha 1: the same form as
/// [`crate::read_png_stored`], so textures read every 8-bit format alike.
///
/// # Errors
/// [`ImageError::Io`] if the file cannot be opened, [`ImageError::Read`] if
/// it cannot be decoded or its decoded size exceeds 1 GiB; both name it.
pub fn read_stored(path: impl AsRef<Path>) -> Result<StoredImage, ImageError> {
    let path = path.as_ref();
    let image = decode(path)?;
    let has_alpha = image.color().has_alpha();
    let (width, height) = (image.width() as usize, image.height() as usize);
    let pixels = if image.color().bytes_per_pixel() / image.color().channel_count() > 1 {
        image
            .to_rgba16()
            .pixels()
            .map(|p| p.0.map(|v| v as f32 / 65535.0))
            .collect()
    } else {
        image
            .to_rgba8()
            .pixels()
            .map(|p| p.0.map(|v| v as f32 / 255.0))
            .collect()
    };
    Ok(StoredImage {
        width,
        height,
        pixels,
        has_alpha,
    })
}

/// Reads a Radiance HDR (`.hdr`, RGBE) file as linear RGB.
///
/// # Errors
/// As [`read_stored`].
pub fn read_radiance_hdr(path: impl AsRef<Path>) -> Result<RgbImage, ImageError> {
    let path = path.as_ref();
    let image = decode(path)?.to_rgb32f();
    let (width, height) = (image.width() as usize, image.height() as usize);
    let pixels = image.pixels().map(|p| p.0).collect();
    RgbImage::from_pixels(width, height, pixels)
}

/// Reads a Portable Float Map (`.pfm`): a text header `PF` (RGB) or `Pf`
/// (grey), the width and height, and a scale whose sign gives the byte
/// order (negative: little endian), then 32-bit floats row by row from the
/// **bottom** row. Grey is replicated to RGB; every value is multiplied by
/// the scale's magnitude, as Mitsuba 3 and pbrt-v4 read it.
///
/// # Errors
/// [`ImageError::Io`] if the file cannot be read, [`ImageError::Read`] for
/// a malformed header, a size over the 1 GiB cap, or too few pixel bytes.
pub fn read_pfm(path: impl AsRef<Path>) -> Result<RgbImage, ImageError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| ImageError::Io {
        action: "cannot read",
        path: path.into(),
        source,
    })?;
    let bad = |why: &str| ImageError::Read {
        path: path.into(),
        source: format!("not a PFM file: {why}").into(),
    };
    // Three whitespace-separated header fields after the magic, then one
    // whitespace byte, then the data.
    let mut fields = Vec::new();
    let mut at = 0;
    while fields.len() < 4 {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        if start == at || at >= bytes.len() {
            return Err(bad("the header ends early"));
        }
        fields.push(String::from_utf8_lossy(&bytes[start..at]).into_owned());
    }
    at += 1;
    let channels = match fields[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        _ => return Err(bad("it does not start with PF or Pf")),
    };
    let size = |s: &str| s.parse::<usize>().ok().filter(|&n| n > 0);
    let (Some(width), Some(height)) = (size(&fields[1]), size(&fields[2])) else {
        return Err(bad("its width or height is not a positive number"));
    };
    let scale: f32 = fields[3]
        .parse()
        .map_err(|_| bad("its scale is not a number"))?;
    let count = width
        .checked_mul(height)
        .and_then(|n| n.checked_mul(channels * 4))
        .filter(|&n| n <= MAX_DECODED_BYTES)
        .ok_or_else(|| bad("its size is over the 1 GiB decoding cap"))?;
    let data = bytes
        .get(at..at + count)
        .ok_or_else(|| bad("it has fewer pixels than its header says"))?;
    let value = |k: usize| {
        let b = [
            data[4 * k],
            data[4 * k + 1],
            data[4 * k + 2],
            data[4 * k + 3],
        ];
        let v = if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        v * scale.abs()
    };
    let mut pixels = Vec::with_capacity(width * height);
    for row in (0..height).rev() {
        for x in 0..width {
            let k = (row * width + x) * channels;
            pixels.push(if channels == 3 {
                [value(k), value(k + 1), value(k + 2)]
            } else {
                [value(k); 3]
            });
        }
    }
    RgbImage::from_pixels(width, height, pixels)
}

/// The decoded image, its format from the file's first bytes (falling back
/// to the extension), within [`MAX_DECODED_BYTES`].
fn decode(path: &Path) -> Result<DynamicImage, ImageError> {
    let io_err = |source| ImageError::Io {
        action: "cannot open",
        path: path.into(),
        source,
    };
    // The decoders' messages may span lines; errors here are one line.
    let read_err = |e: image::ImageError| ImageError::Read {
        path: path.into(),
        source: e
            .to_string()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
            .into(),
    };
    let mut reader = ImageReader::open(path)
        .map_err(io_err)?
        .with_guessed_format()
        .map_err(io_err)?;
    let mut limits = Limits::default();
    limits.max_alloc = Some(MAX_DECODED_BYTES as u64);
    reader.limits(limits);
    reader.decode().map_err(read_err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageFormat, Rgb, RgbImage as Rgb8, Rgba, RgbaImage};

    /// A 3×2 image whose every value differs, so a flip, a channel swap or
    /// an off-by-one row shows.
    fn pattern() -> RgbaImage {
        RgbaImage::from_fn(3, 2, |x, y| {
            Rgba([
                (40 * x + 7) as u8,
                (90 * y + 13) as u8,
                (200 - 30 * x - 50 * y) as u8,
                (255 - 60 * x) as u8,
            ])
        })
    }

    fn stored(p: &Rgba<u8>, alpha: bool) -> [f32; 4] {
        let a = if alpha { p.0[3] } else { 255 };
        [p.0[0], p.0[1], p.0[2], a].map(|v| v as f32 / 255.0)
    }

    #[test]
    fn lossless_formats_read_back_every_stored_value_from_the_top_row() {
        let dir = candela_testkit::TempDir::new("raster-io-lossless");
        let image = pattern();
        let cases = [
            ("t.tga", ImageFormat::Tga, true),
            ("t.bmp", ImageFormat::Bmp, true),
            // The encoder writes lossless WebP (glTF's EXT_texture_webp).
            ("t.webp", ImageFormat::WebP, true),
        ];
        for (name, format, alpha) in cases {
            let path = dir.join(name);
            image.save_with_format(&path, format).unwrap();
            let read = read_stored(&path).unwrap();
            assert_eq!(
                (read.width, read.height, read.has_alpha),
                (3, 2, alpha),
                "{name}"
            );
            let want: Vec<[f32; 4]> = image.pixels().map(|p| stored(p, alpha)).collect();
            assert_eq!(read.pixels, want, "{name}");
        }
    }

    #[test]
    fn a_jpeg_reads_back_within_its_compression_error() {
        // A flat colour survives JPEG's quantisation to a level or two.
        let dir = candela_testkit::TempDir::new("raster-io-jpeg");
        let path = dir.join("flat.jpg");
        Rgb8::from_pixel(16, 8, Rgb([200, 100, 30]))
            .save_with_format(&path, ImageFormat::Jpeg)
            .unwrap();
        let read = read_stored(&path).unwrap();
        assert_eq!((read.width, read.height, read.has_alpha), (16, 8, false));
        for p in &read.pixels {
            let want = [200.0, 100.0, 30.0].map(|v: f32| v / 255.0);
            for c in 0..3 {
                assert!((p[c] - want[c]).abs() <= 3.0 / 255.0, "{p:?}");
            }
            assert_eq!(p[3], 1.0);
        }
    }

    #[test]
    fn radiance_hdr_reads_linear_values_beyond_one() {
        // RGBE keeps 8 bits of mantissa per channel under a shared
        // exponent: relative error below 2^-7 of the largest channel.
        let dir = candela_testkit::TempDir::new("raster-io-hdr");
        let path = dir.join("sky.hdr");
        let values = [[12.5f32, 3.0, 0.25], [0.01, 0.02, 0.04]];
        let image = image::Rgb32FImage::from_fn(2, 1, |x, _| Rgb(values[x as usize]));
        DynamicImage::ImageRgb32F(image)
            .save_with_format(&path, ImageFormat::Hdr)
            .unwrap();
        let read = read_radiance_hdr(&path).unwrap();
        assert_eq!(read.size(), (2, 1));
        for (got, want) in read.pixels().iter().zip(values) {
            let scale = want.iter().cloned().fold(0.0, f32::max);
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() <= scale / 128.0,
                    "{got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn a_pfm_reads_from_the_bottom_row_in_either_byte_order() {
        // 2×2 RGB, rows stored bottom first: the top row read first must be
        // the file's second.
        let dir = candela_testkit::TempDir::new("raster-io-pfm");
        let rows = [
            [[1.5f32, 2.0, 3.0], [0.25, 0.5, 0.75]],
            [[10.0, 20.0, 30.0], [-1.0, 0.0, 1e-3]],
        ];
        for (name, scale, le) in [("le.pfm", "-1.0", true), ("be.pfm", "1.0", false)] {
            let mut bytes = format!("PF\n2 2\n{scale}\n").into_bytes();
            for row in &rows {
                for v in row.iter().flatten() {
                    bytes.extend(if le { v.to_le_bytes() } else { v.to_be_bytes() });
                }
            }
            let path = dir.join(name);
            std::fs::write(&path, &bytes).unwrap();
            let image = read_pfm(&path).unwrap();
            assert_eq!(image.size(), (2, 2));
            let top_first: Vec<[f32; 3]> = rows.iter().rev().flatten().copied().collect();
            assert_eq!(image.pixels(), &top_first[..], "{name}");
        }
        // Grey, replicated, times the scale's magnitude (Mitsuba 3.9 reads
        // this file as 1.0); and a file cut short is an error naming it.
        let grey = dir.join("grey.pfm");
        let mut bytes = b"Pf 1 1 -2\n".to_vec();
        bytes.extend(0.5f32.to_le_bytes());
        std::fs::write(&grey, &bytes).unwrap();
        assert_eq!(read_pfm(&grey).unwrap().pixels(), &[[1.0; 3]]);
        std::fs::write(&grey, &bytes[..bytes.len() - 1]).unwrap();
        let err = read_pfm(&grey).unwrap_err().to_string();
        assert!(
            err.contains("grey.pfm") && err.contains("fewer pixels"),
            "{err}"
        );
    }

    #[test]
    fn a_file_that_is_not_an_image_names_itself() {
        let dir = candela_testkit::TempDir::new("raster-io-bad");
        let path = dir.join("broken.jpg");
        std::fs::write(&path, b"not a jpeg at all").unwrap();
        let err = read_stored(&path).unwrap_err().to_string();
        assert!(err.contains("broken.jpg") && !err.contains('\n'), "{err}");
        // A JPEG cut short: the decoder's message has a line break.
        let cut = dir.join("cut.jpg");
        Rgb8::from_pixel(16, 8, Rgb([200, 100, 30]))
            .save_with_format(&cut, ImageFormat::Jpeg)
            .unwrap();
        let bytes = std::fs::read(&cut).unwrap();
        std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
        let err = read_stored(&cut).unwrap_err().to_string();
        assert!(err.contains("cut.jpg") && !err.contains('\n'), "{err}");
        let missing = read_radiance_hdr(dir.join("missing.hdr"))
            .unwrap_err()
            .to_string();
        assert!(missing.contains("missing.hdr"), "{missing}");
    }
}
