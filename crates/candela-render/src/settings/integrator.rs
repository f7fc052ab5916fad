//! What each camera sample computes: the estimator and its options.

use super::{check, SettingsError};
use crate::integrator::{BidirSettings, LightingMode, PathSettings};
use crate::light::LightSelection;
use serde::{Deserialize, Serialize};
use std::ops::RangeInclusive;

/// The estimator behind each pixel (`--integrator`, or the CS184 flags
/// `--normals`, `--direct-only`, `--indirect-only`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Estimator {
    /// Path tracing: all light up to the maximum depth.
    #[default]
    Path,
    /// Shading normals as colours (n * 0.5 + 0.5): the CS184 Part 1 view.
    Normals,
    /// Light that reached the camera after at most one bounce.
    Direct,
    /// Light that reached the camera after two or more bounces.
    Indirect,
    /// Light tracing: particles from the lights joined to the camera (all
    /// light arrives as splats; surfaces seen only through mirrors or glass
    /// stay black). `-m` counts bounces as for path tracing.
    Light,
    /// Bidirectional path tracing with MIS over every (s, t) strategy
    /// (Veach 1997). `-m` counts bounces as for path tracing.
    Bdpt,
}

/// Bounce count from which Russian roulette may end a path.
pub const ROULETTE_FROM: u32 = 3;

/// The path tracer's Russian roulette leaves a path alone while its
/// throughput (largest channel, times the η² of its refractions) is at
/// least this; below it, the path survives with probability throughput /
/// threshold (the "threshold" form of roulette). Survival = throughput, as
/// in pbrt-v4 and Mitsuba 3 (a threshold of 1), ends paths four times as
/// eagerly: on the CS184 boxes at unlimited depth with the Sobol sampler
/// that cost more noise than the shorter paths saved (relMSE at 64 spp
/// 1.7x higher for 15% fewer rays; thresholds 1, 0.5, 0.25 and 0.125 were
/// measured, see BENCHMARKS.md, "Russian roulette by threshold").
pub const ROULETTE_THRESHOLD: f32 = 0.25;

/// The integrator's settings, as every front end names them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[serde(default)]
pub struct IntegratorSettings {
    /// Estimator: path tracing, light tracing, bidirectional path tracing,
    /// or a CS184 view (normals, direct or indirect light only).
    #[serde(rename = "integrator")]
    #[cfg_attr(feature = "cli", arg(id = "integrator", long = "integrator", value_enum, default_value_t = IntegratorSettings::default().estimator))]
    pub estimator: Estimator,

    /// How direct light is gathered at each vertex: multiple importance
    /// sampling of lights and BSDF, light sampling only, or CS184's
    /// uniform hemisphere rays (`-H`).
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = IntegratorSettings::default().lighting))]
    pub lighting: LightingMode,

    /// Maximum number of bounces: 0 emitters seen directly, 1 direct
    /// lighting, 2 one indirect bounce, ...
    #[cfg_attr(feature = "cli", arg(short = 'm', long, value_name = "N", default_value_t = IntegratorSettings::default().max_depth))]
    pub max_depth: u32,

    /// Light samples per area light at each path vertex (one per delta
    /// light); with `-H`, uniform hemisphere rays per vertex.
    #[cfg_attr(feature = "cli", arg(short = 'l', long, value_name = "N", default_value_t = IntegratorSettings::default().light_samples))]
    pub light_samples: u32,

    /// How each light sample chooses among the non-delta lights: uniformly,
    /// by power, or by the light tree (by what each light can contribute at
    /// the shading point: power, distance, orientation); auto takes the
    /// tree when the scene has more than 64 such lights, power otherwise.
    /// By power and by the tree, lights at infinity (skies, environment
    /// maps) as a group get at most n/(n + 1) of the choices when there
    /// are n of them and lights in the scene too. Path tracing only (light tracing and BDPT start paths by power).
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = IntegratorSettings::default().light_selection))]
    pub light_selection: LightSelection,

    /// 1: add the light of every bounce up to the maximum depth; 0: only
    /// light after exactly that many bounces (CS184 `-o`).
    #[cfg_attr(feature = "cli", arg(short = 'o', long, value_name = "0|1", action = clap::ArgAction::Set,
        value_parser = clap::builder::BoolishValueParser::new(),
        default_value_t = IntegratorSettings::default().accumulate))]
    pub accumulate: bool,

    /// Only the light that reaches the camera after exactly K bounces: 0
    /// emitters seen directly, 1 direct lighting at the first hit, 2 light
    /// after one indirect bounce, ... (with MIS, both strategies' shares of
    /// that path length). At most the maximum depth; path tracing only.
    /// The images of K = 0..=max_depth add up to the full render of the same
    /// seed, sample for sample (without `--clamp`, which is not additive).
    #[cfg_attr(feature = "cli", arg(long, value_name = "K"))]
    pub bounce: Option<u32>,

    /// Also write the light of each bounce count 0..=K as an EXR layer of
    /// its own, `bounce_0` ... `bounce_K`: layer k is the `--bounce k` image
    /// of the same seed, so a whole bounce series comes from one render.
    /// With K equal to the maximum depth the layers add up to the image. At
    /// most the maximum depth; path tracing adding every bounce only.
    #[cfg_attr(feature = "cli", arg(long, value_name = "K"))]
    pub bounce_layers: Option<u32>,

    /// With `--integrator bdpt`: write the contribution of every strategy
    /// (s light vertices, t camera vertices) as extra EXR layers `s{s}_t{t}`
    /// (MIS-weighted: they add up to the image) and `s{s}_t{t}_unweighted`
    /// (each strategy's own estimate of that path length: Veach's figure).
    #[cfg_attr(feature = "cli", arg(long))]
    pub technique_layers: bool,

    /// Russian roulette on the path throughput from the third bounce on;
    /// the path tracer ends only paths whose throughput fell below
    /// 0.25, `ROULETTE_THRESHOLD` (unbiased; `--no-roulette` is `--roulette false`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "BOOL", action = clap::ArgAction::Set,
        value_parser = clap::builder::BoolishValueParser::new(),
        default_value_t = IntegratorSettings::default().roulette))]
    pub roulette: bool,

    /// Hide emitters from the camera, as Mitsuba's `hide_emitters` does:
    /// camera rays pass through emitting surfaces to what is behind them,
    /// and the environment behind everything is black. Emitters still
    /// light the scene and show in mirrors and through glass. Path tracing
    /// only. `--hide-emitters` alone is `--hide-emitters=true` (the value
    /// needs the `=`, so that a scene path after the flag stays the scene).
    #[cfg_attr(feature = "cli", arg(long, value_name = "BOOL", action = clap::ArgAction::Set,
        num_args = 0..=1, require_equals = true, default_missing_value = "true",
        value_parser = clap::builder::BoolishValueParser::new(),
        default_value_t = IntegratorSettings::default().hide_emitters))]
    pub hide_emitters: bool,

    /// Largest radiance a camera sample may carry: brighter samples are
    /// scaled down to it, hue kept (pbrt's `maxcomponentvalue`). Removes
    /// fireflies at the cost of bias; off by default.
    #[cfg_attr(feature = "cli", arg(long, value_name = "RADIANCE"))]
    pub clamp: Option<f32>,
}

impl Default for IntegratorSettings {
    fn default() -> Self {
        Self {
            estimator: Estimator::Path,
            lighting: LightingMode::Mis,
            max_depth: 5,
            light_samples: 1,
            light_selection: LightSelection::Auto,
            accumulate: true,
            bounce: None,
            bounce_layers: None,
            technique_layers: false,
            roulette: true,
            hide_emitters: false,
            clamp: None,
        }
    }
}

impl IntegratorSettings {
    /// Path tracing with these options and everything else at its default.
    pub fn path(max_depth: u32, lighting: LightingMode) -> Self {
        Self {
            max_depth,
            lighting,
            ..Self::default()
        }
    }

    /// Bounce counts whose light reaches the image.
    pub fn bounces(&self) -> RangeInclusive<u32> {
        let m = self.max_depth;
        let range = match (self.bounce, self.estimator) {
            (Some(k), _) => k..=k,
            (None, Estimator::Direct) => 0..=m.min(1),
            (None, Estimator::Indirect) => 2..=m,
            (None, Estimator::Path | Estimator::Normals) if !self.accumulate => m..=m,
            (None, Estimator::Path | Estimator::Normals | Estimator::Light | Estimator::Bdpt) => {
                0..=m
            }
        };
        (*range.start()).max(self.first_bounce())..=*range.end()
    }

    /// The fewest bounces a path's light may have to reach the image: 1
    /// when emitters are hidden from the camera, else 0.
    pub fn first_bounce(&self) -> u32 {
        u32::from(self.hide_emitters)
    }

    /// The bidirectional estimators' options (light tracing, BDPT).
    pub fn bidir_settings(&self) -> BidirSettings {
        BidirSettings {
            max_depth: self.max_depth,
            roulette_from: self.roulette.then_some(ROULETTE_FROM),
            technique_layers: self.technique_layers,
        }
    }

    /// The path tracer's options, or `None` for the normals view.
    pub fn path_settings(&self) -> Option<PathSettings> {
        (self.estimator != Estimator::Normals).then(|| PathSettings {
            bounces: self.bounces(),
            lighting: self.lighting,
            light_samples: self.light_samples,
            roulette_from: self.roulette.then_some(ROULETTE_FROM),
            light_selection: self.light_selection,
            hide_emitters: self.hide_emitters,
        })
    }

    pub(super) fn validate(&self) -> Result<(), SettingsError> {
        let bounce_options = [
            ("bounce", "--bounce", self.bounce),
            ("bounce_layers", "--bounce-layers", self.bounce_layers),
        ];
        for (key, flag, k) in bounce_options {
            let Some(k) = k else { continue };
            check(
                k <= self.max_depth,
                key,
                flag,
                k,
                format_args!("at most the maximum depth (-m {})", self.max_depth),
            )?;
            // The CS184 views choose their own bounce counts.
            let view = match (self.estimator, self.accumulate) {
                (Estimator::Path, true) => None,
                (Estimator::Path, false) => Some("-o 0"),
                (Estimator::Normals, _) => Some("--integrator normals"),
                (Estimator::Direct, _) => Some("--integrator direct"),
                (Estimator::Indirect, _) => Some("--integrator indirect"),
                (Estimator::Light, _) => Some("--integrator light"),
                (Estimator::Bdpt, _) => Some("--integrator bdpt"),
            };
            if let Some(view) = view {
                check(
                    false,
                    key,
                    flag,
                    k,
                    format_args!("only with the path integrator adding every bounce, not {view}"),
                )?;
            }
        }
        if matches!(self.estimator, Estimator::Light | Estimator::Bdpt) {
            check(
                !self.hide_emitters,
                "hide_emitters",
                "--hide-emitters",
                true,
                "only with the path tracer (a scene may ask for it: --hide-emitters=false)",
            )?;
            check(
                self.accumulate,
                "accumulate",
                "-o",
                0,
                "1 with light tracing and BDPT (they add every bounce)",
            )?;
        }
        check(
            !self.technique_layers || self.estimator == Estimator::Bdpt,
            "technique_layers",
            "--technique-layers",
            true,
            "only with --integrator bdpt",
        )?;
        if let (Some(k), Some(layers)) = (self.bounce, self.bounce_layers) {
            check(
                false,
                "bounce_layers",
                "--bounce-layers",
                layers,
                format_args!("not with --bounce {k}, which keeps one bounce count only"),
            )?;
        }
        if let Some(k) = self.bounce {
            check(
                k >= self.first_bounce(),
                "bounce",
                "--bounce",
                k,
                "at least 1 with --hide-emitters (bounce 0 is the emitters it hides)",
            )?;
        }
        if let Some(c) = self.clamp {
            let ok = c.is_finite() && c > 0.0;
            check(ok, "clamp", "--clamp", c, "a radiance > 0")?;
        }
        check(
            self.light_samples >= 1,
            "light_samples",
            "-l",
            self.light_samples,
            "at least one light sample per vertex",
        )
    }
}
