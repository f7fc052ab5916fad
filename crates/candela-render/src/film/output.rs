//! Film to file: the one path every front end (CLI, Python, viewer, tests)
//! writes a render by. PNG goes through a tone map; EXR keeps linear
//! radiance with the layers asked for and every extra layer the film
//! carries ([`super::FilmLayers`]); with adaptive sampling the CS184
//! sample-rate image is written beside the output. Every file is written
//! atomically, so a failed write leaves no file.
//!
//! An EXR can carry the per-pixel variance of the mean (`variance.R/G/B`,
//! with the `samples` layer it needs to be merged) and, in its header, how
//! it was made ([`RenderInfo`]: spp, time, seed, integrator, scene); the
//! sample spread is taken from the film itself.

use super::{CostMeasure, Film};
use candela_image::{
    rate_image, write_exr_compressed, write_png, write_png_display, ExrCompression, ExrLayers,
    ImageError, LayerData, RenderInfo, SppSpread, ToneMap, VARIANCE_LAYER,
};
use std::path::{Path, PathBuf};

/// The output file types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB through a tone map.
    Png,
    /// Linear float layers.
    Exr,
}

impl OutputFormat {
    /// The format of `path`, from its extension (case-insensitive).
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

/// What goes into the files besides the beauty image.
#[derive(Clone, Debug, Default)]
pub struct OutputOptions {
    /// PNG exposure and curve.
    pub tone: ToneMap,
    /// EXR: the albedo and normal layers denoisers read.
    pub aovs: bool,
    /// EXR: a `samples` layer with each pixel's sample count.
    pub sample_counts: bool,
    /// EXR: a `depth` layer, the mean first-hit distance ([`Film::depth`];
    /// +inf where nothing was hit).
    pub depth: bool,
    /// EXR: the cost layers `cost.nodes` and `cost.prims`, BVH nodes
    /// visited and primitive tests per sample ([`Film::cost`]).
    pub cost: bool,
    /// EXR: a `variance` layer, the variance of each pixel's mean
    /// ([`Film::variance`]), and with it the `samples` layer (`candela merge`
    /// needs both).
    pub variance: bool,
    /// EXR header metadata; its `spp` is filled from the film when `None`.
    pub info: RenderInfo,
    /// Also write `<stem>_rate.png`, the CS184 sample-rate image, with this
    /// sample count shown as red (adaptive sampling).
    pub rate_image: Option<u32>,
    /// EXR: how the scanlines are compressed (`OutputSettings::exr_compression`).
    pub exr_compression: ExrCompression,
}

/// Why a film could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The file name ends in neither `.png` nor `.exr`.
    #[error("{0}: the output must end in .png or .exr")]
    Format(PathBuf),
    /// The image could not be encoded or written.
    #[error("cannot write {0}: {1}")]
    Write(PathBuf, ImageError),
}

/// `<folder>/<stem>_rate.png` beside `output`.
pub fn rate_path(output: &Path) -> PathBuf {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    output.with_file_name(format!("{stem}_rate.png"))
}

/// Writes `film` to `path` (its extension chooses the format) and, if asked,
/// the rate image beside it. Returns the paths written.
pub fn write_film(
    path: &Path,
    film: &Film,
    opts: &OutputOptions,
) -> Result<Vec<PathBuf>, OutputError> {
    let format = OutputFormat::of(path).ok_or_else(|| OutputError::Format(path.to_path_buf()))?;
    let failed = |p: &Path| {
        let p = p.to_path_buf();
        move |e| OutputError::Write(p, e)
    };
    match format {
        OutputFormat::Png => write_png(path, &film.resolve(), &opts.tone),
        OutputFormat::Exr => {
            let mut extra = Vec::new();
            if opts.depth {
                extra.push(("depth".to_string(), LayerData::Gray(film.depth())));
            }
            if opts.cost {
                for (name, measure) in [
                    ("cost.nodes", CostMeasure::Nodes),
                    ("cost.prims", CostMeasure::PrimTests),
                ] {
                    extra.push((name.to_string(), LayerData::Gray(film.cost(measure))));
                }
            }
            // The variance of a pixel's mean is known from its camera
            // samples' sums; light-subpath splats are summed without their
            // squares, so a film with splats (light tracing, BDPT) gets no
            // variance layer rather than one that understates its noise
            // (`candela compare` then estimates it from each block's spread).
            if opts.variance && film.splats.is_empty() {
                extra.push((VARIANCE_LAYER.to_string(), LayerData::Rgb(film.variance())));
            }
            let counts = film.pixels.iter().map(|p| p.count as f64);
            let info = RenderInfo {
                spp: opts.info.spp.or_else(|| SppSpread::of_counts(counts)),
                ..opts.info.clone()
            };
            for (index, name) in film.layers.names().iter().enumerate() {
                extra.push((name.clone(), LayerData::Rgb(film.layer(index))));
            }
            let layers = ExrLayers {
                albedo: opts.aovs.then(|| film.albedo()),
                normal: opts.aovs.then(|| film.normal()),
                sample_count: (opts.sample_counts || opts.variance)
                    .then(|| film.sample_count_image()),
                extra,
                info,
                ..ExrLayers::beauty(film.resolve())
            };
            write_exr_compressed(path, &layers, opts.exr_compression)
        }
    }
    .map_err(failed(path))?;
    let mut written = vec![path.to_path_buf()];
    if let Some(max_samples) = opts.rate_image {
        let rate = rate_path(path);
        rate_image(&film.sample_count_image(), max_samples.max(1))
            .and_then(|image| write_png_display(&rate, &image))
            .map_err(failed(&rate))?;
        written.push(rate);
    }
    Ok(written)
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

    #[test]
    fn an_unknown_extension_writes_nothing() {
        let dir = candela_testkit::TempDir::new("film-output");
        let path = dir.path().join("x.jpg");
        let err = write_film(&path, &Film::new(2, 2), &OutputOptions::default()).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: the output must end in .png or .exr", path.display())
        );
        assert!(!path.exists());
    }

    #[test]
    fn extra_layers_go_into_the_exr_by_name() {
        let dir = candela_testkit::TempDir::new("film-layers");
        let path = dir.path().join("layers.exr");
        let names = vec!["bounce_0".to_string(), "bounce_1".to_string()];
        let mut film = Film::with_layers(3, 2, names.clone());
        let values = [glam::Vec3::new(1.0, 2.0, 3.0), glam::Vec3::splat(0.5)];
        film.pixels[4].add_sample(values[0] + values[1]);
        film.layers.add(4, &values);
        write_film(&path, &film, &OutputOptions::default()).expect("written");
        let read = candela_image::read_exr_layers(&path).expect("read back");
        let layers: Vec<(&str, &LayerData)> =
            read.extra.iter().map(|(n, d)| (n.as_str(), d)).collect();
        assert_eq!(layers.len(), 2, "{:?}", read.extra);
        for (index, name) in names.iter().enumerate() {
            let (_, data) = layers.iter().find(|(n, _)| n == name).expect("layer");
            assert_eq!(**data, LayerData::Rgb(film.layer(index)));
        }
    }
}
