//! How many samples, which ones, and when to stop.

use super::{check, SettingsError};
use crate::film::Adaptive;
use crate::sampling::SamplerKind;
use serde::{Deserialize, Deserializer, Serialize};
use std::time::Duration;

/// Samples per pixel when neither `spp` nor a time budget is given.
pub const DEFAULT_SPP: u32 = 16;

/// What `adaptive` means (the CLI's `-a`, Python's `adaptive=`).
pub const ADAPTIVE_HELP: &str =
    "Adaptive sampling (CS184): every BATCH samples, stop a pixel once the \
    95% confidence interval of its mean illuminance is within TOL of the mean (the course uses \
    -a 64 0.05); also writes <name>_rate.png. In JSON: true (64, 0.05), a tolerance, \
    [batch, tolerance] or {batch, tolerance}.";

/// The sampling settings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[serde(default)]
pub struct SamplingSettings {
    /// Samples (camera paths) per pixel [default: 16, or no limit with a
    /// time budget]. With adaptive sampling, the most a pixel takes.
    #[cfg_attr(feature = "cli", arg(short = 's', long, value_name = "N"))]
    pub spp: Option<u32>,

    /// Seed of the sample sequence: the same seed gives the same image for
    /// any thread count and tiling.
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", default_value_t = SamplingSettings::default().seed))]
    pub seed: u64,

    /// Sample sequence: Owen-scrambled Sobol (lower noise) or independent
    /// random numbers.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = SamplingSettings::default().sampler))]
    pub sampler: SamplerKind,

    /// Adaptive sampling, or none: see [`ADAPTIVE_HELP`].
    #[serde(deserialize_with = "adaptive_spec")]
    #[cfg_attr(feature = "cli", arg(skip))]
    pub adaptive: Option<Adaptive>,

    /// Time budget in seconds: render in passes until it is spent (the last
    /// pass may overrun by about half a second), then stop.
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECONDS"))]
    pub time: Option<f64>,
}

impl SamplingSettings {
    /// Samples per pixel: `spp`, else 16, else (under a time budget) no limit.
    pub fn spp(&self) -> u32 {
        match (self.spp, self.time) {
            (Some(n), _) => n,
            (None, Some(_)) => u32::MAX,
            (None, None) => DEFAULT_SPP,
        }
    }

    /// The time budget, once validated.
    pub fn time_budget(&self) -> Option<Duration> {
        self.time.and_then(|s| Duration::try_from_secs_f64(s).ok())
    }

    pub(super) fn validate(&self) -> Result<(), SettingsError> {
        if let Some(spp) = self.spp {
            check(spp >= 1, "spp", "-s", spp, "at least one sample per pixel")?;
        }
        if let Some(a) = self.adaptive {
            check(
                a.batch >= 1 && a.tolerance.is_finite() && a.tolerance >= 0.0,
                "adaptive",
                "-a",
                format_args!("{} {}", a.batch, a.tolerance),
                "BATCH must be a whole number >= 1 and TOL a number >= 0",
            )?;
        }
        if let Some(t) = self.time {
            let ok = Duration::try_from_secs_f64(t).is_ok_and(|d| !d.is_zero());
            check(ok, "time", "--time", t, "a positive number of seconds")?;
        }
        Ok(())
    }
}

/// The ways a front end may ask for adaptive sampling.
#[derive(Deserialize)]
#[serde(untagged)]
enum AdaptiveSpec {
    On(bool),
    Tolerance(f64),
    Pair(f64, f64),
    Full { batch: f64, tolerance: f64 },
}

/// `adaptive`: null/false (off), true (CS184's 64, 0.05), a tolerance,
/// `[batch, tolerance]` or `{batch, tolerance}`. A batch that is not a
/// whole number >= 1 becomes 0, which validation refuses by name.
fn adaptive_spec<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Adaptive>, D::Error> {
    let whole = |b: f64| {
        if b.fract() == 0.0 && (1.0..=u32::MAX as f64).contains(&b) {
            b as u32
        } else {
            0
        }
    };
    Ok(match Option::<AdaptiveSpec>::deserialize(d)? {
        None | Some(AdaptiveSpec::On(false)) => None,
        Some(AdaptiveSpec::On(true)) => Some(Adaptive::default()),
        Some(AdaptiveSpec::Tolerance(tolerance)) => Some(Adaptive {
            tolerance,
            ..Adaptive::default()
        }),
        Some(AdaptiveSpec::Pair(batch, tolerance))
        | Some(AdaptiveSpec::Full { batch, tolerance }) => Some(Adaptive {
            batch: whole(batch),
            tolerance,
        }),
    })
}
