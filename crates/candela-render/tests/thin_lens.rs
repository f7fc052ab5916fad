//! Depth of field: with a thin lens of radius `A` focused at distance
//! `d_f`, a point at depth `z` spreads over a disk of diameter
//! `CoC = 2 A |1/z − 1/d_f|` in tangent units, i.e.
//! `CoC_px = A |1/z − 1/d_f| · W / tan(hfov/2)` pixels.
//!
//! The scene is a self-emitting half-plane (x > 0, radiance 1) facing a
//! camera on the z axis, so its edge falls on the image's centre line at
//! any depth. Each pixel's value is then the fraction of the lens that sees
//! the bright side, averaged over the pixel: for a blur-disk radius `R`
//! the exact profile is the box-filtered CDF of a uniform disk's
//! x-coordinate, `F(x) = ½ + (x√(1−x²) + asin x)/π` at `x = offset / R`.
//! Every column is compared with that profile (Bernoulli samples: the
//! standard error is `√(p(1−p)/n)`), and the blur radius measured from the
//! edge's line-spread variance (`R²/4` plus `1/6` for the two pixel boxes
//! of a differenced edge) is reported against the formula.

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{BsdfDesc, MeshDesc, SceneDesc};
use glam::Vec3;

const WIDTH: u32 = 64;
const HEIGHT: u32 = 16;
const SPP: u32 = 512;

/// The emitting half-plane x > 0 at depth `z` in front of a camera at the
/// origin looking down −Z.
fn half_plane(z: f32) -> SceneDesc {
    let (x1, y1) = (20.0 * z, 20.0 * z);
    let mesh = MeshDesc {
        name: "bright half".into(),
        positions: vec![
            Vec3::new(0.0, -y1, -z),
            Vec3::new(x1, -y1, -z),
            Vec3::new(x1, y1, -z),
            Vec3::new(0.0, y1, -z),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        normals: vec![Vec3::Z],
        normal_indices: vec![[0; 3]; 2],
        material: 0,
        ..Default::default()
    };
    SceneDesc {
        source: "half plane".into(),
        cameras: vec![common::camera_at(Vec3::ZERO)],
        meshes: vec![mesh],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        materials: vec![common::material("lamp", BsdfDesc::Black, Some(Vec3::ONE))],
        ..Default::default()
    }
}

/// CDF of the x-coordinate of a point uniform in the unit disk.
fn disk_cdf(x: f64) -> f64 {
    let x = x.clamp(-1.0, 1.0);
    0.5 + (x * (1.0 - x * x).sqrt() + x.asin()) / std::f64::consts::PI
}

/// Expected value of pixel column `i` for a blur radius `r` (pixels).
fn expected_column(i: u32, r: f64) -> f64 {
    let centre = f64::from(WIDTH) / 2.0;
    let steps = 400;
    (0..steps)
        .map(|k| {
            let x = f64::from(i) + (k as f64 + 0.5) / steps as f64 - centre;
            if r == 0.0 {
                if x > 0.0 {
                    1.0
                } else {
                    0.0
                }
            } else {
                disk_cdf(x / r)
            }
        })
        .sum::<f64>()
        / steps as f64
}

/// Renders the half-plane at depth `z` through a lens of radius `a`
/// focused at `d_f`; returns the mean of each column and the predicted
/// blur radius in pixels.
fn render_edge(z: f32, a: f32, d_f: f32) -> (Vec<f64>, f64) {
    let opts = SceneOptions {
        width: WIDTH,
        height: HEIGHT,
        camera_mode: CameraMode::File,
        lens_radius: a,
        focal_distance: Some(d_f),
        ..Default::default()
    };
    let scene = Scene::build(&half_plane(z), &opts).expect("scene builds");
    assert_eq!(scene.camera.lens_radius, a);
    assert_eq!(scene.camera.focal_distance, d_f);
    let settings = RenderSettings {
        spp: SPP,
        seed: 11,
        integrator: IntegratorSettings {
            max_depth: 0,
            lighting: LightingMode::Mis,
            roulette: false,
            ..Default::default()
        },
        ..Default::default()
    };
    let out = render(&scene, &settings, &|_| {}).expect("render");
    let image = out.film.resolve();
    let columns = (0..WIDTH as usize)
        .map(|x| {
            (0..HEIGHT as usize)
                .map(|y| f64::from(image.pixels()[y * WIDTH as usize + x][0]))
                .sum::<f64>()
                / f64::from(HEIGHT)
        })
        .collect();
    let k = f64::from((1.0 / z - 1.0 / d_f).abs());
    let r = f64::from(a) * k * f64::from(WIDTH) / (2.0 * f64::from(scene.camera.tan_half_width));
    (columns, r)
}

/// Blur radius from the edge's line-spread variance.
fn measured_radius(columns: &[f64]) -> f64 {
    let d: Vec<f64> = columns.windows(2).map(|w| w[1] - w[0]).collect();
    let total: f64 = d.iter().sum();
    let mean: f64 = d.iter().enumerate().map(|(i, v)| i as f64 * v).sum::<f64>() / total;
    let var: f64 = d
        .iter()
        .enumerate()
        .map(|(i, v)| (i as f64 - mean).powi(2) * v)
        .sum::<f64>()
        / total;
    2.0 * (var - 1.0 / 6.0).max(0.0).sqrt()
}

fn check_edge(label: &str, z: f32, a: f32, d_f: f32) -> (f64, f64) {
    let (columns, r) = render_edge(z, a, d_f);
    let n = f64::from(HEIGHT * SPP);
    let mut worst = 0.0f64;
    for (i, &got) in columns.iter().enumerate() {
        let expected = expected_column(i as u32, r);
        let se = (expected * (1.0 - expected) / n).sqrt();
        // 4.5 standard errors: a false alarm over 64 columns is ~1e-4.
        let bound = 4.5 * se + 1e-4;
        worst = worst.max((got - expected).abs() / bound);
        assert!(
            (got - expected).abs() <= bound,
            "{label}: column {i}: {got:.4} vs {expected:.4} (R = {r:.3} px)"
        );
    }
    let measured = measured_radius(&columns);
    eprintln!(
        "{label}: CoC diameter expected {:.3} px, measured {:.3} px; worst column at {:.2} of its bound",
        2.0 * r,
        2.0 * measured,
        worst
    );
    (r, measured)
}

#[test]
fn a_plane_at_the_focal_distance_is_sharp() {
    let (r, measured) = check_edge("in focus", 4.0, 1.2, 4.0);
    assert_eq!(r, 0.0);
    assert!(measured < 0.05, "{measured}");
}

#[test]
fn planes_off_the_focal_distance_blur_by_the_circle_of_confusion() {
    for (label, z) in [("near plane", 2.0), ("far plane", 16.0)] {
        let (r, measured) = check_edge(label, z, 1.2, 4.0);
        assert!(r > 2.0, "{label}: the test needs a visible blur ({r})");
        assert!(
            (measured - r).abs() < 0.05 * r,
            "{label}: measured radius {measured:.3} px vs {r:.3} px"
        );
    }
}

#[test]
fn negative_apertures_and_focal_distances_are_errors() {
    for (a, d) in [(-0.1, Some(1.0)), (0.1, Some(0.0)), (f32::NAN, None)] {
        let opts = SceneOptions {
            camera_mode: CameraMode::File,
            lens_radius: a,
            focal_distance: d,
            ..Default::default()
        };
        assert!(Scene::build(&half_plane(1.0), &opts).is_err(), "{a} {d:?}");
    }
}
