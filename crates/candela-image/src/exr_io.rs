//! Linear float OpenEXR output with the auxiliary layers denoisers use, and
//! EXR input for environment maps and references.
//!
//! # Channel names
//! One single-part file, 32-bit float channels, scanlines compressed
//! losslessly as [`ExrCompression`] says (ZIP by default, which every EXR
//! tool reads):
//!
//! | layer | channels | content |
//! |---|---|---|
//! | beauty | `R`, `G`, `B` | linear radiance |
//! | albedo | `albedo.R`, `albedo.G`, `albedo.B` | first-hit albedo in `[0, 1]` |
//! | normal | `normal.R`, `normal.G`, `normal.B` | first-hit normal, components X, Y, Z in `[-1, 1]` |
//! | sample count | `samples` | samples taken per pixel |
//! | variance | `variance.R`, `variance.G`, `variance.B` | variance of the pixel's mean estimate ([`crate::variance`]) |
//! | extra RGB layer `name` | `name.R`, `name.G`, `name.B` | anything, e.g. a standard error |
//! | extra scalar layer `name` | `name` | anything |
//!
//! `layer.R/G/B` is OpenEXR's own multi-layer convention (layer name, dot,
//! channel name), which EXR tools split into layers; a denoiser front end
//! finds the guides by the names `albedo` and `normal`. Normals use
//! `R/G/B` rather than `X/Y/Z` so every three-channel layer reads the same
//! way. Open Image Denoise itself takes separate buffers, so a caller hands
//! it these layers one by one.
//!
//! The header carries [`RenderInfo`] (sample counts, render time, seed,
//! ...; see [`crate::render_info`] for the attribute names).
//!
//! # Reading other programs' files
//! The beauty image is the unprefixed `R`, `G`, `B` channels (what pbrt-v4
//! and Mitsuba 3 write), else a luminance-only `Y`, else the one RGB layer of
//! the file (`<layer>.R/G/B`, e.g. Blender's `ViewLayer.Combined.R`); with
//! several RGB layers and no bare one, a layer called `Combined`, `beauty`,
//! `rgb`, `color` or `image` (case-insensitive, last name component) is
//! taken. An alpha channel `A` is kept as a scalar layer.

use std::collections::BTreeSet;
use std::path::Path;

use exr::prelude::{
    read_first_flat_layer_from_file, AnyChannel, AnyChannels, Blocks, Compression, Encoding,
    FlatSamples, Image, Layer, LayerAttributes, LineOrder, SmallVec, Text, Vec2, WritableImage,
};

use crate::{atomic_write, GrayImage, ImageError, RenderInfo, RgbImage};

/// The name of the variance layer (`variance.R/G/B`).
pub const VARIANCE_LAYER: &str = "variance";

/// How the scanlines of an EXR file are compressed. Every choice is
/// lossless, so the pixels read back are the ones written; they trade file
/// size against the time spent writing. The 15 channels of a 480×360
/// CBbunny render with its layers: ZIP 2.8 MB, PIZ 3.9 MB, RLE 8.1 MB,
/// none 11.1 MB; ZIP costs the most CPU time (BENCHMARKS.md, "EXR
/// compression"). The `--exr-compression` setting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ExrCompression {
    /// No compression: the fastest to write, the largest file.
    None,
    /// Run-length encoding: fast, little gain on noisy renders.
    Rle,
    /// Deflate in blocks of 16 scanlines: small files, slow to write.
    #[default]
    Zip,
    /// Wavelet-based PIZ: small files for noisy images, faster than ZIP.
    Piz,
}

impl ExrCompression {
    /// The `exr` crate's encoding: this compression over scanlines.
    fn encoding(self) -> Encoding {
        let compression = match self {
            ExrCompression::None => Compression::Uncompressed,
            ExrCompression::Rle => Compression::RLE,
            ExrCompression::Zip => Compression::ZIP16,
            ExrCompression::Piz => Compression::PIZ,
        };
        Encoding {
            compression,
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        }
    }
}

/// The data of an extra layer: three colour channels or one scalar.
#[derive(Clone, Debug, PartialEq)]
pub enum LayerData {
    /// Written as `<name>.R`, `<name>.G`, `<name>.B`.
    Rgb(RgbImage),
    /// Written as `<name>`.
    Gray(GrayImage),
}

/// Everything that goes into one EXR file: the beauty image and optional
/// auxiliary layers of the same size.
#[derive(Clone, Debug, PartialEq)]
pub struct ExrLayers {
    /// Linear radiance, channels `R`, `G`, `B`.
    pub beauty: RgbImage,
    /// Albedo for denoising, channels `albedo.R/G/B`.
    pub albedo: Option<RgbImage>,
    /// Shading normals (X, Y, Z) for denoising, channels `normal.R/G/B`.
    pub normal: Option<RgbImage>,
    /// Samples per pixel, channel `samples`: shows where adaptive sampling
    /// spent its effort.
    pub sample_count: Option<GrayImage>,
    /// Further layers by name (e.g. a per-pixel standard error for
    /// statistical comparison). Names must be ASCII and distinct from the
    /// channels above.
    pub extra: Vec<(String, LayerData)>,
    /// Header metadata: how the image was rendered.
    pub info: RenderInfo,
}

impl ExrLayers {
    /// Just a beauty image, no auxiliary layers.
    pub fn beauty(beauty: RgbImage) -> Self {
        Self {
            beauty,
            albedo: None,
            normal: None,
            sample_count: None,
            extra: Vec::new(),
            info: RenderInfo::default(),
        }
    }

    /// The extra layer called `name`, if any.
    pub fn layer(&self, name: &str) -> Option<&LayerData> {
        self.extra.iter().find(|(n, _)| n == name).map(|(_, d)| d)
    }

    /// The per-pixel variance of the mean (layer [`VARIANCE_LAYER`]), if
    /// the file has it.
    pub fn variance(&self) -> Option<&RgbImage> {
        match self.layer(VARIANCE_LAYER) {
            Some(LayerData::Rgb(image)) => Some(image),
            _ => None,
        }
    }

    /// Every layer as `(channel name, values)` pairs, checking sizes.
    fn channels(&self) -> Result<Vec<(String, Vec<f32>)>, ImageError> {
        let size = self.beauty.size();
        let mut layers: Vec<(&str, LayerRef)> = Vec::new();
        if let Some(albedo) = &self.albedo {
            layers.push(("albedo", LayerRef::Rgb(albedo)));
        }
        if let Some(normal) = &self.normal {
            layers.push(("normal", LayerRef::Rgb(normal)));
        }
        if let Some(count) = &self.sample_count {
            layers.push(("samples", LayerRef::Gray(count)));
        }
        for (name, data) in &self.extra {
            layers.push(match data {
                LayerData::Rgb(image) => (name, LayerRef::Rgb(image)),
                LayerData::Gray(image) => (name, LayerRef::Gray(image)),
            });
        }
        let mut out = rgb_channels("", &self.beauty);
        for (name, data) in layers {
            let layer_size = match data {
                LayerRef::Rgb(image) => image.size(),
                LayerRef::Gray(image) => image.size(),
            };
            if layer_size != size {
                let what = "EXR layer must match the beauty image size";
                return Err(ImageError::SizeMismatch {
                    what,
                    a: size,
                    b: layer_size,
                });
            }
            match data {
                LayerRef::Rgb(image) => out.extend(rgb_channels(name, image)),
                LayerRef::Gray(image) => out.push((name.to_string(), image.values().to_vec())),
            }
        }
        let mut seen = BTreeSet::new();
        for (name, _) in &out {
            if !seen.insert(name.as_str()) {
                return Err(ImageError::InvalidArgument(format!(
                    "duplicate EXR channel {name}"
                )));
            }
        }
        Ok(out)
    }
}

/// A borrowed layer, so collecting channels does not copy whole images.
enum LayerRef<'a> {
    Rgb(&'a RgbImage),
    Gray(&'a GrayImage),
}

/// The three channels of an RGB layer; `prefix` empty for the beauty layer.
fn rgb_channels(prefix: &str, image: &RgbImage) -> Vec<(String, Vec<f32>)> {
    let dot = if prefix.is_empty() { "" } else { "." };
    ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(c, suffix)| {
            let values = image.pixels().iter().map(|p| p[c]).collect();
            (format!("{prefix}{dot}{suffix}"), values)
        })
        .collect()
}

/// Writes `layers` as a linear 32-bit float OpenEXR file, atomically.
///
/// Values are stored exactly, NaN and infinities included: an EXR is data,
/// and hiding a bad sample would defeat debugging.
///
/// # Errors
/// [`ImageError::SizeMismatch`] if a layer's size differs from the beauty
/// image, [`ImageError::InvalidArgument`] for non-ASCII or duplicate channel
/// names, and the errors of [`atomic_write`].
pub fn write_exr(path: impl AsRef<Path>, layers: &ExrLayers) -> Result<(), ImageError> {
    write_exr_compressed(path, layers, ExrCompression::default())
}

/// [`write_exr`] with the given compression.
///
/// # Errors
/// As [`write_exr`].
pub fn write_exr_compressed(
    path: impl AsRef<Path>,
    layers: &ExrLayers,
    compression: ExrCompression,
) -> Result<(), ImageError> {
    let (width, height) = layers.beauty.size();
    let mut channels = SmallVec::new();
    for (name, values) in layers.channels()? {
        let text = Text::new_or_none(&name).ok_or_else(|| {
            ImageError::InvalidArgument(format!("EXR channel name {name:?} is not plain ASCII"))
        })?;
        channels.push(AnyChannel::new(text, FlatSamples::F32(values)));
    }
    let attributes = LayerAttributes {
        other: layers.info.to_attributes(),
        software_name: layers.info.software.as_deref().and_then(Text::new_or_none),
        ..LayerAttributes::default()
    };
    let layer = Layer::new(
        Vec2(width, height),
        attributes,
        compression.encoding(),
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    atomic_write(path, |writer| image.write().to_buffered(writer))
}

/// Reads the first layer of an EXR file as linear RGB from its `R`, `G`, `B`
/// channels; a luminance-only file (`Y`) is read as grey.
///
/// # Errors
/// [`ImageError::Read`] naming the file if it cannot be opened or decoded,
/// or has neither `R`, `G`, `B` nor `Y` channels.
pub fn read_exr(path: impl AsRef<Path>) -> Result<RgbImage, ImageError> {
    Ok(read_exr_layers(path)?.beauty)
}

/// Reads an EXR file written by [`write_exr`] (or any file following the
/// same channel names) back into its layers.
///
/// Channels named `<layer>.R/G/B` become RGB layers, any other channel a
/// scalar layer; 16-bit and integer channels are converted to `f32`.
///
/// # Errors
/// As [`read_exr`].
pub fn read_exr_layers(path: impl AsRef<Path>) -> Result<ExrLayers, ImageError> {
    let path = path.as_ref();
    let read_err = |source| ImageError::Read {
        path: path.into(),
        source,
    };
    let image = read_first_flat_layer_from_file(path).map_err(|e| read_err(e.into()))?;
    let mut attributes = image.attributes.other;
    let layer = image.layer_data;
    attributes.extend(layer.attributes.other);
    let software = layer.attributes.software_name.map(|t| t.to_string());
    let info = RenderInfo::from_attributes(&attributes, software);
    let (width, height) = (layer.size.width(), layer.size.height());
    let mut channels: Vec<(String, Vec<f32>)> = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect();

    let beauty = match take_rgb(&mut channels, "", width, height)? {
        Some(beauty) => beauty,
        None => match take(&mut channels, "Y") {
            Some(y) => {
                RgbImage::from_pixels(width, height, y.into_iter().map(|v| [v; 3]).collect())?
            }
            None => match beauty_layer_prefix(&channels) {
                Some(prefix) => take_rgb(&mut channels, &prefix, width, height)?
                    .ok_or_else(|| read_err("no R, G, B or Y channels".into()))?,
                None => return Err(read_err("no R, G, B or Y channels".into())),
            },
        },
    };
    let albedo = take_rgb(&mut channels, "albedo", width, height)?;
    let normal = take_rgb(&mut channels, "normal", width, height)?;
    let sample_count = take(&mut channels, "samples")
        .map(|v| GrayImage::from_values(width, height, v))
        .transpose()?;
    let mut extra = Vec::new();
    while let Some((name, _)) = channels.first() {
        let prefix = name.rsplit_once('.').map(|(p, _)| p.to_string());
        if let Some(rgb) = prefix
            .as_ref()
            .map(|p| take_rgb(&mut channels, p, width, height))
        {
            if let Some(rgb) = rgb? {
                extra.push((prefix.unwrap_or_default(), LayerData::Rgb(rgb)));
                continue;
            }
        }
        let (name, values) = channels.remove(0);
        extra.push((
            name,
            LayerData::Gray(GrayImage::from_values(width, height, values)?),
        ));
    }
    Ok(ExrLayers {
        beauty,
        albedo,
        normal,
        sample_count,
        extra,
        info,
    })
}

/// The layer prefix of the beauty image in a file without bare `R`, `G`,
/// `B`: the only RGB layer, or the one with a conventional name.
fn beauty_layer_prefix(channels: &[(String, Vec<f32>)]) -> Option<String> {
    let has = |name: String| channels.iter().any(|(c, _)| *c == name);
    let mut prefixes: Vec<String> = channels
        .iter()
        .filter_map(|(name, _)| name.strip_suffix(".R").map(str::to_string))
        .filter(|p| has(format!("{p}.G")) && has(format!("{p}.B")))
        .collect();
    prefixes.dedup();
    if prefixes.len() == 1 {
        return prefixes.pop();
    }
    const NAMES: [&str; 5] = ["combined", "beauty", "rgb", "color", "image"];
    prefixes.into_iter().find(|p| {
        let last = p.rsplit('.').next().unwrap_or(p).to_ascii_lowercase();
        NAMES.contains(&last.as_str())
    })
}

/// Removes and returns the channel called `name`.
fn take(channels: &mut Vec<(String, Vec<f32>)>, name: &str) -> Option<Vec<f32>> {
    let index = channels.iter().position(|(n, _)| n == name)?;
    Some(channels.remove(index).1)
}

/// Removes and returns the RGB layer `prefix` if all three channels exist.
fn take_rgb(
    channels: &mut Vec<(String, Vec<f32>)>,
    prefix: &str,
    width: usize,
    height: usize,
) -> Result<Option<RgbImage>, ImageError> {
    let dot = if prefix.is_empty() { "" } else { "." };
    let names = ["R", "G", "B"].map(|s| format!("{prefix}{dot}{s}"));
    if !names.iter().all(|n| channels.iter().any(|(c, _)| c == n)) {
        return Ok(None);
    }
    let [r, g, b] = names.map(|n| take(channels, &n).unwrap_or_default());
    let pixels = r
        .iter()
        .zip(&g)
        .zip(&b)
        .map(|((&r, &g), &b)| [r, g, b])
        .collect();
    RgbImage::from_pixels(width, height, pixels).map(Some)
}

#[cfg(test)]
#[path = "exr_io_tests.rs"]
mod tests;
