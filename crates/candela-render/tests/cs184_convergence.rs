//! Independent estimators converge to the same image on the CS184 scenes:
//! uniform hemisphere sampling, light sampling and MIS differ only in
//! noise (the task's "hemisphere vs light sampling" comparison, made a
//! statistical test; see `common/agreement.rs`).

mod common;

use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LoadOptions};
use common::agreement::{assert_estimators_agree, Agreement};

fn estimators_agree(file: &str, max_bounces: u32, spp: [u32; 3]) {
    let path = common::cs184(file);
    let desc = load(&path, &LoadOptions::default())
        .expect("scene loads")
        .scene;
    let opts = SceneOptions {
        width: 64,
        height: 48,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("scene builds");
    let label = format!("{file} -m {max_bounces}");
    assert_estimators_agree(
        &scene,
        &Agreement {
            label: &label,
            max_bounces,
            spp,
            roulette_from: Some(3),
            seed_base: 0,
        },
    );
}

#[test]
fn direct_lighting_estimators_agree_on_cbspheres() {
    // Hemisphere sampling finds the small lamp rarely: give it more samples.
    estimators_agree("CBspheres_lambertian.dae", 1, [64, 8, 8]);
}

#[test]
fn direct_lighting_estimators_agree_on_cbbunny() {
    estimators_agree("CBbunny.dae", 1, [64, 8, 8]);
}

#[test]
fn global_illumination_estimators_agree_on_cbspheres() {
    estimators_agree("CBspheres_lambertian.dae", 4, [64, 16, 16]);
}
