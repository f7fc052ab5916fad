//! A 4-wide BVH collapsed from the binary one, for SIMD box tests.
//!
//! Each node holds the boxes of up to four children in
//! structure-of-arrays form, so one set of 4-lane operations tests all four
//! (as in Embree's BVH4 and Wald et al., "Getting Rid of Packets", 2008).
//! Collapsing repeatedly opens the child with the largest surface area, the
//! one most likely to be visited, until four children are reached. Leaves
//! and the primitive order are the binary tree's.

use crate::node::Node;
use crate::{Aabb, Bvh};

/// The primitive order's entry for an unused slot (see [`Bvh4::pad_leaves`]).
pub const PADDING: u32 = u32::MAX;

/// Four child boxes and references. 128 bytes, cache-line aligned.
///
/// Rows of `bounds`: min x, min y, min z, max x, max y, max z; lane `i`
/// belongs to child `i`. An unused lane has an empty box (`min = +inf`,
/// `max = -inf`), which no ray enters.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Node4 {
    /// Child boxes, one lane per child.
    pub bounds: [[f32; 4]; 6],
    /// Interior child: its node index. Leaf child: its first primitive slot.
    pub child: [u32; 4],
    /// Leaf child: its primitive count. Zero for an interior child or an unused lane.
    pub count: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<Node4>() == 128);

impl Node4 {
    const EMPTY: Node4 = Node4 {
        bounds: [
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
            [f32::NEG_INFINITY; 4],
        ],
        child: [0; 4],
        count: [0; 4],
    };

    /// The box of lane `i` (empty for an unused lane).
    pub fn lane_bounds(&self, i: usize) -> Aabb {
        let b = &self.bounds;
        Aabb::new(
            glam::Vec3::new(b[0][i], b[1][i], b[2][i]),
            glam::Vec3::new(b[3][i], b[4][i], b[5][i]),
        )
    }

    fn set_lane(&mut self, i: usize, b: Aabb) {
        for a in 0..3 {
            self.bounds[a][i] = b.min[a];
            self.bounds[3 + a][i] = b.max[a];
        }
    }
}

/// The 4-wide hierarchy; see the module docs.
#[derive(Clone, Debug, Default)]
pub struct Bvh4 {
    pub(crate) nodes: Vec<Node4>,
    pub(crate) order: Vec<u32>,
    pub(crate) depth: u32,
}

impl Bvh4 {
    /// Collapses a binary BVH, taking over its primitive order.
    pub fn from_binary(bvh: Bvh) -> Self {
        let mut nodes = Vec::with_capacity(bvh.nodes.len() / 2 + 1);
        let mut depth = 0;
        if !bvh.nodes.is_empty() {
            let root = if bvh.nodes[0].is_leaf() {
                vec![0]
            } else {
                vec![1, bvh.nodes[0].offset as usize]
            };
            depth = emit(&bvh.nodes, root, &mut nodes, 1);
        }
        Self {
            nodes,
            order: bvh.order,
            depth,
        }
    }

    /// Moves every leaf to start at a multiple of `block` slots, filling
    /// the gaps in the primitive order with [`PADDING`]. A caller that packs
    /// each leaf's primitives into blocks of `block` then finds a leaf's
    /// first block at `first / block`, with no lookup table between the
    /// node and the primitives (one dependent load less per leaf visited).
    pub fn pad_leaves(&mut self, block: u32) {
        let block = block.max(1);
        let mut leaves: Vec<(u32, usize, usize)> = Vec::new();
        for (i, n) in self.nodes.iter().enumerate() {
            for lane in 0..4 {
                if n.count[lane] > 0 {
                    leaves.push((n.child[lane], i, lane));
                }
            }
        }
        leaves.sort_unstable();
        let mut order = Vec::with_capacity(self.order.len() + 3 * leaves.len());
        for (first, node, lane) in leaves {
            let count = self.nodes[node].count[lane];
            let start = order.len() as u32;
            order.extend_from_slice(&self.order[first as usize..(first + count) as usize]);
            let padded = count.div_ceil(block) * block;
            order.resize((start + padded) as usize, PADDING);
            self.nodes[node].child[lane] = start;
        }
        self.order = order;
    }

    /// `primitive_order()[slot]` is the caller's index of the primitive in
    /// `slot`, or [`PADDING`] for a gap left by [`Bvh4::pad_leaves`].
    pub fn primitive_order(&self) -> &[u32] {
        &self.order
    }

    /// The node array, root first.
    pub fn nodes(&self) -> &[Node4] {
        &self.nodes
    }

    /// Levels of 4-wide nodes.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Memory held by nodes and the primitive order.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node4>() + self.order.len() * 4
    }
}

/// Writes a node for the binary nodes `lanes` (and, recursively, below);
/// returns the depth reached.
fn emit(bin: &[Node], mut lanes: Vec<usize>, out: &mut Vec<Node4>, depth: u32) -> u32 {
    while lanes.len() < 4 {
        let widest = lanes
            .iter()
            .enumerate()
            .filter(|(_, &i)| !bin[i].is_leaf())
            .max_by(|a, b| {
                bin[*a.1]
                    .bounds()
                    .half_area()
                    .total_cmp(&bin[*b.1].bounds().half_area())
            });
        let Some((k, &i)) = widest else { break };
        lanes[k] = i + 1;
        lanes.push(bin[i].offset as usize);
    }
    let me = out.len();
    out.push(Node4::EMPTY);
    let mut deepest = depth;
    for (lane, &i) in lanes.iter().enumerate() {
        let b = &bin[i];
        out[me].set_lane(lane, b.bounds());
        if b.is_leaf() {
            out[me].child[lane] = b.offset;
            out[me].count[lane] = b.count;
        } else {
            out[me].child[lane] = out.len() as u32;
            let d = emit(bin, vec![i + 1, b.offset as usize], out, depth + 1);
            deepest = deepest.max(d);
        }
    }
    deepest
}
