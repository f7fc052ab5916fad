//! Closest-hit and any-hit traversal with a caller-supplied primitive test.
//!
//! Children are tested together and the nearer one is visited first; the far
//! one goes on a fixed-size stack with its entry distance, so it is skipped
//! without a box test if a hit closer than that was found meanwhile.

use crate::build::SAH_DEPTH_LIMIT;
use crate::node::Node;
use crate::Bvh;
use glam::Vec3;

/// Stack entries: one per level is the most traversal can need.
const STACK_SIZE: usize = SAH_DEPTH_LIMIT as usize + 40;

/// Slab tests round; widening the interval by this factor keeps the box
/// test conservative, so a ray that hits a primitive always reaches its leaf
/// (pbrt: `tMax *= 1 + 2 * gamma(3)`).
pub(crate) const ROBUST_SCALE: f32 =
    1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Receives traversal events; `()` ignores them at no cost, [`TraversalStats`] counts.
pub trait StatsSink {
    /// A node was visited.
    fn node(&mut self);
    /// A primitive was tested.
    fn prim(&mut self);
    /// `n` primitives were tested.
    #[inline(always)]
    fn prims(&mut self, n: u32) {
        for _ in 0..n {
            self.prim();
        }
    }
}

impl StatsSink for () {
    #[inline(always)]
    fn node(&mut self) {}
    #[inline(always)]
    fn prim(&mut self) {}
}

/// Per-thread counters, so the renderer can report traversal cost without
/// atomics in the hot loop: keep one per thread and add them up at the end.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalStats {
    /// Nodes whose children (or primitives) were examined.
    pub nodes_visited: u64,
    /// Primitive intersection tests run.
    pub prims_tested: u64,
}

impl StatsSink for TraversalStats {
    #[inline(always)]
    fn node(&mut self) {
        self.nodes_visited += 1;
    }
    #[inline(always)]
    fn prim(&mut self) {
        self.prims_tested += 1;
    }
    #[inline(always)]
    fn prims(&mut self, n: u32) {
        self.prims_tested += n as u64;
    }
}

impl std::ops::AddAssign for TraversalStats {
    fn add_assign(&mut self, o: Self) {
        self.nodes_visited += o.nodes_visited;
        self.prims_tested += o.prims_tested;
    }
}

/// A ray prepared for box tests: the reciprocal direction is computed once
/// per ray instead of three divisions per box.
#[derive(Clone, Copy, Debug)]
pub struct RayBoxQuery {
    origin: Vec3,
    inv_dir: Vec3,
}

impl RayBoxQuery {
    /// Prepares `origin + t * dir`. Zero direction components give infinite
    /// reciprocals, which the slab test handles.
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            inv_dir: dir.recip(),
        }
    }

    /// The ray origin.
    #[inline(always)]
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Componentwise `1 / dir`.
    #[inline(always)]
    pub fn inv_dir(&self) -> Vec3 {
        self.inv_dir
    }

    /// Entry distance into `node`'s box within `[0, t_max]`, or infinity on a miss.
    ///
    /// `max`/`min` are written as comparisons with the running value second,
    /// so a NaN (origin on a slab plane of a parallel ray) is ignored.
    #[inline(always)]
    fn enter(&self, node: &Node, t_max: f32) -> f32 {
        let mut near = 0.0f32;
        let mut far = t_max * ROBUST_SCALE;
        for a in 0..3 {
            let t0 = (node.min[a] - self.origin[a]) * self.inv_dir[a];
            let t1 = (node.max[a] - self.origin[a]) * self.inv_dir[a];
            let (lo, hi) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
            near = if lo > near { lo } else { near };
            far = if hi < far { hi } else { far };
        }
        if near <= far {
            near
        } else {
            f32::INFINITY
        }
    }
}

impl Bvh {
    /// Finds the closest primitive. `test(slot, t_max)` intersects the
    /// primitive in `slot` of [`Bvh::primitive_order`] and returns its
    /// distance if it is hit before `t_max`. Returns the slot and distance of
    /// the closest accepted hit.
    #[inline]
    pub fn closest_hit<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let mut best = None;
        self.walk(ray, &mut t_max, stats, |slot, t_max| {
            if let Some(t) = test(slot, *t_max) {
                *t_max = t;
                best = Some((slot, t));
            }
            false
        });
        best
    }

    /// True as soon as any primitive reports a hit before `t_max` (shadow rays).
    #[inline]
    pub fn any_hit<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        mut t_max: f32,
        stats: &mut S,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> bool {
        self.walk(ray, &mut t_max, stats, |slot, t_max| {
            test(slot, *t_max).is_some()
        })
    }

    /// The shared loop; `visit` returns true to stop.
    #[inline(always)]
    fn walk<S: StatsSink>(
        &self,
        ray: &RayBoxQuery,
        t_max: &mut f32,
        stats: &mut S,
        mut visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        let nodes = self.nodes.as_slice();
        let Some(root) = nodes.first() else {
            return false;
        };
        if ray.enter(root, *t_max) == f32::INFINITY {
            return false;
        }
        let mut stack = [(0u32, 0.0f32); STACK_SIZE];
        let mut sp = 0usize;
        let mut current = 0usize;
        loop {
            let node = &nodes[current];
            stats.node();
            if node.is_leaf() {
                for slot in node.offset..node.offset + node.count {
                    stats.prim();
                    if visit(slot, t_max) {
                        return true;
                    }
                }
            } else {
                let (l, r) = (current + 1, node.offset as usize);
                let tl = ray.enter(&nodes[l], *t_max);
                let tr = ray.enter(&nodes[r], *t_max);
                let (near, t_near, far, t_far) = if tl <= tr {
                    (l, tl, r, tr)
                } else {
                    (r, tr, l, tl)
                };
                if t_near != f32::INFINITY {
                    if t_far != f32::INFINITY && sp < STACK_SIZE {
                        stack[sp] = (far as u32, t_far);
                        sp += 1;
                    }
                    current = near;
                    continue;
                }
            }
            // Pop the next node that may still hold a closer hit.
            loop {
                if sp == 0 {
                    return false;
                }
                sp -= 1;
                let (n, t) = stack[sp];
                if t <= *t_max * ROBUST_SCALE {
                    current = n as usize;
                    break;
                }
            }
        }
    }
}
