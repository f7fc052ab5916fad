//! Wide BVHs (4 or 8 children per node) collapsed from the binary one, for
//! SIMD box tests.
//!
//! Each node holds the boxes of up to `W` children in structure-of-arrays
//! form, so one set of `W`-lane operations tests all of them (as in
//! Embree's BVH4/BVH8 and Wald et al., "Getting Rid of Packets", 2008).
//! By default ([`crate::Collapse::Greedy`]) collapsing repeatedly opens the
//! child with the largest surface area, the one the SAH deems most likely to
//! be visited, until `W` children are reached (the greedy collapse of Wald
//! et al. and of pbrt-v4's wide BVH discussions); a leaf is never opened.
//! [`crate::Collapse::Sah`] instead takes the collapse of least SAH cost,
//! found by dynamic programming over the binary nodes (Ylitie et al. 2017,
//! `wide_collapse.rs`), which may also merge small subtrees into one leaf.
//! Either way the
//! primitive order is the binary tree's, unless
//! [`WideBvh::from_binary_filled`] then splits leaves of two SIMD blocks
//! into the lanes still free (`wide_fill.rs`).
//! [`Bvh4`] is traversed with SSE (baseline on x86_64), [`Bvh8`] with AVX2
//! where the CPU has it and two SSE halves otherwise.

use crate::node::Node;
use crate::wide_collapse::{CollapseCosts, SahCollapse};
use crate::wide_fill::{Lane, LeafSplitter};
use crate::{Aabb, Bvh, Collapse};

/// The primitive order's entry for an unused slot (see [`WideBvh::pad_leaves`]).
pub const PADDING: u32 = u32::MAX;

/// `W` child boxes and references, cache-line aligned (128 bytes for
/// [`Node4`], 256 for [`Node8`]).
///
/// Rows of `bounds`: min x, min y, min z, max x, max y, max z; lane `i`
/// belongs to child `i`. An unused lane has an empty box (`min = +inf`,
/// `max = -inf`), which no ray enters.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct WideNode<const W: usize> {
    /// Child boxes, one lane per child.
    pub bounds: [[f32; W]; 6],
    /// Interior child: its node index. Leaf child: its first primitive slot.
    pub child: [u32; W],
    /// Leaf child: its primitive count. Zero for an interior child or an unused lane.
    pub count: [u32; W],
}

/// A node of the 4-wide tree.
pub type Node4 = WideNode<4>;
/// A node of the 8-wide tree.
pub type Node8 = WideNode<8>;

const _: () = assert!(std::mem::size_of::<Node4>() == 128);
const _: () = assert!(std::mem::size_of::<Node8>() == 256);

impl<const W: usize> WideNode<W> {
    const EMPTY: Self = Self {
        bounds: [
            [f32::INFINITY; W],
            [f32::INFINITY; W],
            [f32::INFINITY; W],
            [f32::NEG_INFINITY; W],
            [f32::NEG_INFINITY; W],
            [f32::NEG_INFINITY; W],
        ],
        child: [0; W],
        count: [0; W],
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

/// A wide hierarchy; see the module docs.
#[derive(Clone, Debug, Default)]
pub struct WideBvh<const W: usize> {
    pub(crate) nodes: Vec<WideNode<W>>,
    pub(crate) order: Vec<u32>,
    pub(crate) depth: u32,
    /// Traverse with AVX2 (8-wide trees only; set when the CPU has it).
    pub(crate) avx2: bool,
}

/// The 4-wide hierarchy (SSE).
pub type Bvh4 = WideBvh<4>;
/// The 8-wide hierarchy (AVX2, with an SSE fallback).
pub type Bvh8 = WideBvh<8>;

impl<const W: usize> WideBvh<W> {
    /// Collapses a binary BVH as its build options say
    /// ([`crate::BuildOptions::collapse`]), taking over its primitive order.
    pub fn from_binary(bvh: Bvh) -> Self {
        Self::collapse(bvh, None)
    }

    /// Collapses a binary BVH and fills the lanes left empty by splitting
    /// leaves of `block + 1 ..= 2 * block` primitives into two of at most
    /// `block` (by the SAH with free box tests, largest leaf first): for
    /// callers that test leaves in SIMD blocks of `block`. `boxes` are the
    /// primitive boxes the tree was built over; the primitive order is
    /// permuted within leaves. With too few boxes (not the tree's input)
    /// nothing is split.
    pub fn from_binary_filled(bvh: Bvh, boxes: &[Aabb], block: u32) -> Self {
        let block = block.max(1);
        Self::collapse(bvh, Some((boxes, block)))
    }

    fn collapse(bvh: Bvh, fill: Option<(&[Aabb], u32)>) -> Self {
        let Bvh {
            nodes: bin,
            mut order,
            options,
            ..
        } = bvh;
        let mut nodes = Vec::with_capacity(bin.len() / (W / 2).max(1) + 1);
        let mut depth = 0;
        // Boxes that are not the tree's input (too few) neither split
        // leaves nor order lanes.
        let input_boxes =
            fill.filter(|(boxes, _)| order.iter().all(|&i| (i as usize) < boxes.len()));
        let mut splitter = input_boxes.map(|(boxes, block)| LeafSplitter {
            boxes,
            order: &mut order,
            block,
            leaf_cost: options.wide_leaf_cost / options.intersection_cost.max(f32::MIN_POSITIVE),
        });
        let costs = CollapseCosts {
            node: options.wide_node_cost,
            block: options.intersection_cost,
            leaf: options.wide_leaf_cost,
            // Blocks as the leaves are tested: the fill's, else the build's.
            block_size: fill.map_or(options.leaf_block, |(_, b)| b as usize).max(1) as u32,
            max_leaf: options.max_leaf_size.max(1) as u32,
        };
        if !bin.is_empty() {
            let opening = match options.collapse {
                Collapse::Greedy => Opening::Greedy,
                Collapse::Sah => Opening::Sah(SahCollapse::new(&bin, costs)),
            };
            let root = if bin[0].is_leaf() {
                vec![Lane::of(&bin, 0)]
            } else {
                opening.lanes(&bin, 0)
            };
            depth = emit(&bin, root, &opening, &mut nodes, 1, &mut splitter);
        }
        let mut tree = Self {
            nodes,
            order,
            depth,
            avx2: W == 8 && crate::avx2::has_avx2(),
        };
        if let Some((boxes, _)) = input_boxes {
            tree.order_lanes_for_any_hit(boxes, &costs);
        }
        tree.nodes = crate::on_huge_pages(tree.nodes);
        tree
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
            for lane in 0..W {
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
    /// `slot`, or [`PADDING`] for a gap left by [`WideBvh::pad_leaves`].
    pub fn primitive_order(&self) -> &[u32] {
        &self.order
    }

    /// The node array, root first.
    pub fn nodes(&self) -> &[WideNode<W>] {
        &self.nodes
    }

    /// Levels of wide nodes.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Memory held by nodes and the primitive order.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<WideNode<W>>() + self.order.len() * 4
    }
}

impl Bvh8 {
    /// Whether queries run the AVX2 node test (true by default where the CPU
    /// supports AVX2 and FMA).
    pub fn uses_avx2(&self) -> bool {
        self.avx2
    }

    /// Chooses the node test: AVX2 (ignored where the CPU lacks it) or the
    /// portable one of two 4-lane halves. For tests and benchmarks that
    /// compare the two; both give identical answers.
    pub fn set_avx2(&mut self, on: bool) {
        self.avx2 = on && crate::avx2::has_avx2();
    }
}

/// How the lanes of a wide node are chosen.
enum Opening<const W: usize> {
    /// Open the child of largest area until full.
    Greedy,
    /// Read the lanes from the table of least SAH cost.
    Sah(SahCollapse<W>),
}

impl<const W: usize> Opening<W> {
    /// The lanes of the wide node made for the binary interior node `i`.
    fn lanes(&self, bin: &[Node], i: usize) -> Vec<Lane> {
        match self {
            Opening::Sah(table) => table.lanes(bin, i),
            Opening::Greedy => {
                let mut lanes = vec![i + 1, bin[i].offset as usize];
                while lanes.len() < W {
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
                lanes.into_iter().map(|i| Lane::of(bin, i)).collect()
            }
        }
    }
}

/// Writes a node with `lanes` (and, recursively, below); returns the depth
/// reached.
fn emit<const W: usize>(
    bin: &[Node],
    mut lanes: Vec<Lane>,
    opening: &Opening<W>,
    out: &mut Vec<WideNode<W>>,
    depth: u32,
    splitter: &mut Option<LeafSplitter>,
) -> u32 {
    if let Some(s) = splitter {
        s.fill(&mut lanes, W);
    }
    let me = out.len();
    out.push(WideNode::EMPTY);
    let mut deepest = depth;
    for (lane, l) in lanes.into_iter().enumerate() {
        match l {
            Lane::Leaf {
                bounds,
                first,
                count,
            } => {
                out[me].set_lane(lane, bounds);
                out[me].child[lane] = first;
                out[me].count[lane] = count;
            }
            Lane::Node(i) => {
                out[me].set_lane(lane, bin[i].bounds());
                out[me].child[lane] = out.len() as u32;
                let below = opening.lanes(bin, i);
                let d = emit(bin, below, opening, out, depth + 1, splitter);
                deepest = deepest.max(d);
            }
        }
    }
    deepest
}
