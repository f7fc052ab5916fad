//! The collapse of least SAH cost, from a binary tree to a `W`-wide one.
//!
//! After Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on
//! GPUs Through Compressed Wide BVHs" (HPG 2017), section 4: the greedy
//! collapse ([`crate::Collapse::Greedy`]) opens the child of largest area
//! until a node is full, which says nothing about what the lanes cost
//! below; here a dynamic programme over the binary nodes finds, for every
//! binary node `n` and every lane budget `i ≤ W`, the cheapest way to cover
//! `n`'s subtree with at most `i` lanes, and the wide tree is read back from
//! the choices. With `A(n)` the surface area of `n`'s box (the chance that a
//! ray through the root enters it, up to a constant):
//!
//! - one lane as a leaf: `C_leaf(n) = A(n) · (c_leaf + c_block ·
//!   ⌈count(n) / block⌉)`, allowed for up to `max_leaf` primitives (a
//!   binary leaf is always one);
//! - one lane as a wide node: `C_node(n) = A(n) · c_node + D(n, W)`, where
//!   `D(n, j) = min_{0<k<j} C(left, k) + C(right, j − k)` spreads `j` lanes
//!   over the two children;
//! - `C(n, 1) = min(C_leaf, C_node)`, `C(n, i) = min(D(n, i), C(n, i − 1))`.
//!
//! Unlike the paper's, our leaves are tested in SIMD blocks, so the leaf
//! cost counts blocks, not primitives, and the leaf limit is the build's
//! (two blocks). The paper's leaf costs only its triangles; ours may also
//! charge `c_leaf` per leaf entered, for what a leaf visit costs before its
//! first block (the out-of-line leaf call and the ray's registers saved
//! around it; BENCHMARKS.md, "Leaf runs and the closest-hit leaf call").
//! Measured, it saved no instructions on any ray set and made flat patches
//! dearer ("A leaf cost for the SAH collapse"), so the renderer charges none;
//! it stays an option for trees whose leaf visits cost more.
//!
//! The table is filled children first (a binary child's index
//! is larger than its parent's), in index order, so the result is the same
//! for any number of build threads.

use crate::node::Node;
use crate::wide_fill::Lane;
use crate::{Aabb, WideBvh};

/// The costs the collapse minimises.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CollapseCosts {
    /// One wide node's box test.
    pub(crate) node: f32,
    /// One leaf block's test.
    pub(crate) block: f32,
    /// Entering a leaf, before its first block.
    pub(crate) leaf: f32,
    /// Primitives per leaf block.
    pub(crate) block_size: u32,
    /// The most primitives a merged leaf may hold.
    pub(crate) max_leaf: u32,
}

impl CollapseCosts {
    /// The cost of a leaf lane of `count` primitives whose box has half
    /// area `area`.
    pub(crate) fn leaf_lane(&self, area: f32, count: u32) -> f32 {
        area * (self.leaf + self.block * count.div_ceil(self.block_size.max(1)) as f32)
    }
}

/// The filled table: per binary node, the best cost and choice for each
/// lane budget, and the node's primitive range.
pub(crate) struct SahCollapse<const W: usize> {
    /// `choice[n][i - 1]` for a budget of `i` lanes: 0 for "as with
    /// `i - 1`" (or, at `i = 1`, a leaf), else the lanes given to the left child.
    choice: Vec<[u8; W]>,
    /// Whether `n` as one lane is a wide node (else a leaf).
    opened: Vec<bool>,
    /// First slot and primitive count of `n`'s subtree.
    range: Vec<(u32, u32)>,
    /// `D(n, W)`'s split for an opened `n`: lanes for the left child.
    node_split: Vec<u8>,
    /// The cost of the whole tree, the root opened (in area units, not
    /// divided by the root's area).
    #[cfg_attr(not(test), allow(dead_code))]
    pub(crate) total: f32,
}

impl<const W: usize> SahCollapse<W> {
    /// Fills the table for the binary tree `bin` (depth-first: the left
    /// child follows its parent, `offset` is the right child).
    pub(crate) fn new(bin: &[Node], costs: CollapseCosts) -> Self {
        let n = bin.len();
        let mut cost = vec![[0.0f32; W]; n];
        let mut choice = vec![[0u8; W]; n];
        let mut opened = vec![false; n];
        let mut range = vec![(0u32, 0u32); n];
        let mut node_split = vec![0u8; n];
        let mut total = 0.0;
        for i in (0..n).rev() {
            let b = &bin[i];
            let area = b.bounds().half_area();
            if b.is_leaf() {
                range[i] = (b.offset, b.count);
                let leaf = costs.leaf_lane(area, b.count);
                cost[i] = [leaf; W];
                total = leaf;
                continue;
            }
            let (l, r) = (i + 1, b.offset as usize);
            range[i] = (range[l].0, range[l].1 + range[r].1);
            // D(i, j) for j = 2..=W, with the best split of each.
            // (A split of one lane to the left stands when every cost is
            // infinite, e.g. for infinite boxes.)
            let mut dist = [(f32::INFINITY, 1u8); W];
            for j in 2..=W {
                for k in 1..j {
                    let c = cost[l][k - 1] + cost[r][j - k - 1];
                    if c < dist[j - 1].0 {
                        dist[j - 1] = (c, k as u8);
                    }
                }
            }
            let count = range[i].1;
            let as_leaf = if count <= costs.max_leaf {
                costs.leaf_lane(area, count)
            } else {
                f32::INFINITY
            };
            let as_node = area * costs.node + dist[W - 1].0;
            if i == 0 {
                total = as_node;
            }
            opened[i] = as_node < as_leaf || count > costs.max_leaf;
            node_split[i] = dist[W - 1].1;
            cost[i][0] = as_leaf.min(as_node);
            for j in 2..=W {
                let (c, k) = dist[j - 1];
                if c < cost[i][j - 2] {
                    cost[i][j - 1] = c;
                    choice[i][j - 1] = k;
                } else {
                    cost[i][j - 1] = cost[i][j - 2];
                }
            }
        }
        Self {
            choice,
            opened,
            range,
            node_split,
            total,
        }
    }

    /// The lanes of the wide node made for the opened binary node `i`
    /// (the root is always opened).
    pub(crate) fn lanes(&self, bin: &[Node], i: usize) -> Vec<Lane> {
        let mut out = Vec::with_capacity(W);
        let k = self.node_split[i] as usize;
        self.spread(bin, i + 1, k, &mut out);
        self.spread(bin, bin[i].offset as usize, W - k, &mut out);
        out
    }

    /// Appends the lanes covering `i`'s subtree with at most `budget` lanes.
    fn spread(&self, bin: &[Node], i: usize, budget: usize, out: &mut Vec<Lane>) {
        let mut j = budget;
        while j > 1 && self.choice[i][j - 1] == 0 {
            j -= 1;
        }
        if j > 1 {
            let k = self.choice[i][j - 1] as usize;
            self.spread(bin, i + 1, k, out);
            self.spread(bin, bin[i].offset as usize, j - k, out);
        } else if self.opened[i] {
            out.push(Lane::Node(i));
        } else {
            let (first, count) = self.range[i];
            out.push(Lane::Leaf {
                bounds: bin[i].bounds(),
                first,
                count,
            });
        }
    }
}

impl<const W: usize> WideBvh<W> {
    /// The tree's SAH cost: `(Σ A(node) · node_cost + Σ A(leaf) ·
    /// (leaf_cost + ⌈count / block⌉)) / A(root)` over wide nodes and leaf
    /// lanes, the expected cost of the node, leaf and block tests of a ray
    /// through the root's box that hits nothing, in block tests (what
    /// [`crate::Collapse::Sah`] minimises).
    pub fn sah_cost(&self, node_cost: f32, leaf_cost: f32, block: u32) -> f64 {
        let Some(root) = self.nodes.first() else {
            return 0.0;
        };
        let root_box = (0..W).fold(Aabb::EMPTY, |b, l| b.union(root.lane_bounds(l)));
        let mut total = node_cost as f64 * root_box.half_area() as f64;
        for n in &self.nodes {
            for l in 0..W {
                let area = n.lane_bounds(l).half_area() as f64;
                if n.count[l] > 0 {
                    let blocks = n.count[l].div_ceil(block.max(1)) as f64;
                    total += area * (leaf_cost as f64 + blocks);
                } else if !n.lane_bounds(l).is_empty() {
                    total += area * node_cost as f64;
                }
            }
        }
        total / (root_box.half_area() as f64).max(f64::MIN_POSITIVE)
    }
}

#[cfg(test)]
#[path = "wide_collapse_tests.rs"]
mod tests;
