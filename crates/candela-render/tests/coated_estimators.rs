//! Hemisphere, light and MIS estimators converge to the same image on a
//! Cornell box with rough plastic (both Mitsuba modes), a smooth conductor
//! and a rough conductor (`scenes/mitsuba/cornell-coated.xml`, the scene
//! also compared with Mitsuba 3 in `mitsuba_reference.rs`): the glossy and
//! diffuse lobes of the rough plastic are sampled, evaluated and weighted
//! consistently (see `common/agreement.rs` for the block z-test). The same
//! holds on the box with a rough glass sphere (Walter et al.'s rough
//! dielectric, Beckmann α = 0.2), a smooth glass sphere and a rough gold
//! sphere (`scenes/mitsuba/cornell-materials.xml`).

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LoadOptions};
use common::agreement::{assert_estimators_agree, Agreement};
use std::path::PathBuf;

/// The project's Mitsuba scene `name` at 64x48 through its own camera.
fn mitsuba_scene(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/mitsuba")
        .join(name);
    let desc = load(&path, &LoadOptions::default())
        .expect("scene loads")
        .scene;
    let opts = SceneOptions {
        width: 64,
        height: 48,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    Scene::build(&desc, &opts).expect("scene builds")
}

#[test]
fn estimators_agree_on_the_coated_cornell_box() {
    let scene = mitsuba_scene("cornell-coated.xml");
    // Hemisphere sampling finds the small lamp rarely: more samples.
    assert_estimators_agree(
        &scene,
        &Agreement {
            label: "cornell-coated -m 3",
            max_bounces: 3,
            spp: [64, 16, 16],
            roulette_from: Some(3),
            seed_base: 14,
        },
    );
}

#[test]
fn estimators_agree_on_the_rough_glass_cornell_box() {
    let scene = mitsuba_scene("cornell-materials.xml");
    assert_estimators_agree(
        &scene,
        &Agreement {
            label: "cornell-materials (rough glass) -m 4",
            max_bounces: 4,
            spp: [64, 16, 16],
            roulette_from: Some(3),
            seed_base: 15,
        },
    );
}
