//! The denoised image of a film, and its file beside the raw output.
//!
//! Denoising reads the film's own guides, the mean first-hit albedo and
//! shading normal ([`Film::albedo`], [`Film::normal`]), and runs Intel Open
//! Image Denoise ([`candela_image::denoise`]). The result goes to its own
//! file, `<stem>.denoised.<ext>` beside the output, so the raw image (the
//! unbiased estimate every statistic is about) is always kept.

use super::output::OutputError;
use super::{Film, OutputFormat};
use candela_image::denoise::{DenoiseError, Guides, Oidn};
use candela_image::{write_exr, write_png, ExrLayers, RgbImage, ToneMap};
use std::path::{Path, PathBuf};

/// The film's image denoised by `oidn`, guided by its albedo and normal.
pub fn denoise_film(film: &Film, oidn: &Oidn) -> Result<RgbImage, DenoiseError> {
    let (albedo, normal) = (film.albedo(), film.normal());
    let guides = Guides {
        albedo: &albedo,
        normal: &normal,
    };
    oidn.denoise(&film.resolve(), Some(guides))
}

/// `<folder>/<stem>.denoised.<ext>` beside `output`.
pub fn denoised_path(output: &Path) -> PathBuf {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = output
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    output.with_file_name(format!("{stem}.denoised{ext}"))
}

/// Writes a denoised image to `path` as the output of that name would be
/// written: PNG through `tone`, EXR as linear radiance.
pub fn write_denoised(path: &Path, image: &RgbImage, tone: &ToneMap) -> Result<(), OutputError> {
    match OutputFormat::of(path) {
        Some(OutputFormat::Png) => write_png(path, image, tone),
        Some(OutputFormat::Exr) => write_exr(path, &ExrLayers::beauty(image.clone())),
        None => return Err(OutputError::Format(path.to_path_buf())),
    }
    .map_err(|e| OutputError::Write(path.to_path_buf(), e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_denoised_file_sits_beside_the_output() {
        assert_eq!(
            denoised_path(Path::new("out/bunny.exr")),
            PathBuf::from("out/bunny.denoised.exr")
        );
        assert_eq!(
            denoised_path(Path::new("b.png")),
            PathBuf::from("b.denoised.png")
        );
    }
}
