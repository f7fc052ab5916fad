//! The BVH against brute force, for every strategy and degenerate inputs.
//!
//! Primitives are the boxes themselves, intersected in f64; rays either aim
//! at an interior point of a random box (so most hit something) or are
//! random. Closest-hit must return the brute-force distance and any-hit the
//! brute-force verdict, for every ray.

use candela_bvh::{
    has_avx2, Aabb, BuildOptions, BuildStrategy, Bvh, Bvh4, Bvh8, Collapse, RayBoxQuery,
    TraversalStats, WideBvh, PADDING,
};
use glam::Vec3;

use candela_testkit::SplitMix64 as Rng;

/// Entry distance of the ray into the box in f64 (`t >= 0`), if it hits.
fn box_hit(o: Vec3, d: Vec3, b: &Aabb, t_max: f32) -> Option<f32> {
    let (o, d) = (o.as_dvec3(), d.as_dvec3());
    let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
    let (mut near, mut far) = (0.0f64, t_max as f64);
    for a in 0..3 {
        if d[a] == 0.0 {
            if o[a] < lo[a] || o[a] > hi[a] {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
        near = near.max(t0.min(t1));
        far = far.min(t0.max(t1));
    }
    (near <= far && near < t_max as f64).then_some(near as f32)
}

/// Every leaf of a padded tree starts at a multiple of 4 slots.
fn assert_padded_aligned<const W: usize>(padded: &WideBvh<W>, label: &str) {
    for n in padded.nodes() {
        for lane in 0..W {
            if n.count[lane] > 0 {
                assert_eq!(n.child[lane] % 4, 0, "{label}: padded leaf unaligned");
            }
        }
    }
}

/// One ray against the boxes, replayed through a wide tree's queries.
struct Query<'a> {
    o: Vec3,
    d: Vec3,
    t_max: f32,
    boxes: &'a [Aabb],
}

impl Query<'_> {
    fn hit(&self, id: u32, tm: f32) -> Option<f32> {
        box_hit(self.o, self.d, &self.boxes[id as usize], tm).filter(|&t| t < tm)
    }

    /// Closest and any hit, slot by slot and leaf by leaf, against `brute`;
    /// returns the closest-hit statistics.
    fn check_wide<const W: usize>(
        &self,
        wide: &WideBvh<W>,
        brute: Option<f32>,
        ctx: &str,
    ) -> TraversalStats {
        let (q, t_max) = (RayBoxQuery::new(self.o, self.d), self.t_max);
        let order = wide.primitive_order();
        let mut stats = TraversalStats::default();
        let got = wide.closest_hit(&q, t_max, &mut stats, |slot, tm| {
            self.hit(order[slot as usize], tm)
        });
        assert_eq!(got.map(|g| g.1), brute, "{ctx}: closest");
        assert!(
            stats.prims_tested as usize <= self.boxes.len(),
            "{ctx}: a primitive tested twice"
        );
        let any = wide.any_hit(&q, t_max, &mut (), |slot, tm| {
            self.hit(order[slot as usize], tm)
        });
        assert_eq!(any, brute.is_some(), "{ctx}: any");
        // Whole leaves per call, as SIMD packet callers use it.
        let mut leaf_stats = TraversalStats::default();
        let leaves = wide.closest_hit_leaves(
            &q,
            t_max,
            &mut leaf_stats,
            |_, _| {},
            |first, count, tm| {
                (first..first + count)
                    .filter_map(|slot| self.hit(order[slot as usize], tm).map(|t| (slot, t)))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
            },
        );
        assert_eq!(leaves.map(|g| g.1), brute, "{ctx}: leaf-wise closest");
        assert_eq!(leaf_stats, stats, "{ctx}: leaf-wise statistics");
        let any_leaves = wide.any_hit_leaves(
            &q,
            t_max,
            &mut (),
            |_, _| {},
            |first, count, tm| {
                (first..first + count).any(|slot| self.hit(order[slot as usize], tm).is_some())
            },
        );
        assert_eq!(any_leaves, brute.is_some(), "{ctx}: leaf-wise any");
        stats
    }

    /// Closest hit through a padded tree, which must never visit padding.
    fn check_padded<const W: usize>(&self, padded: &WideBvh<W>, brute: Option<f32>, ctx: &str) {
        let q = RayBoxQuery::new(self.o, self.d);
        let porder = padded.primitive_order();
        let got = padded.closest_hit(&q, self.t_max, &mut (), |slot, tm| {
            let id = porder[slot as usize];
            assert_ne!(id, PADDING, "{ctx}: padding slot visited");
            self.hit(id, tm)
        });
        assert_eq!(got.map(|g| g.1), brute, "{ctx}: padded");
    }
}

fn check(boxes: &[Aabb], rng: &mut Rng, rays: usize, label: &str) {
    let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
    for strategy in [
        BuildStrategy::Sah,
        BuildStrategy::Median,
        BuildStrategy::None,
    ] {
        for (max_leaf, collapse) in [1, 4, 8]
            .into_iter()
            .flat_map(|m| [(m, Collapse::Greedy), (m, Collapse::Sah)])
        {
            let opts = BuildOptions {
                max_leaf_size: max_leaf,
                leaf_block: if max_leaf == 8 { 4 } else { 1 },
                collapse,
                ..BuildOptions::with_strategy(strategy)
            };
            let label = &format!("{label} {collapse:?}");
            let bvh = Bvh::build(boxes, &centroids, opts);
            if let Err(e) = bvh.validate(boxes) {
                panic!("{label} {strategy:?}/{max_leaf}: {e}");
            }
            let wide = Bvh4::from_binary(bvh.clone());
            if let Err(e) = wide.validate(boxes) {
                panic!("{label} {strategy:?}/{max_leaf} (4-wide): {e}");
            }
            assert!(wide.depth() <= bvh.depth());
            let order = bvh.primitive_order();
            assert_eq!(order, wide.primitive_order());
            let mut padded = wide.clone();
            padded.pad_leaves(4);
            if let Err(e) = padded.validate(boxes) {
                panic!("{label} {strategy:?}/{max_leaf} (padded): {e}");
            }
            let wide8 = Bvh8::from_binary(bvh.clone());
            if let Err(e) = wide8.validate(boxes) {
                panic!("{label} {strategy:?}/{max_leaf} (8-wide): {e}");
            }
            // The SAH collapse may trade depth for cost, but a wide level
            // always descends at least one binary level.
            assert!(wide8.depth() <= bvh.depth());
            if collapse == Collapse::Greedy {
                assert!(wide8.depth() <= wide.depth());
            }
            assert_eq!(order, wide8.primitive_order());
            assert_eq!(wide8.uses_avx2(), has_avx2());
            let mut wide8_portable = wide8.clone();
            wide8_portable.set_avx2(false);
            let mut padded8 = wide8.clone();
            padded8.pad_leaves(4);
            if let Err(e) = padded8.validate(boxes) {
                panic!("{label} {strategy:?}/{max_leaf} (8-wide padded): {e}");
            }
            assert_padded_aligned(&padded, label);
            assert_padded_aligned(&padded8, label);
            // Leaves of two blocks split into the free lanes: same nodes,
            // every invariant, the same answers.
            let filled = Bvh4::from_binary_filled(bvh.clone(), boxes, 4);
            let filled8 = Bvh8::from_binary_filled(bvh.clone(), boxes, 4);
            let mut filled8_padded = filled8.clone();
            filled8_padded.pad_leaves(4);
            for (name, v) in [
                ("4-wide filled", filled.validate(boxes)),
                ("8-wide filled", filled8.validate(boxes)),
                ("8-wide filled padded", filled8_padded.validate(boxes)),
            ] {
                if let Err(e) = v {
                    panic!("{label} {strategy:?}/{max_leaf} ({name}): {e}");
                }
            }
            // Same nodes, unless the SAH collapse counted other blocks
            // (the build's leaf block against the fill's 4).
            if collapse == Collapse::Greedy || opts.leaf_block == 4 {
                assert_eq!(filled.nodes().len(), wide.nodes().len());
                assert_eq!(filled8.nodes().len(), wide8.nodes().len());
            }
            assert_padded_aligned(&filled8_padded, label);
            let world = bvh.bounds();
            for k in 0..rays {
                let o = if world.is_empty() {
                    Vec3::ZERO
                } else {
                    world.center() + world.extent().max(Vec3::ONE) * rng.vec(-1.5, 1.5)
                };
                let target = if boxes.is_empty() || k % 4 == 3 {
                    o + rng.vec(-1.0, 1.0)
                } else {
                    let b = boxes[rng.next_u64() as usize % boxes.len()];
                    b.min + (b.max - b.min) * rng.vec(0.05, 0.95)
                };
                let d = (target - o).normalize_or(Vec3::X);
                let t_max = if k % 5 == 4 {
                    rng.range(0.0, 3.0)
                } else {
                    f32::INFINITY
                };
                let brute = boxes
                    .iter()
                    .filter_map(|b| box_hit(o, d, b, t_max))
                    .reduce(f32::min);
                let q = RayBoxQuery::new(o, d);
                let mut stats = TraversalStats::default();
                let got = bvh.closest_hit(&q, t_max, &mut stats, |slot, tm| {
                    box_hit(o, d, &boxes[order[slot as usize] as usize], tm).filter(|&t| t < tm)
                });
                assert_eq!(
                    got.map(|g| g.1),
                    brute,
                    "{label} {strategy:?}/{max_leaf} ray {k}: closest hit"
                );
                assert!(
                    stats.prims_tested as usize <= boxes.len(),
                    "{label}: a primitive tested twice"
                );
                let any = bvh.any_hit(&q, t_max, &mut (), |slot, tm| {
                    box_hit(o, d, &boxes[order[slot as usize] as usize], tm).filter(|&t| t < tm)
                });
                assert_eq!(
                    any,
                    brute.is_some(),
                    "{label} {strategy:?}/{max_leaf} ray {k}: any hit"
                );
                let ctx = format!("{label} {strategy:?}/{max_leaf} ray {k}");
                let query = Query { o, d, t_max, boxes };
                let s4 = query.check_wide(&wide, brute, &format!("{ctx} 4-wide"));
                let s8 = query.check_wide(&wide8, brute, &format!("{ctx} 8-wide"));
                let s8p = query.check_wide(&wide8_portable, brute, &format!("{ctx} 8-wide SSE"));
                // The AVX2 and SSE node tests are the same arithmetic.
                assert_eq!(s8, s8p, "{ctx}: 8-wide AVX2 and SSE statistics differ");
                assert!(s4.prims_tested.max(s8.prims_tested) as usize <= boxes.len());
                query.check_padded(&padded, brute, &ctx);
                query.check_padded(&padded8, brute, &format!("{ctx} 8-wide"));
                query.check_wide(&filled, brute, &format!("{ctx} 4-wide filled"));
                query.check_wide(&filled8, brute, &format!("{ctx} 8-wide filled"));
                query.check_padded(&filled8_padded, brute, &format!("{ctx} 8-wide filled"));
            }
        }
    }
}

fn random_boxes(rng: &mut Rng, n: usize, size: f32) -> Vec<Aabb> {
    (0..n)
        .map(|_| {
            let c = rng.vec(-10.0, 10.0);
            let h = rng.vec(0.0, size);
            Aabb::new(c - h, c + h)
        })
        .collect()
}

#[test]
fn random_scenes_match_brute_force() {
    let mut rng = Rng(1);
    for n in [1, 2, 3, 7, 31, 200, 1500] {
        let boxes = random_boxes(&mut rng, n, 1.0);
        check(&boxes, &mut rng, 150, &format!("random n={n}"));
    }
}

#[test]
fn parallel_build_matches_brute_force() {
    let mut rng = Rng(2);
    let boxes = random_boxes(&mut rng, 20_000, 0.3);
    let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
    let bvh = Bvh::build(&boxes, &centroids, BuildOptions::default());
    bvh.validate(&boxes).unwrap();
    assert!(
        bvh.depth() < 40,
        "depth {} for 20k random boxes",
        bvh.depth()
    );
    check(&boxes, &mut rng, 100, "20k boxes");
}

#[test]
fn empty_input() {
    let bvh = Bvh::build(&[], &[], BuildOptions::default());
    assert!(bvh.nodes().is_empty());
    bvh.validate(&[]).unwrap();
    let q = RayBoxQuery::new(Vec3::ZERO, Vec3::X);
    assert!(bvh
        .closest_hit(&q, f32::INFINITY, &mut (), |_, _| Some(1.0))
        .is_none());
    check(&[], &mut Rng(3), 10, "empty");
}

#[test]
fn coincident_centroids() {
    let mut rng = Rng(4);
    // Nested boxes around one centre: no split plane separates them.
    let boxes: Vec<Aabb> = (0..100)
        .map(|_| {
            let h = rng.vec(0.1, 2.0);
            Aabb::new(Vec3::splat(1.0) - h, Vec3::splat(1.0) + h)
        })
        .collect();
    check(&boxes, &mut rng, 100, "coincident");
    let same = vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 5000];
    check(&same, &mut rng, 20, "identical");
}

#[test]
fn flat_boxes() {
    let mut rng = Rng(5);
    let boxes: Vec<Aabb> = (0..300)
        .map(|i| {
            let c = rng.vec(-5.0, 5.0);
            let mut h = rng.vec(0.2, 1.0);
            h[i % 3] = 0.0;
            Aabb::new(c - h, c + h)
        })
        .collect();
    check(&boxes, &mut rng, 200, "flat");
}

#[test]
fn huge_boxes_among_small_ones() {
    let mut rng = Rng(6);
    let mut boxes = random_boxes(&mut rng, 300, 0.5);
    boxes.push(Aabb::new(Vec3::splat(-1e30), Vec3::splat(1e30)));
    boxes.push(Aabb::new(
        Vec3::new(-1e30, -1.0, -1.0),
        Vec3::new(1e30, 1.0, 1.0),
    ));
    let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
    for s in [BuildStrategy::Sah, BuildStrategy::Median] {
        let bvh = Bvh::build(&boxes, &centroids, BuildOptions::with_strategy(s));
        bvh.validate(&boxes).unwrap();
        let wide = Bvh4::from_binary(bvh.clone());
        wide.validate(&boxes).unwrap();
        let wide8 = Bvh8::from_binary(bvh.clone());
        wide8.validate(&boxes).unwrap();
        // Every ray starts inside the first huge box, so any-hit is always true.
        let order = bvh.primitive_order();
        for _ in 0..100 {
            let (o, d) = (
                rng.vec(-20.0, 20.0),
                rng.vec(-1.0, 1.0).normalize_or(Vec3::Y),
            );
            let q = RayBoxQuery::new(o, d);
            let hit = bvh.any_hit(&q, f32::INFINITY, &mut (), |slot, tm| {
                box_hit(o, d, &boxes[order[slot as usize] as usize], tm)
            });
            assert!(hit);
            let hit4 = wide.any_hit(&q, f32::INFINITY, &mut (), |slot, tm| {
                box_hit(o, d, &boxes[order[slot as usize] as usize], tm)
            });
            assert!(hit4);
            let hit8 = wide8.any_hit(&q, f32::INFINITY, &mut (), |slot, tm| {
                box_hit(o, d, &boxes[order[slot as usize] as usize], tm)
            });
            assert!(hit8);
        }
    }
}
