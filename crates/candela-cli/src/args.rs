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

    /// Samples (camera paths) per pixel [default: 16, or no limit with --time].
    /// With -a, the most a pixel takes.
    #[arg(short = 's', long = "spp", value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..))]
    pub spp: Option<u32>,

    /// Adaptive sampling (CS184): every BATCH samples, stop a pixel once the
    /// 95% confidence interval of its mean illuminance is within TOL of the
    /// mean (the course uses -a 64 0.05). Also writes <name>_rate.png.
    #[arg(short = 'a', long = "adaptive", num_args = 2, value_names = ["BATCH", "TOL"])]
    pub adaptive: Option<Vec<f64>>,

    /// Render only the cell of DX × DY pixels at (X, Y) (y = 0 at the top),
    /// into the full-size image; the rest stays black.
    #[arg(short = 'p', long = "cell", num_args = 4, value_names = ["X", "Y", "DX", "DY"])]
    pub cell: Option<Vec<u32>>,

    /// Time budget in seconds: render in passes until it is spent (the last
    /// pass may overrun by about half a second), then stop.
    #[arg(long = "time", value_name = "SECONDS")]
    pub time: Option<f64>,

    /// Environment map: an equirectangular HDR image (.exr, or .png), +Y up,
    /// lighting the scene from infinitely far away; `sky` is a built-in
    /// procedural sky with a sun.
    #[arg(short = 'e', long = "env", value_name = "MAP")]
    pub env_map: Option<PathBuf>,

    /// Multiplies the environment map's radiance.
    #[arg(long = "env-scale", value_name = "S", default_value_t = 1.0)]
    pub env_scale: f32,

    /// Turns the environment map about the vertical axis, in degrees.
    #[arg(long = "env-rotate", value_name = "DEG", default_value_t = 0.0)]
    pub env_rotate: f32,

    /// Thin-lens aperture radius in scene units (depth of field; 0 is a pinhole).
    #[arg(short = 'b', long = "aperture", value_name = "RADIUS")]
    pub aperture: Option<f32>,

    /// Distance from the lens to the plane in focus (default: the framing's
    /// distance to the scene centre).
    #[arg(short = 'd', long = "focal-distance", value_name = "DIST")]
    pub focal_distance: Option<f32>,

    /// Render on a Dask cluster (`tcp://host:8786`, or `local:N` for N local
    /// worker processes) through the Python package `candela`.
    #[arg(long, value_name = "ADDRESS")]
    pub dask: Option<String>,

    /// With --dask: the image is cut into NX × NY cells.
    #[arg(long, num_args = 2, value_names = ["NX", "NY"], default_values_t = [4u32, 4], requires = "dask")]
    pub tiles: Vec<u32>,

    /// With --dask: each pixel's samples are split into this many ranges.
    #[arg(long, value_name = "P", default_value_t = 1, requires = "dask")]
    pub passes: u32,

    /// Tile edge in pixels (changes only speed, never the image).
    #[arg(long, value_name = "N", default_value_t = 16, hide = true,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub tile: u32,

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

    /// Direct lighting by uniform hemisphere sampling: -l rays per vertex (CS184), no light sampling.
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

    /// PNG exposure in stops: radiance is scaled by 2^STOPS before the tone curve.
    #[arg(
        long,
        value_name = "STOPS",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub exposure: f32,

    /// PNG tone curve: exact sRGB, the CS184 program's (×√2, then gamma 2.2),
    /// or an ACES filmic curve that rolls off highlights.
    #[arg(long, value_enum, default_value_t = ToneArg::Srgb)]
    pub tone: ToneArg,

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

/// `--tone` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ToneArg {
    /// Clamp, then the sRGB curve.
    Srgb,
    /// What the CS184 program writes: exposure √2, then gamma 2.2.
    Cs184,
    /// ACES filmic (Narkowicz's fit), then sRGB.
    Filmic,
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
        assert_eq!(cli.render.spp, Some(16));
        assert_eq!(cli.render.threads, Some(2));
        assert_eq!(cli.render.scene, Some(PathBuf::from("scene.dae")));
    }

    #[test]
    fn part5_flags_parse() {
        let cli = Cli::try_parse_from([
            "candela",
            "-a",
            "64",
            "0.05",
            "-p",
            "10",
            "20",
            "30",
            "40",
            "--time",
            "2.5",
            "--exposure",
            "-1.5",
            "--tone",
            "cs184",
            "--tile",
            "8",
        ])
        .unwrap();
        let r = cli.render;
        assert_eq!(r.adaptive, Some(vec![64.0, 0.05]));
        assert_eq!(r.cell, Some(vec![10, 20, 30, 40]));
        assert_eq!(r.time, Some(2.5));
        assert_eq!(r.exposure, -1.5);
        assert_eq!(r.tone, ToneArg::Cs184);
        assert_eq!((r.tile, r.spp), (8, None));
        assert!(Cli::try_parse_from(["candela", "-p", "1", "2", "3"]).is_err());
        assert!(Cli::try_parse_from(["candela", "--tile", "0"]).is_err());
    }

    #[test]
    fn unknown_flag_is_a_usage_error() {
        let err = Cli::try_parse_from(["candela", "--bogus"]).unwrap_err();
        assert_eq!(err.exit_code(), 2);
    }
}
