//! Building: binned SAH (parallel at the top levels), median split, or one leaf.
//!
//! Binned SAH after Wald, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies" (2007): centroids are dropped into a few bins per axis and
//! the split cost is evaluated only at bin boundaries, which is O(n) per node.

use crate::node::Node;
use crate::{Aabb, BuildOptions, BuildStrategy};
use glam::Vec3;

/// Ranges at least this large are split in parallel with `rayon::join`.
const PARALLEL_MIN: usize = 4096;
/// Bins per axis for the SAH sweep.
const BINS: usize = 16;
/// Below this depth the build may use SAH; deeper it uses object median
/// splits, which halve the range, so the tree depth stays below
/// `SAH_DEPTH_LIMIT + 32` and the fixed traversal stack never overflows.
pub(crate) const SAH_DEPTH_LIMIT: u32 = 48;

/// The inputs shared by every recursive call.
struct Ctx<'a> {
    boxes: &'a [Aabb],
    centroids: &'a [Vec3],
    opts: BuildOptions,
}

/// A built subtree: either laid out already (node indices local to the
/// vector) or a split whose children were built in parallel.
enum Subtree {
    Flat(Vec<Node>, u32),
    Split(Aabb, Box<Subtree>, Box<Subtree>, u32),
}

impl Subtree {
    fn depth(&self) -> u32 {
        match self {
            Subtree::Flat(_, d) | Subtree::Split(_, _, _, d) => *d,
        }
    }
}

/// Builds the flat node array and the primitive order; returns them with the depth.
pub(crate) fn build(
    boxes: &[Aabb],
    centroids: &[Vec3],
    opts: BuildOptions,
) -> (Vec<Node>, Vec<u32>, u32) {
    let n = boxes.len().min(centroids.len());
    let mut order: Vec<u32> = (0..n as u32).collect();
    if n == 0 {
        return (Vec::new(), order, 0);
    }
    let ctx = Ctx {
        boxes,
        centroids,
        opts,
    };
    let tree = build_parallel(&ctx, &mut order, 0, 1);
    let depth = tree.depth();
    let mut nodes = Vec::with_capacity(2 * n);
    flatten(tree, &mut nodes);
    (nodes, order, depth)
}

/// Appends `tree` to `out`, shifting subtree-local child indices.
fn flatten(tree: Subtree, out: &mut Vec<Node>) {
    match tree {
        Subtree::Flat(nodes, _) => {
            let base = out.len() as u32;
            out.extend(nodes.into_iter().map(|mut node| {
                if !node.is_leaf() {
                    node.offset += base;
                }
                node
            }));
        }
        Subtree::Split(bounds, left, right, _) => {
            let me = out.len();
            out.push(Node::interior(bounds, 0));
            flatten(*left, out);
            out[me].offset = out.len() as u32;
            flatten(*right, out);
        }
    }
}

fn build_parallel(ctx: &Ctx, order: &mut [u32], first: u32, depth: u32) -> Subtree {
    if order.len() < PARALLEL_MIN {
        let mut nodes = Vec::with_capacity(2 * order.len());
        let d = build_serial(ctx, order, first, depth, &mut nodes);
        return Subtree::Flat(nodes, d);
    }
    let (bounds, decision) = decide(ctx, order, depth);
    let Some(mid) = decision else {
        let nodes = vec![Node::leaf(bounds, first, order.len() as u32)];
        return Subtree::Flat(nodes, depth);
    };
    let (lo, hi) = order.split_at_mut(mid);
    let (l, r) = rayon::join(
        || build_parallel(ctx, lo, first, depth + 1),
        || build_parallel(ctx, hi, first + mid as u32, depth + 1),
    );
    let d = l.depth().max(r.depth());
    Subtree::Split(bounds, Box::new(l), Box::new(r), d)
}

/// Depth-first serial build into `nodes`; returns the deepest level reached.
fn build_serial(
    ctx: &Ctx,
    order: &mut [u32],
    first: u32,
    depth: u32,
    nodes: &mut Vec<Node>,
) -> u32 {
    let (bounds, decision) = decide(ctx, order, depth);
    let me = nodes.len();
    let Some(mid) = decision else {
        nodes.push(Node::leaf(bounds, first, order.len() as u32));
        return depth;
    };
    nodes.push(Node::interior(bounds, 0));
    let (lo, hi) = order.split_at_mut(mid);
    let dl = build_serial(ctx, lo, first, depth + 1, nodes);
    nodes[me].offset = nodes.len() as u32;
    let dr = build_serial(ctx, hi, first + mid as u32, depth + 1, nodes);
    dl.max(dr)
}

/// Computes the node box and decides: `None` for a leaf, or the index at
/// which `order` (already partitioned) splits into the two children.
fn decide(ctx: &Ctx, order: &mut [u32], depth: u32) -> (Aabb, Option<usize>) {
    let mut bounds = Aabb::EMPTY;
    let mut cbounds = Aabb::EMPTY;
    for &i in order.iter() {
        bounds = bounds.union(ctx.boxes[i as usize]);
        cbounds = cbounds.grow(ctx.centroids[i as usize]);
    }
    let n = order.len();
    let max_leaf = ctx.opts.max_leaf_size.max(1);
    let split = match ctx.opts.strategy {
        BuildStrategy::None => None,
        BuildStrategy::Median if n <= max_leaf => None,
        BuildStrategy::Median => Some(median_split(ctx, order, &cbounds)),
        BuildStrategy::Sah if n <= 1 => None,
        BuildStrategy::Sah if depth >= SAH_DEPTH_LIMIT => {
            (n > max_leaf).then(|| median_split(ctx, order, &cbounds))
        }
        BuildStrategy::Sah => match sah_split(ctx, order, &bounds, &cbounds) {
            Some(mid) => Some(mid),
            None if n > max_leaf => Some(median_split(ctx, order, &cbounds)),
            None => None,
        },
    };
    (bounds, split)
}

/// Object median on the longest centroid axis: `select_nth` gives the same
/// partition as sorting and cutting in the middle, in linear time.
fn median_split(ctx: &Ctx, order: &mut [u32], cbounds: &Aabb) -> usize {
    let axis = cbounds.longest_axis();
    let mid = order.len() / 2;
    let key = |i: &u32| ctx.centroids[*i as usize][axis];
    order.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
    mid
}

/// Binned SAH. Returns the partition point when splitting is cheaper than a
/// leaf (or when the leaf would exceed the size limit), `None` for a leaf or
/// when no bin boundary separates the centroids.
fn sah_split(ctx: &Ctx, order: &mut [u32], bounds: &Aabb, cbounds: &Aabb) -> Option<usize> {
    let n = order.len();
    let ext = cbounds.extent();
    let block = ctx.opts.leaf_block.max(1) as u32;
    let blocks = |count: u32| count.div_ceil(block) as f32;
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bin on the right)
    for axis in 0..3 {
        if ext[axis].is_nan() || ext[axis] <= 0.0 || !ext[axis].is_finite() {
            continue;
        }
        let scale = BINS as f32 * (1.0 - 1e-6) / ext[axis];
        let lo = cbounds.min[axis];
        let mut bins = [(Aabb::EMPTY, 0u32); BINS];
        for &i in order.iter() {
            let b = bin_of(ctx.centroids[i as usize][axis], lo, scale);
            bins[b].0 = bins[b].0.union(ctx.boxes[i as usize]);
            bins[b].1 += 1;
        }
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for b in (1..BINS).rev() {
            acc = acc.union(bins[b].0);
            cnt += bins[b].1;
            right_cost[b] = acc.half_area() * blocks(cnt);
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0u32);
        for b in 1..BINS {
            acc = acc.union(bins[b - 1].0);
            cnt += bins[b - 1].1;
            if cnt == 0 || cnt as usize == n {
                continue;
            }
            let cost = acc.half_area() * blocks(cnt) + right_cost[b];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, b));
            }
        }
    }
    let (cost, axis, split_bin) = best?;
    let area = bounds.half_area();
    let o = &ctx.opts;
    let split_cost = o.traversal_cost + o.intersection_cost * cost / area;
    let leaf_cost = o.intersection_cost * blocks(n as u32);
    if !split_cost.is_finite() || (n <= o.max_leaf_size && leaf_cost <= split_cost) {
        return None;
    }
    let lo = cbounds.min[axis];
    let scale = BINS as f32 * (1.0 - 1e-6) / ext[axis];
    let mid = partition(order, |i| {
        bin_of(ctx.centroids[i as usize][axis], lo, scale) < split_bin
    });
    (mid > 0 && mid < n).then_some(mid)
}

#[inline]
fn bin_of(c: f32, lo: f32, scale: f32) -> usize {
    // `as usize` saturates (and maps NaN to 0), so a stray value cannot index out of range.
    (((c - lo) * scale) as usize).min(BINS - 1)
}

/// In-place partition; returns how many elements satisfy `left`.
fn partition(order: &mut [u32], left: impl Fn(u32) -> bool) -> usize {
    let mut mid = 0;
    for j in 0..order.len() {
        if left(order[j]) {
            order.swap(mid, j);
            mid += 1;
        }
    }
    mid
}
