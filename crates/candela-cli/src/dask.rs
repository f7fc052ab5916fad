//! `candela --dask ADDRESS scene.dae ...`: the same render spread over a Dask
//! cluster, by handing it to the Python package's distributed front
//! (`python3 -m candela.distributed`, installed with
//! `pip install ./crates/candela-py`). Dask does the scheduling, retries and
//! data movement; this module only translates the command line, and refuses
//! (by name) every flag the distributed path does not honour yet, so that
//! nothing a user asks for is silently dropped.

use crate::args::{BvhArg, CameraArg, RenderArgs, SamplerArg, ToneArg};
use crate::render_cmd::{Outcome, UsageError};
use anyhow::{Context, Result};
use std::process::Command;

/// Runs the render on the cluster at `address` (`tcp://host:port` or
/// `local:N`).
pub fn run(args: &RenderArgs, address: &str) -> Result<Outcome> {
    let unsupported = unsupported_flags(args);
    if !unsupported.is_empty() {
        return Err(UsageError(format!(
            "--dask does not support {} yet",
            unsupported.join(", ")
        ))
        .into());
    }
    let scene = args
        .scene
        .as_ref()
        .ok_or_else(|| UsageError("--dask needs a scene file that every worker can read".into()))?;
    let python = std::env::var("CANDELA_PYTHON").unwrap_or_else(|_| "python3".into());
    let mut cmd = Command::new(&python);
    cmd.args(["-m", "candela.distributed"])
        .arg(scene)
        .args(["--dask", address])
        .args(["-s", &args.spp.unwrap_or(16).to_string()])
        .args(["-m", &args.max_depth.to_string()])
        .args(["-l", &args.light_samples.to_string()])
        .args([
            "-r",
            &args.resolution[0].to_string(),
            &args.resolution[1].to_string(),
        ])
        .arg("-f")
        .arg(&args.output)
        .args(["--seed", &args.seed.to_string()])
        .args(["--integrator", integrator(args)])
        .args([
            "--tiles",
            &args.tiles[0].to_string(),
            &args.tiles[1].to_string(),
        ])
        .args(["--passes", &args.passes.to_string()])
        .args(["-t", &args.threads.unwrap_or(1).to_string()]);
    if args.quiet {
        cmd.arg("-q");
    }
    let status = cmd.status().with_context(|| {
        format!(
            "cannot start {python} (the Python package `candela` with Dask is needed for --dask)"
        )
    })?;
    match status.code() {
        Some(0) => Ok(Outcome::Done),
        code => anyhow::bail!(
            "the distributed render failed (python -m candela.distributed exited with {})",
            code.map_or("a signal".to_string(), |c| c.to_string())
        ),
    }
}

fn integrator(args: &RenderArgs) -> &'static str {
    if args.normals {
        "normals"
    } else if args.direct_only {
        "direct"
    } else if args.indirect_only {
        "indirect"
    } else {
        "path"
    }
}

/// Flags (set away from their defaults) that the distributed front ignores.
fn unsupported_flags(args: &RenderArgs) -> Vec<&'static str> {
    let checks = [
        (args.adaptive.is_some(), "-a"),
        (args.cell.is_some(), "-p"),
        (args.time.is_some(), "--time"),
        (args.env_map.is_some(), "-e"),
        (args.aperture.is_some(), "-b"),
        (args.focal_distance.is_some(), "-d"),
        (args.hemisphere, "-H"),
        (args.light_only, "--light-only"),
        (args.no_roulette, "--no-roulette"),
        (args.accumulate == 0, "-o 0"),
        (args.camera != CameraArg::Cs184, "--camera"),
        (args.bvh != BvhArg::Sah, "--bvh"),
        (args.sampler != SamplerArg::Sobol, "--sampler"),
        (args.exposure != 0.0, "--exposure"),
        (args.tone != ToneArg::Srgb, "--tone"),
        (args.strict, "--strict"),
    ];
    checks
        .iter()
        .filter(|(set, _)| *set)
        .map(|&(_, name)| name)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::args::Cli;
    use clap::Parser;

    #[test]
    fn unsupported_flags_are_named() {
        let cli = Cli::try_parse_from([
            "candela", "--dask", "local:2", "-a", "64", "0.05", "-H", "s.dae",
        ])
        .unwrap();
        assert_eq!(unsupported_flags(&cli.render), vec!["-a", "-H"]);
        let err = run(&cli.render, "local:2").unwrap_err();
        assert!(err.to_string().contains("-a, -H"), "{err}");
    }

    #[test]
    fn plain_render_flags_are_supported() {
        let cli = Cli::try_parse_from([
            "candela", "--dask", "local:2", "-s", "64", "-m", "3", "-r", "80", "60", "s.dae",
        ])
        .unwrap();
        assert!(unsupported_flags(&cli.render).is_empty());
    }
}
