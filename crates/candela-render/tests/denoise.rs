//! Denoising a render: Open Image Denoise, guided by the film's albedo and
//! normal, brings a noisy render of the demo Cornell box much closer to a
//! converged reference. Needs the library (`pip install pyoidn`); skips
//! with a printed reason without it, and fails instead when
//! `CANDELA_REQUIRE_OIDN=1` (CI sets it where it installed the library).

use candela_image::denoise::Oidn;
use candela_image::metrics::rel_mse;
use candela_render::camera::framing::CameraMode;
use candela_render::film::{denoise_film, Film};
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_testkit::optional_dependency;

fn demo_film(scene: &Scene, spp: u32, seed: u64) -> Film {
    let settings = RenderSettings {
        spp,
        seed,
        integrator: IntegratorSettings::path(5, LightingMode::Mis),
        threads: 2,
        ..Default::default()
    };
    render(scene, &settings, &|_| {}).expect("render runs").film
}

#[test]
fn denoising_a_noisy_render_brings_it_much_closer_to_the_reference() {
    let Some(oidn) = optional_dependency(Oidn::load(), "CANDELA_REQUIRE_OIDN") else {
        return;
    };
    let desc = candela_scene::demo_scene().scene;
    let opts = SceneOptions {
        width: 48,
        height: 36,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("the demo builds");
    // Independent seeds: the reference's own error (1/64 of the noisy
    // image's variance) is in both figures alike.
    let reference = demo_film(&scene, 256, 1).resolve();
    let noisy = demo_film(&scene, 4, 2);
    let denoised = denoise_film(&noisy, oidn).expect("OIDN runs");
    let before = rel_mse(&noisy.resolve(), &reference).unwrap();
    let after = rel_mse(&denoised, &reference).unwrap();
    eprintln!("relMSE against 256 spp: 4 spp {before:.5}, denoised {after:.5}");
    // Returning the input unchanged gives `before`; a black image gives
    // about 1 per lit pixel; a blur that loses the walls' and spheres'
    // edges cannot reach a third. (OIDN 2.5: 0.124 before, 0.0164 after.)
    assert!(after < before / 3.0, "before {before}, after {after}");
}
