//! Filling the lanes a greedy collapse leaves empty by splitting leaves.
//!
//! The collapse ([`crate::wide`]) opens interior nodes only, so a node
//! whose children are mostly leaves keeps empty lanes (maxplanck: 3,261
//! 8-wide nodes for 4,512 4-wide ones). A leaf of more than one SIMD block
//! (5–8 triangles in blocks of 4) costs two block tests whenever its box is
//! entered; split into two leaves of one block each, with their own boxes,
//! it costs one test per part entered, and the extra box tests ride in the
//! node's SIMD test for free. By the SAH with free box tests, splitting a
//! leaf `P` into `L` and `R` pays when `A(L) + A(R) < 2 A(P)` (areas as the
//! chance that a ray through the parent enters each), which holds unless
//! both parts span the whole box. Embree's wide builders get the same effect
//! by opening any child of more than a leaf's minimum size while the node
//! has room (Wald et al., "Embree: A Kernel Framework for Efficient CPU Ray
//! Tracing", 2014); here the binary SAH tree is kept and only its leaves of
//! more than one block are split, largest box first, while lanes are free.
//! With a cost `c` for entering a leaf (in block tests,
//! [`crate::BuildOptions::wide_leaf_cost`]) the split pays when
//! `(c + 1) (A(L) + A(R)) < (c + 2) A(P)`: each part entered is a leaf
//! visit of its own.

use crate::Aabb;

/// A lane being filled: a binary node to emit (index), or a leaf.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Lane {
    /// An interior node of the binary tree.
    Node(usize),
    /// A leaf over slots `first .. first + count`, with its box.
    Leaf {
        bounds: Aabb,
        first: u32,
        count: u32,
    },
}

impl Lane {
    /// Binary node `i` as a lane: a leaf lane for a leaf, else a node.
    pub(crate) fn of(bin: &[crate::node::Node], i: usize) -> Self {
        match bin[i] {
            b if b.is_leaf() => Lane::Leaf {
                bounds: b.bounds(),
                first: b.offset,
                count: b.count,
            },
            _ => Lane::Node(i),
        }
    }
}

/// Splits leaves, given the primitive boxes (by caller's id) and the
/// primitive order, whose leaf ranges it permutes in place.
pub(crate) struct LeafSplitter<'a> {
    pub(crate) boxes: &'a [Aabb],
    pub(crate) order: &'a mut [u32],
    /// Primitives per SIMD block: leaves of `block + 1 ..= 2 * block` are split.
    pub(crate) block: u32,
    /// The cost of entering a leaf, in block tests.
    pub(crate) leaf_cost: f32,
}

impl LeafSplitter<'_> {
    /// Splits leaf lanes of two blocks into two lanes of one, largest box
    /// first, until `width` lanes are used or no split pays.
    pub(crate) fn fill(&mut self, lanes: &mut Vec<Lane>, width: usize) {
        let mut kept = vec![false; width];
        while lanes.len() < width {
            let widest = lanes
                .iter()
                .enumerate()
                .filter_map(|(k, l)| match *l {
                    Lane::Leaf { bounds, count, .. }
                        if !kept[k] && count > self.block && count <= 2 * self.block =>
                    {
                        Some((k, bounds.half_area()))
                    }
                    _ => None,
                })
                .max_by(|a, b| a.1.total_cmp(&b.1));
            let Some((k, _)) = widest else { break };
            let Lane::Leaf { first, count, .. } = lanes[k] else {
                unreachable!("only leaf lanes are chosen")
            };
            match self.split(first, count) {
                Some((left, n_left, right)) => {
                    lanes[k] = Lane::Leaf {
                        bounds: left,
                        first,
                        count: n_left,
                    };
                    lanes.push(Lane::Leaf {
                        bounds: right,
                        first: first + n_left,
                        count: count - n_left,
                    });
                }
                None => kept[k] = true,
            }
        }
    }

    /// The cheapest cut of slots `first .. first + count` into two parts of
    /// at most one block each, sorted by box centre along one axis: the
    /// left box, the left count and the right box, with the slots
    /// reordered to match; `None` when no cut lowers `A(L) + A(R)` below
    /// `(c + 2) / (c + 1) · A(P)` for leaf cost `c` (or a box is not finite).
    fn split(&mut self, first: u32, count: u32) -> Option<(Aabb, u32, Aabb)> {
        let boxes = self.boxes;
        let slots = &mut self.order[first as usize..(first + count) as usize];
        let n = slots.len();
        let block = self.block as usize;
        let union = |ids: &[u32]| {
            ids.iter()
                .fold(Aabb::EMPTY, |b, &i| b.union(boxes[i as usize]))
        };
        let leaf = self.leaf_cost.max(0.0);
        let bound = (leaf + 2.0) / (leaf + 1.0) * union(slots).half_area();
        let mut best: Option<(f32, Vec<u32>, usize)> = None;
        for axis in 0..3 {
            let mut ids = slots.to_vec();
            let key = |i: &u32| boxes[*i as usize].center()[axis];
            ids.sort_by(|a, b| key(a).total_cmp(&key(b)));
            for k in n.saturating_sub(block).max(1)..=block.min(n - 1) {
                let cost = union(&ids[..k]).half_area() + union(&ids[k..]).half_area();
                if cost < bound && best.as_ref().is_none_or(|b| cost < b.0) {
                    best = Some((cost, ids.clone(), k));
                }
            }
        }
        let (_, ids, k) = best?;
        slots.copy_from_slice(&ids);
        Some((union(&ids[..k]), k as u32, union(&ids[k..])))
    }
}

#[cfg(test)]
mod tests {
    use super::LeafSplitter;
    use crate::test_boxes::{build, random_boxes};
    use crate::{Aabb, BuildOptions, Bvh, Bvh8, Collapse, WideBvh};
    use candela_testkit::SplitMix64 as Rng;

    /// The binary tree the greedy collapse starts from, leaves in blocks of 4.
    fn greedy_tree(boxes: &[Aabb]) -> Bvh {
        let opts = BuildOptions {
            leaf_block: 4,
            collapse: Collapse::Greedy,
            ..BuildOptions::default()
        };
        build(boxes, opts)
    }

    /// Leaf sizes per node: (lanes used, sizes of the leaf lanes).
    fn leaves<const W: usize>(t: &WideBvh<W>) -> Vec<(usize, Vec<u32>)> {
        t.nodes()
            .iter()
            .map(|n| {
                let used = (0..W).filter(|&l| !n.lane_bounds(l).is_empty()).count();
                (used, n.count.iter().copied().filter(|&c| c > 0).collect())
            })
            .collect()
    }

    /// With blocks of 4, no leaf of 5–8 boxes is left beside a free lane
    /// (random boxes: every split lowers the area sum), the splits did
    /// happen, and nothing else changed: same nodes, same primitives per
    /// node. Too few boxes (not the tree's input) split nothing.
    #[test]
    fn two_block_leaves_fill_free_lanes() {
        let boxes = random_boxes(&mut Rng(7), 3000, 0.3);
        let bvh = greedy_tree(&boxes);
        let plain = leaves(&Bvh8::from_binary(bvh.clone()));
        let filled_tree = Bvh8::from_binary_filled(bvh.clone(), &boxes, 4);
        filled_tree.validate(&boxes).unwrap();
        let filled = leaves(&filled_tree);
        assert_eq!(plain.len(), filled.len());
        let mut splits = 0;
        for ((used0, sizes0), (used, sizes)) in plain.iter().zip(&filled) {
            assert_eq!(sizes0.iter().sum::<u32>(), sizes.iter().sum::<u32>());
            assert!(used >= used0);
            splits += used - used0;
            if *used < 8 {
                assert!(sizes.iter().all(|&c| c <= 4 || c > 8), "{sizes:?}");
            }
        }
        let two_block = plain
            .iter()
            .flat_map(|(_, s)| s)
            .filter(|&&c| c > 4)
            .count();
        assert!(two_block > 10 && splits > 0, "{splits} of {two_block}");
        let unsplit = Bvh8::from_binary_filled(bvh.clone(), &boxes[..10], 4);
        assert_eq!(unsplit.primitive_order(), bvh.primitive_order());
        assert_eq!(leaves(&unsplit), plain);
    }

    /// A leaf cost makes a split pay only when it shrinks the boxes more:
    /// on the two-block leaves of a tree over random boxes, every split
    /// made at leaf cost 3 has `A(L) + A(R) < 5/4 A(P)`, and fewer leaves
    /// are split than at leaf cost 0, but some still are.
    #[test]
    fn leaf_cost_splits_fewer_leaves() {
        let boxes = random_boxes(&mut Rng(8), 3000, 1.0);
        let bvh = greedy_tree(&boxes);
        let two_block: Vec<(u32, u32)> = bvh
            .nodes()
            .iter()
            .filter(|n| n.is_leaf() && n.count > 4)
            .map(|n| (n.offset, n.count))
            .collect();
        let splits = |leaf_cost: f32| {
            let mut order = bvh.primitive_order().to_vec();
            let mut splitter = LeafSplitter {
                boxes: &boxes,
                order: &mut order,
                block: 4,
                leaf_cost,
            };
            let mut made = 0;
            for &(first, count) in &two_block {
                let parent = (first..first + count)
                    .map(|s| boxes[bvh.primitive_order()[s as usize] as usize])
                    .fold(Aabb::EMPTY, Aabb::union)
                    .half_area();
                if let Some((left, _, right)) = splitter.split(first, count) {
                    let bound = (leaf_cost + 2.0) / (leaf_cost + 1.0) * parent;
                    assert!(left.half_area() + right.half_area() < bound);
                    made += 1;
                }
            }
            made
        };
        let (cheap, dear) = (splits(0.0), splits(3.0));
        assert!(
            0 < dear && dear < cheap,
            "{dear} at leaf cost 3, {cheap} at 0 of {}",
            two_block.len()
        );
    }
}
