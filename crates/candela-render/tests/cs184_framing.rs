//! The CS184 framing rule on the course's own files: at 480x360 the
//! Cornell boxes are seen from 4.80 units away with a 30.68 degree
//! horizontal field of view (the numbers the course's users know).

mod common;

use candela_render::camera::framing::{frame_scene, CameraMode};
use candela_scene::{load, LoadOptions};

#[test]
fn cbspheres_lambertian_at_480x360_matches_the_course_program() {
    let path = common::cs184("CBspheres_lambertian.dae");
    let desc = load(&path, &LoadOptions::default()).unwrap().scene;
    let camera = frame_scene(&desc, CameraMode::Cs184, 480, 360).unwrap();
    let (lo, hi) = desc.bounds().unwrap();
    let centre = (lo + hi) * 0.5;
    let distance = (camera.eye - centre).length();
    assert!((distance - 4.80).abs() < 0.005, "eye at {distance}");
    assert!(
        (camera.hfov_deg() - 30.68).abs() < 0.005,
        "hfov {}",
        camera.hfov_deg()
    );
    // The camera looks at the box centre, upright.
    assert!((camera.forward - (centre - camera.eye).normalize()).length() < 1e-5);
    assert!(camera.up.y > 0.99);
}

#[test]
fn file_camera_is_the_literal_collada_camera() {
    let path = common::cs184("CBspheres_lambertian.dae");
    let desc = load(&path, &LoadOptions::default()).unwrap().scene;
    let camera = frame_scene(&desc, CameraMode::File, 800, 600).unwrap();
    let expected_eye = desc.cameras[0]
        .world_from_camera
        .transform_point3(glam::Vec3::ZERO);
    assert!((camera.eye - expected_eye).length() < 1e-6);
    assert!((camera.vfov_deg() - desc.cameras[0].fov_deg().unwrap().1).abs() < 1e-3);
}
