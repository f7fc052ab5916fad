//! The path inspector: re-traces chosen camera samples of one pixel and
//! records every step of their paths, for the viewer's table and 3D lines.
//!
//! It cannot drift from the renderer because it *is* the renderer: it calls
//! [`super::pixel_sample`], the function the render loop calls, with a
//! [`Recording`] in the [`PathRecorder`] seam instead of `()`. Samples are a
//! pure function of (seed, pixel, sample index, dimension), so sample `i`
//! traced here is sample `i` of the render with the same settings.
//!
//! Each [`PathRecord`] lists its vertices (surface, material, throughput,
//! light samples with their MIS weights and shadow-ray results, the BSDF
//! sample that continued the path, Russian roulette), its contributions
//! (which bounce count, which strategy, how much), their sum and the value
//! the film adds for the sample. Vectors are `[x, y, z]` in world space;
//! non-finite numbers serialise as JSON `null`.

mod recording;
mod records;

pub use records::{
    Contribution, EmissionRecord, EscapeRecord, HemisphereRecord, LightSampleRecord, PathRecord,
    RayRecord, RouletteRecord, ScatterRecord, Strategy, VertexRecord, V3,
};

use super::{pixel_sample, Estimator, ThreadContext};
use crate::render::RenderSettings;
use crate::sampling::Sampler;
use crate::scene::Scene;
use glam::Vec3;
use recording::Recording;
use std::ops::Range;

/// Most samples one call traces (each record holds a whole path).
pub const MAX_TRACED_SAMPLES: u32 = 4096;

/// Why paths cannot be traced.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InspectError {
    /// The pixel lies outside the image.
    #[error("pixel ({x}, {y}) lies outside the {width}x{height} image")]
    Pixel {
        /// Column asked for.
        x: u32,
        /// Row asked for.
        y: u32,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// The sample range is empty or too long.
    #[error("sample range {start}..{end}: expected 1 to {MAX_TRACED_SAMPLES} samples")]
    Samples {
        /// First index.
        start: u32,
        /// One past the last index.
        end: u32,
    },
    /// The normals view traces no paths.
    #[error("the normals view traces no light paths; choose the path integrator")]
    Normals,
}

/// Traces samples `samples` of `pixel` exactly as [`crate::render::render`]
/// with `settings` takes them (same seed, sampler and integrator options;
/// the thread count, tiling and cell do not matter) and records their
/// paths. Adaptive sampling may stop a pixel before a given index; the
/// record shows what that sample would have added.
pub fn trace_paths(
    scene: &Scene,
    settings: &RenderSettings,
    pixel: (u32, u32),
    samples: Range<u32>,
) -> Result<Vec<PathRecord>, InspectError> {
    let (width, height) = (scene.camera.width, scene.camera.height);
    if pixel.0 >= width || pixel.1 >= height {
        return Err(InspectError::Pixel {
            x: pixel.0,
            y: pixel.1,
            width,
            height,
        });
    }
    if samples.is_empty() || samples.len() > MAX_TRACED_SAMPLES as usize {
        return Err(InspectError::Samples {
            start: samples.start,
            end: samples.end,
        });
    }
    if settings.integrator.estimator == Estimator::Normals {
        return Err(InspectError::Normals);
    }
    let mut sampler = Sampler::new(settings.sampler, settings.seed);
    let mut ctx = ThreadContext::default();
    Ok(samples
        .map(|index| {
            let mut rec = Recording::new(scene, pixel, index);
            let s = pixel_sample(
                &settings.integrator,
                scene,
                pixel,
                index,
                &mut sampler,
                &mut ctx,
                &mut rec,
            );
            // The film's rule (render/tile.rs): a non-finite sample counts
            // as black.
            let value = if s.radiance.is_finite() {
                s.radiance
            } else {
                Vec3::ZERO
            };
            rec.record.value = value.to_array();
            rec.record
        })
        .collect())
}
