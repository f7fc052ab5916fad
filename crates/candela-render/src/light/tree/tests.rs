//! The light tree's choice against its pmf: normalisation, a chi-square
//! fit of the choices (the crate's harness, fixed seeds), exact agreement
//! of the reported probability with `pmf`, and conservative zeros (a light
//! that can reach the point always keeps a positive probability).

use super::LightContext;
use crate::light::{
    AmbientLight, AreaLight, AreaShape, Light, LightSelection, LightSet, AUTO_TREE_ABOVE,
};
use crate::sampling::chi2::discrete_fit;
use candela_testkit::SplitMix64;
use glam::Vec3;

fn triangle(v: [Vec3; 3], radiance: f32) -> Light {
    let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    Light::Area(AreaLight {
        shape: AreaShape::Triangle { v, normal },
        radiance: Vec3::splat(radiance),
        textured: None,
    })
}

/// `count` lights scattered in [-5, 5]³: small triangles facing every way
/// with powers over two decades, and a few spheres.
fn scattered_lights(count: usize, seed: u64) -> Vec<Light> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|k| {
            let c = rng.vec(-5.0, 5.0);
            let radiance = rng.log(-1.0, 1.0);
            if k % 10 == 9 {
                return Light::Area(AreaLight {
                    shape: AreaShape::Sphere {
                        center: c,
                        radius: rng.range(0.05, 0.3),
                        inward: false,
                    },
                    radiance: Vec3::splat(radiance),
                    textured: None,
                });
            }
            let size = rng.range(0.05, 0.5);
            let v = [c, c + size * rng.dir(), c + size * rng.dir()];
            triangle(v, radiance)
        })
        .collect()
}

/// Receivers in the lights' box: one-sided and two-sided surfaces, and a
/// point without a normal.
fn receivers(count: usize, seed: u64) -> Vec<LightContext> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|k| {
            let p = rng.vec(-6.0, 6.0);
            match k % 3 {
                0 => LightContext::surface(p, rng.dir(), false),
                1 => LightContext::surface(p, rng.dir(), true),
                _ => LightContext::point(p),
            }
        })
        .collect()
}

/// The pmf over every light sums to 1, within the rounding of a product
/// of `depth` branch probabilities, once the mass of the subtrees the walk
/// finds dark (no light chosen) is counted: at a point where a node's
/// bounds allow light but both its children's prove none, the walk stops
/// there. That mass is reported, and small.
#[test]
fn pmf_sums_to_one_at_every_point() {
    let set = LightSet::new(scattered_lights(300, 1), &[], 10.0);
    let tree = set.tree();
    let tolerance = 4.0 * (tree.depth() + 2) as f64 * f64::from(f32::EPSILON);
    let mut dark_total = 0.0;
    let points = receivers(60, 2);
    for ctx in &points {
        let sum: f64 = (0..300).map(|i| f64::from(tree.pmf(ctx, i))).sum();
        let dark = tree.dark_probability(ctx);
        dark_total += dark;
        assert!(
            (sum + dark - 1.0).abs() <= tolerance,
            "{ctx:?}: Σ pmf = {sum}, dark {dark}"
        );
        // Points without a normal see every light that faces them.
        if ctx.n == Vec3::ZERO {
            assert!((sum - 1.0).abs() <= 0.5, "{ctx:?}: Σ pmf = {sum}");
        }
    }
    eprintln!(
        "depth {}, mean dark probability {:.4}",
        tree.depth(),
        dark_total / points.len() as f64
    );
}

/// The choices follow the pmf (chi-square, the crate's harness) and each
/// reports exactly `pmf` of the light it chose.
#[test]
fn choices_follow_the_pmf() {
    let count = 300;
    let set = LightSet::new(scattered_lights(count, 3), &[], 10.0);
    let tree = set.tree();
    let mut rng = SplitMix64::new(4);
    for (k, ctx) in receivers(6, 5).into_iter().enumerate() {
        let pmf: Vec<f64> = (0..count as u32)
            .map(|i| f64::from(tree.pmf(&ctx, i)))
            .collect();
        let mut counts = vec![0u64; count + 1];
        for _ in 0..200_000 {
            match tree.choose(&ctx, rng.f32()) {
                Some((i, p)) => {
                    assert_eq!(p, tree.pmf(&ctx, i), "{ctx:?}: light {i}");
                    counts[i as usize] += 1;
                }
                None => counts[count] += 1,
            }
        }
        discrete_fit(&format!("light tree, receiver {k}"), &counts, &pmf).assert_ok();
    }
}

/// Uniform and power selection through the same interface.
#[test]
fn uniform_and_power_choices_follow_their_pmf() {
    let count = 50;
    let set = LightSet::new(scattered_lights(count, 6), &[], 10.0);
    let ctx = LightContext::point(Vec3::ZERO);
    let mut rng = SplitMix64::new(7);
    for how in [LightSelection::Uniform, LightSelection::Power] {
        let selector = set.selector(how);
        assert!(!selector.uses_tree());
        let pmf: Vec<f64> = (0..count as u32)
            .map(|i| f64::from(selector.pmf(&ctx, i)))
            .collect();
        let mut counts = vec![0u64; count + 1];
        for _ in 0..100_000 {
            let (i, p) = selector.choose(&ctx, rng.f32()).expect("a light");
            assert_eq!(p, selector.pmf(&ctx, i));
            counts[i as usize] += 1;
        }
        discrete_fit(&format!("{how:?} selection"), &counts, &pmf).assert_ok();
    }
    assert_eq!(
        set.selector(LightSelection::Uniform).pmf(&ctx, 3),
        1.0 / 50.0
    );
}

/// A light whose every point lies below the receiver's horizon, or which
/// faces away from it, has probability 0 and is never chosen; lights only
/// barely visible keep a positive probability.
#[test]
fn hidden_lights_are_never_chosen_and_barely_visible_ones_are() {
    let mut lights = scattered_lights(100, 8);
    let first = lights.len() as u32;
    let tri = |a: [f32; 3], b: [f32; 3], c: [f32; 3]| {
        triangle([Vec3::from(a), Vec3::from(b), Vec3::from(c)], 5.0)
    };
    // The receiver: the origin, normal +Z, reflecting only.
    lights.extend([
        // Below the horizon, facing up toward the receiver's back.
        tri([-1.0, -1.0, -4.0], [1.0, -1.0, -4.0], [0.0, 1.0, -3.0]),
        // Above, facing away (normal +Z).
        tri([-1.0, -1.0, 3.0], [1.0, -1.0, 3.0], [0.0, 1.0, 3.0]),
        // Facing the receiver, one corner 1 mm above its horizon, 2 m away.
        tri([2.0, 1.0, -1.0], [2.0, -1.0, -1.0], [2.0, 0.0, 1e-3]),
        // Above, seen almost edge-on (cos 0.01) from its emitting side.
        tri([-1.0, 0.01, 1.0], [1.0, 0.01, 1.0], [0.0, 0.01, 3.0]),
    ]);
    let (hidden, visible) = ([first, first + 1], [first + 2, first + 3]);
    let set = LightSet::new(lights, &[], 10.0);
    let tree = set.tree();
    let ctx = LightContext::surface(Vec3::ZERO, Vec3::Z, false);
    for i in hidden {
        assert_eq!(tree.pmf(&ctx, i), 0.0, "hidden light {i}");
    }
    for i in visible {
        assert!(tree.pmf(&ctx, i) > 0.0, "barely visible light {i}");
    }
    let mut rng = SplitMix64::new(9);
    for _ in 0..100_000 {
        if let Some((i, _)) = tree.choose(&ctx, rng.f32()) {
            assert!(!hidden.contains(&i), "hidden light {i} chosen");
        }
    }
    // Seen from a surface that transmits, the light below counts again.
    let two_sided = LightContext::surface(Vec3::ZERO, Vec3::Z, true);
    assert!(tree.pmf(&two_sided, first) > 0.0);
}

/// Whether some of `points` (on light `light`) sends light to `ctx` with a
/// margin: in front of the emitter and above the receiver's horizon.
fn reaches(ctx: &LightContext, normal: Vec3, points: &[Vec3]) -> bool {
    const MARGIN: f32 = 1e-3;
    points.iter().any(|&q| {
        let d = (ctx.p - q).normalize();
        let emits = normal.dot(d) > MARGIN;
        let received = ctx.n == Vec3::ZERO
            || if ctx.two_sided {
                ctx.n.dot(d).abs() > MARGIN
            } else {
                -ctx.n.dot(d) > MARGIN
            };
        emits && received
    })
}

/// The zeros are conservative through the whole tree: at random
/// receivers, every triangle that some probe point of it can light has a
/// positive probability.
#[test]
fn every_light_that_can_contribute_has_positive_probability() {
    let lights = scattered_lights(300, 10);
    let set = LightSet::new(lights.clone(), &[], 10.0);
    let tree = set.tree();
    let mut checked = 0;
    let mut zeros = 0;
    for ctx in receivers(300, 11) {
        for (i, light) in lights.iter().enumerate() {
            let Light::Area(AreaLight {
                shape: AreaShape::Triangle { v, normal },
                ..
            }) = light
            else {
                continue;
            };
            // Corners, edge midpoints and interior points.
            let mut probes = Vec::new();
            for a in 0..=4 {
                for b in 0..=(4 - a) {
                    let (wa, wb) = (a as f32 / 4.0, b as f32 / 4.0);
                    probes.push(wa * v[0] + wb * v[1] + (1.0 - wa - wb) * v[2]);
                }
            }
            let pmf = tree.pmf(&ctx, i as u32);
            if reaches(&ctx, *normal, &probes) {
                assert!(pmf > 0.0, "light {i} reaches {ctx:?} but has pmf 0");
                checked += 1;
            } else if pmf == 0.0 {
                zeros += 1;
            }
        }
    }
    // Both cases occur, so the test looks at something.
    assert!(checked > 10_000 && zeros > 10_000, "{checked} {zeros}");
}

/// Lights at infinity keep their power share; the tree shares the rest.
#[test]
fn lights_at_infinity_keep_their_power_probability() {
    let mut lights = scattered_lights(80, 12);
    lights.push(Light::Ambient(AmbientLight {
        radiance: Vec3::splat(0.05),
    }));
    let sky = lights.len() as u32 - 1;
    let set = LightSet::new(lights, &[], 10.0);
    let power = set.selector(LightSelection::Power);
    let tree = set.selector(LightSelection::Bvh);
    let ctx = LightContext::surface(Vec3::new(0.5, 0.2, -0.3), Vec3::Y, false);
    let p_sky = power.pmf(&ctx, sky);
    assert!(p_sky > 0.01 && p_sky < 0.99, "{p_sky}");
    assert_eq!(tree.pmf(&ctx, sky), p_sky);
    let sum: f64 = (0..=sky).map(|i| f64::from(tree.pmf(&ctx, i))).sum();
    let dark = set.tree().dark_probability(&ctx);
    assert!((sum + dark - 1.0).abs() < 1e-5, "{sum} + {dark}");
    let mut rng = SplitMix64::new(13);
    let n = 100_000;
    let mut counts = vec![0u64; sky as usize + 2];
    for _ in 0..n {
        match tree.choose(&ctx, rng.f32()) {
            Some((i, p)) => {
                assert_eq!(p, tree.pmf(&ctx, i));
                counts[i as usize] += 1;
            }
            None => counts[sky as usize + 1] += 1,
        }
    }
    let pmf: Vec<f64> = (0..=sky).map(|i| f64::from(tree.pmf(&ctx, i))).collect();
    discrete_fit("light tree with a sky", &counts, &pmf).assert_ok();
}

/// `auto` takes the tree only above [`AUTO_TREE_ABOVE`] sampled lights
/// (the setting's help, `LightSelection::Auto`, quotes the number).
#[test]
fn auto_takes_the_tree_only_for_many_lights() {
    let few = LightSet::new(scattered_lights(AUTO_TREE_ABOVE, 14), &[], 10.0);
    assert!(!few.selector(LightSelection::Auto).uses_tree());
    let many = LightSet::new(scattered_lights(AUTO_TREE_ABOVE + 1, 14), &[], 10.0);
    assert!(many.selector(LightSelection::Auto).uses_tree());
    assert!(few.selector(LightSelection::Bvh).uses_tree());
}

/// A tree of one light behind the receiver chooses nothing.
#[test]
fn a_single_hidden_light_is_not_chosen() {
    let light = triangle(
        [
            Vec3::new(-1.0, -1.0, -4.0),
            Vec3::new(1.0, -1.0, -4.0),
            Vec3::new(0.0, 1.0, -3.0),
        ],
        1.0,
    );
    let set = LightSet::new(vec![light], &[], 10.0);
    let ctx = LightContext::surface(Vec3::ZERO, Vec3::Z, false);
    let tree = set.selector(LightSelection::Bvh);
    assert_eq!(tree.choose(&ctx, 0.5), None);
    assert_eq!(tree.pmf(&ctx, 0), 0.0);
    let front = LightContext::surface(Vec3::ZERO, -Vec3::Z, false);
    assert_eq!(tree.choose(&front, 0.5), Some((0, 1.0)));
}

/// A ceiling of small lamps facing down (a 32 × 32 grid of quads of
/// several sizes, as in the many-lights hall, whose computed normals
/// differ in the last bit) and a wall of lamps facing in: at a point on
/// the ceiling 1 cm behind the lamps, the walk goes to the wall lamps and
/// loses no mass in subtrees of ceiling lamps (it lost 96 % when merging
/// two nearly equal normals made a whole-sphere cone).
#[test]
fn a_point_just_behind_a_grid_of_lamps_wastes_no_walk() {
    let mut lights = Vec::new();
    for j in 0..32 {
        for i in 0..32 {
            let (x, z) = (i as f32 * 0.25, j as f32 * 0.25);
            let s = 0.04 * (1.0 + 0.125 * ((i * 7 + j * 13) % 5) as f32);
            let y = 2.99;
            let [a, b, c, d] =
                [(-s, -s), (s, -s), (s, s), (-s, s)].map(|(dx, dz)| Vec3::new(x + dx, y, z + dz));
            // Counter-clockwise seen from below: normal -Y.
            lights.push(triangle([a, b, c], 1.0));
            lights.push(triangle([a, c, d], 1.0));
        }
    }
    let ceiling = lights.len();
    for j in 0..8 {
        for i in 0..16 {
            let (y, z) = (2.2 + j as f32 * 0.1, i as f32 * 0.5);
            let (a, b, c) = (
                Vec3::new(-0.01, y, z),
                Vec3::new(-0.01, y + 0.03, z),
                Vec3::new(-0.01, y, z + 0.03),
            );
            // Normal +X, toward the ceiling lamps' side of the room.
            lights.push(triangle([a, b, c], 10.0));
        }
    }
    let set = LightSet::new(lights, &[], 20.0);
    let tree = set.tree();
    let mut rng = SplitMix64::new(15);
    for _ in 0..20 {
        let p = Vec3::new(rng.range(0.5, 7.5), 3.0, rng.range(0.5, 7.5));
        let ctx = LightContext::surface(p, -Vec3::Y, false);
        let dark = tree.dark_probability(&ctx);
        assert!(dark < 1e-6, "{dark} of the walk lost at {p}");
        for i in 0..ceiling as u32 {
            assert_eq!(tree.pmf(&ctx, i), 0.0, "ceiling lamp {i} behind {p}");
        }
    }
}
