//! Tests of the SAH collapse: optimal against an exhaustive search on small
//! trees, never dearer than the greedy collapse, valid and deterministic.

use super::{CollapseCosts, SahCollapse};
use crate::node::Node;
use crate::{Aabb, BuildOptions, Bvh, Bvh4, Bvh8, Collapse, WideBvh};
use candela_testkit::SplitMix64 as Rng;
use glam::Vec3;

fn random_boxes(rng: &mut Rng, n: usize, size: f32) -> Vec<Aabb> {
    (0..n)
        .map(|_| {
            let c = rng.vec(-10.0, 10.0);
            let h = rng.vec(0.01, size);
            Aabb::new(c - h, c + h)
        })
        .collect()
}

fn build(boxes: &[Aabb], opts: BuildOptions) -> Bvh {
    let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
    Bvh::build(boxes, &centroids, opts)
}

/// Exhaustive search: the cheapest cost of binary node `n` as one lane,
/// trying every cut of its subtree into at most `W` lanes.
struct Exhaustive<'a, const W: usize> {
    bin: &'a [Node],
    costs: CollapseCosts,
}

impl<const W: usize> Exhaustive<'_, W> {
    fn count(&self, n: usize) -> u32 {
        let b = &self.bin[n];
        if b.is_leaf() {
            b.count
        } else {
            self.count(n + 1) + self.count(b.offset as usize)
        }
    }

    /// Every set of at most `budget` disjoint subtrees covering `m`'s.
    fn cuts(&self, m: usize, budget: usize) -> Vec<Vec<usize>> {
        let mut out = vec![vec![m]];
        let b = &self.bin[m];
        if !b.is_leaf() && budget >= 2 {
            for left in self.cuts(m + 1, budget - 1) {
                for right in self.cuts(b.offset as usize, budget - left.len()) {
                    out.push([left.clone(), right].concat());
                }
            }
        }
        out
    }

    fn opened(&self, n: usize) -> f32 {
        let b = &self.bin[n];
        let mut best = f32::INFINITY;
        for left in self.cuts(n + 1, W - 1) {
            for right in self.cuts(b.offset as usize, W - left.len()) {
                let c: f32 = left.iter().chain(&right).map(|&m| self.lane(m)).sum();
                best = best.min(c);
            }
        }
        b.bounds().half_area() * self.costs.node + best
    }

    fn lane(&self, n: usize) -> f32 {
        let b = &self.bin[n];
        let count = self.count(n);
        let leaf = b.bounds().half_area()
            * self.costs.block
            * count.div_ceil(self.costs.block_size) as f32;
        if b.is_leaf() {
            leaf
        } else if count <= self.costs.max_leaf {
            leaf.min(self.opened(n))
        } else {
            self.opened(n)
        }
    }
}

fn costs(opts: &BuildOptions) -> CollapseCosts {
    CollapseCosts {
        node: opts.wide_node_cost,
        block: opts.intersection_cost,
        block_size: opts.leaf_block as u32,
        max_leaf: opts.max_leaf_size as u32,
    }
}

/// On small trees (one or two primitives per binary leaf, so merging
/// leaves is a real choice), the table's optimum equals an exhaustive
/// search over every collapse, and the emitted tree has that cost.
#[test]
fn table_optimum_matches_exhaustive_search() {
    let mut rng = Rng(11);
    for (n, max_leaf, node) in [(12, 4, 1.0), (20, 8, 0.5), (24, 8, 2.0), (30, 4, 1.0)] {
        let boxes = random_boxes(&mut rng, n, 2.0);
        let opts = BuildOptions {
            max_leaf_size: max_leaf,
            leaf_block: 4,
            intersection_cost: 4.0, // binary leaves of one or two primitives
            wide_node_cost: node,
            collapse: Collapse::Sah,
            ..BuildOptions::default()
        };
        let opts_collapse = BuildOptions {
            intersection_cost: 1.0,
            ..opts
        };
        // Build with small leaves, collapse with block cost 1.
        let bvh = build(&boxes, opts);
        let boxes_bvh = Bvh {
            options: opts_collapse,
            ..bvh
        };
        assert!(boxes_bvh.nodes().len() > 8, "n={n}: too small a tree");
        check_optimal_of::<4>(&boxes, boxes_bvh.clone());
        check_optimal_of::<8>(&boxes, boxes_bvh);
    }
}

fn check_optimal_of<const W: usize>(boxes: &[Aabb], bvh: Bvh) {
    let opts = *bvh.options();
    let bin = bvh.nodes();
    let table = SahCollapse::<W>::new(bin, costs(&opts));
    let exhaustive = Exhaustive::<W> {
        bin,
        costs: costs(&opts),
    }
    .opened(0);
    let tol = 1e-4 * exhaustive;
    assert!(
        (table.total - exhaustive).abs() <= tol,
        "W={W}: table {} exhaustive {exhaustive}",
        table.total
    );
    let root_area = bin[0].bounds().half_area() as f64;
    let tree = WideBvh::<W>::from_binary(bvh);
    tree.validate(boxes).unwrap();
    let emitted = tree.sah_cost(opts.wide_node_cost, opts.leaf_block as u32) * root_area;
    assert!(
        (emitted - exhaustive as f64).abs() <= 2.0 * tol as f64,
        "W={W}: emitted {emitted} exhaustive {exhaustive}"
    );
}

/// The greedy collapse is one of the collapses the table ranges over, so
/// the SAH collapse never costs more (on random inputs of several sizes
/// and node costs), and on these inputs it costs less overall.
#[test]
fn sah_collapse_never_dearer_than_greedy() {
    let mut rng = Rng(12);
    let (mut greedy_sum, mut sah_sum) = (0.0, 0.0);
    for (n, size, node) in [
        (200, 1.0, 1.0),
        (3000, 0.3, 0.5),
        (3000, 2.0, 1.0),
        (8000, 0.1, 2.0),
    ] {
        let boxes = random_boxes(&mut rng, n, size);
        let opts = BuildOptions {
            leaf_block: 4,
            wide_node_cost: node,
            collapse: Collapse::Sah,
            ..BuildOptions::default()
        };
        let bvh = build(&boxes, opts);
        let greedy = |bvh: &Bvh| Bvh {
            options: BuildOptions {
                collapse: Collapse::Greedy,
                ..opts
            },
            ..bvh.clone()
        };
        let pairs = [
            (
                Bvh8::from_binary(greedy(&bvh)).sah_cost(node, 4),
                Bvh8::from_binary(bvh.clone()).sah_cost(node, 4),
            ),
            (
                Bvh4::from_binary(greedy(&bvh)).sah_cost(node, 4),
                Bvh4::from_binary(bvh.clone()).sah_cost(node, 4),
            ),
        ];
        for (g, s) in pairs {
            assert!(
                s <= g * (1.0 + 1e-5),
                "n={n}: SAH collapse {s} > greedy {g}"
            );
            greedy_sum += g;
            sah_sum += s;
        }
    }
    assert!(sah_sum < 0.99 * greedy_sum, "{sah_sum} vs {greedy_sum}");
}

/// The collapse reads only the binary tree, which the build makes the same
/// for any thread count: one and two threads give identical wide trees.
#[test]
fn same_wide_tree_for_any_thread_count() {
    let boxes = random_boxes(&mut Rng(13), 20_000, 0.3);
    let opts = BuildOptions {
        leaf_block: 4,
        collapse: Collapse::Sah,
        ..BuildOptions::default()
    };
    let on = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| Bvh8::from_binary_filled(build(&boxes, opts), &boxes, 4))
    };
    let (one, two) = (on(1), on(2));
    one.validate(&boxes).unwrap();
    assert_eq!(one.nodes(), two.nodes());
    assert_eq!(one.primitive_order(), two.primitive_order());
}
