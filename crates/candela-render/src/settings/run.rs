//! How the work runs: threads, tiles, the acceleration structure, the
//! memory a render may claim and its checkpoints. None of these changes the
//! image.

use super::{check, SettingsError};
use candela_bvh::BuildStrategy;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// BVH construction (`--bvh`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Bvh {
    /// Binned surface area heuristic.
    #[default]
    Sah,
    /// Split at the median centroid on the longest axis (the CS184 seed).
    Median,
    /// No hierarchy: test every primitive.
    None,
}

impl From<Bvh> for BuildStrategy {
    fn from(b: Bvh) -> Self {
        match b {
            Bvh::Sah => BuildStrategy::Sah,
            Bvh::Median => BuildStrategy::Median,
            Bvh::None => BuildStrategy::None,
        }
    }
}

/// Default edge of a render tile in pixels.
pub const DEFAULT_TILE: u32 = 16;
/// Default cap on the memory a render's film may claim, in GiB.
pub const DEFAULT_MEMORY_LIMIT_GIB: f64 = 16.0;
/// Default seconds between two checkpoints.
pub const DEFAULT_CHECKPOINT_EVERY: f64 = 60.0;

/// The execution settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[serde(default)]
pub struct RunSettings {
    /// Render threads, also used to build the BVH (0: all cores).
    #[cfg_attr(feature = "cli", arg(short = 't', long, value_name = "N", default_value_t = RunSettings::default().threads))]
    pub threads: usize,

    /// Tile edge in pixels (changes only speed, never the image).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", default_value_t = RunSettings::default().tile, hide = true))]
    pub tile: u32,

    /// BVH construction: surface area heuristic, median split, or none.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = RunSettings::default().bvh))]
    pub bvh: Bvh,

    /// Refuse renders whose film and images would need more than this many
    /// GiB of memory.
    #[cfg_attr(feature = "cli", arg(long, value_name = "GIB", default_value_t = RunSettings::default().memory_limit))]
    pub memory_limit: f64,

    /// Save the film to this checkpoint file (atomically) every
    /// `checkpoint_every` seconds between passes, on Ctrl-C and at the end;
    /// `candela resume PATH` continues it. If PATH already holds a
    /// checkpoint of the same scene and settings, the render continues from
    /// it; one of another render is refused.
    #[cfg_attr(feature = "cli", arg(long, value_name = "PATH"))]
    pub checkpoint: Option<PathBuf>,

    /// Seconds between two checkpoints (with `checkpoint`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECS", default_value_t = RunSettings::default().checkpoint_every))]
    pub checkpoint_every: f64,
}

impl Default for RunSettings {
    fn default() -> Self {
        Self {
            threads: 0,
            tile: DEFAULT_TILE,
            bvh: Bvh::Sah,
            memory_limit: DEFAULT_MEMORY_LIMIT_GIB,
            checkpoint: None,
            checkpoint_every: DEFAULT_CHECKPOINT_EVERY,
        }
    }
}

impl RunSettings {
    pub(super) fn validate(&self) -> Result<(), SettingsError> {
        check(
            self.tile >= 1,
            "tile",
            "--tile",
            self.tile,
            "at least 1 pixel",
        )?;
        let m = self.memory_limit;
        check(
            m.is_finite() && m > 0.0,
            "memory_limit",
            "--memory-limit",
            m,
            "a positive number of GiB",
        )?;
        let every = self.checkpoint_every;
        check(
            every.is_finite() && every >= 0.0,
            "checkpoint_every",
            "--checkpoint-every",
            every,
            "a number of seconds >= 0 (0: after every pass)",
        )
    }
}
