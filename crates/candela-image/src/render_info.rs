//! What a render file says about how it was made: sample counts, render
//! time, seed, integrator, scene and program, stored as OpenEXR header
//! attributes.
//!
//! | attribute | type | content |
//! |---|---|---|
//! | `samplesPerPixel` | int | samples of every rendered pixel, when they are all equal (pbrt-v4's name) |
//! | `samplesPerPixelMin`, `samplesPerPixelMax` | int | fewest and most samples of a rendered pixel |
//! | `samplesPerPixelMean` | double | mean samples over the rendered pixels |
//! | `renderTimeSeconds` | float | wall-clock time of the render loop (pbrt-v4's name and type) |
//! | `seed` | string | seed of the sample sequence, decimal; a merge lists its parts' seeds, comma-separated |
//! | `sampleRange` | string | the sample indices rendered, half-open, `first..end` (`0..64`) |
//! | `integrator` | string | the estimator, e.g. `path (mis)` |
//! | `scene` | string | the scene file's name |
//! | `software` | string | `candela <version>` (OpenEXR's standard attribute) |
//!
//! "Rendered pixels" are those with at least one sample (a cell render `-p`
//! leaves the rest empty). pbrt-v4 writes `samplesPerPixel` and
//! `renderTimeSeconds` too, so its EXRs carry what an efficiency comparison
//! needs. Seeds are strings because a `u64` does not fit OpenEXR's 32-bit
//! integers.

use exr::meta::attribute::{AttributeValue, Text};
use std::collections::HashMap;
use std::ops::Range;

/// Fewest, mean and most samples over the rendered pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SppSpread {
    /// Fewest samples of a rendered pixel.
    pub min: u32,
    /// Mean samples per rendered pixel.
    pub mean: f64,
    /// Most samples of a rendered pixel.
    pub max: u32,
}

impl SppSpread {
    /// The spread of per-pixel sample counts over the pixels with at least
    /// one sample; `None` if no pixel has one.
    pub fn of_counts(counts: impl IntoIterator<Item = f64>) -> Option<Self> {
        let (mut min, mut max, mut total, mut pixels) = (f64::INFINITY, 0.0_f64, 0.0, 0u64);
        for n in counts.into_iter().filter(|&n| n > 0.0) {
            min = min.min(n);
            max = max.max(n);
            total += n;
            pixels += 1;
        }
        (pixels > 0).then(|| Self {
            min: min as u32,
            mean: total / pixels as f64,
            max: max as u32,
        })
    }

    /// Every rendered pixel took the same number of samples.
    pub fn is_uniform(&self) -> bool {
        self.min == self.max
    }
}

/// The header metadata of a render file; every field is optional, since
/// other programs' files carry little or none of it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderInfo {
    /// Samples per pixel.
    pub spp: Option<SppSpread>,
    /// Render time in seconds.
    pub time_seconds: Option<f64>,
    /// Seed(s) of the sample sequence.
    pub seed: Option<String>,
    /// The sample indices rendered (half-open).
    pub sample_range: Option<Range<u32>>,
    /// The estimator.
    pub integrator: Option<String>,
    /// The scene file's name.
    pub scene: Option<String>,
    /// The program that wrote the file.
    pub software: Option<String>,
}

impl RenderInfo {
    /// `candela <version>`: what Candela writes as `software`.
    pub fn candela_software() -> String {
        format!("candela {}", env!("CARGO_PKG_VERSION"))
    }

    /// The custom header attributes (everything but `software`, which has
    /// its own slot in the header).
    pub(crate) fn to_attributes(&self) -> HashMap<Text, AttributeValue> {
        let mut out = HashMap::new();
        let mut put = |name: &str, value| {
            out.insert(Text::from(name), value);
        };
        if let Some(spp) = self.spp {
            if spp.is_uniform() {
                put("samplesPerPixel", AttributeValue::I32(clamp_i32(spp.min)));
            }
            put(
                "samplesPerPixelMin",
                AttributeValue::I32(clamp_i32(spp.min)),
            );
            put("samplesPerPixelMean", AttributeValue::F64(spp.mean));
            put(
                "samplesPerPixelMax",
                AttributeValue::I32(clamp_i32(spp.max)),
            );
        }
        if let Some(t) = self.time_seconds {
            put("renderTimeSeconds", AttributeValue::F32(t as f32));
        }
        let texts = [
            ("seed", self.seed.clone()),
            (
                "sampleRange",
                self.sample_range
                    .as_ref()
                    .map(|r| format!("{}..{}", r.start, r.end)),
            ),
            ("integrator", self.integrator.clone()),
            ("scene", self.scene.clone()),
        ];
        for (name, value) in texts {
            if let Some(text) = value.and_then(|v| Text::new_or_none(v.as_str())) {
                put(name, AttributeValue::Text(text));
            }
        }
        out
    }

    /// Reads what it knows from header attributes; unknown or mistyped
    /// attributes are ignored (they are another program's).
    pub(crate) fn from_attributes(
        attributes: &HashMap<Text, AttributeValue>,
        software: Option<String>,
    ) -> Self {
        let get = |name: &str| attributes.get(&Text::from(name));
        let number = |name: &str| match get(name) {
            Some(AttributeValue::I32(v)) => Some(*v as f64),
            Some(AttributeValue::F32(v)) => Some(*v as f64),
            Some(AttributeValue::F64(v)) => Some(*v),
            _ => None,
        };
        let text = |name: &str| match get(name) {
            Some(AttributeValue::Text(t)) => Some(t.to_string()),
            _ => None,
        };
        let count = |v: f64| v.clamp(0.0, u32::MAX as f64) as u32;
        let spread = match (
            number("samplesPerPixelMin"),
            number("samplesPerPixelMean"),
            number("samplesPerPixelMax"),
        ) {
            (Some(min), Some(mean), Some(max)) => Some(SppSpread {
                min: count(min),
                mean,
                max: count(max),
            }),
            _ => number("samplesPerPixel").map(|n| SppSpread {
                min: count(n),
                mean: n,
                max: count(n),
            }),
        };
        let sample_range = text("sampleRange").and_then(|r| {
            let (a, b) = r.split_once("..")?;
            Some(a.trim().parse().ok()?..b.trim().parse().ok()?)
        });
        Self {
            spp: spread,
            time_seconds: number("renderTimeSeconds"),
            seed: text("seed"),
            sample_range,
            integrator: text("integrator"),
            scene: text("scene"),
            software,
        }
    }
}

fn clamp_i32(n: u32) -> i32 {
    n.min(i32::MAX as u32) as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_skips_empty_pixels() {
        let s = SppSpread::of_counts([0.0, 4.0, 8.0, 0.0]).unwrap();
        assert_eq!((s.min, s.mean, s.max), (4, 6.0, 8));
        assert!(!s.is_uniform());
        assert_eq!(SppSpread::of_counts([0.0, 0.0]), None);
    }

    #[test]
    fn attributes_round_trip() {
        let info = RenderInfo {
            spp: Some(SppSpread {
                min: 3,
                mean: 3.5,
                max: 4,
            }),
            time_seconds: Some(1.5),
            seed: Some("18446744073709551615".into()),
            sample_range: Some(64..128),
            integrator: Some("path (mis)".into()),
            scene: Some("CBbox.dae".into()),
            software: Some(RenderInfo::candela_software()),
        };
        let back = RenderInfo::from_attributes(&info.to_attributes(), info.software.clone());
        assert_eq!(back, info);
        // pbrt-v4's pair of attributes alone.
        let mut pbrt = HashMap::new();
        pbrt.insert(Text::from("samplesPerPixel"), AttributeValue::I32(16));
        pbrt.insert(Text::from("renderTimeSeconds"), AttributeValue::F32(2.0));
        let read = RenderInfo::from_attributes(&pbrt, None);
        assert_eq!(read.spp.map(|s| (s.min, s.max)), Some((16, 16)));
        assert_eq!(read.time_seconds, Some(2.0));
    }
}
