//! Traversal of the wide BVHs: one SIMD slab test for all children of a
//! node, the entered children visited nearest first.
//!
//! One loop serves both widths; only the node test differs: 4-lane SSE
//! chunks ([`RayLanes`], any width that is a multiple of 4, portable) or one
//! 8-lane AVX2 test ([`crate::avx2`]). Both perform the same operations in
//! the same order, so they return identical hits and statistics.

use crate::simd::{prefetch, F32x4};
use crate::traverse::{StatsSink, ROBUST_SCALE};
use crate::{RayBoxQuery, WideBvh, WideNode};
use std::mem::MaybeUninit;

/// Bound on the tree depth (see `build::SAH_DEPTH_LIMIT`): median splits
/// below the SAH limit halve the range, so 40 more levels cover any input.
const MAX_DEPTH: usize = crate::build::SAH_DEPTH_LIMIT as usize + 40;

/// A pending subtree or leaf: reference, leaf count (0 for a node), entry distance.
#[derive(Clone, Copy)]
pub(crate) struct Entry {
    child: u32,
    count: u32,
    t: f32,
}

/// Tests a ray against the `W` boxes of a node.
pub(crate) trait NodeTest<const W: usize> {
    /// Entry distances and the mask of lanes entered within `[0, t_max]`.
    fn enter(&self, b: &[[f32; W]; 6], t_max: f32) -> ([f32; W], u32);
}

/// The ray in 4-lane form, with the near plane chosen per axis by the
/// direction's sign (so the slab test needs no min/max between planes).
pub(crate) struct RayLanes {
    origin: [F32x4; 3],
    inv_dir: [F32x4; 3],
    near_row: [usize; 3],
}

impl RayLanes {
    #[inline(always)]
    pub(crate) fn new(q: &RayBoxQuery) -> Self {
        let (o, inv) = (q.origin(), q.inv_dir());
        Self {
            origin: [F32x4::splat(o.x), F32x4::splat(o.y), F32x4::splat(o.z)],
            inv_dir: [
                F32x4::splat(inv.x),
                F32x4::splat(inv.y),
                F32x4::splat(inv.z),
            ],
            near_row: near_rows(q),
        }
    }
}

/// Per axis, the row of the near plane (min for a positive direction).
#[inline(always)]
pub(crate) fn near_rows(q: &RayBoxQuery) -> [usize; 3] {
    let inv = q.inv_dir();
    [0, 1, 2].map(|a| if inv[a].is_sign_negative() { a + 3 } else { a })
}

impl<const W: usize> NodeTest<W> for RayLanes {
    /// Four lanes at a time. NaNs (a flat box seen edge-on from its own
    /// plane) are dropped by the operand order of `min`/`max`.
    #[inline(always)]
    fn enter(&self, b: &[[f32; W]; 6], t_max: f32) -> ([f32; W], u32) {
        let mut dist = [0.0f32; W];
        let mut mask = 0;
        for c in 0..W / 4 {
            let row = |r: usize| F32x4::load(b[r][4 * c..4 * c + 4].try_into().unwrap());
            let mut near = F32x4::splat(0.0);
            let mut far = F32x4::splat(t_max * ROBUST_SCALE);
            for a in 0..3 {
                let nr = self.near_row[a];
                let fr = if nr >= 3 { nr - 3 } else { nr + 3 };
                let tn = (row(nr) - self.origin[a]) * self.inv_dir[a];
                let tf = (row(fr) - self.origin[a]) * self.inv_dir[a];
                near = tn.max(near);
                far = tf.min(far);
            }
            dist[4 * c..4 * c + 4].copy_from_slice(&near.to_array());
            mask |= near.le_mask(far) << (4 * c);
        }
        (dist, mask)
    }
}

/// The leaf prefetch of callers that have nothing to prefetch.
#[inline(always)]
fn no_prefetch(_first: u32, _count: u32) {}

impl<const W: usize> WideBvh<W> {
    /// Closest hit; same contract as [`crate::Bvh::closest_hit`].
    #[inline]
    pub fn closest_hit<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let mut best = None;
        self.walk::<true, S>(
            ray,
            &mut t_max,
            stats,
            no_prefetch,
            |first, count, t_max| {
                for slot in first..first + count {
                    if let Some(t) = test(slot, *t_max) {
                        *t_max = t;
                        best = Some((slot, t));
                    }
                }
                false
            },
        );
        best
    }

    /// Closest hit with a whole leaf per call, for callers that test
    /// primitives in SIMD blocks: `test(first, count, t_max)` intersects
    /// slots `first .. first + count` and returns the closest `(slot, t)`
    /// with `t < t_max`. `prefetch(first, count)` is called for a leaf
    /// put aside for later, so the caller can start loading its data.
    #[inline]
    pub fn closest_hit_leaves<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        prefetch: impl Fn(u32, u32),
        mut test: impl FnMut(u32, u32, f32) -> Option<(u32, f32)>,
    ) -> Option<(u32, f32)> {
        let mut best = None;
        // Not forced inline (unlike the any-hit test): compiled into the
        // AVX2 loop, the closest-hit leaf test ran 7% fewer instructions
        // but 7% slower on cbbunny primary rays (BENCHMARKS.md).
        self.walk::<true, S>(ray, &mut t_max, stats, prefetch, |first, count, t_max| {
            if let Some((slot, t)) = test(first, count, *t_max) {
                *t_max = t;
                best = Some((slot, t));
            }
            false
        });
        best
    }

    /// Any hit with a whole leaf per call; see [`WideBvh::closest_hit_leaves`].
    #[inline]
    pub fn any_hit_leaves<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        prefetch: impl Fn(u32, u32),
        mut test: impl FnMut(u32, u32, f32) -> bool,
    ) -> bool {
        self.walk::<false, S>(
            ray,
            &mut t_max,
            stats,
            prefetch,
            // Compiled into the traversal loop (AVX2 encoding, no call).
            #[inline(always)]
            |first, count, t_max| test(first, count, *t_max),
        )
    }

    /// Any hit; same contract as [`crate::Bvh::any_hit`].
    #[inline]
    pub fn any_hit<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> bool {
        self.walk::<false, S>(
            ray,
            &mut t_max,
            stats,
            no_prefetch,
            #[inline(always)]
            |first, count, t_max| (first..first + count).any(|slot| test(slot, *t_max).is_some()),
        )
    }

    /// Picks the node test: AVX2 for an 8-wide tree on a CPU that has it,
    /// 4-lane chunks otherwise. `ORDERED` visits entered children nearest
    /// first, which closest-hit queries need to shrink `t_max` early;
    /// any-hit queries skip the sorting (a shadow ray is usually unoccluded
    /// and then visits the same nodes in any order).
    #[inline(always)]
    fn walk<const ORDERED: bool, S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        t_max: &mut f32,
        stats: &mut S,
        prefetch_leaf: impl Fn(u32, u32),
        visit: impl FnMut(u32, u32, &mut f32) -> bool,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            if let Some(bvh8) = (self as &dyn std::any::Any).downcast_ref::<crate::Bvh8>() {
                // SAFETY: `avx2` is only set after run-time detection.
                return unsafe {
                    crate::avx2::walk::<ORDERED, S>(bvh8, ray, t_max, stats, prefetch_leaf, visit)
                };
            }
        }
        walk_with::<W, ORDERED, S, _>(
            self,
            &RayLanes::new(ray),
            t_max,
            stats,
            prefetch_leaf,
            visit,
        )
    }
}

/// Starts loading what a pushed entry will read: every cache line of a
/// node, or the caller's leaf data.
#[inline(always)]
fn prefetch_entry<const W: usize>(
    nodes: &[WideNode<W>],
    e: &Entry,
    prefetch_leaf: &impl Fn(u32, u32),
) {
    if e.count == 0 {
        let node = &nodes[e.child as usize];
        prefetch(node);
        prefetch(&node.bounds[W / 4 + 1][0]);
        if W == 8 {
            prefetch(&node.bounds[5][0]);
            prefetch(&node.child);
        }
    } else {
        prefetch_leaf(e.child, e.count);
    }
}

/// Whether `a` is visited before `b`, for `a` in an earlier lane than `b`.
/// Closest hit: the nearer entry (ties to the later lane). Any hit: leaves
/// before subtrees, in lane order otherwise, which the build chose for any
/// hit (`wide_order.rs`: the likeliest occluders for their cost first). A
/// leaf costs about one node visit and may end the query at once: large
/// occluders (a wall, a ground quad) sit in leaves near the root, and an
/// occluded shadow ray then stops there instead of first walking the
/// detailed geometry its path also crosses. An unoccluded ray visits
/// everything it enters in either order.
#[inline(always)]
fn takes_first(a: &Entry, b: &Entry, ordered: bool) -> bool {
    if ordered {
        a.t < b.t
    } else {
        a.count > 0 || b.count == 0
    }
}

/// Pushes `e` unless the stack is full (which the depth bound rules out).
#[inline(always)]
fn push(stack: &mut [MaybeUninit<Entry>], sp: &mut usize, e: Entry) {
    if let Some(slot) = stack.get_mut(*sp) {
        slot.write(e);
        *sp += 1;
    }
}

/// The traversal loop, for any width and node test.
#[inline(always)]
pub(crate) fn walk_with<const W: usize, const ORDERED: bool, S: StatsSink, T: NodeTest<W>>(
    bvh: &WideBvh<W>,
    r: &T,
    t_max: &mut f32,
    stats: &mut S,
    prefetch_leaf: impl Fn(u32, u32),
    mut visit: impl FnMut(u32, u32, &mut f32) -> bool,
) -> bool {
    if bvh.nodes.is_empty() {
        return false;
    }
    let nodes = bvh.nodes.as_slice();
    // A node pushes at most W - 1 entries per level. Entries below `sp` are
    // always written before they are read.
    let mut stack = [const { MaybeUninit::<Entry>::uninit() }; 7 * MAX_DEPTH];
    let cap = (W - 1) * MAX_DEPTH;
    let mut sp = 0usize;
    let mut item = Entry {
        child: 0,
        count: 0,
        t: 0.0,
    };
    loop {
        if item.count > 0 {
            stats.prims(item.count);
            if visit(item.child, item.count, t_max) {
                return true;
            }
        } else {
            stats.node();
            let node = &nodes[item.child as usize];
            let (dist, mask) = r.enter(&node.bounds, *t_max);
            let entry = |lane: usize| Entry {
                child: node.child[lane],
                count: node.count[lane],
                t: dist[lane],
            };
            // One or two children entered (most nodes on incoherent
            // rays) skip the general sort, with the same order as
            // `takes_first` (ties go to the higher lane).
            let a = mask.trailing_zeros() as usize;
            let rest = mask & mask.wrapping_sub(1);
            if mask != 0 && rest == 0 {
                item = entry(a);
                continue;
            }
            if mask != 0 && rest & (rest - 1) == 0 {
                let b = rest.trailing_zeros() as usize;
                let b_first = if ORDERED {
                    dist[b] <= dist[a]
                } else {
                    node.count[b] > 0 && node.count[a] == 0
                };
                let (near, far) = if b_first { (b, a) } else { (a, b) };
                let e = entry(far);
                prefetch_entry(nodes, &e, &prefetch_leaf);
                push(&mut stack[..cap], &mut sp, e);
                item = entry(near);
                continue;
            }
            if mask != 0 {
                // Hit lanes sorted far to near; the nearest is taken now.
                let mut hits = [Entry {
                    child: 0,
                    count: 0,
                    t: 0.0,
                }; W];
                let mut k = 0;
                let mut bits = mask;
                while bits != 0 {
                    let lane = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let e = entry(lane);
                    let mut j = k;
                    while j > 0 && takes_first(&hits[j - 1], &e, ORDERED) {
                        hits[j] = hits[j - 1];
                        j -= 1;
                    }
                    hits[j] = e;
                    k += 1;
                }
                for e in &hits[..k - 1] {
                    prefetch_entry(nodes, e, &prefetch_leaf);
                    push(&mut stack[..cap], &mut sp, *e);
                }
                item = hits[k - 1];
                continue;
            }
        }
        loop {
            if sp == 0 {
                return false;
            }
            sp -= 1;
            // SAFETY: slots below `sp` were written by `push`.
            let e = unsafe { stack[sp].assume_init() };
            if e.t <= *t_max * ROBUST_SCALE {
                item = e;
                break;
            }
        }
    }
}
