//! Emitters hidden from the camera (`--hide-emitters`, Mitsuba's
//! `hide_emitters`): camera rays pass through emitting surfaces and the sky
//! behind everything is black, while the emitters still light the scene.
//!
//! The statistical check is a z-test at z = 4.5 against a closed form, as
//! in `estimators.rs`; the exact checks are of estimates with no variance.

mod common;

use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::light::LightSelection;
use candela_scene::{
    BsdfDesc, EnvironmentDesc, InstanceDesc, Projection, SceneDesc, SourceLoc, SphereDesc,
};
use common::*;
use glam::Vec3;

const Z: f64 = 4.5;
const MODES: [LightingMode; 2] = [LightingMode::Light, LightingMode::Mis];

/// Path tracing to 16 bounces, lights chosen uniformly: by power, the
/// 1000-unit floor's sky (power ∝ the scene's radius²) would take nearly
/// every light sample from the small lamp, which light sampling alone
/// (`LightingMode::Light`) then almost never sees.
fn shown(lighting: LightingMode) -> IntegratorSettings {
    IntegratorSettings {
        light_selection: LightSelection::Uniform,
        ..IntegratorSettings::path(16, lighting)
    }
}

fn hidden(lighting: LightingMode) -> IntegratorSettings {
    IntegratorSettings {
        hide_emitters: true,
        ..shown(lighting)
    }
}

fn sphere(center: Vec3, radius: f32, material: usize) -> SphereDesc {
    SphereDesc {
        axes: SphereDesc::Y_POLE,
        name: "lamp".into(),
        center,
        radius,
        material,
        inward: false,
        loc: SourceLoc::default(),
    }
}

fn grey(name: &str, albedo: f32, emission: Option<f32>) -> candela_scene::MaterialDesc {
    let bsdf = BsdfDesc::Diffuse {
        albedo: Vec3::splat(albedo),
    };
    material(name, bsdf, emission.map(Vec3::splat))
}

fn sky(radiance: f32) -> Option<EnvironmentDesc> {
    Some(EnvironmentDesc::Constant {
        radiance: Vec3::splat(radiance),
    })
}

#[test]
fn a_hidden_lamp_filling_the_view_shows_the_hidden_sky_behind_it() {
    // An emitting grey ball around which only the sky is seen: shown, every
    // sample sees the ball or the sky; hidden, camera rays pass the ball
    // and escape to a sky that is hidden too, so every sample is 0.
    let desc = SceneDesc {
        cameras: vec![camera_at(Vec3::new(0.0, 0.0, 3.0))],
        spheres: vec![sphere(Vec3::ZERO, 1.0, 0)],
        materials: vec![grey("lamp", 0.5, Some(2.0))],
        environment: sky(0.3),
        ..SceneDesc::default()
    };
    for mode in MODES {
        let shown = estimate(&desc, shown(mode), 8, 4, 1);
        assert!(shown.mean > 0.3, "{mode:?}: shown {}", shown.mean);
        let e = estimate(&desc, hidden(mode), 8, 4, 1);
        assert_eq!((e.mean, e.invalid), (0.0, 0), "{mode:?}: hidden");
    }
}

#[test]
fn behind_a_hidden_lamp_is_the_surface_it_lights() {
    // A large diffuse floor (albedo rho) under a constant sky E, and a
    // black lamp ball of radiance le (radius r, centre d above the floor)
    // between it and the camera, which looks straight down at the point
    // under the ball through a 0.5° field. Hidden, the camera sees that
    // point, lit by the ball over a cosine-weighted share (r/d)² of its
    // hemisphere (a sphere on the normal) and by the sky over the rest:
    // L = rho (E (1 − (r/d)²) + le (r/d)²).
    let (rho, e_sky, le, r, d) = (0.6f32, 0.5f32, 3.0f32, 0.2f32, 0.5f32);
    let mut camera = camera_at(Vec3::new(0.0, 0.0, 3.0));
    camera.projection = Projection::Perspective {
        xfov_deg: 0.5,
        yfov_deg: 0.5,
    };
    let desc = SceneDesc {
        cameras: vec![camera],
        meshes: vec![square_z0("floor", 1000.0, 0)],
        instances: vec![InstanceDesc::identity(0, SourceLoc::default())],
        spheres: vec![sphere(Vec3::new(0.0, 0.0, d), r, 1)],
        materials: vec![
            grey("floor", rho, None),
            material("lamp", BsdfDesc::Black, Some(Vec3::splat(le))),
        ],
        environment: sky(e_sky),
        ..SceneDesc::default()
    };
    let share = (r / d).powi(2) as f64;
    let expected = rho as f64 * (e_sky as f64 * (1.0 - share) + le as f64 * share);
    for (mode, seed) in MODES.into_iter().zip([5, 6]) {
        let e = estimate(&desc, hidden(mode), 4, 4096, seed);
        assert_converges(&format!("{mode:?}"), &e, expected, Z);
        // Shown, the camera sees the lamp itself: le, exactly.
        let shown = estimate(&desc, shown(mode), 4, 16, seed);
        assert!(
            (shown.mean - le as f64).abs() < 1e-4,
            "{mode:?}: shown {}",
            shown.mean
        );
    }
}
