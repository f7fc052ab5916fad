//! The bilinear environment lookups: values at and between pixel centres
//! under both row conventions, the seam and the poles, sampling against
//! the pdf (chi-square) and a constant sky's integral.

use super::envmap_bilinear::sample_linear;
use super::*;
use crate::sampling::chi2::Chi2Test;
use candela_image::RgbImage;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::Arc;

const W: usize = 8;
const H: usize = 5;

/// Pixel (x, y) is (x, y, 1) scaled: every texel differs from its
/// neighbours, so a blend shows which texels it read.
fn ramp_map(lookup: EnvironmentLookup) -> EnvironmentMap {
    let image = RgbImage::from_fn(W, H, |x, y| [x as f32, y as f32, 1.0]).unwrap();
    let opts = EnvironmentOptions {
        lookup,
        ..Default::default()
    };
    EnvironmentMap::from_image(&image, &opts).unwrap()
}

fn texel(x: usize, y: usize) -> Vec3 {
    Vec3::new(x as f32, y as f32, 1.0)
}

/// `v` of image row `y` under `lookup`.
fn row_v(lookup: EnvironmentLookup, y: f32) -> f32 {
    match lookup {
        EnvironmentLookup::BilinearPoleRows => y / (H - 1) as f32,
        _ => (y + 0.5) / H as f32,
    }
}

fn le_at(m: &EnvironmentMap, u: f32, v: f32) -> Vec3 {
    m.le(m.uv_to_direction(Vec2::new(u, v)))
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 2e-4 * (1.0 + b.abs().max_element())
}

#[test]
fn texel_centres_return_the_texel_and_midpoints_the_mean() {
    for lookup in [
        EnvironmentLookup::Bilinear,
        EnvironmentLookup::BilinearPoleRows,
    ] {
        let m = ramp_map(lookup);
        // Rows at the poles themselves are checked below (the direction
        // there has no azimuth).
        for y in 1..H - 1 {
            let v = row_v(lookup, y as f32);
            let v_mid = row_v(lookup, y as f32 + 0.5);
            for x in 0..W {
                let u = (x as f32 + 0.5) / W as f32;
                let got = le_at(&m, u, v);
                assert!(close(got, texel(x, y)), "{lookup:?} ({x},{y}): {got}");
                // Halfway to the next column (across the seam for the
                // last one) and to the next row.
                let right = le_at(&m, (u + 0.5 / W as f32).fract(), v);
                let mean = 0.5 * (texel(x, y) + texel((x + 1) % W, y));
                assert!(
                    close(right, mean),
                    "{lookup:?} ({x}.5,{y}): {right} vs {mean}"
                );
                let below = le_at(&m, u, v_mid);
                let mean = 0.5 * (texel(x, y) + texel(x, y + 1));
                assert!(
                    close(below, mean),
                    "{lookup:?} ({x},{y}.5): {below} vs {mean}"
                );
            }
        }
    }
}

#[test]
fn the_poles_clamp_or_hold_the_first_and_last_rows() {
    // CS184's lookup holds row 0 within half a row of the zenith.
    let m = ramp_map(EnvironmentLookup::Bilinear);
    let u = 2.5 / W as f32;
    assert!(close(le_at(&m, u, 0.2 / H as f32), texel(2, 0)));
    assert!(close(le_at(&m, u, 1.0 - 0.2 / H as f32), texel(2, H - 1)));
    // Mitsuba's rows reach the poles: a quarter of the way down the first
    // row spacing is a 3:1 blend of rows 0 and 1.
    let m = ramp_map(EnvironmentLookup::BilinearPoleRows);
    let got = le_at(&m, u, 0.25 / (H - 1) as f32);
    assert!(close(got, 0.75 * texel(2, 0) + 0.25 * texel(2, 1)), "{got}");
}

#[test]
fn linear_inversion_is_exact_at_its_ends_and_for_a_flat_density() {
    for (a, b) in [(1.0, 1.0), (0.0, 2.0), (3.0, 0.0), (0.2, 5.0)] {
        assert_eq!(sample_linear(0.0, a, b), 0.0);
        assert!((sample_linear(1.0, a, b) - 1.0).abs() < 1e-6);
    }
    assert!((sample_linear(0.37, 2.0, 2.0) - 0.37).abs() < 1e-6);
    // CDF of (1 - t) a + t b at the sample returns u.
    let (a, b, u) = (0.5f64, 3.0f64, 0.6f32);
    let t = f64::from(sample_linear(u, a as f32, b as f32));
    let cdf = (a * t + 0.5 * (b - a) * t * t) / (0.5 * (a + b));
    assert!((cdf - f64::from(u)).abs() < 1e-6, "{cdf}");
}

/// A map with sharp colour edges and a black band (density zero there):
/// what Mitsuba's test map looks like.
fn edgy_image() -> RgbImage {
    RgbImage::from_fn(24, 12, |x, y| match (x / 6, y / 3) {
        (0, _) => [4.0, 0.2, 0.1],
        (1, 0) => [0.0, 0.0, 0.0],
        (2, _) => [0.1, 0.3, 6.0],
        (_, 3) => [0.5, 2.0, 0.5],
        _ => [0.3, 0.3, 0.3],
    })
    .unwrap()
}

#[test]
fn bilinear_sampling_matches_its_pdf() {
    for lookup in [
        EnvironmentLookup::Bilinear,
        EnvironmentLookup::BilinearPoleRows,
    ] {
        let opts = EnvironmentOptions {
            lookup,
            rotate_y_deg: 23.0,
            scale: 1.5,
            // A tilt as a scene's `to_world` gives: samples and their pdf
            // must follow it as they follow the yaw.
            to_world: glam::Mat3::from_rotation_x(0.4),
        };
        let map = EnvironmentMap::from_image(&edgy_image(), &opts).unwrap();
        let light = Light::Environment(EnvironmentLight { map: Arc::new(map) });
        let p = Vec3::new(0.3, -1.0, 2.0);
        let outcome = Chi2Test::sphere(&format!("environment {lookup:?}")).run(
            |u| {
                let s = light.sample_li(p, Vec2::new(u[1], u[2]))?;
                assert_eq!(s.l, light.le(s.wi));
                Some((s.wi, s.pdf))
            },
            |wi| light.pdf_li(p, wi, Vec3::ZERO),
        );
        outcome.assert_ok();
    }
}

#[test]
fn a_constant_sky_integrates_to_four_pi_through_its_samples() {
    // The furnace of light sampling: E[L / p] = ∫ L dω = 4π L for a
    // constant map, whatever density the bilinear weights give. The bound
    // is five standard errors of the estimate, measured.
    let image = RgbImage::from_fn(16, 8, |_, _| [0.8; 3]).unwrap();
    for lookup in [
        EnvironmentLookup::Bilinear,
        EnvironmentLookup::BilinearPoleRows,
    ] {
        let opts = EnvironmentOptions {
            lookup,
            ..Default::default()
        };
        let m = EnvironmentMap::from_image(&image, &opts).unwrap();
        let n = 64 * 64;
        let (mut sum, mut sum_sq, mut misses) = (0.0f64, 0.0f64, 0usize);
        for i in 0..64 {
            for j in 0..64 {
                let u = Vec2::new((i as f32 + 0.37) / 64.0, (j as f32 + 0.61) / 64.0);
                let Some(s) = m.sample(u) else {
                    misses += 1;
                    continue;
                };
                assert!(close(s.l, Vec3::splat(0.8)), "{}", s.l);
                let x = f64::from(s.l.x / s.pdf);
                sum += x;
                sum_sq += x * x;
            }
        }
        assert_eq!(misses, 0, "{lookup:?}: no sample of a lit sky is lost");
        let mean = sum / n as f64;
        let se = ((sum_sq / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
        let expected = 4.0 * f64::from(PI) * 0.8;
        assert!(
            (mean - expected).abs() < 5.0 * se + 1e-5 * expected,
            "{lookup:?}: {mean} ± {se} vs {expected}"
        );
        let power = f64::from(m.luminance_integral());
        assert!((power - expected).abs() < 1e-3 * expected, "{power}");
    }
}
