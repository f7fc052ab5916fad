//! A geometry-agnostic bounding volume hierarchy.
//!
//! The BVH is built over bounding boxes and centroids only; it never sees a
//! triangle. Traversal hands primitive slots to a closure, so the caller owns
//! the intersection code and the primitive data. After building, the caller
//! reorders its primitives by [`Bvh::primitive_order`], so a leaf's
//! primitives are contiguous in memory.
//!
//! Layout after pbrt's `LinearBVHNode`: a flat array of 32-byte nodes in
//! depth-first order (see [`Node`]).
#![warn(missing_docs)]

mod aabb;
mod avx2;
mod build;
mod huge_pages;
mod node;
pub mod simd;
#[cfg(test)]
mod test_boxes;
mod traverse;
mod validate;
mod wide;
mod wide_collapse;
mod wide_fill;
mod wide_order;
mod wide_traverse;
mod wide_validate;

pub use aabb::Aabb;
pub use avx2::has_avx2;
pub use huge_pages::on_huge_pages;
pub use node::Node;
pub use traverse::{RayBoxQuery, StatsSink, TraversalStats};
pub use wide::{Bvh4, Bvh8, Node4, Node8, WideBvh, WideNode, PADDING};

use glam::Vec3;

/// How the hierarchy is split.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BuildStrategy {
    /// Binned surface area heuristic: the fast choice for rendering.
    #[default]
    Sah,
    /// Sort centroids on the longest axis and split at the middle (the CS184
    /// assignment's algorithm); kept as a baseline.
    Median,
    /// One leaf holding everything: brute force, the reference for tests.
    None,
}

/// How a binary tree is collapsed into a wide one ([`WideBvh::from_binary`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Collapse {
    /// Repeatedly open the child of largest area until the node is full;
    /// binary leaves stay leaves. The default of [`BuildOptions`]; the
    /// renderer's wide trees use [`Collapse::Sah`] (BENCHMARKS.md, "The SAH
    /// collapse" and "A leaf cost for the SAH collapse").
    #[default]
    Greedy,
    /// The collapse of least SAH cost, by dynamic programming over the
    /// binary nodes (Ylitie et al. 2017); it may also merge small subtrees
    /// into one leaf. See `wide_collapse.rs`.
    Sah,
}

/// Build parameters. The costs are relative; only their ratio matters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    /// Split strategy.
    pub strategy: BuildStrategy,
    /// Leaves never hold more than this (except with [`BuildStrategy::None`]);
    /// SAH may choose smaller leaves.
    pub max_leaf_size: usize,
    /// Cost of visiting a node, relative to `intersection_cost`.
    pub traversal_cost: f32,
    /// Cost of one primitive test.
    pub intersection_cost: f32,
    /// Primitives are tested in blocks of this many (e.g. 4 with SIMD
    /// packets), so the SAH charges a leaf `ceil(n / block)` tests and
    /// prefers leaf sizes that fill whole blocks. With [`Collapse::Sah`]
    /// it is the wide collapse that charges blocks (it chooses the leaves
    /// again, merging subtrees); the binary build then charges each
    /// primitive, so that the collapse has small leaves to choose from.
    pub leaf_block: usize,
    /// How a wide tree is collapsed from this binary one.
    pub collapse: Collapse,
    /// For [`Collapse::Sah`]: the cost of one wide node's box test, in the
    /// units of `intersection_cost` (the cost of one leaf block's test).
    /// By instruction counts a node step costs about 0.8 block tests, but
    /// its 256 bytes miss the cache more often on incoherent rays. Without a
    /// leaf cost, 0.5–1 gave the fewest instructions per ray and 2 the
    /// smallest trees but slower primary rays; with a leaf cost of 1–3,
    /// 1.5 keeps the instruction counts of 1 with fewer nodes than the
    /// greedy collapse (BENCHMARKS.md, "The SAH collapse" and "A leaf cost
    /// for the SAH collapse").
    pub wide_node_cost: f32,
    /// For [`Collapse::Sah`], and for the leaf splits of
    /// [`WideBvh::from_binary_filled`]: the cost of entering a leaf before
    /// its first block's test, in the units of `intersection_cost`. A
    /// leaf visit costs about 100 instructions before its first triangle
    /// (the leaf call and the ray's registers saved around it) against
    /// about 45 per block test and 35 per node step, so the measured ratio
    /// is about 2; 0 charges blocks only (BENCHMARKS.md, "A leaf cost for
    /// the SAH collapse").
    pub wide_leaf_cost: f32,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            strategy: BuildStrategy::Sah,
            max_leaf_size: 8,
            traversal_cost: 1.0,
            intersection_cost: 1.0,
            leaf_block: 1,
            collapse: Collapse::Greedy,
            wide_node_cost: 2.0,
            wide_leaf_cost: 0.0,
        }
    }
}

impl BuildOptions {
    /// Default options with another strategy.
    pub fn with_strategy(strategy: BuildStrategy) -> Self {
        Self {
            strategy,
            ..Self::default()
        }
    }
}

/// A built hierarchy: nodes plus the primitive order its leaves index.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    depth: u32,
    /// The options it was built with (the wide collapse reads its own).
    options: BuildOptions,
}

impl Bvh {
    /// Builds over `boxes[i]` with `centroids[i]` (the point used to sort
    /// primitive `i`; usually its box centre). Extra entries in the longer
    /// slice are ignored. Never fails: empty input gives an empty tree, and
    /// inputs the SAH cannot separate (equal centroids, infinite boxes) fall
    /// back to median splits.
    pub fn build(boxes: &[Aabb], centroids: &[Vec3], opts: BuildOptions) -> Self {
        let (nodes, order, depth) = build::build(boxes, centroids, opts);
        Self {
            nodes,
            order,
            depth,
            options: opts,
        }
    }

    /// The options the tree was built with.
    pub fn options(&self) -> &BuildOptions {
        &self.options
    }

    /// `primitive_order()[slot]` is the caller's index of the primitive in
    /// `slot`; leaves refer to slots.
    pub fn primitive_order(&self) -> &[u32] {
        &self.order
    }

    /// The flat node array, root first.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Number of levels (1 for a single leaf, 0 when empty).
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Memory held by nodes and the primitive order.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + self.order.len() * 4
    }

    /// Box of everything, empty for an empty tree.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, Node::bounds)
    }
}
