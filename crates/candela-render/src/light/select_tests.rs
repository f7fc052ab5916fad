//! Tests of [`LightSelector::choose_with_point`]: the choice it reports
//! and the point numbers it hands on must have the density a separate
//! choice and a fresh 2-D number would have, whether it reuses the
//! choosing number or draws its own.

use super::*;
use crate::sampling::chi2::Chi2Test;
use glam::{Vec2, Vec3};
use std::cell::Cell;

/// Lights 0–3: triangles above the origin facing down, of radiance
/// 1, 2, 5 and 0.002 (the last one's share of the power, about 2.5e-4, is
/// under [`MIN_REUSED_SHARE`], so choosing it draws the choice's own number).
fn four_lamps() -> LightSet {
    let lamp = |x: f32, radiance: f32| {
        let v = [
            Vec3::new(x, 2.0, 0.0),
            Vec3::new(x, 2.0, 1.0),
            Vec3::new(x + 1.0, 2.0, 0.0),
        ];
        Light::Area(AreaLight {
            shape: AreaShape::Triangle {
                v,
                normal: Vec3::NEG_Y,
            },
            radiance: Vec3::splat(radiance),
            textured: None,
        })
    };
    let lights = vec![
        lamp(-2.0, 1.0),
        lamp(-1.0, 2.0),
        lamp(0.5, 5.0),
        lamp(2.0, 0.002),
    ];
    LightSet::new(lights, &[], 10.0)
}

fn receiver() -> LightContext {
    LightContext::surface(Vec3::new(0.3, 0.0, 0.2), Vec3::Y, false)
}

/// Chi-square over the strip [0, 4) × [0, 1): a sample of light `k` with
/// point numbers (x, y) lands at (k + x, y), where the density must be
/// light k's probability (uniform numbers given the choice) and the
/// probability the selector reports must be the one `pmf` gives.
fn choice_and_point_have_the_right_density(how: LightSelection) {
    let set = four_lamps();
    let selector = set.selector(how);
    let ctx = receiver();
    let pmf: Vec<f32> = (0..4).map(|k| selector.pmf(&ctx, k)).collect();
    assert!(
        (pmf.iter().sum::<f32>() - 1.0).abs() < 1e-5,
        "{how:?}: {pmf:?}"
    );
    Chi2Test::plane(
        &format!("{how:?} choice with point"),
        Vec2::ZERO,
        Vec2::new(4.0, 1.0),
    )
    .with_resolution(4 * 8, 8)
    .run(
        |u| {
            let (k, p, point) = selector.choose_with_point(&ctx, Vec2::new(u[0], u[1]), || u[2])?;
            assert!((0.0..1.0).contains(&point.x) && (0.0..1.0).contains(&point.y));
            Some((Vec3::new(k as f32 + point.x, point.y, 0.0), p))
        },
        |q| pmf[(q.x.max(0.0) as usize).min(3)],
    )
    .assert_ok();
}

#[test]
fn choice_by_power_with_reused_number_has_the_right_density() {
    choice_and_point_have_the_right_density(LightSelection::Power);
}

#[test]
fn uniform_choice_with_reused_number_has_the_right_density() {
    choice_and_point_have_the_right_density(LightSelection::Uniform);
}

#[test]
fn tree_choice_with_its_own_number_has_the_right_density() {
    choice_and_point_have_the_right_density(LightSelection::Bvh);
}

/// The choosing number is reused unless the chosen light's share is too
/// small; the tree always takes its own and leaves the point's numbers be.
#[test]
fn own_number_is_drawn_only_when_reuse_would_lose_precision() {
    let set = four_lamps();
    let ctx = receiver();
    let power = set.selector(LightSelection::Power);
    let mut chosen = [0u32; 4];
    for i in 0..16_384 {
        let u = Vec2::new((i as f32 + 0.5) / 16_384.0, 0.25);
        let called = Cell::new(false);
        let (k, p, point) = power
            .choose_with_point(&ctx, u, || {
                called.set(true);
                0.75
            })
            .unwrap();
        chosen[k as usize] += 1;
        assert_eq!(called.get(), p < MIN_REUSED_SHARE, "light {k}, pmf {p}");
        assert_eq!(point.y, 0.25);
        if called.get() {
            assert_eq!(point.x, 0.75);
        }
    }
    assert!(chosen.iter().all(|&c| c > 0), "{chosen:?}");
    let tree = set.selector(LightSelection::Bvh);
    let u = Vec2::new(0.3, 0.6);
    let (_, _, point) = tree.choose_with_point(&ctx, u, || 0.5).unwrap();
    assert_eq!(point, u);
}

/// With one light the point's numbers pass through unchanged, bit for bit:
/// single-lamp scenes render exactly as with a separate choice.
#[test]
fn a_single_light_keeps_the_points_numbers() {
    let set = LightSet::new(vec![four_lamps().get(2).clone()], &[], 10.0);
    let ctx = receiver();
    for how in [LightSelection::Power, LightSelection::Uniform] {
        let selector = set.selector(how);
        for i in 0..1000 {
            let u = Vec2::new(i as f32 / 1000.0, 1.0 - (i as f32 + 0.5) / 1000.0);
            let (k, p, point) = selector
                .choose_with_point(&ctx, u, || panic!("drew its own number"))
                .unwrap();
            assert_eq!((k, p), (0, 1.0));
            assert_eq!(
                (point.x.to_bits(), point.y.to_bits()),
                (u.x.to_bits(), u.y.to_bits())
            );
        }
    }
}
