//! `candela [flags] [scene.dae]`: load, build, render, write.
//!
//! The render runs in progressive passes: Ctrl-C (or `--time`) stops it
//! between passes, and the image rendered so far is still written.

use crate::args::{BvhArg, CameraArg, RenderArgs, SamplerArg, ToneArg};
use crate::output::{self, OutputFormat, OutputOptions};
use crate::progress::RenderBar;
use crate::report::{print_stats, ReportContext};
use anyhow::{Context, Result};
use candela_bvh::BuildStrategy;
use candela_image::{ToneCurve, ToneMap};
use candela_render::camera::framing::CameraMode;
use candela_render::film::{Adaptive, PixelRect};
use candela_render::integrator::{IntegratorKind, LightingMode, PathSettings};
use candela_render::light::{EnvironmentMap, EnvironmentOptions, ProceduralSky};
use candela_render::render::{
    render_with, Cancel, Progress, RenderControl, RenderSettings, StopReason,
};
use candela_render::sampling::SamplerKind;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{LoadOptions, Loaded};
use std::sync::Arc;
use std::time::{Duration, Instant};

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

/// Runs one render from the command line.
pub fn run(args: &RenderArgs) -> Result<Outcome> {
    let format = OutputFormat::of(&args.output).ok_or_else(|| {
        UsageError(format!(
            "-f {}: the output must end in .png or .exr",
            args.output.display()
        ))
    })?;
    let (width, height) = (args.resolution[0], args.resolution[1]);
    if width == 0 || height == 0 {
        return Err(UsageError(format!("-r {width} {height}: the image must not be empty")).into());
    }
    let adaptive = adaptive_arg(args.adaptive.as_deref())?;
    let cell = cell_arg(args.cell.as_deref(), width, height)?;
    let region = cell.unwrap_or(PixelRect::full(width, height));
    let time_budget = time_arg(args.time)?;
    let (scene, load_time) = load_scene(args, width, height)?;
    let settings = RenderSettings {
        spp: spp(args),
        seed: args.seed,
        integrator: integrator(args),
        sampler: match args.sampler {
            SamplerArg::Sobol => SamplerKind::Sobol,
            SamplerArg::Independent => SamplerKind::Independent,
        },
        threads: args.threads.unwrap_or(0),
        cell,
        sample_range: None,
        adaptive,
        time_budget,
        tile: args.tile,
    };
    let cancel = Cancel::new();
    watch_ctrl_c(&cancel, args.quiet);
    let bar = RenderBar::new(time_budget, args.quiet);
    let on_progress = |p: &Progress| bar.update(p);
    let control = RenderControl {
        cancel: Some(cancel),
        progress: Some(&on_progress),
    };
    let output = render_with(&scene, &settings, &control)?;
    bar.finish();
    let max_samples = if args.spp.is_none() && time_budget.is_some() {
        output.film.sample_spread(region).max
    } else {
        settings.spp
    };
    let opts = OutputOptions {
        tone: ToneMap {
            exposure: args.exposure,
            curve: match args.tone {
                ToneArg::Srgb => ToneCurve::Srgb,
                ToneArg::Cs184 => ToneCurve::Cs184,
                ToneArg::Filmic => ToneCurve::Filmic,
            },
        },
        sample_rate: adaptive.is_some(),
        max_samples,
    };
    let written = output::write(&args.output, format, &output.film, &opts)?;
    if !args.quiet {
        let cx = ReportContext {
            load_time,
            path_integrator: matches!(settings.integrator, IntegratorKind::Path(_)),
            adaptive: adaptive.is_some(),
            region,
            max_samples,
        };
        print_stats(&scene, &output, &cx);
        for path in &written {
            eprintln!("candela: wrote {}", path.display());
        }
    }
    Ok(match output.stop {
        StopReason::Cancelled => Outcome::Interrupted,
        StopReason::Complete | StopReason::TimeBudget => Outcome::Done,
    })
}

/// `-e sky` names the built-in procedural sky (a gradient and a sun).
const BUILT_IN_SKY: &str = "sky";

/// Loads the scene (or the demo), prints its warnings, and builds it.
fn load_scene(args: &RenderArgs, width: u32, height: u32) -> Result<(Scene, Duration)> {
    let load_start = Instant::now();
    let loaded = match &args.scene {
        Some(path) => candela_scene::load(
            path,
            &LoadOptions {
                strict: args.strict,
                ..Default::default()
            },
        )?,
        None => candela_scene::demo_scene(),
    };
    let load_time = load_start.elapsed();
    let Loaded {
        scene: desc,
        report,
    } = loaded;
    if !args.quiet {
        for warning in &report.warnings {
            eprintln!("candela: warning: {}:{warning}", desc.source.display());
        }
        for note in &report.notes {
            eprintln!("candela: note: {}:{note}", desc.source.display());
        }
    }
    let environment = match &args.env_map {
        Some(path) => {
            let options = EnvironmentOptions {
                scale: args.env_scale,
                rotate_y_deg: args.env_rotate,
            };
            let map = if path.as_os_str() == BUILT_IN_SKY && !path.exists() {
                let image = ProceduralSky::default().image(512, 256)?;
                EnvironmentMap::from_image(&image, &options)?
            } else {
                EnvironmentMap::load(path, &options).map_err(|err| {
                    UsageError(format!(
                        "-e {}: cannot read the environment map: {err}",
                        path.display()
                    ))
                })?
            };
            Some(Arc::new(map))
        }
        None => None,
    };
    let opts = SceneOptions {
        width,
        height,
        lens_radius: args.aperture.unwrap_or(0.0),
        focal_distance: args.focal_distance,
        environment,
        camera_mode: match args.camera {
            CameraArg::Cs184 => CameraMode::Cs184,
            CameraArg::File => CameraMode::File,
        },
        bvh: match args.bvh {
            BvhArg::Sah => BuildStrategy::Sah,
            BvhArg::Median => BuildStrategy::Median,
            BvhArg::None => BuildStrategy::None,
        },
    };
    let scene = Scene::build(&desc, &opts)
        .with_context(|| format!("cannot render {}", desc.source.display()))?;
    if !args.quiet {
        for warning in &scene.warnings {
            eprintln!("candela: warning: {}: {warning}", desc.source.display());
        }
        for what in &scene.unsupported {
            eprintln!(
                "candela: warning: {}: not supported yet: {what}",
                desc.source.display()
            );
        }
        if !args.normals && scene.lights.is_empty() {
            eprintln!(
                "candela: warning: {}: the scene has no lights; the image will be black (try --normals)",
                desc.source.display()
            );
        }
    }
    Ok((scene, load_time))
}

/// Samples per pixel: `-s`, else 16, else (under a time budget) no limit.
fn spp(args: &RenderArgs) -> u32 {
    match (args.spp, args.time) {
        (Some(n), _) => n,
        (None, Some(_)) => u32::MAX,
        (None, None) => 16,
    }
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

/// `-a BATCH TOL`, checked.
fn adaptive_arg(values: Option<&[f64]>) -> Result<Option<Adaptive>> {
    let Some(&[batch, tolerance]) = values else {
        return Ok(None);
    };
    let whole = batch.fract() == 0.0 && (1.0..=u32::MAX as f64).contains(&batch);
    if !whole || !tolerance.is_finite() || tolerance < 0.0 {
        return Err(UsageError(format!(
            "-a {batch} {tolerance}: BATCH must be a whole number >= 1 and TOL a number >= 0"
        ))
        .into());
    }
    Ok(Some(Adaptive {
        batch: batch as u32,
        tolerance,
    }))
}

/// `-p X Y DX DY`, checked against the frame.
fn cell_arg(values: Option<&[u32]>, width: u32, height: u32) -> Result<Option<PixelRect>> {
    let Some(&[x, y, dx, dy]) = values else {
        return Ok(None);
    };
    let cell = PixelRect::new(x, y, dx, dy);
    if !cell.fits_in(width, height) {
        return Err(UsageError(format!(
            "-p {x} {y} {dx} {dy}: the cell must be non-empty and inside the {width}x{height} image"
        ))
        .into());
    }
    Ok(Some(cell))
}

/// `--time SECONDS`, checked.
fn time_arg(seconds: Option<f64>) -> Result<Option<Duration>> {
    let Some(seconds) = seconds else {
        return Ok(None);
    };
    Duration::try_from_secs_f64(seconds)
        .ok()
        .filter(|d| !d.is_zero())
        .map(Some)
        .ok_or_else(|| {
            UsageError(format!(
                "--time {seconds}: give a positive number of seconds"
            ))
            .into()
        })
}

/// The integrator the flags ask for.
fn integrator(args: &RenderArgs) -> IntegratorKind {
    if args.normals {
        return IntegratorKind::Normals;
    }
    let m = args.max_depth;
    let bounces = if args.direct_only {
        0..=m.min(1)
    } else if args.indirect_only {
        2..=m
    } else if args.accumulate == 0 {
        m..=m
    } else {
        0..=m
    };
    IntegratorKind::Path(PathSettings {
        bounces,
        lighting: if args.hemisphere {
            LightingMode::Hemisphere
        } else if args.light_only {
            LightingMode::Light
        } else {
            LightingMode::Mis
        },
        light_samples: args.light_samples,
        roulette_from: (!args.no_roulette).then_some(3),
    })
}
