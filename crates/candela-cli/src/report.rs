//! The statistics printed after a render, on stderr.

use candela_render::film::PixelRect;
use candela_render::render::{RenderOutput, StopReason};
use candela_render::scene::Scene;
use std::time::Duration;

/// What the report needs besides the render itself.
pub struct ReportContext {
    /// Scene loading time.
    pub load_time: Duration,
    /// Whether the path integrator ran (path lengths mean something).
    pub path_integrator: bool,
    /// Whether adaptive sampling was on.
    pub adaptive: bool,
    /// The pixels rendered.
    pub region: PixelRect,
    /// Most samples a pixel could take.
    pub max_samples: u32,
}

/// Prints the statistics of a finished or stopped render.
pub fn print_stats(scene: &Scene, output: &RenderOutput, cx: &ReportContext) {
    let s = &output.stats;
    let a = scene.accel_info();
    eprintln!(
        "candela: {} primitives, load {:.1} ms, BVH build {:.1} ms ({} nodes, depth {}, {:.1} bytes/primitive)",
        scene.primitive_count(),
        cx.load_time.as_secs_f64() * 1e3,
        scene.build_time.as_secs_f64() * 1e3,
        a.nodes,
        a.depth,
        a.total_bytes as f64 / scene.primitive_count().max(1) as f64,
    );
    eprintln!(
        "candela: {} rays (camera {}, shadow {}, bounce {}) in {:.3} s on {} threads, {} passes: {:.2} Mrays/s, {:.0} samples/s",
        s.rays.total(),
        s.rays.camera,
        s.rays.shadow,
        s.rays.bounce,
        s.render_time.as_secs_f64(),
        s.threads,
        s.passes,
        s.mrays_per_second(),
        s.samples_per_second(),
    );
    eprintln!(
        "candela: {:.1} nodes visited and {:.1} intersection tests per ray",
        s.nodes_per_ray(),
        s.tests_per_ray()
    );
    if cx.path_integrator {
        eprintln!(
            "candela: {:.2} segments per path on average",
            s.mean_path_length()
        );
    }
    let spread = output.film.sample_spread(cx.region);
    let spread_text = format!(
        "samples per pixel min {} / mean {:.1} / max {}",
        spread.min, spread.mean, spread.max
    );
    if cx.adaptive {
        let pixels = cx.region.area().max(1) as f64;
        eprintln!(
            "candela: adaptive: {:.1}% of pixels converged, {spread_text} ({:.1}% of the {} samples of a uniform render)",
            100.0 * s.converged_pixels as f64 / pixels,
            100.0 * spread.mean / cx.max_samples.max(1) as f64,
            cx.max_samples,
        );
    }
    match output.stop {
        StopReason::Complete => {}
        StopReason::TimeBudget => eprintln!("candela: time budget spent: {spread_text}"),
        StopReason::Cancelled => {
            eprintln!("candela: interrupted: the image is partial, {spread_text}")
        }
    }
}

/// Prints what went wrong in a render without stopping it, even with `-q`
/// (which silences statistics, not warnings).
pub fn print_render_warnings(output: &RenderOutput) {
    if output.stats.invalid_samples > 0 {
        eprintln!(
            "candela: warning: {} NaN or infinite samples were dropped",
            output.stats.invalid_samples
        );
    }
}
