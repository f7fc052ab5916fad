//! Built render scenes, kept between connections.
//!
//! Each connection's worker owns the [`Scene`] it renders (it moves the
//! camera between renders). Building one (BVH, lights, textures) costs as
//! much as a coarse frame or more, so a scene is not built per tab: the
//! studio builds the starting scene once, a worker takes a spare scene of
//! the same build settings when it needs one, and a worker that ends (tab
//! closed or reloaded) or switches to other build settings gives its scene
//! back. At most [`SPARE_SCENES`] are kept (a scene can be large).

use crate::worker::Source;
use candela_render::scene::Scene;
use candela_render::settings::Settings;
use serde_json::Value;
use std::sync::Mutex;

/// Most spare scenes kept.
pub const SPARE_SCENES: usize = 2;

/// The settings a scene build reads besides the camera: scenes built with
/// the same key render the same, whatever their camera.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildKey(Value);

impl BuildKey {
    /// The key of `settings`.
    pub fn of(s: &Settings) -> Self {
        let j = s.to_json();
        let keys = ["bvh", "env_map", "env_scale", "env_rotate", "threads"];
        BuildKey(
            keys.iter()
                .map(|k| j.get(*k).cloned().unwrap_or_default())
                .collect(),
        )
    }
}

/// Spare scenes with their build keys, newest last.
#[derive(Default)]
pub struct ScenePool {
    spare: Mutex<Vec<(Scene, BuildKey)>>,
}

impl ScenePool {
    /// Keeps `scene`, dropping the oldest spare beyond [`SPARE_SCENES`].
    pub fn give(&self, scene: Scene, key: BuildKey) {
        let mut spare = self.spare.lock().unwrap_or_else(|e| e.into_inner());
        spare.push((scene, key));
        if spare.len() > SPARE_SCENES {
            spare.remove(0);
        }
    }

    /// A spare scene built with `key`, if there is one.
    pub fn take(&self, key: &BuildKey) -> Option<Scene> {
        let mut spare = self.spare.lock().unwrap_or_else(|e| e.into_inner());
        let i = spare.iter().rposition(|(_, k)| k == key)?;
        Some(spare.remove(i).0)
    }

    /// Spare scenes kept now.
    pub fn len(&self) -> usize {
        self.spare.lock().unwrap_or_else(|e| e.into_inner()).len()
    }

    /// Whether no scene is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Builds the scene `settings` read from `source`'s description.
pub fn build_scene(source: &Source, settings: &Settings) -> Result<Scene, String> {
    let desc = &source.loaded.scene;
    let opts = settings.scene_options().map_err(|e| e.to_string())?;
    settings
        .with_threads(|| Scene::build(desc, &opts))
        .map_err(|e| e.to_string())?
        .map_err(|e| format!("cannot render {}: {e}", desc.source.display()))
}

/// The scene for `settings` in `slot`, its camera set: the one there if
/// built with the same key, else a spare one, else a new one (the one
/// there goes back to the pool).
pub fn scene_for<'a>(
    slot: &'a mut Option<(Scene, BuildKey)>,
    source: &Source,
    settings: &Settings,
) -> Result<&'a mut Scene, String> {
    let key = BuildKey::of(settings);
    let mut scene = match slot.take() {
        Some((scene, built)) if built == key => scene,
        other => {
            if let Some((scene, built)) = other {
                source.scenes.give(scene, built);
            }
            match source.scenes.take(&key) {
                Some(scene) => scene,
                None => build_scene(source, settings)?,
            }
        }
    };
    scene.camera = Scene::camera_for(&source.loaded.scene, &settings.camera_options())
        .map_err(|e| e.to_string())?;
    *slot = Some((scene, key));
    Ok(&mut slot.as_mut().expect("the scene was just set").0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{json, Map};

    fn source() -> Source {
        Source {
            loaded: candela_scene::demo_scene(),
            path: None,
            out_dir: std::env::temp_dir(),
            base: Map::new(),
            scenes: ScenePool::default(),
        }
    }

    fn settings(changes: Value) -> Settings {
        let changes: Map<String, Value> = serde_json::from_value(changes).unwrap();
        Settings::resolve(&candela_scene::demo_scene().hints, &changes).unwrap()
    }

    #[test]
    fn the_pool_gives_back_scenes_by_build_key_and_keeps_the_newest() {
        let source = source();
        let keys: Vec<_> = ["sah", "median", "none"]
            .iter()
            .map(|b| settings(json!({"bvh": b, "width": 8, "height": 6})))
            .collect();
        for s in &keys {
            source
                .scenes
                .give(build_scene(&source, s).unwrap(), BuildKey::of(s));
        }
        assert_eq!(source.scenes.len(), SPARE_SCENES);
        assert!(
            source.scenes.take(&BuildKey::of(&keys[0])).is_none(),
            "the oldest went"
        );
        assert!(source.scenes.take(&BuildKey::of(&keys[2])).is_some());
        assert!(
            source.scenes.take(&BuildKey::of(&keys[2])).is_none(),
            "taken once"
        );
        // The camera does not change the key.
        let moved = settings(json!({"bvh": "median", "width": 8, "height": 6, "fov": 20}));
        assert_eq!(BuildKey::of(&moved), BuildKey::of(&keys[1]));
    }

    #[test]
    fn a_slot_with_other_build_settings_goes_back_to_the_pool() {
        let source = source();
        let sah = settings(json!({"width": 8, "height": 6}));
        let median = settings(json!({"bvh": "median", "width": 8, "height": 6}));
        let mut slot = None;
        scene_for(&mut slot, &source, &sah).unwrap();
        assert!(source.scenes.is_empty());
        scene_for(&mut slot, &source, &median).unwrap();
        assert_eq!(source.scenes.len(), 1, "the SAH scene is spare");
        scene_for(&mut slot, &source, &sah).unwrap();
        assert_eq!(
            source.scenes.len(),
            1,
            "the SAH scene back, the median one spare"
        );
        assert_eq!(slot.as_ref().unwrap().1, BuildKey::of(&sah));
    }
}
