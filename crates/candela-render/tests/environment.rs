//! Environment lighting converges to the same image with light sampling,
//! BSDF sampling and MIS: a diffuse sphere on a diffuse plane under the
//! procedural sky (gradient, ground, sun disk), compared block by block
//! over independent batches (`candela_image::metrics::ztest`), as in
//! `cs184_convergence.rs`.

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::light::{EnvironmentMap, EnvironmentOptions, ProceduralSky};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{BsdfDesc, MeshDesc, SceneDesc, SourceLoc, SphereDesc};
use common::agreement::{assert_estimators_agree, Agreement};
use glam::{Mat4, Vec3};
use std::sync::Arc;

/// A unit sphere resting on a 20 × 20 plane at y = 0, seen from the front
/// and a little above.
fn sphere_on_plane() -> SceneDesc {
    let s = 10.0;
    let plane = MeshDesc {
        name: "ground".into(),
        positions: vec![
            Vec3::new(-s, 0.0, -s),
            Vec3::new(s, 0.0, -s),
            Vec3::new(s, 0.0, s),
            Vec3::new(-s, 0.0, s),
        ],
        triangles: vec![[0, 2, 1], [0, 3, 2]],
        material: 0,
        ..Default::default()
    };
    let mut camera = common::camera_at(Vec3::ZERO);
    // From (0, 2, 5), pitched down toward the ball's middle.
    let pitch = -(1.3f32 / 5.0).atan();
    camera.world_from_camera =
        Mat4::from_translation(Vec3::new(0.0, 2.0, 5.0)) * Mat4::from_rotation_x(pitch);
    SceneDesc {
        source: "sphere under the sky".into(),
        cameras: vec![camera],
        meshes: vec![plane],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        spheres: vec![SphereDesc {
            name: "ball".into(),
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 1.0,
            material: 1,
            loc: SourceLoc::default(),
        }],
        materials: vec![
            common::material(
                "ground",
                BsdfDesc::Diffuse {
                    albedo: Vec3::splat(0.5),
                },
                None,
            ),
            common::material(
                "ball",
                BsdfDesc::Diffuse {
                    albedo: Vec3::new(0.8, 0.4, 0.2),
                },
                None,
            ),
        ],
        ..Default::default()
    }
}

fn sky() -> Arc<EnvironmentMap> {
    // A sun wide enough (10°) for uniform hemisphere sampling to find it
    // often enough for normal statistics at a few dozen samples per pixel.
    let sky = ProceduralSky {
        sun_radius_deg: 10.0,
        sun: Vec3::new(12.0, 11.0, 9.0),
        ..Default::default()
    };
    let image = sky.image(128, 64).expect("sky image");
    Arc::new(EnvironmentMap::from_image(&image, &EnvironmentOptions::default()).expect("map"))
}

#[test]
fn environment_lighting_estimators_agree() {
    let opts = SceneOptions {
        width: 48,
        height: 32,
        camera_mode: CameraMode::File,
        environment: Some(sky()),
        ..Default::default()
    };
    let scene = Scene::build(&sphere_on_plane(), &opts).expect("scene builds");
    assert_eq!(scene.lights.lights().len(), 1, "the sky is the only light");
    assert_estimators_agree(
        &scene,
        &Agreement {
            label: "environment",
            max_bounces: 2,
            spp: [48, 8, 8],
            roulette_from: None,
            seed_base: 7000,
        },
    );
}
