//! Whether a checkpoint belongs to a render: the same scene content and the
//! same settings wherever they change the film's sums.

use super::{Checkpoint, ContentHash};
use crate::settings::Settings;

/// Settings that never change the film's sums: how the work runs, when it
/// stops (a time budget) and how the film becomes a PNG. A checkpoint may be
/// continued with other values of these.
pub const FREE_SETTINGS: &[&str] = &[
    "threads",
    "tile",
    "bvh",
    "memory_limit",
    "checkpoint",
    "checkpoint_every",
    "time",
    "exposure",
    "tone",
];

/// The sample target: a pixel's samples depend only on their indices (not
/// on how many follow), so a checkpoint is the start of any render with a
/// target at least its own, and may be continued to more samples per pixel.
const RAISABLE: &str = "spp";

/// Whether `here` continues `there` for setting `key`: equal, or the sample
/// target raised.
fn continues(key: &str, there: Option<&serde_json::Value>, here: &serde_json::Value) -> bool {
    if there == Some(here) {
        return true;
    }
    key == RAISABLE
        && matches!((there.and_then(|v| v.as_u64()), here.as_u64()), (Some(a), Some(b)) if b >= a)
}

/// Why a checkpoint is not of this render: one line naming what differs.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct Mismatch(String);

impl Checkpoint {
    /// Checks that this checkpoint is of the scene whose content hash is
    /// `scene` rendered with `settings` (or with a lower sample target); the
    /// error names the first difference (settings by their key, the value
    /// there and here).
    pub fn check_matches(&self, scene: ContentHash, settings: &Settings) -> Result<(), Mismatch> {
        let (there, here) = (self.settings.to_json(), settings.to_json());
        let differ: Vec<String> = here
            .iter()
            .filter(|(key, _)| !FREE_SETTINGS.contains(&key.as_str()))
            .filter(|(key, value)| !continues(key, there.get(*key), value))
            .map(|(key, value)| {
                let was = there.get(key).map_or("unset".into(), |v| v.to_string());
                let why = if key.as_str() == RAISABLE {
                    " (a checkpoint continues to more samples per pixel, not fewer)"
                } else {
                    ""
                };
                format!("{key} = {was} in the checkpoint, {value} here{why}")
            })
            .collect();
        if !differ.is_empty() {
            return Err(Mismatch(format!(
                "the checkpoint is of a render with other settings: {}",
                differ.join(", ")
            )));
        }
        if scene != self.scene_hash {
            return Err(Mismatch(
                "the checkpoint is of another scene: the scene's content (geometry, materials, \
                 textures, lights or cameras) changed since it was written"
                    .into(),
            ));
        }
        Ok(())
    }
}
