//! What a finished render writes into its EXR header.

use super::{RenderOutput, RenderSettings};
use crate::integrator::IntegratorSettings;
use candela_image::RenderInfo;
use std::path::Path;

impl RenderOutput {
    /// The header metadata of this render of `settings` ([`RenderInfo`]):
    /// render time, seed, sample range, integrator, scene file name and the
    /// program; the sample spread is left to the film writer, which reads
    /// it from the film.
    pub fn info(&self, settings: &RenderSettings, scene: Option<&Path>) -> RenderInfo {
        RenderInfo {
            spp: None,
            time_seconds: Some(self.stats.render_time.as_secs_f64()),
            seed: Some(settings.seed.to_string()),
            sample_range: Some(settings.samples()),
            integrator: Some(integrator_name(&settings.integrator)),
            scene: Some(
                scene
                    .and_then(Path::file_name)
                    .map_or("demo".into(), |n| n.to_string_lossy().into_owned()),
            ),
            software: Some(RenderInfo::candela_software()),
        }
    }
}

/// `path (mis)`, `direct (hemisphere)`, `normals`: the estimator and, where
/// it gathers light, the lighting mode, in the settings' own spellings.
pub fn integrator_name(integrator: &IntegratorSettings) -> String {
    let estimator = format!("{:?}", integrator.estimator).to_lowercase();
    if estimator == "normals" {
        return estimator;
    }
    format!(
        "{estimator} ({})",
        format!("{:?}", integrator.lighting).to_lowercase()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{Estimator, LightingMode};

    #[test]
    fn integrator_names_use_the_settings_spellings() {
        let mut s = IntegratorSettings::default();
        assert_eq!(integrator_name(&s), "path (mis)");
        s.lighting = LightingMode::Hemisphere;
        s.estimator = Estimator::Direct;
        assert_eq!(integrator_name(&s), "direct (hemisphere)");
        s.estimator = Estimator::Normals;
        assert_eq!(integrator_name(&s), "normals");
    }
}
