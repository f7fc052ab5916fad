//! `candela bench`: replays fixed ray sets through the acceleration
//! structure (the yardstick is Embree on the same rays) and measures how
//! build time, memory and query rate scale with triangle count; and times
//! scene loading.

mod files;
mod load;
mod replay;
mod scaling;
mod timing;

use anyhow::Result;
use candela_render::accel::{Accel, Layout};
use candela_render::geometry::Ray;
use candela_render::settings::Bvh;
use clap::{Args, Subcommand, ValueEnum};
use rayon::prelude::*;
use std::path::PathBuf;
use timing::{measure, Measure};

/// Benchmarks of the ray-intersection core.
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Replay a ray set against a mesh, checked against reference hits.
    Rays(RaysArgs),
    /// Build and query synthetic meshes from 10k to 2M triangles.
    Scaling(ScalingArgs),
    /// Load a scene file repeatedly: best time, triangles, peak memory beyond the mesh.
    Load(load::LoadArgs),
}

/// Arguments of `candela bench rays`.
#[derive(Debug, Args)]
pub struct RaysArgs {
    /// Triangle mesh (`.tri`).
    pub mesh: PathBuf,
    /// Ray set (`.rays`).
    pub rays: PathBuf,
    /// Reference closest hits (`.hits`) for the first rays; a mismatch fails the run.
    #[arg(long)]
    pub hits: Option<PathBuf>,
    /// Threads for the multi-threaded figures (the single-thread figure is always reported).
    #[arg(short = 't', long, default_value_t = 2)]
    pub threads: usize,
    /// Time only any-hit (shadow) queries.
    #[arg(long)]
    pub any_hit: bool,
    /// BVH build strategy.
    #[arg(long, value_enum, default_value_t = Bvh::Sah)]
    pub bvh: Bvh,
    /// BVH node layout.
    #[arg(long, value_enum, default_value_t = NodeLayout::Auto)]
    pub layout: NodeLayout,
    /// Replay only the first N rays (brute force over a big set is slow).
    #[arg(long)]
    pub limit: Option<usize>,
    /// Override the SAH cost of a primitive test (block), relative to a node visit.
    #[arg(long)]
    pub isect_cost: Option<f32>,
    /// Override the largest leaf.
    #[arg(long)]
    pub max_leaf: Option<usize>,
    /// Override the binary build's leaf block under `--collapse greedy` (the
    /// SAH then charges `ceil(n / block)` primitive tests per leaf; the wide
    /// collapse still counts blocks of 4). No effect under `--collapse sah`,
    /// whose binary build always charges single primitives.
    #[arg(long)]
    pub leaf_block: Option<usize>,
    /// Override how the binary tree is collapsed into the wide one.
    #[arg(long, value_enum)]
    pub collapse: Option<CollapseArg>,
    /// Override the SAH collapse's cost of a wide node test, relative to a block test.
    #[arg(long)]
    pub node_cost: Option<f32>,
    /// Override the SAH collapse's cost of entering a leaf (before its
    /// first block), relative to a block test; also the leaf splits' cost.
    #[arg(long)]
    pub leaf_cost: Option<f32>,
    /// Minimum seconds per timed measurement.
    #[arg(long, default_value_t = 1.0)]
    pub seconds: f64,
}

/// Arguments of `candela bench scaling`.
#[derive(Debug, Args)]
pub struct ScalingArgs {
    /// Triangle counts to generate (approximate).
    #[arg(long, value_delimiter = ',', default_values_t = [10_000usize, 50_000, 200_000, 1_200_000, 2_000_000])]
    pub sizes: Vec<usize>,
    /// Rays per query measurement.
    #[arg(long, default_value_t = 200_000)]
    pub rays: usize,
    /// BVH build strategy.
    #[arg(long, value_enum, default_value_t = Bvh::Sah)]
    pub bvh: Bvh,
    /// BVH node layout.
    #[arg(long, value_enum, default_value_t = NodeLayout::Auto)]
    pub layout: NodeLayout,
}

/// The wide collapse as a command-line value.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum CollapseArg {
    /// Open the child of largest area until a node is full.
    Greedy,
    /// The collapse of least SAH cost (dynamic programming).
    Sah,
}

impl From<CollapseArg> for candela_bvh::Collapse {
    fn from(c: CollapseArg) -> Self {
        match c {
            CollapseArg::Greedy => Self::Greedy,
            CollapseArg::Sah => Self::Sah,
        }
    }
}

/// The node layout as a command-line value.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum NodeLayout {
    /// Binary BVH, scalar box tests.
    Binary,
    /// 4-wide BVH, SSE box tests.
    Wide4,
    /// 8-wide BVH, AVX2 box tests (SSE on CPUs without AVX2).
    Wide8,
    /// What the renderer uses: 8-wide with AVX2, else 4-wide.
    Auto,
}

impl From<NodeLayout> for Layout {
    fn from(l: NodeLayout) -> Self {
        match l {
            NodeLayout::Binary => Layout::Binary,
            NodeLayout::Wide4 => Layout::Wide4,
            NodeLayout::Wide8 => Layout::Wide8,
            NodeLayout::Auto => Layout::default(),
        }
    }
}

/// Runs a benchmark command, printing a report to stdout.
pub fn run(cmd: BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Rays(args) => replay::run(&args),
        BenchCommand::Scaling(args) => scaling::run(&args),
        BenchCommand::Load(args) => load::run(&args),
    }
}

/// Traces every ray on `threads` threads (closest or any hit) for at least
/// `seconds`; returns the measurement and the number of hits.
fn throughput(
    accel: &Accel,
    rays: &[Ray],
    threads: usize,
    any_hit: bool,
    seconds: f64,
) -> Result<(Measure, u64)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()?;
    let pass = || {
        pool.install(|| {
            rays.par_chunks(4096)
                .map(|chunk| {
                    let mut hits = 0u64;
                    for r in chunk {
                        hits += if any_hit {
                            accel.occluded(r)
                        } else {
                            accel.intersect(r).is_some()
                        } as u64;
                    }
                    hits
                })
                .sum::<u64>()
        })
    };
    Ok(measure(rays.len() as u64, seconds, pass))
}

/// One line of a throughput table; `hits` of `n_rays` in one pass.
fn report_line(label: &str, threads: usize, m: &Measure, hits: u64, n_rays: usize) {
    let cpu = m.cpu_rate().map_or("?".to_string(), |r| format!("{r:.3}"));
    println!(
        "  {label:<8} {threads} thread(s): {:>7.3} Mrays/s wall, {:>6.3} per thread, {cpu:>6} per CPU-second  ({hits} of {n_rays} hit)",
        m.wall_rate(),
        m.wall_rate() / threads as f64,
    );
}
