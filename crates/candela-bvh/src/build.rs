//! Building: binned SAH (parallel at the top levels), median split, or one leaf.
//!
//! Binned SAH after Wald, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies" (2007): centroids are dropped into a few bins per axis and
//! the split cost is evaluated only at bin boundaries. The build works on a
//! compact array of primitive references (box, centroid, id) that is
//! partitioned in place, so every pass reads memory sequentially; each node
//! costs one binning pass (all three axes at once) and one partition pass,
//! which also gathers the children's boxes.

use crate::node::Node;
use crate::{Aabb, BuildOptions, BuildStrategy, Collapse};
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

/// Ranges at least this large are split in parallel with `rayon::join`.
const PARALLEL_MIN: usize = 4096;
/// Bins per axis for the SAH sweep (32 and 8 measured no better: BENCHMARKS.md,
/// "The SAH collapse").
const BINS: usize = 16;
/// Below this depth the build may use SAH; deeper it uses object median
/// splits, which halve the range, so the tree depth stays below
/// `SAH_DEPTH_LIMIT + 32` and the fixed traversal stack never overflows.
pub(crate) const SAH_DEPTH_LIMIT: u32 = 48;

/// A box in SIMD registers: `Vec3A` min/max are single instructions,
/// where `Vec3`'s NaN-aware `f32::min` costs several. Build-internal.
#[derive(Clone, Copy, Debug)]
struct BoxA {
    min: Vec3A,
    max: Vec3A,
}

impl BoxA {
    const EMPTY: Self = Self {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn union(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    #[inline(always)]
    fn half_area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3A::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    fn aabb(&self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }
}

/// A primitive during the build.
#[derive(Clone, Copy, Debug)]
struct PrimRef {
    bounds: BoxA,
    centroid: Vec3A,
    id: u32,
}

/// A range's box and centroid box.
#[derive(Clone, Copy, Debug)]
struct RangeBounds {
    bounds: BoxA,
    centroids: BoxA,
}

impl RangeBounds {
    const EMPTY: Self = Self {
        bounds: BoxA::EMPTY,
        centroids: BoxA::EMPTY,
    };

    fn of(refs: &[PrimRef]) -> Self {
        refs.iter().fold(Self::EMPTY, |b, r| b.grow(r))
    }

    fn union(self, o: Self) -> Self {
        Self {
            bounds: self.bounds.union(o.bounds),
            centroids: self.centroids.union(o.centroids),
        }
    }

    #[inline(always)]
    fn grow(self, r: &PrimRef) -> Self {
        Self {
            bounds: self.bounds.union(r.bounds),
            centroids: self.centroids.grow(r.centroid),
        }
    }
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
    let mut refs: Vec<PrimRef> = (&boxes[..n], &centroids[..n])
        .into_par_iter()
        .enumerate()
        .map(|(i, (b, &c))| PrimRef {
            bounds: BoxA {
                min: b.min.into(),
                max: b.max.into(),
            },
            centroid: c.into(),
            id: i as u32,
        })
        .collect();
    if refs.is_empty() {
        return (Vec::new(), Vec::new(), 0);
    }
    let rb = refs
        .par_chunks(PARALLEL_MIN)
        .map(RangeBounds::of)
        .reduce(|| RangeBounds::EMPTY, RangeBounds::union);
    let tree = build_parallel(&opts, &mut refs, rb, 0, 1);
    let depth = tree.depth();
    let mut nodes = Vec::with_capacity(2 * refs.len());
    flatten(tree, &mut nodes);
    (nodes, refs.iter().map(|r| r.id).collect(), depth)
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

fn build_parallel(
    opts: &BuildOptions,
    refs: &mut [PrimRef],
    rb: RangeBounds,
    first: u32,
    depth: u32,
) -> Subtree {
    if refs.len() < PARALLEL_MIN {
        let mut nodes = Vec::with_capacity(2 * refs.len());
        let d = build_serial(opts, refs, rb, first, depth, &mut nodes);
        return Subtree::Flat(nodes, d);
    }
    let Some((mid, lb, rbs)) = split(opts, refs, &rb, depth) else {
        let nodes = vec![Node::leaf(rb.bounds.aabb(), first, refs.len() as u32)];
        return Subtree::Flat(nodes, depth);
    };
    let (lo, hi) = refs.split_at_mut(mid);
    let (l, r) = rayon::join(
        || build_parallel(opts, lo, lb, first, depth + 1),
        || build_parallel(opts, hi, rbs, first + mid as u32, depth + 1),
    );
    let d = l.depth().max(r.depth());
    Subtree::Split(rb.bounds.aabb(), Box::new(l), Box::new(r), d)
}

/// Depth-first serial build into `nodes`; returns the deepest level reached.
fn build_serial(
    opts: &BuildOptions,
    refs: &mut [PrimRef],
    rb: RangeBounds,
    first: u32,
    depth: u32,
    nodes: &mut Vec<Node>,
) -> u32 {
    let me = nodes.len();
    let Some((mid, lb, rbs)) = split(opts, refs, &rb, depth) else {
        nodes.push(Node::leaf(rb.bounds.aabb(), first, refs.len() as u32));
        return depth;
    };
    nodes.push(Node::interior(rb.bounds.aabb(), 0));
    let (lo, hi) = refs.split_at_mut(mid);
    let dl = build_serial(opts, lo, lb, first, depth + 1, nodes);
    nodes[me].offset = nodes.len() as u32;
    let dr = build_serial(opts, hi, rbs, first + mid as u32, depth + 1, nodes);
    dl.max(dr)
}

/// Decides a node: `None` for a leaf, or the partition point (with `refs`
/// partitioned) and the two children's bounds.
fn split(
    opts: &BuildOptions,
    refs: &mut [PrimRef],
    rb: &RangeBounds,
    depth: u32,
) -> Option<(usize, RangeBounds, RangeBounds)> {
    let n = refs.len();
    let max_leaf = opts.max_leaf_size.max(1);
    let mid = match opts.strategy {
        BuildStrategy::None => None,
        BuildStrategy::Median if n <= max_leaf => None,
        BuildStrategy::Median => Some(median_split(refs, &rb.centroids)),
        BuildStrategy::Sah if n <= 1 => None,
        BuildStrategy::Sah if depth >= SAH_DEPTH_LIMIT => {
            (n > max_leaf).then(|| median_split(refs, &rb.centroids))
        }
        BuildStrategy::Sah => match sah_split(opts, refs, rb) {
            Some(mid) => Some(mid),
            None if n > max_leaf => Some(median_split(refs, &rb.centroids)),
            None => None,
        },
    }?;
    Some((
        mid,
        RangeBounds::of(&refs[..mid]),
        RangeBounds::of(&refs[mid..]),
    ))
}

/// Object median on the longest centroid axis: `select_nth` gives the same
/// partition as sorting and cutting in the middle, in linear time.
fn median_split(refs: &mut [PrimRef], cbounds: &BoxA) -> usize {
    let axis = cbounds.aabb().longest_axis();
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

/// Binned SAH over all three axes in one pass. Returns the partition point
/// when splitting is cheaper than a leaf (or when the leaf would exceed the
/// size limit), `None` for a leaf or when no bin boundary separates the
/// centroids.
fn sah_split(opts: &BuildOptions, refs: &mut [PrimRef], rb: &RangeBounds) -> Option<usize> {
    let n = refs.len();
    // A tree for the SAH collapse charges leaves per primitive: the collapse
    // decides the leaves again (merging subtrees) and counts blocks there.
    let block = match opts.collapse {
        Collapse::Sah => 1,
        Collapse::Greedy => opts.leaf_block.max(1) as u32,
    };
    let blocks = |count: u32| count.div_ceil(block) as f32;
    let lo = rb.centroids.min;
    let ext = (rb.centroids.max - rb.centroids.min).max(Vec3A::ZERO);
    let usable = |a: usize| ext[a] > 0.0 && ext[a].is_finite();
    let scale = Vec3A::from_array([0, 1, 2].map(|a| {
        if usable(a) {
            BINS as f32 * (1.0 - 1e-6) / ext[a]
        } else {
            0.0
        }
    }));
    let mut bins = [[(BoxA::EMPTY, 0u32); BINS]; 3];
    for r in refs.iter() {
        let k = bin_index(r.centroid, lo, scale);
        for a in 0..3 {
            let bin = &mut bins[a][k[a]];
            bin.0 = bin.0.union(r.bounds);
            bin.1 += 1;
        }
    }
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, first bin on the right)
    for (axis, bins) in bins.iter().enumerate() {
        if !usable(axis) {
            continue;
        }
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut cnt) = (BoxA::EMPTY, 0u32);
        for b in (1..BINS).rev() {
            acc = acc.union(bins[b].0);
            cnt += bins[b].1;
            right_cost[b] = acc.half_area() * blocks(cnt);
        }
        let (mut acc, mut cnt) = (BoxA::EMPTY, 0u32);
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
    let split_cost = opts.traversal_cost + opts.intersection_cost * cost / rb.bounds.half_area();
    let leaf_cost = opts.intersection_cost * blocks(n as u32);
    if !split_cost.is_finite() || (n <= opts.max_leaf_size && leaf_cost <= split_cost) {
        return None;
    }
    let mid = partition(refs, |r| bin_index(r.centroid, lo, scale)[axis] < split_bin);
    (mid > 0 && mid < n).then_some(mid)
}

/// Bin of a centroid on each axis. `as usize` saturates (and maps NaN to
/// 0), so a stray value cannot index out of range.
#[inline(always)]
fn bin_index(c: Vec3A, lo: Vec3A, scale: Vec3A) -> [usize; 3] {
    // Clamped in float first, so the conversion is a plain truncation;
    // `max` with 0 sends NaN (from infinite boxes) to bin 0.
    let f = ((c - lo) * scale)
        .max(Vec3A::ZERO)
        .min(Vec3A::splat((BINS - 1) as f32));
    [f.x as usize, f.y as usize, f.z as usize]
}

/// In-place partition; returns how many elements satisfy `left`.
fn partition(refs: &mut [PrimRef], left: impl Fn(&PrimRef) -> bool) -> usize {
    let mut mid = 0;
    for j in 0..refs.len() {
        if left(&refs[j]) {
            refs.swap(mid, j);
            mid += 1;
        }
    }
    mid
}
