//! `candela bench load FILE`: how fast a scene file loads and how much
//! memory loading takes beyond the mesh it produces. Loads the file
//! `runs` times and reports the fastest (the least disturbed on a shared
//! machine), the triangles, and the peak resident memory (`VmHWM` of
//! `/proc/self/status`) above the resident memory before loading, minus the
//! bytes of the loaded mesh data: what the loader needs on the side (file
//! buffers, parse state, growth slack of its vectors).

use anyhow::{anyhow, Context, Result};
use candela_scene::{load, LoadOptions, SceneDesc};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `candela bench load`.
#[derive(Debug, Args)]
pub struct LoadArgs {
    /// Scene file (any format `candela` reads).
    pub file: PathBuf,
    /// Times to load the file; the fastest is reported.
    #[arg(short = 'n', long, default_value_t = 5)]
    pub runs: u32,
}

/// A `kB` field of `/proc/self/status` (`VmRSS`, `VmHWM`), in bytes.
fn status_bytes(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(field))?;
    let kb: u64 = line[field.len()..]
        .trim_start_matches(':')
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    Some(kb * 1024)
}

/// Bytes of the loaded meshes' vertex and index arrays (their lengths,
/// not capacities: slack left by the loader counts as its overhead).
fn mesh_bytes(scene: &SceneDesc) -> u64 {
    let size = |n: usize, bytes: usize| (n * bytes) as u64;
    scene
        .meshes
        .iter()
        .map(|m| {
            size(m.positions.len(), 12)
                + size(m.triangles.len(), 12)
                + size(m.normals.len(), 12)
                + size(m.normal_indices.len(), 12)
                + size(m.uvs.len(), 8)
                + size(m.uv_indices.len(), 12)
        })
        .sum()
}

/// Runs the benchmark, printing a report to stdout.
pub fn run(args: &LoadArgs) -> Result<()> {
    let before = status_bytes("VmRSS");
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..args.runs.max(1) {
        // The previous scene is dropped before the next load starts.
        drop(last.take());
        let t0 = Instant::now();
        let loaded = load(&args.file, &LoadOptions::default())
            .with_context(|| format!("loading {}", args.file.display()))?;
        best = best.min(t0.elapsed().as_secs_f64());
        last = Some(loaded);
    }
    let scene = &last.ok_or_else(|| anyhow!("no run"))?.scene;
    let tris = scene.triangle_count();
    let mesh = mesh_bytes(scene);
    let per_tri = |bytes: f64| bytes / tris.max(1) as f64;
    let mb = |bytes: f64| bytes / 1e6;
    println!("file:        {}", args.file.display());
    println!(
        "triangles:   {tris} in {} meshes, {} vertices",
        scene.meshes.len(),
        scene
            .meshes
            .iter()
            .map(|m| m.positions.len())
            .sum::<usize>()
    );
    println!(
        "load:        {best:.3} s best of {} ({:.1} Mtriangles/s)",
        args.runs.max(1),
        tris as f64 / best / 1e6
    );
    println!(
        "mesh data:   {:.1} MB ({:.1} bytes/triangle)",
        mb(mesh as f64),
        per_tri(mesh as f64)
    );
    match before.zip(status_bytes("VmHWM")) {
        Some((before, peak)) => {
            let beyond = peak as f64 - before as f64 - mesh as f64;
            println!(
                "peak RSS:    {:.1} MB above the {:.1} MB before loading; beyond the mesh: {:.1} MB ({:.1} bytes/triangle)",
                mb(peak as f64 - before as f64),
                mb(before as f64),
                mb(beyond),
                per_tri(beyond)
            );
        }
        None => println!("peak RSS:    unknown (no /proc/self/status)"),
    }
    Ok(())
}
