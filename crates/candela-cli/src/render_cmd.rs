//! `candela [flags] [scene.dae]`: load, build, render, write.

use crate::args::{BvhArg, CameraArg, RenderArgs, SamplerArg};
use crate::progress::samples_bar;
use anyhow::{Context, Result};
use candela_bvh::BuildStrategy;
use candela_image::{write_exr, write_png, ExrLayers, RgbImage, ToneMap};
use candela_render::camera::framing::CameraMode;
use candela_render::integrator::{IntegratorKind, LightingMode, PathSettings};
use candela_render::render::{render, RenderOutput, RenderSettings};
use candela_render::sampling::SamplerKind;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{LoadOptions, Loaded};
use std::path::Path;
use std::time::Instant;

/// A command line that parses but asks for something impossible.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Runs one render from the command line.
pub fn run(args: &RenderArgs) -> Result<()> {
    let format = OutputFormat::of(&args.output)?;
    let (width, height) = (args.resolution[0], args.resolution[1]);
    if width == 0 || height == 0 {
        return Err(UsageError(format!("-r {width} {height}: the image must not be empty")).into());
    }
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
    let opts = SceneOptions {
        width,
        height,
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
    let settings = RenderSettings {
        spp: args.spp,
        seed: args.seed,
        integrator: integrator(args),
        sampler: match args.sampler {
            SamplerArg::Sobol => SamplerKind::Sobol,
            SamplerArg::Independent => SamplerKind::Independent,
        },
        threads: args.threads.unwrap_or(0),
    };
    let total = width as u64 * height as u64 * args.spp as u64;
    let bar = samples_bar(total, args.quiet);
    let output = render(&scene, &settings, &|n| bar.inc(n))?;
    bar.finish_and_clear();
    write_output(&args.output, format, &output)?;
    if !args.quiet {
        print_stats(&scene, &output, load_time);
        eprintln!("candela: wrote {}", args.output.display());
    }
    Ok(())
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

#[derive(Clone, Copy)]
enum OutputFormat {
    Png,
    Exr,
}

impl OutputFormat {
    fn of(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Self::Png),
            Some("exr") => Ok(Self::Exr),
            _ => Err(UsageError(format!(
                "-f {}: the output must end in .png or .exr",
                path.display()
            ))
            .into()),
        }
    }
}

fn write_output(path: &Path, format: OutputFormat, output: &RenderOutput) -> Result<()> {
    let film = &output.film;
    let pixels = film.resolve().into_iter().map(|c| c.to_array()).collect();
    let image = RgbImage::from_pixels(film.width as usize, film.height as usize, pixels)?;
    match format {
        OutputFormat::Png => write_png(path, &image, &ToneMap::default()),
        OutputFormat::Exr => write_exr(path, &ExrLayers::beauty(image)),
    }
    .with_context(|| format!("cannot write {}", path.display()))
}

fn print_stats(scene: &Scene, output: &RenderOutput, load_time: std::time::Duration) {
    let s = &output.stats;
    let a = scene.accel_info();
    eprintln!(
        "candela: {} primitives, load {:.1} ms, BVH build {:.1} ms ({} nodes, depth {}, {:.1} bytes/primitive)",
        scene.primitive_count(),
        load_time.as_secs_f64() * 1e3,
        scene.build_time.as_secs_f64() * 1e3,
        a.nodes,
        a.depth,
        a.total_bytes as f64 / scene.primitive_count().max(1) as f64,
    );
    eprintln!(
        "candela: {} rays (camera {}, shadow {}, bounce {}) in {:.3} s on {} threads: {:.2} Mrays/s, {:.0} samples/s",
        s.rays.total(),
        s.rays.camera,
        s.rays.shadow,
        s.rays.bounce,
        s.render_time.as_secs_f64(),
        s.threads,
        s.mrays_per_second(),
        s.samples_per_second(),
    );
    eprintln!(
        "candela: {:.1} nodes visited and {:.1} intersection tests per ray",
        s.nodes_per_ray(),
        s.tests_per_ray()
    );
    eprintln!(
        "candela: {:.2} segments per path on average",
        s.mean_path_length()
    );
    if s.invalid_samples > 0 {
        eprintln!(
            "candela: warning: {} NaN or infinite samples were dropped",
            s.invalid_samples
        );
    }
}
