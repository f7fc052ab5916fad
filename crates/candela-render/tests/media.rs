//! Participating media in the path tracer (`crate::medium`,
//! `integrator/medium.rs`), against closed forms:
//! - a furnace filled with a medium that scatters everything it extinguishes
//!   (albedo 1) keeps the furnace's radiance `le / (1 − a)` whatever the
//!   medium's density, colour or phase function: free-flight sampling,
//!   transmittance of shadow rays, light samples at medium points, phase
//!   sampling and their MIS weights must all agree for that to hold;
//! - a purely absorbing ball behind an invisible boundary dims what is seen
//!   through it by Beer–Lambert's `exp(−σ_t · chord)`, exactly.
//!
//! Statistical checks are z-tests at z = 4.5, as in `estimators.rs`.

mod common;

use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_scene::{
    BsdfDesc, MediumDesc, MediumInterface, Projection, SceneDesc, SourceLoc, SphereDesc,
};
use common::*;
use glam::Vec3;

const Z: f64 = 4.5;
const MODES: [LightingMode; 2] = [LightingMode::Light, LightingMode::Mis];

fn medium(sigma_t: Vec3, albedo: Vec3, g: f32) -> MediumDesc {
    MediumDesc {
        name: "fog".into(),
        sigma_t,
        albedo,
        phase_g: g,
        loc: SourceLoc::default(),
    }
}

/// `furnace(albedo, le)` (an inward icosphere of radius 1 whose walls
/// reflect `albedo` and emit `le`, the camera at its centre) filled with
/// `fog`: the walls' normals point in, so the medium is on their exterior.
fn foggy_furnace(albedo: f32, le: f32, fog: MediumDesc) -> SceneDesc {
    let mut desc = furnace(albedo, le);
    desc.media.push(fog);
    desc.medium_interfaces.push((
        0,
        MediumInterface {
            interior: None,
            exterior: Some(0),
        },
    ));
    desc.camera_medium = Some(0);
    desc
}

/// Adds an invisible ball of `radius` in front of the camera (centre
/// (0, 0, −0.5)) filled with `inside`.
fn with_fog_ball(desc: &mut SceneDesc, radius: f32, inside: MediumDesc) {
    desc.materials
        .push(material("boundary", BsdfDesc::Null, None));
    desc.spheres.push(SphereDesc {
        axes: SphereDesc::Y_POLE,
        name: "ball".into(),
        center: Vec3::new(0.0, 0.0, -0.5),
        radius,
        material: desc.materials.len() - 1,
        inward: false,
        loc: SourceLoc::default(),
    });
    desc.media.push(inside);
    desc.medium_interfaces.push((
        desc.materials.len() - 1,
        MediumInterface {
            interior: Some(desc.media.len() - 1),
            exterior: None,
        },
    ));
}

#[test]
fn a_furnace_full_of_lossless_fog_keeps_its_radiance() {
    let (albedo, le) = (0.5f64, 0.5f64);
    let fogs = [
        ("thin isotropic", Vec3::splat(0.3), 0.0),
        ("dense forward", Vec3::splat(4.0), 0.7),
        ("coloured backward", Vec3::new(0.5, 2.0, 6.0), -0.4),
    ];
    for (i, (name, sigma_t, g)) in fogs.into_iter().enumerate() {
        let desc = foggy_furnace(albedo as f32, le as f32, medium(sigma_t, Vec3::ONE, g));
        for (j, mode) in MODES.into_iter().enumerate() {
            let e = estimate(
                &desc,
                IntegratorSettings::path(100_000, mode),
                8,
                64,
                10 + (2 * i + j) as u64,
            );
            assert_converges(&format!("{name}, {mode:?}"), &e, le / (1.0 - albedo), Z);
        }
    }
}

#[test]
fn fog_inside_an_invisible_ball_in_a_clear_furnace_keeps_its_radiance() {
    // The medium only inside a null sphere around the camera's view: paths
    // cross its boundary both ways, light samples from inside and outside
    // go through it.
    let (albedo, le) = (0.6f64, 0.4f64);
    let mut desc = furnace(albedo as f32, le as f32);
    with_fog_ball(
        &mut desc,
        0.4,
        medium(Vec3::new(1.0, 3.0, 8.0), Vec3::ONE, 0.5),
    );
    for (j, mode) in MODES.into_iter().enumerate() {
        let e = estimate(
            &desc,
            IntegratorSettings::path(100_000, mode),
            8,
            64,
            30 + j as u64,
        );
        assert_converges(&format!("{mode:?}"), &e, le / (1.0 - albedo), Z);
    }
}

#[test]
fn an_absorbing_ball_dims_what_is_seen_through_it_by_beer_lambert() {
    // Black emitting walls (le), and an invisible ball of absorbing medium
    // (albedo 0) between them and the camera, which looks through its
    // centre with a 0.5° field: every camera ray crosses a chord of 2r (to
    // 1e-4) and reaches the wall, so the radiance is le·exp(−σ_t·2r). Free
    // flight samples it: a path passes with that probability (weight 1) or
    // is absorbed, so the estimate is a Bernoulli mean.
    let (le, r, sigma) = (0.8f32, 0.3f32, 1.7f32);
    let mut desc = furnace(0.0, le);
    let mut camera = camera_at(Vec3::ZERO);
    camera.projection = Projection::Perspective {
        xfov_deg: 0.5,
        yfov_deg: 0.5,
    };
    desc.cameras = vec![camera];
    with_fog_ball(&mut desc, r, medium(Vec3::splat(sigma), Vec3::ZERO, 0.0));
    let expected = f64::from(le * (-sigma * 2.0 * r).exp());
    for (j, mode) in MODES.into_iter().enumerate() {
        let e = estimate(
            &desc,
            IntegratorSettings::path(5, mode),
            4,
            1024,
            40 + j as u64,
        );
        assert_eq!(e.invalid, 0);
        assert_converges(&format!("{mode:?}"), &e, expected, Z);
    }
}

#[test]
fn integrators_that_ignore_media_say_so() {
    use candela_render::integrator::{media_ignored, Estimator};
    use candela_render::scene::{Scene, SceneOptions};
    let build = |desc: &SceneDesc| {
        let opts = SceneOptions {
            width: 4,
            height: 4,
            camera_mode: candela_render::camera::framing::CameraMode::File,
            ..Default::default()
        };
        Scene::build(desc, &opts).expect("test scene builds")
    };
    let foggy = build(&foggy_furnace(0.5, 0.5, medium(Vec3::ONE, Vec3::ONE, 0.0)));
    let clear = build(&furnace(0.5, 0.5));
    let path = IntegratorSettings::path(5, LightingMode::Mis);
    assert_eq!(media_ignored(&foggy, &path), None);
    assert_eq!(media_ignored(&clear, &path), None);
    for estimator in [Estimator::Bdpt, Estimator::Light] {
        let s = IntegratorSettings {
            estimator,
            ..path.clone()
        };
        assert!(media_ignored(&foggy, &s).is_some(), "{estimator:?}");
        assert_eq!(media_ignored(&clear, &s), None);
    }
    let hemisphere = IntegratorSettings::path(5, LightingMode::Hemisphere);
    assert!(media_ignored(&foggy, &hemisphere).unwrap().contains("-H"));
}
