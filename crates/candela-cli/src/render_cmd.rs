//! `candela [flags] [scene.dae]`: load, build, render, write.
//!
//! The render runs in progressive passes: Ctrl-C (or `--time`) stops it
//! between passes, and the image rendered so far is still written. With
//! `--checkpoint PATH` the film is also saved between passes (see
//! [`candela_render::checkpoint`]); `candela resume PATH` continues it.

use crate::args::RenderArgs;
use crate::progress::RenderBar;
use crate::report::{print_render_warnings, print_stats, ReportContext};
use anyhow::{Context, Result};
use candela_image::denoise::Oidn;
use candela_render::checkpoint::CheckpointWriter;
use candela_render::film::{
    denoise_film, denoised_path, write_denoised, write_film, OutputFormat, OutputOptions,
};
use candela_render::integrator::Estimator;
use candela_render::render::{
    render_from, Cancel, Continuation, PassEnd, Progress, RenderControl, StopReason,
};
use candela_render::scene::Scene;
use candela_render::settings::{Settings, SettingsError};
use candela_scene::{LoadOptions, Loaded};
use clap::ArgMatches;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Exit code of a render stopped by Ctrl-C (128 + SIGINT, as shells do).
pub const INTERRUPTED: u8 = 130;

/// How a render command ended, when it did not fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The render ran to its end (all samples, or the time budget).
    Done,
    /// Ctrl-C stopped it; the partial image was written.
    Interrupted,
}

/// A command line that parses but asks for something impossible.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

impl From<SettingsError> for UsageError {
    fn from(e: SettingsError) -> Self {
        UsageError(e.to_string())
    }
}

/// The explicit settings of the command line, checked before anything is
/// loaded (so `--exposure nan` or an absurd `-r` fail at once).
pub fn explicit_settings(
    args: &RenderArgs,
    matches: &ArgMatches,
) -> Result<serde_json::Map<String, serde_json::Value>, UsageError> {
    if OutputFormat::of(&args.output).is_none() {
        return Err(UsageError(format!(
            "-f {}: the output must end in .png or .exr",
            args.output.display()
        )));
    }
    // A folder that is missing or read-only fails now, not after the render.
    candela_image::check_writable(&args.output)
        .map_err(|e| UsageError(format!("-f {}: {e}", args.output.display())))?;
    let explicit = args.explicit_settings(matches);
    // Check the parsed values themselves too: JSON cannot carry a NaN.
    let mut given = args.settings.clone();
    args.cs184.apply(&mut given);
    given.validate()?;
    Settings::from_json(&explicit)?;
    if given.output.denoise {
        // Before anything is rendered: a missing denoiser is bad input.
        Oidn::load().map_err(|e| UsageError(format!("--denoise: {e}")))?;
    }
    Ok(explicit)
}

/// What a render command renders and writes, beside its settings: what a
/// checkpoint records so that `candela resume` finishes the same job.
#[derive(Clone, Debug, PartialEq)]
pub struct Job {
    /// The scene file (`None`: the built-in demo).
    pub scene: Option<PathBuf>,
    /// The output image.
    pub output: PathBuf,
    /// `--strict`.
    pub strict: bool,
    /// `-D NAME=VALUE`.
    pub defines: Vec<(String, String)>,
    /// `-q`.
    pub quiet: bool,
}

/// Runs one render from the command line.
pub fn run(args: &RenderArgs, matches: &ArgMatches) -> Result<Outcome> {
    let explicit = explicit_settings(args, matches)?;
    let job = Job {
        scene: args.scene.clone(),
        output: args.output.clone(),
        strict: args.strict,
        defines: args.defines.clone(),
        quiet: args.quiet,
    };
    let load_start = Instant::now();
    let loaded = load(&job)?;
    let load_time = load_start.elapsed();
    let settings = Settings::resolve(&loaded.hints, &explicit).map_err(UsageError::from)?;
    render_job(&job, &loaded, load_time, &settings)
}

/// Renders a loaded scene with resolved settings and writes the outputs
/// (and checkpoints, if the settings ask for them).
pub fn render_job(
    job: &Job,
    loaded: &Loaded,
    load_time: std::time::Duration,
    settings: &Settings,
) -> Result<Outcome> {
    let scene = build(loaded, settings)?;
    let checkpoints = CheckpointWriter::start(settings, &loaded.scene, job.record())
        .map_err(|e| UsageError(e.to_string()))?;
    let mut render = settings.render_settings();
    let (writer, resumed) = match checkpoints {
        Some((writer, resumed)) => (Some(writer), resumed),
        None => (None, None),
    };
    if let Some(w) = &writer {
        render.time_budget = w.budget_left(render.time_budget);
        if let (Some(r), false) = (&resumed, job.quiet) {
            let done: u64 = r.film.pixels.iter().map(|p| p.count as u64).sum();
            eprintln!(
                "candela: continuing {} ({done} samples done, {:.1} s rendered)",
                w.path().display(),
                r.elapsed.as_secs_f64()
            );
        }
    }
    let cancel = Cancel::new();
    watch_ctrl_c(&cancel, job.quiet);
    let bar = RenderBar::new(render.time_budget, job.quiet);
    let on_progress = |p: &Progress| bar.update(p);
    let control = RenderControl {
        cancel: Some(cancel),
        progress: Some(&on_progress),
    };
    let after_pass = |pass: &PassEnd<'_>| {
        if let Some(w) = &writer {
            w.after_pass(pass);
        }
    };
    let from = Continuation {
        start: resumed.as_ref().map(|r| &r.film),
        after_pass: Some(&after_pass),
    };
    let output = render_from(&scene, &render, &control, &from)?;
    bar.finish();
    let region = settings.image.region();
    let max_samples = if settings.sampling.spp.is_none() && render.time_budget.is_some() {
        output.film.sample_spread(region).max
    } else {
        render.spp
    };
    let adaptive = render.adaptive.is_some();
    let opts = OutputOptions {
        tone: settings.output.tone_map(),
        aovs: true,
        sample_counts: adaptive,
        depth: true,
        cost: true,
        variance: true,
        info: output.info(&render, job.scene.as_deref()),
        rate_image: adaptive.then_some(max_samples),
        exr_compression: settings.output.exr_compression,
    };
    let mut written = write_film(&job.output, &output.film, &opts)?;
    if settings.output.denoise {
        let oidn = Oidn::load().map_err(|e| UsageError(format!("--denoise: {e}")))?;
        let image = denoise_film(&output.film, oidn)?;
        let path = denoised_path(&job.output);
        write_denoised(&path, &image, &opts.tone)?;
        written.push(path);
    }
    if let Some(w) = &writer {
        if let Some(e) = w.take_failure() {
            eprintln!("candela: warning: {e}");
        }
        // After the image: a checkpoint that cannot be written costs no image.
        w.save(output.film.clone(), output.stats.render_time)?;
    }
    print_render_warnings(&output);
    if !job.quiet {
        let cx = ReportContext {
            load_time,
            path_integrator: settings.integrator.estimator != Estimator::Normals,
            adaptive,
            region,
            max_samples,
        };
        print_stats(&scene, &output, &cx);
        for path in &written {
            eprintln!("candela: wrote {}", path.display());
        }
        if let Some(w) = &writer {
            eprintln!("candela: wrote checkpoint {}", w.path().display());
        }
    }
    Ok(match output.stop {
        StopReason::Cancelled => Outcome::Interrupted,
        StopReason::Complete | StopReason::TimeBudget => Outcome::Done,
    })
}

/// Loads the scene (or the demo) and prints its warnings.
pub fn load(job: &Job) -> Result<Loaded> {
    load_scene(job.scene.as_deref(), job.strict, &job.defines, job.quiet)
}

/// Loads `scene` (`None`: the demo) with `--strict` and `-D` defines, and
/// prints its warnings, and its notes unless `quiet`: `-q` silences progress
/// and statistics, never a report that something asked for was left out.
pub fn load_scene(
    scene: Option<&Path>,
    strict: bool,
    defines: &[(String, String)],
    quiet: bool,
) -> Result<Loaded> {
    let loaded = match scene {
        Some(path) => candela_scene::load(
            path,
            &LoadOptions {
                strict,
                defines: defines.to_vec(),
                ..Default::default()
            },
        )?,
        None => candela_scene::demo_scene(),
    };
    let source = loaded.scene.source.display();
    for warning in &loaded.report.warnings {
        eprintln!("candela: warning: {source}:{warning}");
    }
    if !quiet {
        for note in &loaded.report.notes {
            eprintln!("candela: note: {source}:{note}");
        }
    }
    Ok(loaded)
}

/// Builds the render-ready scene on the render's threads, and prints its
/// warnings (even with `-q`, as `load_scene`).
fn build(loaded: &Loaded, settings: &Settings) -> Result<Scene> {
    let desc = &loaded.scene;
    settings
        .image
        .validate_for_scene(desc.cameras.len())
        .map_err(UsageError::from)?;
    let opts = settings.scene_options().map_err(UsageError::from)?;
    let scene = settings
        .with_threads(|| Scene::build(desc, &opts))
        .map_err(UsageError::from)?
        .with_context(|| format!("cannot render {}", desc.source.display()))?;
    let source = desc.source.display();
    for warning in &scene.warnings {
        eprintln!("candela: warning: {source}: {warning}");
    }
    for what in &scene.unsupported {
        eprintln!("candela: warning: {source}: not supported yet: {what}");
    }
    if let Some(what) = candela_render::integrator::media_ignored(&scene, &settings.integrator) {
        eprintln!("candela: warning: {source}: not supported yet: {what}");
    }
    if settings.integrator.estimator != Estimator::Normals && scene.lights.is_empty() {
        eprintln!(
            "candela: warning: {source}: the scene has no lights; the image will be black (try --normals)"
        );
    }
    Ok(scene)
}

/// The first Ctrl-C cancels the render (which then writes what it has);
/// a second one exits at once.
fn watch_ctrl_c(cancel: &Cancel, quiet: bool) {
    let cancel = cancel.clone();
    let installed = ctrlc::set_handler(move || {
        if cancel.is_cancelled() {
            std::process::exit(INTERRUPTED.into());
        }
        cancel.cancel();
    });
    if let Err(err) = installed {
        if !quiet {
            eprintln!("candela: warning: Ctrl-C will not stop the render cleanly: {err}");
        }
    }
}
