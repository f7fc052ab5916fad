//! Building the light tree: a binary tree over the lights' bounds, split
//! where the paper's cost is least (Conty Estevez and Kulla 2018, §4.4:
//! power × orientation measure × surface area, with a penalty for
//! splitting a box across its short side; pbrt-v4's `EvaluateCost`).

use super::bounds::LightBounds;
use super::Node;

/// Buckets per axis when looking for the cheapest split.
const BUCKETS: usize = 12;

/// From this depth on, splits halve the lights by count, so that no trail
/// of branch choices (two bits per level of the 4-wide tree, which takes
/// two levels of this one at a time, in a `u64`) can overflow: depth stays
/// below 40 + log2(lights).
const BALANCED_FROM_DEPTH: u32 = 40;

/// The binary tree's nodes (depth first: a node's first child follows it),
/// which `wide.rs` collapses into the 4-wide tree the walk reads.
pub(super) struct Built {
    pub nodes: Vec<Node>,
}

/// Builds the tree over `lights` (light index, bounds); at least one.
pub(super) fn build(mut lights: Vec<(u32, LightBounds)>) -> Built {
    let mut built = Built {
        nodes: Vec::with_capacity(2 * lights.len()),
    };
    if !lights.is_empty() {
        subtree(&mut lights, 0, &mut built);
    }
    built
}

/// Appends the subtree over `lights` and returns its bounds.
fn subtree(lights: &mut [(u32, LightBounds)], depth: u32, out: &mut Built) -> LightBounds {
    if let [(light, bounds)] = lights {
        out.nodes.push(Node {
            bounds: *bounds,
            second_or_light: *light,
            leaf: true,
        });
        return *bounds;
    }
    let at = out.nodes.len();
    out.nodes.push(Node {
        bounds: lights[0].1,
        second_or_light: 0,
        leaf: false,
    });
    let mid = split(lights, depth);
    let (first, second) = lights.split_at_mut(mid);
    let b0 = subtree(first, depth + 1, out);
    let second_index = out.nodes.len() as u32;
    let b1 = subtree(second, depth + 1, out);
    // The parent's bounds are its children's union, so they hold every
    // light below (the zero-importance test stays conservative).
    let bounds = b0.union(&b1);
    out.nodes[at] = Node {
        bounds,
        second_or_light: second_index,
        leaf: false,
    };
    bounds
}

/// Reorders `lights` and returns where the second child's lights start
/// (strictly inside).
fn split(lights: &mut [(u32, LightBounds)], depth: u32) -> usize {
    let all = lights[1..]
        .iter()
        .fold(lights[0].1, |acc, (_, b)| acc.union(b));
    let (mut lo, mut hi) = (lights[0].1.centroid(), lights[0].1.centroid());
    for (_, b) in lights.iter() {
        lo = lo.min(b.centroid());
        hi = hi.max(b.centroid());
    }
    let extent = hi - lo;
    let half = lights.len() / 2;
    let widest = extent.max_position();
    if depth < BALANCED_FROM_DEPTH && extent.max_element() > 0.0 {
        if let Some((dim, bucket)) = cheapest_split(lights, &all, lo, extent) {
            let mut key = |b: &LightBounds| bucket_of(b, dim, lo, extent) < bucket;
            let mid = partition(lights, &mut key);
            if mid > 0 && mid < lights.len() {
                return mid;
            }
        }
    }
    // Equal centroids, no useful split, or deep: halve along the widest axis.
    lights.select_nth_unstable_by(half, |a, b| {
        a.1.centroid()[widest]
            .total_cmp(&b.1.centroid()[widest])
            .then(a.0.cmp(&b.0))
    });
    half
}

fn bucket_of(b: &LightBounds, dim: usize, lo: glam::Vec3, extent: glam::Vec3) -> usize {
    let t = (b.centroid()[dim] - lo[dim]) / extent[dim];
    ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
}

/// The paper's cost of a group, relative to its parent `all` split along
/// `dim`: power × orientation measure × surface area, times the ratio of
/// the parent's longest side to the split side (thin slabs cost more).
fn cost(b: &LightBounds, all: &LightBounds, dim: usize) -> f32 {
    let diagonal = all.hi - all.lo;
    let regular = if diagonal[dim] > 0.0 {
        diagonal.max_element() / diagonal[dim]
    } else {
        f32::INFINITY
    };
    let c = regular * b.phi * b.orientation_measure() * b.surface_area();
    if c.is_nan() {
        f32::INFINITY
    } else {
        c
    }
}

/// The axis and first bucket of the second child of the cheapest split
/// between buckets, if any split leaves lights on both sides.
fn cheapest_split(
    lights: &[(u32, LightBounds)],
    all: &LightBounds,
    lo: glam::Vec3,
    extent: glam::Vec3,
) -> Option<(usize, usize)> {
    let mut best: Option<(f32, usize, usize)> = None;
    for dim in 0..3 {
        if extent[dim] <= 0.0 {
            continue;
        }
        let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for (_, b) in lights {
            let slot = &mut buckets[bucket_of(b, dim, lo, extent)];
            *slot = Some(slot.map_or(*b, |s| s.union(b)));
        }
        // below[k]: buckets 0..=k merged; above[k]: buckets k.. merged.
        let sweep = |acc: &mut Option<LightBounds>, b: &Option<LightBounds>| {
            if let Some(b) = b {
                *acc = Some(acc.map_or(*b, |a| a.union(b)));
            }
            *acc
        };
        let mut acc = None;
        let below: Vec<Option<LightBounds>> = buckets.iter().map(|b| sweep(&mut acc, b)).collect();
        let mut acc = None;
        let mut above: Vec<Option<LightBounds>> =
            buckets.iter().rev().map(|b| sweep(&mut acc, b)).collect();
        above.reverse();
        for split in 1..BUCKETS {
            let (Some(lower), Some(upper)) = (below[split - 1], above[split]) else {
                continue;
            };
            let c = cost(&lower, all, dim) + cost(&upper, all, dim);
            if best.is_none_or(|(bc, _, _)| c < bc) {
                best = Some((c, dim, split));
            }
        }
    }
    best.map(|(_, dim, split)| (dim, split))
}

/// Moves the lights for which `first` holds to the front, keeping the
/// order within each side; returns how many there are.
fn partition(
    lights: &mut [(u32, LightBounds)],
    first: &mut impl FnMut(&LightBounds) -> bool,
) -> usize {
    let (front, back): (Vec<_>, Vec<_>) = lights.iter().partition(|(_, b)| first(b));
    let mid = front.len();
    for (slot, item) in lights.iter_mut().zip(front.into_iter().chain(back)) {
        *slot = item;
    }
    mid
}
