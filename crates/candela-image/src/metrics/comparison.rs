//! The whole report of `candela compare [--reference R] A B`, and its JSON
//! form (the CLI's `--json` and Python's `candela.compare` print and parse
//! the same document).

use std::path::PathBuf;

use serde_json::{json, Value};

use super::compare::{compare_pair, CompareImage, CompareOptions, PairReport};
use crate::{ImageError, RenderInfo};

/// One test image measured against the reference (or A against B).
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The test image's file.
    pub test: PathBuf,
    /// The file it was measured against.
    pub against: PathBuf,
    /// The test image's header metadata.
    pub info: RenderInfo,
    /// The metrics.
    pub report: PairReport,
    /// `1 / (relMSE × time)`, with a reference and the header data.
    pub efficiency: Option<f64>,
}

/// `A` against `B`, or `A` and `B` each against a reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The reference, if one was given.
    pub reference: Option<PathBuf>,
    /// One entry without a reference (A against B), two with one.
    pub entries: Vec<Entry>,
    /// A's efficiency over B's: how much faster A reaches equal relMSE.
    pub efficiency_ratio: Option<f64>,
    /// The settings used.
    pub options: CompareOptions,
}

/// Compares `a` with `b`, or, given a `reference`, each of them with it
/// (and then their efficiencies, if their headers carry time and samples).
///
/// # Errors
/// As [`compare_pair`].
pub fn compare_images(
    a: &CompareImage,
    b: &CompareImage,
    reference: Option<&CompareImage>,
    options: &CompareOptions,
) -> Result<Comparison, ImageError> {
    let entry = |test: &CompareImage, against: &CompareImage| -> Result<Entry, ImageError> {
        let report = compare_pair(test, against, options)?;
        Ok(Entry {
            test: test.path.clone(),
            against: against.path.clone(),
            info: test.info.clone(),
            efficiency: reference.and_then(|_| test.efficiency(report.rel_mse)),
            report,
        })
    };
    let entries = match reference {
        None => vec![entry(a, b)?],
        Some(r) => vec![entry(a, r)?, entry(b, r)?],
    };
    let efficiency_ratio = match entries.as_slice() {
        [ea, eb] => ea.efficiency.zip(eb.efficiency).map(|(x, y)| x / y),
        _ => None,
    };
    Ok(Comparison {
        reference: reference.map(|r| r.path.clone()),
        entries,
        efficiency_ratio,
        options: *options,
    })
}

impl Comparison {
    /// The report as JSON. Non-finite numbers (the PSNR of identical
    /// images, an infinite |z|) become `null`, which JSON has instead.
    pub fn to_json(&self) -> Value {
        let entries: Vec<Value> = self.entries.iter().map(Entry::to_json).collect();
        json!({
            "reference": self.reference.as_ref().map(|p| p.display().to_string()),
            "block_size": self.options.block_size,
            "false_alarm_rate": self.options.false_alarm_rate,
            "comparisons": entries,
            "efficiency_ratio": self.efficiency_ratio,
        })
    }
}

impl Entry {
    fn to_json(&self) -> Value {
        let r = &self.report;
        let z = &r.z;
        let worst_channel = ["R", "G", "B"][z.worst.2.min(2)];
        json!({
            "test": self.test.display().to_string(),
            "against": self.against.display().to_string(),
            "mse": r.mse,
            "rel_mse": r.rel_mse,
            "psnr": r.psnr,
            "z_test": {
                "passed": z.passed(),
                "max_abs_z": z.max_abs_z,
                "worst_block": [z.worst.0, z.worst.1],
                "worst_channel": worst_channel,
                "global_abs_z": z.global_abs_z,
                "threshold": z.threshold,
                "blocks": z.blocks,
                "tests_over_threshold": z.count_over,
                "variance_source": r.variance_source.name(),
            },
            "spp": self.info.spp.map(|s| json!({"min": s.min, "mean": s.mean, "max": s.max})),
            "time_seconds": self.info.time_seconds,
            "efficiency": self.efficiency,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{RgbImage, SppSpread};

    fn image(name: &str, value: f32, time: Option<f64>) -> CompareImage {
        let mut image =
            CompareImage::plain(name, RgbImage::from_fn(8, 8, |_, _| [value; 3]).unwrap());
        image.info.time_seconds = time;
        image.info.spp = time.map(|_| SppSpread {
            min: 4,
            mean: 4.0,
            max: 4,
        });
        image
    }

    #[test]
    fn efficiency_ratio_of_equal_error_renders() {
        // Equal relMSE against the reference, A in half the time: twice as efficient.
        let (a, b, r) = (
            image("a", 1.1, Some(1.0)),
            image("b", 0.9, Some(2.0)),
            image("r", 1.0, None),
        );
        let c = compare_images(&a, &b, Some(&r), &CompareOptions::default()).unwrap();
        assert_eq!(c.entries.len(), 2);
        let ratio = c.efficiency_ratio.unwrap();
        assert!((ratio - 2.0).abs() < 1e-4, "{ratio}");
        let json = c.to_json();
        assert_eq!(json["comparisons"][1]["test"], "b");
        assert_eq!(json["reference"], "r");
        // Without a reference: one entry and no efficiency.
        let c = compare_images(&a, &b, None, &CompareOptions::default()).unwrap();
        assert_eq!((c.entries.len(), c.efficiency_ratio), (1, None));
        assert_eq!(c.entries[0].efficiency, None);
        // Identical images: PSNR +inf becomes null.
        let same = compare_images(&a, &a, None, &CompareOptions::default()).unwrap();
        assert!(same.to_json()["comparisons"][0]["psnr"].is_null());
    }
}
