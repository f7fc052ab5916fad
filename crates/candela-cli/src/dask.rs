//! `candela --dask ADDRESS scene.dae ...`: the same render spread over a Dask
//! cluster, by handing it to the Python package's distributed front
//! (`python3 -m candela.distributed`, installed with
//! `pip install ./crates/candela-py`). Dask does the scheduling, retries and
//! data movement; this module only passes the settings the user gave, in
//! their one wire format (the settings' JSON); the scene travels to the
//! workers as its files' bytes, so they need no shared disk. The distributed front
//! refuses by name whatever it cannot honour (exit code 2), so nothing a
//! user asks for is silently dropped.

use crate::args::RenderArgs;
use crate::render_cmd::{explicit_settings, Outcome, UsageError};
use anyhow::{Context, Result};
use clap::ArgMatches;
use std::path::Path;
use std::process::Command;

/// Exit code of the distributed front for settings it refuses.
const REFUSED: i32 = 2;

/// Runs the render on the cluster at `address` (`tcp://host:port` or
/// `local:N`).
pub fn run(args: &RenderArgs, matches: &ArgMatches, address: &str) -> Result<Outcome> {
    let settings = explicit_settings(args, matches)?;
    let scene = args.scene.as_ref().ok_or_else(|| {
        UsageError("--dask needs a scene file (it is shipped to the workers)".into())
    })?;
    let mut cmd = python();
    cmd.args(["-m", "candela.distributed"])
        .arg(scene)
        .args(["--dask", address])
        .arg("-f")
        .arg(&args.output)
        .args([
            "--tiles",
            &args.tiles[0].to_string(),
            &args.tiles[1].to_string(),
        ])
        .args(["--passes", &args.passes.to_string()])
        .args([
            "--settings",
            &serde_json::Value::Object(settings).to_string(),
        ]);
    if args.quiet {
        cmd.arg("-q");
    }
    if args.strict {
        cmd.arg("--strict");
    }
    finish(cmd)
}

/// `candela resume PATH` of a distributed render's checkpoint: continued
/// by the distributed front on the cluster at `address`.
pub fn resume(checkpoint: &Path, address: &str, quiet: bool) -> Result<Outcome> {
    let mut cmd = python();
    cmd.args(["-m", "candela.distributed", "--resume"])
        .arg(checkpoint)
        .args(["--dask", address]);
    if quiet {
        cmd.arg("-q");
    }
    finish(cmd)
}

/// The Python interpreter (`$CANDELA_PYTHON`, else `python3`).
fn python() -> Command {
    Command::new(std::env::var("CANDELA_PYTHON").unwrap_or_else(|_| "python3".into()))
}

/// Runs the distributed front and maps its exit code.
fn finish(mut cmd: Command) -> Result<Outcome> {
    let python = cmd.get_program().to_string_lossy().into_owned();
    let status = cmd.status().with_context(|| {
        format!(
            "cannot start {python} (the Python package `candela` with Dask is needed for --dask)"
        )
    })?;
    match status.code() {
        Some(0) => Ok(Outcome::Done),
        Some(REFUSED) => {
            Err(UsageError("the distributed render refused the settings (see above)".into()).into())
        }
        code => anyhow::bail!(
            "the distributed render failed (python -m candela.distributed exited with {})",
            code.map_or("a signal".to_string(), |c| c.to_string())
        ),
    }
}
