//! Tests of the any-hit lane order: a wall is visited before the detailed
//! object a ray leaves, the answers do not change, and unoccluded rays do
//! the same work in either order.

use crate::wide::{WideBvh, WideNode};
use crate::wide_collapse::CollapseCosts;
use crate::{Aabb, Bvh8, RayBoxQuery, TraversalStats};
use candela_testkit::SplitMix64 as Rng;
use glam::Vec3;

const COSTS: CollapseCosts = CollapseCosts {
    node: 1.5,
    block: 1.0,
    leaf: 1.0,
    block_size: 4,
    max_leaf: 8,
};

/// A room by hand: the root holds, in this lane order, an "object" (a node
/// of eight leaves of four small boxes each, filling the unit cube) and a
/// node holding one leaf with a ceiling (a flat 20 × 20 box at z = 3)
/// beside a leaf of four small boxes far to the side. Returns the tree
/// and the primitive boxes (object boxes first, the ceiling last).
fn room() -> (Bvh8, Vec<Aabb>) {
    let mut rng = Rng(11);
    let mut boxes = Vec::new();
    for _ in 0..32 {
        let c = Vec3::new(
            rng.range(0.1, 0.9),
            rng.range(0.1, 0.9),
            rng.range(0.1, 0.9),
        );
        boxes.push(Aabb::new(c - 0.05, c + 0.05));
    }
    for k in 0..4 {
        let c = Vec3::new(8.0 + k as f32, 8.0, 1.0);
        boxes.push(Aabb::new(c - 0.1, c + 0.1));
    }
    let ceiling = boxes.len() as u32;
    boxes.push(Aabb::new(
        Vec3::new(-10.0, -10.0, 3.0),
        Vec3::new(10.0, 10.0, 3.0),
    ));
    let union =
        |ids: std::ops::Range<u32>| ids.fold(Aabb::EMPTY, |b, i| b.union(boxes[i as usize]));
    let empty = WideNode::<8> {
        bounds: [
            [f32::INFINITY; 8],
            [f32::INFINITY; 8],
            [f32::INFINITY; 8],
            [f32::NEG_INFINITY; 8],
            [f32::NEG_INFINITY; 8],
            [f32::NEG_INFINITY; 8],
        ],
        child: [0; 8],
        count: [0; 8],
    };
    let set = |n: &mut WideNode<8>, lane: usize, b: Aabb, child: u32, count: u32| {
        for a in 0..3 {
            n.bounds[a][lane] = b.min[a];
            n.bounds[3 + a][lane] = b.max[a];
        }
        n.child[lane] = child;
        n.count[lane] = count;
    };
    let (mut root, mut object, mut walls) = (empty, empty, empty);
    for leaf in 0..8u32 {
        set(
            &mut object,
            leaf as usize,
            union(4 * leaf..4 * leaf + 4),
            4 * leaf,
            4,
        );
    }
    set(&mut walls, 0, union(32..36), 32, 4);
    set(&mut walls, 1, boxes[ceiling as usize], ceiling, 1);
    set(&mut root, 0, union(0..32), 1, 0);
    set(&mut root, 1, union(32..37), 2, 0);
    let bvh = WideBvh {
        nodes: vec![root, object, walls],
        order: (0..boxes.len() as u32).collect(),
        depth: 2,
        avx2: crate::avx2::has_avx2(),
    };
    bvh.validate(&boxes).unwrap();
    (bvh, boxes)
}

fn slab_hit(o: Vec3, d: Vec3, b: &Aabb, t_max: f32) -> bool {
    let inv = d.recip();
    let (t0, t1) = ((b.min - o) * inv, (b.max - o) * inv);
    let near = t0.min(t1).max_element().max(0.0);
    let far = t0.max(t1).min_element().min(t_max);
    near <= far
}

/// Any-hit answers and the work spent, over rays from inside the object.
fn any_hits(bvh: &Bvh8, boxes: &[Aabb], rays: &[(Vec3, Vec3)]) -> (Vec<bool>, TraversalStats) {
    let mut stats = TraversalStats::default();
    let order = bvh.primitive_order().to_vec();
    let hits = rays
        .iter()
        .map(|&(o, d)| {
            bvh.any_hit(
                &RayBoxQuery::new(o, d),
                f32::INFINITY,
                &mut stats,
                |slot, t| slab_hit(o, d, &boxes[order[slot as usize] as usize], t).then_some(0.0),
            )
        })
        .collect();
    (hits, stats)
}

fn rays_from_object(rng: &mut Rng, n: usize, up: bool) -> Vec<(Vec3, Vec3)> {
    (0..n)
        .map(|_| {
            let o = Vec3::new(
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
            );
            let z = rng.range(0.5, 1.0);
            let d = Vec3::new(
                rng.range(-0.3, 0.3),
                rng.range(-0.3, 0.3),
                if up { z } else { -z },
            );
            (o, d.normalize())
        })
        .collect()
}

/// The ceiling's subtree (p = 1 for the cost of one node and a leaf) goes
/// before the object's (p well under 1 for eight leaves), and the ceiling's
/// leaf before the four small boxes in its node; rays that leave the object
/// upwards then test one primitive each instead of walking the object, with
/// the same answers.
#[test]
fn walls_come_before_the_object_they_enclose() {
    let (unordered, boxes) = room();
    let mut ordered = unordered.clone();
    ordered.order_lanes_for_any_hit(&boxes, &COSTS);
    ordered.validate(&boxes).unwrap();
    let root = &ordered.nodes()[0];
    let walls = root.child[0] as usize;
    assert_eq!(root.lane_bounds(0), unordered.nodes()[0].lane_bounds(1));
    assert_eq!(
        ordered.nodes()[walls].count[0],
        1,
        "the ceiling's leaf first"
    );

    let mut rng = Rng(5);
    let up = rays_from_object(&mut rng, 500, true);
    let (hits_before, before) = any_hits(&unordered, &boxes, &up);
    let (hits_after, after) = any_hits(&ordered, &boxes, &up);
    assert!(
        hits_after.iter().all(|&h| h),
        "every ray up meets the ceiling"
    );
    assert_eq!(hits_before, hits_after);
    // Ordered: the root and the walls' node, then the ceiling alone.
    assert_eq!(after.nodes_visited, 2 * up.len() as u64);
    assert_eq!(after.prims_tested, up.len() as u64);
    assert!(
        before.prims_tested > 2 * after.prims_tested,
        "{before:?} vs {after:?}"
    );
}

/// Rays that meet nothing (from the object, low and to the side: through
/// the object's box and the walls' node's box, out under the ceiling's
/// edge, the ones that miss every small box) visit every box they enter
/// whatever the order: equal work.
#[test]
fn unoccluded_rays_do_the_same_work() {
    let (unordered, boxes) = room();
    let mut ordered = unordered.clone();
    ordered.order_lanes_for_any_hit(&boxes, &COSTS);
    let mut rng = Rng(9);
    let sideways: Vec<(Vec3, Vec3)> = (0..2000)
        .map(|_| {
            let o = Vec3::new(
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
            );
            let d = Vec3::new(-1.0, rng.range(-0.2, 0.2), rng.range(0.1, 0.15)).normalize();
            (o, d)
        })
        .filter(|&(o, d)| !boxes.iter().any(|b| slab_hit(o, d, b, f32::INFINITY)))
        .collect();
    assert!(sideways.len() > 100, "{} unoccluded rays", sideways.len());
    let (hits_before, before) = any_hits(&unordered, &boxes, &sideways);
    let (hits_after, after) = any_hits(&ordered, &boxes, &sideways);
    assert!(hits_before.iter().chain(&hits_after).all(|&h| !h));
    assert_eq!(before, after);
    // They do enter the walls' node (its box reaches down to z = 0.9).
    assert!(after.nodes_visited > 2 * sideways.len() as u64, "{after:?}");
}
