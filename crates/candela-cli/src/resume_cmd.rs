//! `candela resume PATH`: continues the render a checkpoint was saved from,
//! to its sample target (or time budget), and writes the outputs the
//! original command asked for. The checkpoint carries the settings and the
//! command's job ([`Job`]: scene, output, `--strict`, `-D`), so nothing else
//! is needed; only how the work runs may be changed here, and the sample
//! target raised (`-s`: a finished render continues to more samples per
//! pixel and ends bit for bit where a render started with that target
//! ends, since a pixel's samples depend only on their indices). A distributed
//! render's checkpoint is handed to the distributed front
//! (`python -m candela.distributed --resume`).

use crate::render_cmd::{load, render_job, Job, Outcome, UsageError};
use anyhow::Result;
use candela_render::checkpoint::Checkpoint;
use clap::Args;
use serde_json::{json, Map, Value};
use std::path::PathBuf;
use std::time::Instant;

/// The front-end name the CLI records in its checkpoints.
const FRONT: &str = "cli";

/// Flags of `candela resume`.
#[derive(Args, Debug, Clone)]
pub struct ResumeArgs {
    /// The checkpoint file (written by `candela --checkpoint PATH ...`).
    pub checkpoint: PathBuf,

    /// Samples per pixel to reach [default: the checkpoint's]: a higher
    /// target continues a finished render; a lower one is refused.
    #[arg(short = 's', long, value_name = "N")]
    pub spp: Option<u32>,

    /// Render threads (0: all cores) [default: the checkpoint's].
    #[arg(short = 't', long, value_name = "N")]
    pub threads: Option<usize>,

    /// Time budget in seconds over all runs of the render [default: the
    /// checkpoint's].
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,

    /// Seconds between two checkpoints [default: the checkpoint's].
    #[arg(long, value_name = "SECS")]
    pub checkpoint_every: Option<f64>,

    /// For a distributed render's checkpoint: the Dask cluster to continue
    /// on [default: the one it ran on].
    #[arg(long, value_name = "ADDRESS")]
    pub dask: Option<String>,

    /// No progress bar and no statistics on stderr (warnings and errors still show).
    #[arg(short = 'q', long)]
    pub quiet: bool,
}

impl Job {
    /// The record a checkpoint keeps of the job (absolute paths, so that
    /// `candela resume` works from any folder).
    pub fn record(&self) -> Map<String, Value> {
        let absolute = |p: &PathBuf| std::path::absolute(p).unwrap_or_else(|_| p.clone());
        let record = json!({
            "front": FRONT,
            "scene": self.scene.as_ref().map(absolute),
            "output": absolute(&self.output),
            "strict": self.strict,
            "defines": self.defines,
        });
        match record {
            Value::Object(m) => m,
            _ => unreachable!("a JSON object"),
        }
    }

    /// The job a checkpoint recorded.
    fn from_record(record: &Map<String, Value>) -> Result<Self, String> {
        match record.get("front").and_then(Value::as_str) {
            Some(FRONT) => {}
            other => return Err(format!("unknown front end {other:?} in the checkpoint")),
        }
        let bad = |key: &str| format!("the checkpoint's job has a malformed `{key}`");
        let get = |key: &str| record.get(key).cloned().unwrap_or(Value::Null);
        Ok(Self {
            scene: serde_json::from_value(get("scene")).map_err(|_| bad("scene"))?,
            output: serde_json::from_value(get("output")).map_err(|_| bad("output"))?,
            strict: serde_json::from_value(get("strict")).map_err(|_| bad("strict"))?,
            defines: serde_json::from_value(get("defines")).map_err(|_| bad("defines"))?,
            quiet: false,
        })
    }
}

/// Runs `candela resume`.
pub fn run(args: &ResumeArgs) -> Result<Outcome> {
    let checkpoint = Checkpoint::load(&args.checkpoint).map_err(|e| UsageError(e.to_string()))?;
    if checkpoint.front.get("front").and_then(Value::as_str) == Some("dask") {
        // A distributed render continues on a cluster: `--dask` or the one
        // it ran on.
        let recorded = checkpoint.front.get("address").and_then(Value::as_str);
        let address = args.dask.as_deref().or(recorded).ok_or_else(|| {
            UsageError(format!(
                "{}: a distributed render's checkpoint: give the cluster with --dask ADDRESS",
                args.checkpoint.display()
            ))
        })?;
        refuse_cli_only_flags(args)?;
        return crate::dask::resume(&args.checkpoint, address, args.quiet);
    }
    if args.dask.is_some() {
        return Err(UsageError(format!(
            "{}: --dask applies to a distributed render's checkpoint; this one was rendered by `candela`",
            args.checkpoint.display()
        ))
        .into());
    }
    let mut job = Job::from_record(&checkpoint.front)
        .map_err(|e| UsageError(format!("{}: {e}", args.checkpoint.display())))?;
    job.quiet = args.quiet;
    let mut settings = checkpoint.settings;
    if let Some(spp) = args.spp {
        // A lower target is refused where every checkpoint is matched.
        settings.sampling.spp = Some(spp);
    }
    if let Some(t) = args.threads {
        settings.run.threads = t;
    }
    if let Some(t) = args.time {
        settings.sampling.time = Some(t);
    }
    if let Some(every) = args.checkpoint_every {
        settings.run.checkpoint_every = every;
    }
    settings.run.checkpoint = Some(args.checkpoint.clone());
    settings.validate().map_err(UsageError::from)?;
    let load_start = Instant::now();
    let loaded = load(&job)?;
    render_job(&job, &loaded, load_start.elapsed(), &settings)
}

/// A distributed render continues as its checkpoint says (the cluster runs
/// it): the flags that change a CLI render's run are refused by name rather
/// than dropped.
fn refuse_cli_only_flags(args: &ResumeArgs) -> Result<(), UsageError> {
    let given = [
        ("-s", args.spp.is_some()),
        ("-t", args.threads.is_some()),
        ("--time", args.time.is_some()),
        ("--checkpoint-every", args.checkpoint_every.is_some()),
    ];
    match given.iter().find(|(_, set)| *set) {
        Some((flag, _)) => Err(UsageError(format!(
            "{}: {flag} applies to a checkpoint rendered by `candela`, not to a distributed render's",
            args.checkpoint.display()
        ))),
        None => Ok(()),
    }
}
