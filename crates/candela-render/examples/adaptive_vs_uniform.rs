//! Adaptive against uniform sampling on one scene: wall time, samples and a
//! z-test that both reach the same mean (the BENCHMARKS figure of Part 5).
//!
//! ```text
//! cargo run --release -p candela-render --example adaptive_vs_uniform -- \
//!     SCENE.dae [WIDTH HEIGHT [SPP [BATCH TOL]]]
//! ```
//!
//! Renders with `-l 1 -m 5` (MIS path tracing) at different seeds, so the
//! two renders are independent, and compares them block by block with each
//! pixel's standard error.

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_render::film::{Adaptive, Film};
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use std::error::Error;
use std::time::Instant;

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or_else(|| default.into());
    let path = args
        .first()
        .ok_or("usage: adaptive_vs_uniform SCENE.dae [W H [SPP [BATCH TOL]]]")?;
    let (width, height): (u32, u32) = (arg(1, "240").parse()?, arg(2, "180").parse()?);
    let spp: u32 = arg(3, "2048").parse()?;
    let rule = Adaptive {
        batch: arg(4, "64").parse()?,
        tolerance: arg(5, "0.05").parse()?,
    };
    let loaded = candela_scene::load(std::path::Path::new(path), &Default::default())?;
    let opts = SceneOptions {
        width,
        height,
        ..Default::default()
    };
    let scene = Scene::build(&loaded.scene, &opts)?;
    let base = RenderSettings {
        spp,
        integrator: IntegratorSettings::default(),
        ..Default::default()
    };
    let mut films = Vec::new();
    for (name, settings) in [
        (
            "adaptive",
            RenderSettings {
                seed: 1,
                adaptive: Some(rule),
                ..base.clone()
            },
        ),
        (
            "uniform",
            RenderSettings {
                seed: 2,
                ..base.clone()
            },
        ),
    ] {
        let start = Instant::now();
        let out = render(&scene, &settings, &|_| {})?;
        let spread = out.film.sample_spread(out.film.rect());
        println!(
            "{name}: {:.1} s, {} samples (spp min {} / mean {:.1} / max {}), {:.2} Mrays/s",
            start.elapsed().as_secs_f64(),
            out.stats.samples,
            spread.min,
            spread.mean,
            spread.max,
            out.stats.mrays_per_second()
        );
        films.push(out.film);
    }
    let stats = |f: &Film| -> Result<BlockStats, Box<dyn Error>> {
        Ok(BlockStats::from_pixel_errors(
            &f.resolve(),
            &f.std_error(),
            8,
        )?)
    };
    let test = z_test(&stats(&films[0])?, &stats(&films[1])?, 0.01)?;
    let s = test.summary();
    println!(
        "z-test (8x8 blocks, 1% false alarms): {} blocks, max |z| {:.2}, global |z| {:.2}, threshold {:.2}, {} over: {}",
        s.blocks,
        s.max_abs_z,
        s.global_abs_z,
        s.threshold,
        s.count_over,
        if s.passed() { "same mean" } else { "DIFFERENT" }
    );
    Ok(())
}
