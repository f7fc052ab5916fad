//! Adding independent renders of one image into one (`candela merge`).
//!
//! Each part is an EXR of the same scene and settings rendered with other
//! samples (another seed, or another sample range of the same seed). Per
//! pixel, with `n_k` samples in part `k`:
//!
//! - the beauty is the sample-weighted mean `Σ n_k m_k / Σ n_k`, and the
//!   variance layer is pooled exactly ([`crate::variance`], Chan et al.):
//!   the result is what one render of all the samples would have stored,
//!   up to the `f32` rounding of the stored values;
//! - every other layer (albedo, normal, depth, cost, ...) is the
//!   sample-weighted mean of the parts' finite values: a non-finite AOV
//!   value means "no data" (depth is +inf where no camera ray hit), so a
//!   part without data does not drag the mean to infinity. Depth is thereby
//!   weighted by samples rather than by hits, a small approximation where
//!   some of a pixel's camera rays escape;
//! - the `samples` layer is summed, as are the render times; the sample
//!   spread is recomputed, the seeds listed.
//!
//! The per-pixel counts come from the `samples` layer, or from a uniform
//! `samplesPerPixel` in the header. Merging refuses parts of different
//! size, different layers, different scenes or integrators, and two parts
//! that hold the same samples (same seed, overlapping sample ranges), which
//! are not independent: their pooled variance would be wrong.

use crate::exr_io::VARIANCE_LAYER;
use crate::variance::MeanEstimate;
use crate::{ExrLayers, GrayImage, ImageError, LayerData, RenderInfo, RgbImage, SppSpread};

/// A part to merge: a name for messages (the file name) and its layers.
pub type MergePart = (String, ExrLayers);

/// Adds `parts` into one render. See the module docs.
///
/// # Errors
/// [`ImageError::Incompatible`] naming the parts that cannot be merged.
pub fn merge_renders(parts: &[MergePart]) -> Result<ExrLayers, ImageError> {
    let Some((first_name, first)) = parts.first() else {
        return Err(ImageError::Incompatible("nothing to merge".into()));
    };
    for (name, part) in &parts[1..] {
        check_compatible((first_name, first), (name, part))?;
    }
    check_independent(parts)?;
    let counts = parts
        .iter()
        .map(|(name, part)| sample_counts(name, part))
        .collect::<Result<Vec<_>, _>>()?;
    let (width, height) = first.beauty.size();
    let total: Vec<f64> = (0..width * height)
        .map(|i| counts.iter().map(|c| c[i]).sum())
        .collect();

    let beauty: Vec<&RgbImage> = parts.iter().map(|(_, p)| &p.beauty).collect();
    let variances: Option<Vec<&RgbImage>> = parts.iter().map(|(_, p)| p.variance()).collect();
    let (beauty, variance) = pool_beauty(&beauty, variances.as_deref(), &counts)?;

    let rgb_mean = |pick: &dyn Fn(&ExrLayers) -> Option<&RgbImage>| {
        let images: Option<Vec<&RgbImage>> = parts.iter().map(|(_, p)| pick(p)).collect();
        images
            .map(|images| weighted_rgb(&images, &counts))
            .transpose()
    };
    let albedo = rgb_mean(&|p| p.albedo.as_ref())?;
    let normal = rgb_mean(&|p| p.normal.as_ref())?;
    let sample_count = first
        .sample_count
        .as_ref()
        .map(|_| GrayImage::from_values(width, height, total.iter().map(|&n| n as f32).collect()))
        .transpose()?;
    let mut extra = Vec::new();
    for (index, (name, data)) in first.extra.iter().enumerate() {
        let merged = match (name.as_str(), data) {
            (VARIANCE_LAYER, LayerData::Rgb(_)) => match &variance {
                Some(v) => LayerData::Rgb(v.clone()),
                None => continue,
            },
            (_, LayerData::Rgb(_)) => LayerData::Rgb(
                rgb_mean(&|p| match p.extra.get(index) {
                    Some((_, LayerData::Rgb(image))) => Some(image),
                    _ => None,
                })?
                .ok_or_else(|| layer_mismatch(name))?,
            ),
            (_, LayerData::Gray(_)) => {
                let images: Vec<&GrayImage> = parts
                    .iter()
                    .filter_map(|(_, p)| match p.extra.get(index) {
                        Some((_, LayerData::Gray(image))) => Some(image),
                        _ => None,
                    })
                    .collect();
                LayerData::Gray(weighted_gray(&images, &counts)?)
            }
        };
        extra.push((name.clone(), merged));
    }
    Ok(ExrLayers {
        beauty,
        albedo,
        normal,
        sample_count,
        extra,
        info: merged_info(parts, &total),
    })
}

fn layer_mismatch(name: &str) -> ImageError {
    ImageError::Incompatible(format!("layer {name} differs between the parts"))
}

/// Same size, same layers (names and kinds), same scene and integrator.
fn check_compatible(
    (a_name, a): (&String, &ExrLayers),
    (b_name, b): (&String, &ExrLayers),
) -> Result<(), ImageError> {
    let refuse = |what: String| {
        Err(ImageError::Incompatible(format!(
            "cannot merge {b_name} into {a_name}: {what}"
        )))
    };
    if a.beauty.size() != b.beauty.size() {
        let ((aw, ah), (bw, bh)) = (a.beauty.size(), b.beauty.size());
        return refuse(format!("{b_name} is {bw}x{bh}, {a_name} is {aw}x{ah}"));
    }
    let (la, lb) = (layer_names(a), layer_names(b));
    if la != lb {
        let only = |x: &[String], y: &[String]| {
            x.iter()
                .filter(|n| !y.contains(n))
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        };
        return refuse(format!(
            "different layers (only in {a_name}: [{}]; only in {b_name}: [{}])",
            only(&la, &lb),
            only(&lb, &la)
        ));
    }
    for (what, x, y) in [
        ("scene", &a.info.scene, &b.info.scene),
        ("integrator", &a.info.integrator, &b.info.integrator),
    ] {
        if let (Some(x), Some(y)) = (x, y) {
            if x != y {
                return refuse(format!("different {what}s ({x} vs {y})"));
            }
        }
    }
    Ok(())
}

/// The layer names with their kind, in file order for the extras.
fn layer_names(layers: &ExrLayers) -> Vec<String> {
    let mut names = Vec::new();
    for (name, present) in [
        ("albedo", layers.albedo.is_some()),
        ("normal", layers.normal.is_some()),
        ("samples", layers.sample_count.is_some()),
    ] {
        if present {
            names.push(name.to_string());
        }
    }
    for (name, data) in &layers.extra {
        let kind = match data {
            LayerData::Rgb(_) => ".RGB",
            LayerData::Gray(_) => "",
        };
        names.push(format!("{name}{kind}"));
    }
    names
}

/// Refuses two parts with the same seed whose sample ranges overlap (or
/// are unknown): they hold the same samples.
fn check_independent(parts: &[MergePart]) -> Result<(), ImageError> {
    for (i, (a_name, a)) in parts.iter().enumerate() {
        for (b_name, b) in &parts[i + 1..] {
            let (Some(seed_a), Some(seed_b)) = (&a.info.seed, &b.info.seed) else {
                continue;
            };
            let disjoint = match (&a.info.sample_range, &b.info.sample_range) {
                (Some(x), Some(y)) => x.end <= y.start || y.end <= x.start,
                _ => false,
            };
            if seed_a == seed_b && !disjoint {
                return Err(ImageError::Incompatible(format!(
                    "{a_name} and {b_name} hold the same samples (seed {seed_a}, overlapping \
                     sample ranges): merge independent renders (another --seed)"
                )));
            }
        }
    }
    Ok(())
}

/// Per-pixel sample counts of a part.
fn sample_counts(name: &str, part: &ExrLayers) -> Result<Vec<f64>, ImageError> {
    if let Some(counts) = &part.sample_count {
        return Ok(counts.values().iter().map(|&n| n as f64).collect());
    }
    match part.info.spp {
        Some(spp) if spp.is_uniform() => Ok(vec![spp.min as f64; part.beauty.pixels().len()]),
        _ => Err(ImageError::Incompatible(format!(
            "{name}: no per-pixel sample counts (no samples layer, no uniform samplesPerPixel)"
        ))),
    }
}

/// The pooled beauty and, if every part has one, the pooled variance.
fn pool_beauty(
    beauty: &[&RgbImage],
    variances: Option<&[&RgbImage]>,
    counts: &[Vec<f64>],
) -> Result<(RgbImage, Option<RgbImage>), ImageError> {
    let (width, height) = beauty[0].size();
    let no_samples = MeanEstimate {
        count: 0.0,
        mean: 0.0,
        variance: f64::INFINITY,
    };
    let pool = |i: usize, c: usize| {
        let parts = beauty.iter().zip(counts).enumerate();
        parts.fold(no_samples, |acc, (k, (image, n))| {
            acc.pooled(&MeanEstimate {
                count: n[i],
                mean: image.pixels()[i][c] as f64,
                variance: variances.map_or(0.0, |v| v[k].pixels()[i][c] as f64),
            })
        })
    };
    let pooled: Vec<[MeanEstimate; 3]> = (0..width * height)
        .map(|i| [0, 1, 2].map(|c| pool(i, c)))
        .collect();
    // No samples anywhere: the parts' own value (a film's 0).
    let means = pooled
        .iter()
        .zip(beauty[0].pixels())
        .map(|(p, first)| {
            [0, 1, 2].map(|c| {
                if p[c].count > 0.0 {
                    p[c].mean as f32
                } else {
                    first[c]
                }
            })
        })
        .collect();
    let mean = RgbImage::from_pixels(width, height, means)?;
    let variance = variances
        .map(|_| {
            let values = pooled
                .iter()
                .map(|p| p.map(|e| e.variance as f32))
                .collect();
            RgbImage::from_pixels(width, height, values)
        })
        .transpose()?;
    Ok((mean, variance))
}

/// The sample-weighted mean of finite values; the first part's value where
/// no part has a finite value with samples.
fn weighted(values: impl Iterator<Item = f32> + Clone, weights: impl Iterator<Item = f64>) -> f32 {
    let (mut sum, mut weight) = (0.0, 0.0);
    for (v, w) in values.clone().zip(weights) {
        if v.is_finite() && w > 0.0 {
            sum += v as f64 * w;
            weight += w;
        }
    }
    if weight > 0.0 {
        (sum / weight) as f32
    } else {
        values.into_iter().next().unwrap_or(0.0)
    }
}

fn weighted_rgb(images: &[&RgbImage], counts: &[Vec<f64>]) -> Result<RgbImage, ImageError> {
    let (width, height) = images[0].size();
    RgbImage::from_fn(width, height, |x, y| {
        let i = y * width + x;
        [0, 1, 2].map(|c| {
            weighted(
                images.iter().map(move |im| im.pixels()[i][c]),
                counts.iter().map(|n| n[i]),
            )
        })
    })
}

fn weighted_gray(images: &[&GrayImage], counts: &[Vec<f64>]) -> Result<GrayImage, ImageError> {
    let (width, height) = images[0].size();
    let values = (0..width * height)
        .map(|i| {
            weighted(
                images.iter().map(move |im| im.values()[i]),
                counts.iter().map(|n| n[i]),
            )
        })
        .collect();
    GrayImage::from_values(width, height, values)
}

/// The merged header: summed time, the spread of the summed counts, the
/// seeds, the union of contiguous sample ranges of one seed.
fn merged_info(parts: &[MergePart], total_counts: &[f64]) -> RenderInfo {
    let infos: Vec<&RenderInfo> = parts.iter().map(|(_, p)| &p.info).collect();
    let time_seconds = infos.iter().map(|i| i.time_seconds).sum::<Option<f64>>();
    let mut seeds: Vec<String> = Vec::new();
    for seed in infos.iter().filter_map(|i| i.seed.clone()) {
        if !seeds.contains(&seed) {
            seeds.push(seed);
        }
    }
    let sample_range = if seeds.len() == 1 {
        let mut ranges: Option<Vec<_>> = infos.iter().map(|i| i.sample_range.clone()).collect();
        if let Some(r) = ranges.as_mut() {
            r.sort_by_key(|r| r.start);
        }
        ranges.and_then(|r| {
            let contiguous = r.windows(2).all(|w| w[0].end == w[1].start);
            contiguous.then(|| r[0].start..r[r.len() - 1].end)
        })
    } else {
        None
    };
    RenderInfo {
        spp: SppSpread::of_counts(total_counts.iter().copied()),
        time_seconds,
        seed: (!seeds.is_empty()).then(|| seeds.join(",")),
        sample_range,
        integrator: infos[0].integrator.clone(),
        scene: infos[0].scene.clone(),
        software: Some(RenderInfo::candela_software()),
    }
}

#[cfg(test)]
#[path = "merge_tests.rs"]
mod tests;
