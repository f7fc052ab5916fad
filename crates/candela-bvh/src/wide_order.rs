//! The order in which an any-hit query visits a node's children.
//!
//! A closest-hit query visits entered children nearest first. An any-hit
//! query stops at the first primitive it finds, so the best order is the
//! one that finds a hit soonest for the work spent: for children that end
//! the query with probabilities `p_i` at expected costs `c_i`, visiting
//! them by decreasing `p_i / c_i` minimises the expected cost (the classic
//! ordering of independent tests). Sorting by distance per ray costs more
//! than it saves on shadow rays, so the order is fixed at build time, as
//! the lane order, and the walk keeps it (leaves first, then lanes in
//! order; `wide_traverse.rs`).
//!
//! Both figures come from the boxes alone:
//! - `p`: the chance that a random line through a child's box meets a
//!   primitive inside is at most the primitives' surface area over the
//!   box's (Cauchy–Crofton: a convex body inside a convex box is hit by a
//!   fraction area(body) / area(box) of the lines that cross the box). A
//!   flat primitive has two sides, and its area is at most half the norm
//!   of its box's face areas (a triangle inside a rectangle covers at most
//!   half of it, in each of the three projections). So
//!   `p = min(1, Σ |faces(box_i)| / area(box))`: 1 for a wall that fills
//!   its box, small for a detailed mesh whose box is mostly empty.
//! - `c`: the subtree's SAH cost, in the units of the collapse's costs.
//!
//! What this buys: in a room (a Cornell box, a scene on a ground quad) a
//! ray that leaves an object is stopped by a wall near the root instead of
//! first walking every subtree of the object it left. Unoccluded rays visit
//! every entered child in any order, so they lose nothing.

use crate::wide::WideBvh;
use crate::wide_collapse::CollapseCosts;
use crate::{Aabb, PADDING};

/// What a lane's subtree offers an any-hit query.
#[derive(Clone, Copy, Debug, Default)]
struct Occluder {
    /// Bound on the primitives' area (both sides), the `p` numerator.
    area: f32,
    /// Expected cost of a walk that enters the lane's box.
    cost: f32,
}

/// Twice the bound on a flat primitive's area from its box: the norm of the
/// box's three face areas (`p` counts both sides).
fn occluding_area(b: &Aabb) -> f32 {
    let e = b.extent().max(glam::Vec3::ZERO);
    glam::Vec3::new(e.y * e.z, e.x * e.z, e.x * e.y).length()
}

impl<const W: usize> WideBvh<W> {
    /// Reorders every node's lanes by decreasing `p / c` (see the module
    /// doc), unused lanes last. `boxes` are the primitive boxes the tree was
    /// built over, by the caller's index.
    pub(crate) fn order_lanes_for_any_hit(&mut self, boxes: &[Aabb], costs: &CollapseCosts) {
        let mut lanes = vec![[Occluder::default(); W]; self.nodes.len()];
        // Children come after their parent (the collapse emits depth first),
        // so one backward pass sees every child before its parent.
        for i in (0..self.nodes.len()).rev() {
            let node = self.nodes[i];
            for lane in 0..W {
                let b = node.lane_bounds(lane);
                if b.is_empty() {
                    continue;
                }
                lanes[i][lane] = if node.count[lane] > 0 {
                    let first = node.child[lane] as usize;
                    let slots = &self.order[first..first + node.count[lane] as usize];
                    let area = slots
                        .iter()
                        .filter(|&&p| p != PADDING)
                        .filter_map(|&p| boxes.get(p as usize))
                        .map(occluding_area)
                        .sum();
                    Occluder {
                        area,
                        // Per unit of the box's area: the walk has entered it.
                        cost: costs.leaf_lane(1.0, node.count[lane]),
                    }
                } else {
                    let child = node.child[lane] as usize;
                    let mut area = 0.0;
                    let mut cost = costs.node;
                    let outer = b.half_area().max(f32::MIN_POSITIVE);
                    for (l, o) in lanes[child].iter().enumerate() {
                        area += o.area;
                        cost +=
                            self.nodes[child].lane_bounds(l).half_area().max(0.0) / outer * o.cost;
                    }
                    Occluder { area, cost }
                };
            }
            let mut perm: [usize; W] = std::array::from_fn(|l| l);
            let key = |l: usize| {
                let b = node.lane_bounds(l);
                if b.is_empty() {
                    return f32::NEG_INFINITY;
                }
                let o = lanes[i][l];
                let p = (o.area / (2.0 * b.half_area()).max(f32::MIN_POSITIVE)).min(1.0);
                p / o.cost.max(f32::MIN_POSITIVE)
            };
            // Stable: equal keys keep the collapse's order.
            perm.sort_by(|&a, &b| key(b).total_cmp(&key(a)));
            let mut sorted = node;
            let mut stats = [Occluder::default(); W];
            for (to, &from) in perm.iter().enumerate() {
                for row in 0..6 {
                    sorted.bounds[row][to] = node.bounds[row][from];
                }
                sorted.child[to] = node.child[from];
                sorted.count[to] = node.count[from];
                stats[to] = lanes[i][from];
            }
            self.nodes[i] = sorted;
            lanes[i] = stats;
        }
    }
}

#[cfg(test)]
#[path = "wide_order_tests.rs"]
mod tests;
