//! Command-line flags. The render options come from the one settings
//! description ([`Settings`], flattened here with its documentation as the
//! help); this file adds only what is the command line's own: the scene and
//! output paths, the CS184 spellings that set several settings at once
//! (`-r W H`, `-a B T`, `-p X Y DX DY`, `-H`, `--normals`, ...), and the
//! Dask and reporting flags.
//!
//! The short flags follow the CS184 PathTracer program (`-s`, `-l`, `-m`,
//! `-t`, `-r W H`, `-f`, ...), so its users can keep their commands.

use candela_render::film::{Adaptive, PixelRect};
use candela_render::integrator::{Estimator, LightingMode};
use candela_render::settings::{Settings, ADAPTIVE_HELP, CELL_HELP};
use clap::parser::ValueSource;
use clap::{ArgMatches, Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use serde_json::{Map, Value};
use std::path::PathBuf;

/// Candela: a physically based path tracer that reads the CS184 COLLADA scenes.
#[derive(Parser, Debug)]
#[command(
    name = "candela",
    version,
    about,
    args_conflicts_with_subcommands = true,
    after_help = "With no scene, renders the built-in demo scene (a Cornell box with two spheres)."
)]
pub struct Cli {
    /// Other tools (benchmarks).
    #[command(subcommand)]
    pub command: Option<Command>,

    /// Render flags.
    #[command(flatten)]
    pub render: RenderArgs,
}

/// Subcommands besides rendering.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Benchmarks of the acceleration structure and of scene loading.
    #[command(subcommand)]
    Bench(crate::bench::BenchCommand),
    /// Candela Studio: view and render the scene interactively in the
    /// browser (a local server; prints its URL).
    View(Box<crate::view_cmd::ViewArgs>),
    /// Continue a render from its checkpoint (`--checkpoint PATH`) and write
    /// the outputs the original command asked for.
    Resume(crate::resume_cmd::ResumeArgs),
    /// Compare renders: relMSE, MSE, PSNR, the block z-test, an error heat
    /// map and, against a reference, the equal-error efficiency ratio.
    Compare(crate::compare::CompareArgs),
    /// Add independent renders (different seeds or sample ranges) into one
    /// EXR, pooling the variance layer.
    Merge(crate::merge_cmd::MergeArgs),
}

/// Flags of a render.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// The scene file, in any format the loader reads (the help lists them
    /// from the loader's own table, so it names every format there is).
    #[arg(help = format!(
        "Scene file: {}. Omit it to render the built-in demo scene",
        candela_scene::supported_formats()
    ))]
    pub scene: Option<PathBuf>,

    /// Output image: .png (8-bit sRGB) or .exr (linear float, with albedo
    /// and normal layers).
    #[arg(
        short = 'f',
        long = "file",
        value_name = "PATH",
        default_value = "candela.png"
    )]
    pub output: PathBuf,

    /// The render settings.
    #[command(flatten)]
    pub settings: Settings,

    /// CS184 spellings of settings.
    #[command(flatten, next_help_heading = "CS184 flags")]
    pub cs184: Cs184Flags,

    /// Render on a Dask cluster (`tcp://host:8786`, or `local:N` for N local
    /// worker processes) through the Python package `candela`.
    #[arg(long, value_name = "ADDRESS", help_heading = "Dask")]
    pub dask: Option<String>,

    /// With --dask: the image is cut into NX × NY cells.
    #[arg(long, num_args = 2, value_names = ["NX", "NY"], default_values_t = [4u32, 4],
          requires = "dask", help_heading = "Dask")]
    pub tiles: Vec<u32>,

    /// With --dask: each pixel's samples are split into this many ranges.
    #[arg(
        long,
        value_name = "P",
        default_value_t = 1,
        requires = "dask",
        help_heading = "Dask"
    )]
    pub passes: u32,

    /// Treat every load warning (an ignored element) as an error.
    #[arg(long)]
    pub strict: bool,

    /// Sets a scene parameter, replacing the file's default (Mitsuba's
    /// `$name`): `-D spp=16 -D res=512`.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub defines: Vec<(String, String)>,

    /// No progress bar and no statistics on stderr (warnings and errors still show).
    #[arg(short = 'q', long)]
    pub quiet: bool,
}

/// The CS184 program's flags, each a spelling of one or more settings.
#[derive(Args, Debug, Clone, Default)]
pub struct Cs184Flags {
    /// Image size in pixels [default: 800 600] (--width W --height H).
    #[arg(short = 'r', long = "resolution", num_args = 2, value_names = ["W", "H"],
          conflicts_with_all = ["width", "height"])]
    pub resolution: Option<Vec<u32>>,

    #[arg(short = 'a', long = "adaptive", num_args = 2, value_names = ["BATCH", "TOL"], help = ADAPTIVE_HELP)]
    pub adaptive: Option<Vec<f64>>,

    #[arg(short = 'p', long = "cell", num_args = 4, value_names = ["X", "Y", "DX", "DY"], help = CELL_HELP)]
    pub cell: Option<Vec<u32>>,

    /// Direct lighting by uniform hemisphere sampling: -l rays per vertex
    /// (CS184), no light sampling (--lighting hemisphere).
    #[arg(short = 'H', long = "hemisphere", conflicts_with_all = ["light_only", "lighting"])]
    pub hemisphere: bool,

    /// Direct lighting by light sampling only (--lighting light).
    #[arg(long = "light-only", conflicts_with = "lighting")]
    pub light_only: bool,

    /// Shade by surface normal (--integrator normals): the CS184 Part 1 view.
    #[arg(long, conflicts_with_all = ["direct_only", "indirect_only", "integrator"])]
    pub normals: bool,

    /// Only light that reached the camera after at most one bounce (--integrator direct).
    #[arg(long, conflicts_with_all = ["indirect_only", "integrator"])]
    pub direct_only: bool,

    /// Only light that reached the camera after two or more bounces (--integrator indirect).
    #[arg(long, conflicts_with = "integrator")]
    pub indirect_only: bool,

    /// Disable Russian roulette (paths run to -m): --roulette false.
    #[arg(long, conflicts_with = "roulette")]
    pub no_roulette: bool,
}

impl Cs184Flags {
    /// Writes the settings these flags spell into `s`; returns the keys
    /// set.
    pub fn apply(&self, s: &mut Settings) -> Vec<&'static str> {
        let mut set = Vec::new();
        // A flag given twice keeps its last values, as every other flag.
        if let Some(&[.., w, h]) = self.resolution.as_deref() {
            (s.image.width, s.image.height) = (w, h);
            set.extend(["width", "height"]);
        }
        if let Some(&[.., batch, tolerance]) = self.adaptive.as_deref() {
            // A BATCH that is not a whole number >= 1 becomes 0, which
            // validation refuses with the -a flag named.
            let whole = batch.fract() == 0.0 && (1.0..=u32::MAX as f64).contains(&batch);
            s.sampling.adaptive = Some(Adaptive {
                batch: if whole { batch as u32 } else { 0 },
                tolerance,
            });
            set.push("adaptive");
        }
        if let Some(&[.., x, y, dx, dy]) = self.cell.as_deref() {
            s.image.cell = Some(PixelRect::new(x, y, dx, dy));
            set.push("cell");
        }
        if self.no_roulette {
            s.integrator.roulette = false;
            set.push("roulette");
        }
        let lighting = if self.hemisphere {
            Some(LightingMode::Hemisphere)
        } else if self.light_only {
            Some(LightingMode::Light)
        } else {
            None
        };
        if let Some(l) = lighting {
            s.integrator.lighting = l;
            set.push("lighting");
        }
        let estimator = if self.normals {
            Some(Estimator::Normals)
        } else if self.direct_only {
            Some(Estimator::Direct)
        } else if self.indirect_only {
            Some(Estimator::Indirect)
        } else {
            None
        };
        if let Some(e) = estimator {
            s.integrator.estimator = e;
            set.push("integrator");
        }
        set
    }
}

impl RenderArgs {
    /// The settings the user gave explicitly, as JSON changes: what a
    /// scene's own defaults (a demo's camera, a Mitsuba file's spp) must
    /// not override.
    pub fn explicit_settings(&self, matches: &ArgMatches) -> Map<String, Value> {
        explicit_settings(&self.settings, &self.cs184, matches)
    }
}

/// The settings of `settings` and `cs184` given on the command line
/// (`matches`: of the command that flattens them), as JSON changes.
pub fn explicit_settings(
    settings: &Settings,
    cs184: &Cs184Flags,
    matches: &ArgMatches,
) -> Map<String, Value> {
    let mut settings = settings.clone();
    let aliased = cs184.apply(&mut settings);
    settings
        .to_json()
        .into_iter()
        .filter(|(key, _)| {
            aliased.contains(&key.as_str())
                || matches
                    .try_get_raw(key)
                    .is_ok_and(|_| matches.value_source(key) == Some(ValueSource::CommandLine))
        })
        .collect()
}

/// Parses the command line, keeping the matches (which tell explicit flags
/// from defaults).
pub fn parse() -> (Cli, ArgMatches) {
    let matches = Cli::command().get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    (cli, matches)
}

#[cfg(test)]
mod tests;

/// `NAME=VALUE` of `-D`: the name non-empty, the value possibly empty.
pub fn parse_define(text: &str) -> Result<(String, String), String> {
    match text.split_once('=') {
        Some((name, value)) if !name.trim().is_empty() => {
            Ok((name.trim().to_string(), value.to_string()))
        }
        _ => Err(format!("expected NAME=VALUE, got \"{text}\"")),
    }
}
