//! `candela compare [--reference R] A B`: error metrics, the block z-test
//! and efficiencies of renders (the numbers come from
//! `candela_image::metrics::comparison`, shared with Python's
//! `candela.compare`; this module reads the files and prints).
//!
//! Bad input (a missing file, not an image, different sizes) is a one-line
//! error naming the file, exit code 2.

mod table;

use crate::render_cmd::UsageError;
use anyhow::{Context, Result};
use candela_image::metrics::compare::{error_heatmap, CompareImage, CompareOptions};
use candela_image::metrics::comparison::compare_images;
use candela_image::write_png_display;
use clap::Args;
use std::path::PathBuf;

/// Flags of `candela compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    /// The test image: .exr (Candela's, pbrt's, Mitsuba's, ...) or .png.
    pub a: PathBuf,
    /// The image A is measured against; with --reference, a second test image.
    pub b: PathBuf,
    /// Measure A and B each against this (converged) reference and, when
    /// both carry render time and sample counts, compare their efficiency
    /// 1 / (relMSE x time).
    #[arg(long, value_name = "R")]
    pub reference: Option<PathBuf>,
    /// Write a heat map of A's per-pixel relative squared error (against B,
    /// or the reference) to this PNG.
    #[arg(long, value_name = "PNG")]
    pub heatmap: Option<PathBuf>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Edge of the z-test's square blocks, in pixels.
    #[arg(long, value_name = "PIXELS", default_value_t = CompareOptions::default().block_size)]
    pub block: usize,
    /// Probability that two unbiased renders fail the z-test (family-wise,
    /// Bonferroni over blocks and channels).
    #[arg(long, value_name = "P", default_value_t = CompareOptions::default().false_alarm_rate)]
    pub false_alarm: f64,
}

/// Runs `candela compare`.
pub fn run(args: &CompareArgs) -> Result<()> {
    if args.block == 0 || !(args.false_alarm > 0.0 && args.false_alarm < 1.0) {
        return Err(UsageError(format!(
            "--block must be at least 1 and --false-alarm between 0 and 1 (got {} and {})",
            args.block, args.false_alarm
        ))
        .into());
    }
    let load = |path: &PathBuf| CompareImage::load(path).map_err(|e| UsageError(e.to_string()));
    let a = load(&args.a)?;
    let b = load(&args.b)?;
    let reference = args.reference.as_ref().map(load).transpose()?;
    let options = CompareOptions {
        block_size: args.block,
        false_alarm_rate: args.false_alarm,
    };
    let comparison = compare_images(&a, &b, reference.as_ref(), &options)
        .map_err(|e| UsageError(e.to_string()))?;
    if let Some(path) = &args.heatmap {
        let against = reference.as_ref().unwrap_or(&b);
        let heat = error_heatmap(&a, against).map_err(|e| UsageError(e.to_string()))?;
        write_png_display(path, &heat)
            .with_context(|| format!("cannot write the heat map {}", path.display()))?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&comparison.to_json())?);
    } else {
        print!("{}", table::render(&comparison));
    }
    Ok(())
}
