//! `candela merge A.exr B.exr ... -o C.exr`: adds independent renders of
//! one image (different seeds or sample ranges) into one, with the variance
//! layer pooled exactly (`candela_image::merge_renders` says how).
//!
//! Bad input (a missing or unreadable file, different sizes or layers, the
//! same samples twice) is a one-line error naming the files, exit code 2.

use crate::render_cmd::UsageError;
use anyhow::{Context, Result};
use candela_image::{merge_renders, read_exr_layers, write_exr};
use clap::Args;
use std::path::PathBuf;

/// Flags of `candela merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The renders to add: Candela EXRs of the same scene and settings with
    /// different seeds or sample ranges.
    #[arg(required = true, num_args = 2.., value_name = "EXR")]
    pub inputs: Vec<PathBuf>,
    /// The merged EXR.
    #[arg(short = 'o', long = "output", value_name = "EXR")]
    pub output: PathBuf,
    /// No summary on stderr.
    #[arg(short = 'q', long)]
    pub quiet: bool,
}

/// Runs `candela merge`.
pub fn run(args: &MergeArgs) -> Result<()> {
    let is_exr = |p: &PathBuf| {
        p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
    };
    if let Some(other) = args
        .inputs
        .iter()
        .chain([&args.output])
        .find(|p| !is_exr(p))
    {
        return Err(UsageError(format!(
            "{}: candela merge reads and writes .exr files",
            other.display()
        ))
        .into());
    }
    let parts = args
        .inputs
        .iter()
        .map(|path| {
            read_exr_layers(path)
                .map(|layers| (path.display().to_string(), layers))
                .map_err(|e| UsageError(e.to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let merged = merge_renders(&parts).map_err(|e| UsageError(e.to_string()))?;
    write_exr(&args.output, &merged)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    if !args.quiet {
        let spp = merged.info.spp.map_or("-".into(), |s| {
            if s.min == s.max {
                format!("{} spp", s.min)
            } else {
                format!("{}-{} spp (mean {:.1})", s.min, s.max, s.mean)
            }
        });
        let time = merged
            .info
            .time_seconds
            .map_or(String::new(), |t| format!(", {t:.2} s"));
        eprintln!(
            "candela: merged {} renders ({spp}{time}) into {}",
            parts.len(),
            args.output.display()
        );
    }
    Ok(())
}
