//! Structural checks of a built hierarchy, for tests and debugging.

use crate::{Aabb, Bvh};

impl Bvh {
    /// Checks every invariant against the boxes the tree was built from:
    /// child indices in range and depth first, every node reached exactly
    /// once, child boxes inside their parent, each primitive's box inside
    /// its leaf, leaf ranges tiling the slots, and the order a permutation.
    pub fn validate(&self, boxes: &[Aabb]) -> Result<(), String> {
        let n = self.order.len();
        if n != boxes.len() {
            return Err(format!("order has {n} entries for {} boxes", boxes.len()));
        }
        let mut seen = vec![false; n];
        for &i in &self.order {
            let s = seen
                .get_mut(i as usize)
                .ok_or(format!("order holds {i} >= {n}"))?;
            if *s {
                return Err(format!("primitive {i} appears twice in the order"));
            }
            *s = true;
        }
        if self.nodes.is_empty() {
            return if n == 0 {
                Ok(())
            } else {
                Err("no nodes for a non-empty input".into())
            };
        }
        let mut reached = vec![false; self.nodes.len()];
        let mut slot_used = vec![false; n];
        let mut stack = vec![(0usize, 1u32)];
        let mut max_depth = 0;
        while let Some((i, depth)) = stack.pop() {
            max_depth = max_depth.max(depth);
            if std::mem::replace(&mut reached[i], true) {
                return Err(format!("node {i} reached twice"));
            }
            let node = &self.nodes[i];
            let b = node.bounds();
            if node.is_leaf() {
                let (a, e) = (
                    node.offset as usize,
                    node.offset as usize + node.count as usize,
                );
                if e > n {
                    return Err(format!("leaf {i} range {a}..{e} past {n}"));
                }
                for (slot, used) in slot_used.iter_mut().enumerate().take(e).skip(a) {
                    if std::mem::replace(used, true) {
                        return Err(format!("slot {slot} in two leaves"));
                    }
                    let p = self.order[slot] as usize;
                    if !b.contains(&boxes[p]) {
                        return Err(format!("primitive {p} sticks out of leaf {i}"));
                    }
                }
                continue;
            }
            let (l, r) = (i + 1, node.offset as usize);
            if r <= l || r >= self.nodes.len() {
                return Err(format!("node {i}: bad children {l}, {r}"));
            }
            for c in [l, r] {
                if !b.contains(&self.nodes[c].bounds()) {
                    return Err(format!("child {c} sticks out of node {i}"));
                }
                stack.push((c, depth + 1));
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
