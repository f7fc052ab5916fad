//! Structural checks of the wide hierarchies.

use crate::wide::PADDING;
use crate::{Aabb, WideBvh};

impl<const W: usize> WideBvh<W> {
    /// Checks every invariant against the primitive boxes: every node
    /// reached once from the root, child nodes' boxes inside their lane's
    /// box, each primitive's box inside its leaf lane, leaf ranges tiling
    /// the slots, unused lanes empty, and the order a permutation (apart
    /// from [`PADDING`] entries, which no leaf may count).
    pub fn validate(&self, boxes: &[Aabb]) -> Result<(), String> {
        let n = self.order.iter().filter(|&&i| i != PADDING).count();
        if n != boxes.len() {
            return Err(format!("order has {n} entries for {} boxes", boxes.len()));
        }
        let mut seen = vec![false; n];
        for &i in self.order.iter().filter(|&&i| i != PADDING) {
            let s = seen
                .get_mut(i as usize)
                .ok_or(format!("order holds {i} >= {n}"))?;
            if std::mem::replace(s, true) {
                return Err(format!("primitive {i} appears twice"));
            }
        }
        if self.nodes.is_empty() {
            return if n == 0 {
                Ok(())
            } else {
                Err("no nodes for a non-empty input".into())
            };
        }
        let mut reached = vec![false; self.nodes.len()];
        let mut slot_used: Vec<bool> = self.order.iter().map(|&i| i == PADDING).collect();
        let mut stack = vec![(
            0usize,
            Aabb::new(
                glam::Vec3::splat(f32::NEG_INFINITY),
                glam::Vec3::splat(f32::INFINITY),
            ),
            1u32,
        )];
        let mut max_depth = 0;
        while let Some((i, parent, depth)) = stack.pop() {
            max_depth = max_depth.max(depth);
            let node = self.nodes.get(i).ok_or(format!("node {i} out of range"))?;
            if std::mem::replace(&mut reached[i], true) {
                return Err(format!("node {i} reached twice"));
            }
            for lane in 0..W {
                let b = node.lane_bounds(lane);
                if !parent.contains(&b) {
                    return Err(format!("node {i} lane {lane} sticks out of its parent"));
                }
                let (c, k) = (node.child[lane] as usize, node.count[lane] as usize);
                if b.is_empty() {
                    if k != 0 {
                        return Err(format!(
                            "node {i} lane {lane}: empty box with {k} primitives"
                        ));
                    }
                } else if k == 0 {
                    if c <= i {
                        return Err(format!("node {i} lane {lane}: child {c} not after it"));
                    }
                    stack.push((c, b, depth + 1));
                } else {
                    for slot in c..c + k {
                        let used = slot_used
                            .get_mut(slot)
                            .ok_or(format!("slot {slot} out of range"))?;
                        if std::mem::replace(used, true) {
                            return Err(format!("slot {slot} in two leaves, or padding"));
                        }
                        if !b.contains(&boxes[self.order[slot] as usize]) {
                            return Err(format!("primitive in slot {slot} sticks out of its leaf"));
                        }
                    }
                }
            }
        }
        if let Some(i) = reached.iter().position(|r| !r) {
            return Err(format!("node {i} unreachable"));
        }
        if let Some(s) = slot_used.iter().position(|u| !u) {
            return Err(format!("slot {s} in no leaf"));
        }
        if max_depth != self.depth {
            return Err(format!("depth is {max_depth}, recorded {}", self.depth));
        }
        Ok(())
    }
}
