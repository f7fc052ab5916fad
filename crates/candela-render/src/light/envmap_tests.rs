//! The environment map: its mapping convention, its lookups, its sampling
//! against its pdf (chi-square), its power, and reading it from an EXR.

use super::*;
use crate::sampling::chi2::Chi2Test;
use candela_image::{write_exr, ExrLayers, RgbImage};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// A dim gradient with three bright spots of a few pixels each, one of them
/// straddling the u = 0 seam and one near the zenith.
fn spotty_image(width: usize, height: usize) -> RgbImage {
    RgbImage::from_fn(width, height, |x, y| {
        let (u, v) = (
            (x as f32 + 0.5) / width as f32,
            (y as f32 + 0.5) / height as f32,
        );
        let near = |cu: f32, cv: f32, r: f32| {
            let du = (u - cu).abs().min(1.0 - (u - cu).abs());
            du * du + (v - cv) * (v - cv) < r * r
        };
        if near(0.3, 0.35, 0.04) {
            [200.0, 150.0, 100.0]
        } else if near(0.0, 0.6, 0.05) {
            [10.0, 40.0, 80.0]
        } else if near(0.7, 0.06, 0.03) {
            [60.0, 60.0, 60.0]
        } else {
            [0.05 + 0.3 * v, 0.1, 0.2 * u]
        }
    })
    .unwrap()
}

fn map(opts: EnvironmentOptions) -> EnvironmentMap {
    EnvironmentMap::from_image(&spotty_image(64, 32), &opts).unwrap()
}

/// The density the module docs promise, computed independently:
/// `p(ω) = Y(ω) · mean sin θ of ω's row / (sin θ · ∫ Y dω)`.
fn expected_pdf(m: &EnvironmentMap, w: Vec3) -> f32 {
    let (_, h) = m.size();
    let uv = m.direction_to_uv(w);
    let row = ((uv.y * h as f32) as usize).min(h - 1) as f64;
    let d_theta = std::f64::consts::PI / h as f64;
    let mean_sin = ((row * d_theta).cos() - ((row + 1.0) * d_theta).cos()) / d_theta;
    let sin_theta = f64::from(uv.y * std::f32::consts::PI).sin();
    let y = f64::from(crate::film::luminance(m.le(w)));
    (y * mean_sin / (sin_theta * f64::from(m.luminance_integral()))) as f32
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() < tol
}

#[test]
fn the_mapping_follows_the_y_up_equirect_convention() {
    let m = map(EnvironmentOptions::default());
    let cases = [
        (Vec2::new(0.0, 0.5), -Vec3::Z),
        (Vec2::new(0.25, 0.5), Vec3::X),
        (Vec2::new(0.5, 0.5), Vec3::Z),
        (Vec2::new(0.75, 0.5), -Vec3::X),
        (Vec2::new(0.4, 0.0), Vec3::Y),
        (Vec2::new(0.4, 1.0), -Vec3::Y),
    ];
    for (uv, dir) in cases {
        let d = m.uv_to_direction(uv);
        assert!(close(d, dir, 1e-6), "{uv} -> {d}, expected {dir}");
    }
    for i in 0..100 {
        let uv = Vec2::new(
            (i as f32 * 0.618_034).fract(),
            0.01 + 0.98 * (i as f32 + 0.5) / 100.0,
        );
        let back = m.direction_to_uv(m.uv_to_direction(uv));
        assert!((back - uv).abs().max_element() < 1e-5, "{uv} -> {back}");
    }
}

#[test]
fn rotation_turns_the_map_about_y() {
    let m = map(EnvironmentOptions {
        rotate_y_deg: 90.0,
        ..Default::default()
    });
    assert!(close(
        m.uv_to_direction(Vec2::new(0.0, 0.5)),
        -Vec3::X,
        1e-6
    ));
    assert!(close(
        m.uv_to_direction(Vec2::new(0.25, 0.5)),
        -Vec3::Z,
        1e-6
    ));
    let plain = map(EnvironmentOptions::default());
    let w = Vec3::new(0.3, 0.2, -0.9).normalize();
    let turned = glam::Mat3::from_rotation_y(90f32.to_radians()) * w;
    assert_eq!(m.le(turned), plain.le(w));
}

#[test]
fn lookups_return_the_pixel_of_the_direction() {
    let (w, h) = (16usize, 8usize);
    let image = RgbImage::from_fn(w, h, |x, y| [x as f32, y as f32, 1.0]).unwrap();
    let m = EnvironmentMap::from_image(
        &image,
        &EnvironmentOptions {
            scale: 2.0,
            ..Default::default()
        },
    )
    .unwrap();
    for y in 0..h {
        for x in 0..w {
            // Anywhere inside the pixel, not only its centre.
            let uv = Vec2::new((x as f32 + 0.3) / w as f32, (y as f32 + 0.7) / h as f32);
            let le = m.le(m.uv_to_direction(uv));
            assert_eq!(
                le,
                2.0 * Vec3::new(x as f32, y as f32, 1.0),
                "pixel {x},{y}"
            );
        }
    }
}

fn check_sampling(name: &str, m: EnvironmentMap) {
    let light = Light::Environment(EnvironmentLight { map: Arc::new(m) });
    let p = Vec3::new(0.3, -1.0, 2.0); // irrelevant at infinity
    let outcome = Chi2Test::sphere(name).run(
        |u| {
            let s = light.sample_li(p, Vec2::new(u[1], u[2]))?;
            assert!(s.distance.is_infinite());
            assert_eq!(s.l, light.le(s.wi));
            Some((s.wi, s.pdf))
        },
        |wi| light.pdf_li(p, wi, Vec3::ZERO),
    );
    outcome.assert_ok();
}

#[test]
fn environment_sampling_matches_its_pdf() {
    check_sampling("environment", map(EnvironmentOptions::default()));
}

#[test]
fn rotated_environment_sampling_matches_its_pdf() {
    check_sampling(
        "environment rotated 37°",
        map(EnvironmentOptions {
            rotate_y_deg: 37.0,
            scale: 0.5,
            ..Default::default()
        }),
    );
}

#[test]
fn sampling_favours_the_bright_spots() {
    let m = map(EnvironmentOptions::default());
    // The spots hold most of the luminance: most samples must land there.
    let n = 4096;
    let bright = (0..n)
        .filter_map(|i| {
            let u = Vec2::new(
                (i as f32 * 0.754_877_7).fract(),
                (i as f32 + 0.5) / n as f32,
            );
            m.sample(u)
        })
        .filter(|s| crate::film::luminance(s.l) > 5.0)
        .count();
    let mut spot_integral = 0.0;
    let (w, h) = m.size();
    for row in 0..h {
        let (c0, c1) = (
            (std::f32::consts::PI * row as f32 / h as f32).cos(),
            (std::f32::consts::PI * (row + 1) as f32 / h as f32).cos(),
        );
        for col in 0..w {
            let uv = Vec2::new((col as f32 + 0.5) / w as f32, (row as f32 + 0.5) / h as f32);
            let y = crate::film::luminance(m.le(m.uv_to_direction(uv)));
            if y > 5.0 {
                spot_integral += y * (c0 - c1) * 2.0 * std::f32::consts::PI / w as f32;
            }
        }
    }
    let expected = spot_integral / m.luminance_integral();
    let got = bright as f32 / n as f32;
    // Stratified samples: the fraction is exact up to a few strata.
    assert!((got - expected).abs() < 0.02, "{got} vs {expected}");
    assert!(expected > 0.5);
}

#[test]
fn a_uniform_upper_hemisphere_has_the_ambient_lights_power() {
    let image = RgbImage::from_fn(8, 4, |_, y| if y < 2 { [0.7; 3] } else { [0.0; 3] }).unwrap();
    let env = Light::Environment(EnvironmentLight {
        map: Arc::new(EnvironmentMap::from_image(&image, &EnvironmentOptions::default()).unwrap()),
    });
    let ambient = Light::Ambient(AmbientLight {
        radiance: Vec3::splat(0.7),
    });
    let (a, b) = (env.power(3.0), ambient.power(3.0));
    assert!((a - b).abs() < 1e-5 * b, "{a} vs {b}");
    // And a uniform sphere integrates to 4π L.
    let full = EnvironmentMap::from_image(
        &RgbImage::from_fn(8, 5, |_, _| [2.0; 3]).unwrap(),
        &EnvironmentOptions::default(),
    )
    .unwrap();
    let four_pi = 4.0 * std::f32::consts::PI;
    assert!((full.luminance_integral() - 2.0 * four_pi).abs() < 1e-5 * four_pi);
    // Uniform maps are sampled nearly uniformly over the sphere (exactly
    // uniform in each row's mean).
    for u in [Vec2::new(0.3, 0.6), Vec2::new(0.9, 0.05)] {
        let s = full.sample(u).unwrap();
        let expected = expected_pdf(&full, s.wi);
        assert!(
            (s.pdf - expected).abs() < 1e-4 * expected,
            "{} vs {expected}",
            s.pdf
        );
        assert!((s.pdf * four_pi - 1.0).abs() < 0.2, "{}", s.pdf);
    }
}

#[test]
fn environment_maps_load_from_exr_and_bad_files_are_errors() {
    let dir = std::env::temp_dir().join(format!("candela-envmap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("sky.exr");
    let image = spotty_image(16, 8);
    write_exr(&path, &ExrLayers::beauty(image.clone())).unwrap();
    let loaded = EnvironmentMap::load(&path, &EnvironmentOptions::default()).unwrap();
    let direct = EnvironmentMap::from_image(&image, &EnvironmentOptions::default()).unwrap();
    assert!(loaded == direct, "the EXR round trip changes nothing");
    assert!(EnvironmentMap::load(&dir.join("none.exr"), &Default::default()).is_err());
    assert!(EnvironmentMap::load(&dir.join("sky.hdr"), &Default::default()).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_procedural_sky_has_its_sun_where_asked() {
    let sky = ProceduralSky::default();
    let m = EnvironmentMap::from_image(&sky.image(128, 64).unwrap(), &Default::default()).unwrap();
    assert_eq!(m.le(sky.sun_direction), sky.sun);
    assert_eq!(m.le(-Vec3::Y), sky.ground);
    // Densities follow luminance (times the row's sin θ correction).
    let horizon = Vec3::new(-0.6, 0.05, 0.8).normalize();
    for w in [
        sky.sun_direction,
        horizon,
        Vec3::new(0.1, -0.9, 0.3).normalize(),
    ] {
        let (got, expected) = (m.pdf(w), expected_pdf(&m, w));
        assert!(
            (got - expected).abs() < 1e-4 * expected,
            "{w}: {got} vs {expected}"
        );
    }
    assert!(m.pdf(sky.sun_direction) > 30.0 * m.pdf(horizon));
}
