//! Writing a render: the image (PNG through a tone map, or EXR with the
//! denoiser layers) and, with adaptive sampling, the CS184 sample-rate image.
//! Every file is written atomically, so a failed write leaves no file.

use anyhow::{Context, Result};
use candela_image::{
    rate_image, write_exr, write_png, write_png_display, ExrLayers, GrayImage, RgbImage, ToneMap,
};
use candela_render::film::Film;
use glam::Vec3;
use std::path::{Path, PathBuf};

/// The output file types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB through a tone map.
    Png,
    /// Linear half/float layers.
    Exr,
}

impl OutputFormat {
    /// The format of `path`, from its extension.
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Some(Self::Png),
            Some("exr") => Some(Self::Exr),
            _ => None,
        }
    }
}

/// What goes into the files besides the film.
pub struct OutputOptions {
    /// PNG exposure and curve.
    pub tone: ToneMap,
    /// Whether to write the sample counts (EXR layer `samples`) and the
    /// rate image: set with adaptive sampling.
    pub sample_rate: bool,
    /// The sample count shown as red in the rate image.
    pub max_samples: u32,
}

/// `<folder>/<stem>_rate.png` beside `output`.
pub fn rate_path(output: &Path) -> PathBuf {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    output.with_file_name(format!("{stem}_rate.png"))
}

/// Writes `film` to `path`, and the rate image beside it if asked. Returns
/// the paths written.
pub fn write(
    path: &Path,
    format: OutputFormat,
    film: &Film,
    opts: &OutputOptions,
) -> Result<Vec<PathBuf>> {
    let beauty = rgb(film, film.resolve())?;
    let counts = GrayImage::from_values(
        film.width as usize,
        film.height as usize,
        film.sample_counts().into_iter().map(|n| n as f32).collect(),
    )?;
    match format {
        OutputFormat::Png => write_png(path, &beauty, &opts.tone),
        OutputFormat::Exr => {
            let layers = ExrLayers {
                albedo: Some(rgb(film, film.albedo())?),
                normal: Some(rgb(film, film.normal())?),
                sample_count: opts.sample_rate.then(|| counts.clone()),
                ..ExrLayers::beauty(beauty)
            };
            write_exr(path, &layers)
        }
    }
    .with_context(|| format!("cannot write {}", path.display()))?;
    let mut written = vec![path.to_path_buf()];
    if opts.sample_rate {
        let rate = rate_path(path);
        let image = rate_image(&counts, opts.max_samples.max(1))?;
        write_png_display(&rate, &image)
            .with_context(|| format!("cannot write {}", rate.display()))?;
        written.push(rate);
    }
    Ok(written)
}

fn rgb(film: &Film, values: Vec<Vec3>) -> Result<RgbImage> {
    let pixels = values.into_iter().map(|c| c.to_array()).collect();
    Ok(RgbImage::from_pixels(
        film.width as usize,
        film.height as usize,
        pixels,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rate_image_sits_beside_the_output() {
        assert_eq!(
            rate_path(Path::new("out/bunny.exr")),
            PathBuf::from("out/bunny_rate.png")
        );
        assert_eq!(rate_path(Path::new("b.png")), PathBuf::from("b_rate.png"));
        assert_eq!(
            OutputFormat::of(Path::new("a.EXR")),
            Some(OutputFormat::Exr)
        );
        assert_eq!(OutputFormat::of(Path::new("a.jpg")), None);
    }
}
