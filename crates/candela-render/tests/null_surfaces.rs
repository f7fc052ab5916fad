//! Invisible surfaces (Mitsuba's `null` BSDF): camera, bounce and shadow
//! rays pass straight through them, and one that emits is still seen, on
//! its front side only, in every lighting mode.
//!
//! Bounds are variance-derived as in `estimators.rs` (z = 4.5, fixed
//! seeds); the exact checks are of estimates with no variance.

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{BsdfDesc, EnvironmentDesc, SceneDesc, SourceLoc, SphereDesc};
use common::*;
use glam::Vec3;

const Z: f64 = 4.5;
const MODES: [LightingMode; 3] = [
    LightingMode::Hemisphere,
    LightingMode::Light,
    LightingMode::Mis,
];

/// A sphere of `material` at `center`, its normals outward.
fn sphere(center: Vec3, radius: f32, material: usize) -> SphereDesc {
    SphereDesc {
        axes: SphereDesc::Y_POLE,
        name: "null".into(),
        center,
        radius,
        material,
        inward: false,
        loc: SourceLoc::default(),
    }
}

/// The pixels of `desc` rendered from its file camera (`size`², `spp`).
fn pixels(desc: &SceneDesc, lighting: LightingMode, size: u32, spp: u32) -> Vec<Vec3> {
    let opts = SceneOptions {
        width: size,
        height: size,
        camera_mode: CameraMode::File,
        ..SceneOptions::default()
    };
    let scene = Scene::build(desc, &opts).unwrap();
    let settings = RenderSettings {
        spp,
        integrator: IntegratorSettings::path(8, lighting),
        ..Default::default()
    };
    let out = render(&scene, &settings, &|_| {}).unwrap();
    assert_eq!(out.stats.invalid_samples, 0);
    out.film
        .resolve()
        .pixels()
        .iter()
        .map(|p| Vec3::from(*p))
        .collect()
}

#[test]
fn an_invisible_sphere_hides_nothing_of_the_sky_behind_it() {
    // A constant sky seen through a null sphere filling the view: every
    // camera ray passes it (in, then out) and escapes.
    let sky = Vec3::new(0.25, 0.5, 1.0);
    let desc = SceneDesc {
        cameras: vec![camera_at(Vec3::new(0.0, 0.0, 3.0))],
        spheres: vec![sphere(Vec3::ZERO, 1.5, 0)],
        materials: vec![material("null", BsdfDesc::Null, None)],
        environment: Some(EnvironmentDesc::Constant { radiance: sky }),
        ..SceneDesc::default()
    };
    for mode in MODES {
        for p in pixels(&desc, mode, 8, 2) {
            assert!((p - sky).length() < 1e-5, "{mode:?}: {p}");
        }
    }
}

#[test]
fn an_invisible_emitter_is_seen_from_its_front_only() {
    // A null sphere emitting outward in an empty scene: from outside, its
    // near side faces the camera (radiance le inside its silhouette, 0
    // outside); from inside, only its back is seen, and nothing.
    let le = Vec3::new(2.0, 1.0, 0.5);
    let mut desc = SceneDesc {
        cameras: vec![camera_at(Vec3::new(0.0, 0.0, 3.0))],
        spheres: vec![sphere(Vec3::ZERO, 1.0, 0)],
        materials: vec![material("null lamp", BsdfDesc::Null, Some(le))],
        ..SceneDesc::default()
    };
    for mode in MODES {
        let image = pixels(&desc, mode, 16, 4);
        let lit = image.iter().filter(|p| (**p - le).length() < 1e-5).count();
        let dark = image.iter().filter(|p| **p == Vec3::ZERO).count();
        // Only pixels the silhouette's edge crosses are mixed.
        assert!(
            lit > 40 && lit + dark > 16 * 16 - 40,
            "{mode:?}: {lit} lit, {dark} dark"
        );
    }
    desc.cameras = vec![camera_at(Vec3::new(0.0, 0.0, 0.5))];
    for mode in MODES {
        for p in pixels(&desc, mode, 8, 2) {
            assert_eq!(p, Vec3::ZERO, "{mode:?} from inside");
        }
    }
}

#[test]
fn light_reaches_through_an_invisible_sphere_around_the_bulb() {
    // pbrt's analytic scene (radiance exactly 1 inside a unit sphere of
    // albedo 0.5 with a point light of intensity π at its centre), with a
    // null sphere around the light: shadow rays and bounces pass it.
    let mut desc = analytic_sphere();
    desc.materials.push(material("null", BsdfDesc::Null, None));
    desc.spheres.push(sphere(Vec3::ZERO, 0.2, 1));
    for mode in [LightingMode::Light, LightingMode::Mis] {
        let e = estimate(&desc, IntegratorSettings::path(100_000, mode), 16, 32, 41);
        assert_converges(&format!("{mode:?}"), &e, 1.0, Z);
    }
}

#[test]
fn an_invisible_emitter_lights_a_room_alike_in_every_lighting_mode() {
    // A one-sided white-ish room (inward sphere of albedo 0.5) lit by a
    // small null sphere emitting outward, seen from beside it: hemisphere
    // rays, light samples and MIS must agree, and the room is lit (light
    // samples' shadow rays and BSDF bounces both pass the lamp's surface).
    let mut desc = analytic_sphere();
    desc.lights.clear();
    desc.spheres[0].inward = true;
    desc.materials.push(material(
        "null lamp",
        BsdfDesc::Null,
        Some(Vec3::splat(4.0)),
    ));
    desc.spheres
        .push(sphere(Vec3::new(0.0, 0.3, -0.2), 0.25, 1));
    let settings = |mode| IntegratorSettings::path(3, mode);
    let reference = estimate(&desc, settings(LightingMode::Mis), 16, 64, 51);
    assert!(reference.mean > 0.1, "{}", reference.mean);
    for (i, mode) in [LightingMode::Hemisphere, LightingMode::Light]
        .into_iter()
        .enumerate()
    {
        let e = estimate(&desc, settings(mode), 16, 64, 52 + i as u64);
        let z = (e.mean - reference.mean).abs()
            / (e.std_error.powi(2) + reference.std_error.powi(2)).sqrt();
        eprintln!(
            "{mode:?}: {:.5} ± {:.5} vs MIS {:.5} ± {:.5}",
            e.mean, e.std_error, reference.mean, reference.std_error
        );
        assert!(z < Z, "{mode:?} differs from MIS by {z:.2} standard errors");
    }
}
