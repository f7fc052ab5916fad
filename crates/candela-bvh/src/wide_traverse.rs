//! Traversal of the 4-wide BVH: one SIMD slab test for four children, the
//! hit children visited nearest first.

use crate::simd::{prefetch, F32x4};
use crate::traverse::{StatsSink, ROBUST_SCALE};
use crate::{Bvh4, RayBoxQuery};

/// Each node pushes at most three entries, and the build bounds the depth.
const STACK_SIZE: usize = 3 * (crate::build::SAH_DEPTH_LIMIT as usize + 40);
/// Trees up to this depth use a small stack, which is cheaper to set up per ray.
const SHALLOW_DEPTH: u32 = 21;
const SHALLOW_STACK: usize = 3 * SHALLOW_DEPTH as usize;

/// A pending subtree or leaf: reference, leaf count (0 for a node), entry distance.
#[derive(Clone, Copy)]
struct Entry {
    child: u32,
    count: u32,
    t: f32,
}

/// The ray in 4-lane form, with the near plane chosen per axis by the
/// direction's sign (so the slab test needs no min/max between planes).
struct Ray4 {
    origin: [F32x4; 3],
    inv_dir: [F32x4; 3],
    near_row: [usize; 3],
}

impl Ray4 {
    #[inline(always)]
    fn new(q: &RayBoxQuery) -> Self {
        let (o, inv) = (q.origin(), q.inv_dir());
        Self {
            origin: [F32x4::splat(o.x), F32x4::splat(o.y), F32x4::splat(o.z)],
            inv_dir: [
                F32x4::splat(inv.x),
                F32x4::splat(inv.y),
                F32x4::splat(inv.z),
            ],
            near_row: [0, 1, 2].map(|a| if inv[a].is_sign_negative() { a + 3 } else { a }),
        }
    }

    /// Entry distances and the mask of lanes entered within `[0, t_max]`.
    /// NaNs (a flat box seen edge-on from its own plane) are dropped by the
    /// operand order of `min`/`max`.
    #[inline(always)]
    fn enter(&self, b: &[[f32; 4]; 6], t_max: f32) -> ([f32; 4], u32) {
        let mut near = F32x4::splat(0.0);
        let mut far = F32x4::splat(t_max * ROBUST_SCALE);
        for a in 0..3 {
            let nr = self.near_row[a];
            let fr = if nr >= 3 { nr - 3 } else { nr + 3 };
            let tn = (F32x4::load(&b[nr]) - self.origin[a]) * self.inv_dir[a];
            let tf = (F32x4::load(&b[fr]) - self.origin[a]) * self.inv_dir[a];
            near = tn.max(near);
            far = tf.min(far);
        }
        (near.to_array(), near.le_mask(far))
    }
}

/// The leaf prefetch of callers that have nothing to prefetch.
#[inline(always)]
fn no_prefetch(_first: u32, _count: u32) {}

impl Bvh4 {
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
        self.walk::<true, S>(ray, &mut t_max, stats, prefetch, |first, count, t_max| {
            if let Some((slot, t)) = test(first, count, *t_max) {
                *t_max = t;
                best = Some((slot, t));
            }
            false
        });
        best
    }

    /// Any hit with a whole leaf per call; see [`Bvh4::closest_hit_leaves`].
    #[inline]
    pub fn any_hit_leaves<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        prefetch: impl Fn(u32, u32),
        mut test: impl FnMut(u32, u32, f32) -> bool,
    ) -> bool {
        self.walk::<false, S>(ray, &mut t_max, stats, prefetch, |first, count, t_max| {
            test(first, count, *t_max)
        })
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
            |first, count, t_max| (first..first + count).any(|slot| test(slot, *t_max).is_some()),
        )
    }

    /// Picks the stack size from the tree depth. `ORDERED` visits entered
    /// children nearest first, which closest-hit queries need to shrink
    /// `t_max` early; any-hit queries skip the sorting (a shadow ray is
    /// usually unoccluded and then visits the same nodes in any order).
    #[inline(always)]
    fn walk<const ORDERED: bool, S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        t_max: &mut f32,
        stats: &mut S,
        prefetch_leaf: impl Fn(u32, u32),
        visit: impl FnMut(u32, u32, &mut f32) -> bool,
    ) -> bool {
        if self.depth <= SHALLOW_DEPTH {
            self.walk_with::<ORDERED, SHALLOW_STACK, S>(ray, t_max, stats, prefetch_leaf, visit)
        } else {
            self.walk_with::<ORDERED, STACK_SIZE, S>(ray, t_max, stats, prefetch_leaf, visit)
        }
    }

    /// Starts loading what a pushed entry will read: both cache lines of a
    /// node, or the caller's leaf data.
    #[inline(always)]
    fn prefetch_entry(&self, e: &Entry, prefetch_leaf: &impl Fn(u32, u32)) {
        if e.count == 0 {
            let node = &self.nodes[e.child as usize];
            prefetch(node);
            prefetch(&node.bounds[4]);
        } else {
            prefetch_leaf(e.child, e.count);
        }
    }

    /// The traversal loop; `N` stack entries suffice for the tree's depth.
    #[inline(always)]
    fn walk_with<const ORDERED: bool, const N: usize, S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        t_max: &mut f32,
        stats: &mut S,
        prefetch_leaf: impl Fn(u32, u32),
        mut visit: impl FnMut(u32, u32, &mut f32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let r4 = Ray4::new(ray);
        let mut stack = [Entry {
            child: 0,
            count: 0,
            t: 0.0,
        }; N];
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
                let node = &self.nodes[item.child as usize];
                let (dist, mask) = r4.enter(&node.bounds, *t_max);
                let entry = |lane: usize| Entry {
                    child: node.child[lane],
                    count: node.count[lane],
                    t: dist[lane],
                };
                // One or two children entered (most nodes on incoherent
                // rays) skip the general sort. Ties go to the higher lane,
                // as in the sort below.
                let a = mask.trailing_zeros() as usize;
                let rest = mask & mask.wrapping_sub(1);
                if mask != 0 && rest == 0 {
                    item = entry(a);
                    continue;
                }
                if mask != 0 && rest & (rest - 1) == 0 {
                    let b = rest.trailing_zeros() as usize;
                    let (near, far) = if !ORDERED || dist[a] < dist[b] {
                        (a, b)
                    } else {
                        (b, a)
                    };
                    if sp < N {
                        let e = entry(far);
                        self.prefetch_entry(&e, &prefetch_leaf);
                        stack[sp] = e;
                        sp += 1;
                    }
                    item = entry(near);
                    continue;
                }
                if mask != 0 {
                    // Hit lanes sorted far to near; the nearest is taken now.
                    let mut hits = [Entry {
                        child: 0,
                        count: 0,
                        t: 0.0,
                    }; 4];
                    let mut k = 0;
                    let mut bits = mask;
                    while bits != 0 {
                        let lane = bits.trailing_zeros() as usize;
                        bits &= bits - 1;
                        let e = entry(lane);
                        let mut j = k;
                        while ORDERED && j > 0 && hits[j - 1].t < e.t {
                            hits[j] = hits[j - 1];
                            j -= 1;
                        }
                        hits[j] = e;
                        k += 1;
                    }
                    for e in &hits[..k - 1] {
                        if sp < N {
                            self.prefetch_entry(e, &prefetch_leaf);
                            stack[sp] = *e;
                            sp += 1;
                        }
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
                if stack[sp].t <= *t_max * ROBUST_SCALE {
                    item = stack[sp];
                    break;
                }
            }
        }
    }
}
