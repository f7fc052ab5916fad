//! Keyword arguments of `Scene.render`, checked and turned into the
//! library's settings. The integrator options mirror the CLI flags so that a
//! Python render and a CLI render of the same options are the same image.

use candela_bvh::BuildStrategy;
use candela_render::camera::framing::CameraMode;
use candela_render::film::{Adaptive, PixelRect};
use candela_render::integrator::{IntegratorKind, LightingMode, PathSettings};
use candela_render::render::RenderSettings;
use candela_render::sampling::SamplerKind;
use candela_render::scene::SceneOptions;
use pyo3::exceptions::PyValueError;
use pyo3::PyResult;
use std::ops::Range;

/// Everything one `Scene.render` call asks for, validated.
#[derive(Clone, Debug)]
pub struct RenderRequest {
    /// Image size, camera and BVH: what the built scene depends on.
    pub scene: SceneOptions,
    /// Integrator, sampler, seed, threads, cell, adaptive sampling; the
    /// sample range is set per pass.
    pub settings: RenderSettings,
    /// Sample indices to render in each pixel, split into `passes`.
    pub samples: Range<u32>,
    /// Number of consecutive sample ranges, merged in order.
    pub passes: u32,
}

/// The raw keyword arguments, as Python passed them.
pub struct RenderKwargs<'a> {
    pub spp: u32,
    pub max_depth: u32,
    pub light_samples: u32,
    pub integrator: &'a str,
    pub lighting: &'a str,
    pub accumulate: bool,
    pub roulette: bool,
    pub sampler: &'a str,
    pub seed: u64,
    pub width: u32,
    pub height: u32,
    pub camera: &'a str,
    pub bvh: &'a str,
    pub cell: Option<(u32, u32, u32, u32)>,
    pub sample_range: Option<(u32, u32)>,
    pub passes: u32,
    pub adaptive: Option<Adaptive>,
    pub threads: usize,
    pub aperture: f32,
    pub focal_distance: Option<f32>,
    pub environment: Option<std::sync::Arc<candela_render::light::EnvironmentMap>>,
}

fn bad<T>(msg: String) -> PyResult<T> {
    Err(PyValueError::new_err(msg))
}

fn choice<T: Copy>(name: &str, value: &str, options: &[(&str, T)]) -> PyResult<T> {
    match options.iter().find(|(k, _)| *k == value) {
        Some(&(_, v)) => Ok(v),
        None => {
            let names: Vec<_> = options.iter().map(|(k, _)| format!("{k:?}")).collect();
            bad(format!(
                "{name}={value:?}: expected one of {}",
                names.join(", ")
            ))
        }
    }
}

impl RenderKwargs<'_> {
    /// Checks the arguments and builds the request.
    pub fn validate(&self) -> PyResult<RenderRequest> {
        if self.width == 0 || self.height == 0 {
            return bad(format!(
                "width={}, height={}: the image must not be empty",
                self.width, self.height
            ));
        }
        if self.spp == 0 {
            return bad("spp=0: at least one sample per pixel".into());
        }
        let (x, y, w, h) = self.cell.unwrap_or((0, 0, self.width, self.height));
        let cell = PixelRect::new(x, y, w, h);
        if !cell.fits_in(self.width, self.height) {
            return bad(format!(
                "cell=({x}, {y}, {w}, {h}): expected a non-empty (x, y, width, height) inside the {}x{} image",
                self.width, self.height
            ));
        }
        let (s0, s1) = self.sample_range.unwrap_or((0, self.spp));
        if s0 >= s1 || s1 > self.spp {
            return bad(format!(
                "sample_range=({s0}, {s1}): expected start < end <= spp ({})",
                self.spp
            ));
        }
        if self.passes == 0 || self.passes > s1 - s0 {
            return bad(format!(
                "passes={}: expected 1 to {} (one sample per pass at least)",
                self.passes,
                s1 - s0
            ));
        }
        let sampler = choice(
            "sampler",
            self.sampler,
            &[
                ("sobol", SamplerKind::Sobol),
                ("independent", SamplerKind::Independent),
            ],
        )?;
        let camera_mode = choice(
            "camera",
            self.camera,
            &[("cs184", CameraMode::Cs184), ("file", CameraMode::File)],
        )?;
        let bvh = choice(
            "bvh",
            self.bvh,
            &[
                ("sah", BuildStrategy::Sah),
                ("median", BuildStrategy::Median),
                ("none", BuildStrategy::None),
            ],
        )?;
        Ok(RenderRequest {
            scene: SceneOptions {
                width: self.width,
                height: self.height,
                camera_mode,
                bvh,
                lens_radius: self.aperture,
                focal_distance: self.focal_distance,
                environment: self.environment.clone(),
            },
            settings: RenderSettings {
                spp: self.spp,
                seed: self.seed,
                integrator: self.integrator()?,
                sampler,
                threads: self.threads,
                cell: Some(cell),
                adaptive: self.adaptive,
                ..RenderSettings::default()
            },
            samples: s0..s1,
            passes: self.passes,
        })
    }

    /// The estimator, chosen exactly as the CLI's flags choose it.
    fn integrator(&self) -> PyResult<IntegratorKind> {
        #[derive(Clone, Copy)]
        enum Which {
            Normals,
            Path,
            Direct,
            Indirect,
        }
        let which = choice(
            "integrator",
            self.integrator,
            &[
                ("path", Which::Path),
                ("normals", Which::Normals),
                ("direct", Which::Direct),
                ("indirect", Which::Indirect),
            ],
        )?;
        let lighting = choice(
            "lighting",
            self.lighting,
            &[
                ("mis", LightingMode::Mis),
                ("light", LightingMode::Light),
                ("hemisphere", LightingMode::Hemisphere),
            ],
        )?;
        let m = self.max_depth;
        let bounces = match which {
            Which::Normals => return Ok(IntegratorKind::Normals),
            Which::Direct => 0..=m.min(1),
            Which::Indirect => 2..=m,
            Which::Path if !self.accumulate => m..=m,
            Which::Path => 0..=m,
        };
        Ok(IntegratorKind::Path(PathSettings {
            bounces,
            lighting,
            light_samples: self.light_samples,
            roulette_from: self.roulette.then_some(3),
        }))
    }
}

/// `range` cut into `passes` consecutive parts whose lengths differ by at
/// most one. Local and distributed renders use this same split, so their
/// per-pixel sums are added in the same order.
pub fn split_samples(range: &Range<u32>, passes: u32) -> Vec<Range<u32>> {
    let n = range.end - range.start;
    (0..passes)
        .map(|k| {
            let at = |k: u32| range.start + (n as u64 * k as u64 / passes as u64) as u32;
            at(k)..at(k + 1)
        })
        .collect()
}
