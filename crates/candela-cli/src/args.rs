//! Command-line flags, defined once with their help.
//!
//! The short flags follow the CS184 PathTracer program (`-s`, `-l`, `-m`,
//! `-t`, `-r W H`, `-f`, ...), so its users can keep their commands.

use clap::{Args, Parser, Subcommand, ValueEnum};
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
    /// Benchmarks of the acceleration structure.
    #[command(subcommand)]
    Bench(crate::bench::BenchCommand),
}

/// Flags of a render.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// Scene file (.dae). Omit it to render the built-in demo scene.
    pub scene: Option<PathBuf>,

    /// Samples (camera paths) per pixel.
    #[arg(short = 's', long = "spp", default_value_t = 16, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..))]
    pub spp: u32,

    /// Light samples per area light at each path vertex (one per delta light).
    #[arg(
        short = 'l',
        long = "light-samples",
        default_value_t = 1,
        value_name = "N"
    )]
    pub light_samples: u32,

    /// Maximum number of bounces: 0 emitters seen directly, 1 direct lighting,
    /// 2 one indirect bounce, ...
    #[arg(short = 'm', long = "max-depth", default_value_t = 5, value_name = "N")]
    pub max_depth: u32,

    /// 1: add the light of every bounce up to -m; 0: only light after exactly -m bounces.
    #[arg(short = 'o', long = "accumulate", default_value_t = 1, value_name = "0|1",
          value_parser = clap::value_parser!(u8).range(0..=1))]
    pub accumulate: u8,

    /// Direct lighting by uniform hemisphere sampling (no light sampling).
    #[arg(short = 'H', long = "hemisphere", conflicts_with = "light_only")]
    pub hemisphere: bool,

    /// Direct lighting by light sampling only (no MIS with BSDF sampling).
    #[arg(long = "light-only")]
    pub light_only: bool,

    /// Only light that reached the camera after at most one bounce.
    #[arg(long, conflicts_with = "indirect_only")]
    pub direct_only: bool,

    /// Only light that reached the camera after two or more bounces.
    #[arg(long)]
    pub indirect_only: bool,

    /// Disable Russian roulette (paths run to -m).
    #[arg(long)]
    pub no_roulette: bool,

    /// Number of render threads (default: all cores).
    #[arg(short = 't', long = "threads", value_name = "N")]
    pub threads: Option<usize>,

    /// Image size in pixels.
    #[arg(short = 'r', long = "resolution", num_args = 2, value_names = ["W", "H"],
          default_values_t = [800u32, 600])]
    pub resolution: Vec<u32>,

    /// Output image: .png (8-bit sRGB) or .exr (linear float).
    #[arg(
        short = 'f',
        long = "file",
        value_name = "PATH",
        default_value = "candela.png"
    )]
    pub output: PathBuf,

    /// Seed of the sample sequence; the same seed gives the same image.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// Shade by surface normal (colour = n * 0.5 + 0.5): the CS184 Part 1 view.
    #[arg(long)]
    pub normals: bool,

    /// Sample sequence: Owen-scrambled Sobol (lower noise) or independent random.
    #[arg(long, value_enum, default_value_t = SamplerArg::Sobol)]
    pub sampler: SamplerArg,

    /// Where the camera comes from: the CS184 orbit framing or the file's camera.
    #[arg(long, value_enum, default_value_t = CameraArg::Cs184)]
    pub camera: CameraArg,

    /// BVH construction: surface area heuristic, median split, or none (brute force).
    #[arg(long, value_enum, default_value_t = BvhArg::Sah)]
    pub bvh: BvhArg,

    /// Treat every load warning (an ignored element) as an error.
    #[arg(long)]
    pub strict: bool,

    /// No progress bar and no statistics on stderr.
    #[arg(short = 'q', long)]
    pub quiet: bool,
}

/// `--camera` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraArg {
    /// Orbit the scene's bounds along the file camera's direction (CS184).
    Cs184,
    /// The literal COLLADA camera.
    File,
}

/// `--sampler` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerArg {
    /// Owen-scrambled Sobol points.
    Sobol,
    /// Independent uniform random numbers.
    Independent,
}

/// `--bvh` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BvhArg {
    /// Binned surface area heuristic.
    Sah,
    /// Split at the median centroid on the longest axis (the CS184 seed).
    Median,
    /// No hierarchy: test every primitive.
    None,
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn flags_are_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn cs184_command_line_parses() {
        let cli = Cli::try_parse_from([
            "candela",
            "-t",
            "2",
            "-s",
            "16",
            "-r",
            "480",
            "360",
            "-f",
            "out.png",
            "scene.dae",
        ])
        .unwrap();
        assert_eq!(cli.render.resolution, vec![480, 360]);
        assert_eq!(cli.render.spp, 16);
        assert_eq!(cli.render.threads, Some(2));
        assert_eq!(cli.render.scene, Some(PathBuf::from("scene.dae")));
    }

    #[test]
    fn unknown_flag_is_a_usage_error() {
        let err = Cli::try_parse_from(["candela", "--bogus"]).unwrap_err();
        assert_eq!(err.exit_code(), 2);
    }
}
