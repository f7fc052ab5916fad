//! How the film becomes a displayable picture.

use super::{check, SettingsError};
use candela_image::{ExrCompression, ToneCurve, ToneMap};
use serde::{Deserialize, Serialize};

/// The output settings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[serde(default)]
pub struct OutputSettings {
    /// PNG exposure in stops: radiance is scaled by 2^STOPS before the tone
    /// curve.
    #[cfg_attr(feature = "cli", arg(long, value_name = "STOPS", default_value_t = OutputSettings::default().exposure, allow_negative_numbers = true))]
    pub exposure: f32,

    /// PNG tone curve.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = OutputSettings::default().tone))]
    pub tone: ToneCurve,

    /// Also write a denoised image beside the output (`out.denoised.png`),
    /// filtered by Intel Open Image Denoise with the albedo and normal
    /// layers as guides; the raw image is written as always. Needs the
    /// library: `pip install pyoidn` (or CANDELA_OIDN_LIB=path).
    /// `--denoise` alone is `--denoise=true`.
    #[cfg_attr(feature = "cli", arg(long, value_name = "BOOL", num_args = 0..=1,
        require_equals = true, default_missing_value = "true", action = clap::ArgAction::Set,
        value_parser = clap::builder::BoolishValueParser::new(),
        default_value_t = OutputSettings::default().denoise))]
    pub denoise: bool,

    /// How EXR files are compressed (lossless in every case); `none` writes
    /// fastest, `zip` smallest.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = OutputSettings::default().exr_compression))]
    pub exr_compression: ExrCompression,
}

impl OutputSettings {
    /// The tone map for 8-bit output.
    pub fn tone_map(&self) -> ToneMap {
        ToneMap {
            exposure: self.exposure,
            curve: self.tone,
        }
    }

    pub(super) fn validate(&self) -> Result<(), SettingsError> {
        check(
            self.exposure.is_finite(),
            "exposure",
            "--exposure",
            self.exposure,
            "a finite number of stops",
        )
    }
}
