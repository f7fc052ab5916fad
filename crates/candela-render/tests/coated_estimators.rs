//! Hemisphere, light and MIS estimators converge to the same image on a
//! Cornell box with rough plastic (both Mitsuba modes), a smooth conductor
//! and a rough conductor (`scenes/mitsuba/cornell-coated.xml`, the scene
//! also compared with Mitsuba 3 in `mitsuba_reference.rs`): the glossy and
//! diffuse lobes of the rough plastic are sampled, evaluated and weighted
//! consistently (see `common/agreement.rs` for the block z-test).

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LoadOptions};
use common::agreement::{assert_estimators_agree, Agreement};
use std::path::PathBuf;

#[test]
fn estimators_agree_on_the_coated_cornell_box() {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mitsuba/cornell-coated.xml");
    let desc = load(&path, &LoadOptions::default())
        .expect("scene loads")
        .scene;
    let opts = SceneOptions {
        width: 64,
        height: 48,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("scene builds");
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
