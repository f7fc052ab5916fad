//! Tests of the SAH collapse: optimal against an exhaustive search on small
//! trees, never dearer than the greedy collapse, valid and deterministic.

use super::{CollapseCosts, SahCollapse};
use crate::node::Node;
use crate::test_boxes::{build, random_boxes};
use crate::{Aabb, BuildOptions, Bvh, Bvh4, Bvh8, Collapse, WideBvh};
use candela_testkit::SplitMix64 as Rng;

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
        let leaf = self.costs.leaf_lane(b.bounds().half_area(), count);
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
        leaf: opts.wide_leaf_cost,
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
    for (n, max_leaf, node, leaf) in [
        (12, 4, 1.0, 0.0),
        (20, 8, 0.5, 0.0),
        (24, 8, 2.0, 0.0),
        (30, 4, 1.0, 0.0),
        (20, 8, 0.75, 2.0),
        (24, 8, 1.0, 3.0),
        (30, 4, 1.5, 1.0),
    ] {
        let boxes = random_boxes(&mut rng, n, 2.0);
        let opts = BuildOptions {
            max_leaf_size: max_leaf,
            leaf_block: 4,
            intersection_cost: 4.0, // binary leaves of one or two primitives
            wide_node_cost: node,
            wide_leaf_cost: leaf,
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
    let emitted = tree.sah_cost(
        opts.wide_node_cost,
        opts.wide_leaf_cost,
        opts.leaf_block as u32,
    ) * root_area;
    assert!(
        (emitted - exhaustive as f64).abs() <= 2.0 * tol as f64,
        "W={W}: emitted {emitted} exhaustive {exhaustive}"
    );
}

/// The greedy collapse is one of the collapses the table ranges over, so
/// the SAH collapse never costs more under the same cost model (on random
/// inputs of several sizes, node and leaf costs), and on these inputs it
/// costs less overall.
#[test]
fn sah_collapse_never_dearer_than_greedy() {
    let mut rng = Rng(12);
    let (mut greedy_sum, mut sah_sum) = (0.0, 0.0);
    for (n, size, node, leaf) in [
        (200, 1.0, 1.0, 0.0),
        (3000, 0.3, 0.5, 0.0),
        (3000, 2.0, 1.0, 0.0),
        (8000, 0.1, 2.0, 0.0),
        (3000, 0.3, 0.75, 2.0),
        (3000, 2.0, 1.0, 3.0),
        (8000, 0.1, 1.5, 1.0),
    ] {
        let boxes = random_boxes(&mut rng, n, size);
        let opts = BuildOptions {
            leaf_block: 4,
            wide_node_cost: node,
            wide_leaf_cost: leaf,
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
                Bvh8::from_binary(greedy(&bvh)).sah_cost(node, leaf, 4),
                Bvh8::from_binary(bvh.clone()).sah_cost(node, leaf, 4),
            ),
            (
                Bvh4::from_binary(greedy(&bvh)).sah_cost(node, leaf, 4),
                Bvh4::from_binary(bvh.clone()).sah_cost(node, leaf, 4),
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

/// The expected leaf visits of a ray through the root's box,
/// `Σ A(leaf) / A(root)` over leaf lanes.
fn leaf_visits<const W: usize>(tree: &WideBvh<W>) -> f64 {
    let root = tree.nodes()[0];
    let root_box = (0..W).fold(Aabb::EMPTY, |b, l| b.union(root.lane_bounds(l)));
    let leaves: f64 = tree
        .nodes()
        .iter()
        .flat_map(|n| (0..W).filter(|&l| n.count[l] > 0).map(|l| n.lane_bounds(l)))
        .map(|b| b.half_area() as f64)
        .sum();
    leaves / root_box.half_area() as f64
}

/// The leaf cost `c` enters the cost as `c · Σ A(leaf)`, so between two
/// optimal collapses at `c₁ < c₂` the exchange argument (each optimum is no
/// dearer than the other at its own `c`) gives `Σ A(leaf)` at `c₂` ≤ at
/// `c₁`: a dearer leaf never gives more expected leaf visits. On random
/// boxes at node costs 0.75 and 1.5, leaf costs 0, 1, 2, 3 (with float
/// slack of 1e-4), and the leaf visits fall overall from 0 to 3.
#[test]
fn dearer_leaf_never_more_leaf_visits() {
    let mut rng = Rng(14);
    for (n, size) in [(3000, 0.3), (6000, 1.0)] {
        let boxes = random_boxes(&mut rng, n, size);
        for node in [0.75, 1.5] {
            let visits: Vec<f64> = [0.0, 1.0, 2.0, 3.0]
                .iter()
                .map(|&leaf| {
                    let opts = BuildOptions {
                        leaf_block: 4,
                        wide_node_cost: node,
                        wide_leaf_cost: leaf,
                        collapse: Collapse::Sah,
                        ..BuildOptions::default()
                    };
                    let tree = Bvh8::from_binary(build(&boxes, opts));
                    tree.validate(&boxes).unwrap();
                    leaf_visits(&tree)
                })
                .collect();
            for w in visits.windows(2) {
                assert!(
                    w[1] <= w[0] * (1.0 + 1e-4),
                    "n={n} node {node}: leaf visits {visits:?}"
                );
            }
            assert!(
                visits[3] < 0.95 * visits[0],
                "n={n} node {node}: leaf visits {visits:?}"
            );
        }
    }
}
