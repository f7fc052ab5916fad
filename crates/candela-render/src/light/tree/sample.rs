//! Choosing a light by walking the tree, and the probability of a given
//! light by retracing its trail: one rule ([`weights`]: each lane's
//! importance over the node's total) serves both, so [`LightTree::pmf`]
//! returns exactly the probability [`LightTree::choose`] reports.

use super::wide::{WideNode, LEAF};
use super::{LightContext, LightTree};
use crate::light::ONE_MINUS_EPSILON;

/// The importance of each child of `node` at `ctx` and their sum, or
/// `None` when no child can reach the point.
fn weights(node: &WideNode, ctx: &LightContext) -> Option<([f32; 4], f32)> {
    let w = node.bounds.importance(ctx);
    let total = w[0] + w[1] + w[2] + w[3];
    if total.is_nan() || total <= 0.0 || total.is_infinite() {
        return None;
    }
    Some((w, total))
}

impl LightTree {
    /// Chooses a light for `ctx` with the uniform number `u`: (light index,
    /// probability), or `None` when no light can reach the point.
    pub fn choose(&self, ctx: &LightContext, u: f32) -> Option<(u32, f32)> {
        let mut u = u;
        if !self.infinite.is_empty() {
            if u < self.p_infinite {
                let v = u / self.p_infinite;
                let k = self
                    .infinite_cdf
                    .partition_point(|&c| c <= v)
                    .min(self.infinite.len() - 1);
                return Some(self.infinite[k]);
            }
            u = ((u - self.p_infinite) / (1.0 - self.p_infinite)).min(ONE_MINUS_EPSILON);
        }
        if self.nodes.is_empty() {
            return None;
        }
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0usize;
        loop {
            let node = &self.nodes[at];
            let (w, total) = weights(node, ctx)?;
            // The first lane whose running sum passes u · total; rounding
            // past the last one takes the last lane that can be taken.
            let target = u * total;
            let (mut lane, mut before, mut sum) = (0, 0.0, 0.0);
            for (k, &wk) in w.iter().enumerate() {
                if wk > 0.0 {
                    (lane, before) = (k, sum);
                    sum += wk;
                    if target < sum {
                        break;
                    }
                }
            }
            pmf *= w[lane] / total;
            u = ((target - before) / w[lane]).clamp(0.0, ONE_MINUS_EPSILON);
            let child = node.child[lane];
            if child & LEAF != 0 {
                return Some((child & !LEAF, pmf));
            }
            at = child as usize;
        }
    }

    /// Probability that [`LightTree::choose`] at `ctx` picks light `i` (0
    /// for delta lights).
    pub fn pmf(&self, ctx: &LightContext, i: u32) -> f32 {
        if let Some(&(_, p)) = self.infinite.iter().find(|&&(l, _)| l == i) {
            return p;
        }
        let Some(Some(mut trail)) = self.trails.get(i as usize).copied() else {
            return 0.0;
        };
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0usize;
        loop {
            let node = &self.nodes[at];
            let Some((w, total)) = weights(node, ctx) else {
                return 0.0;
            };
            let lane = (trail & 3) as usize;
            pmf *= w[lane] / total;
            let child = node.child[lane];
            if child & LEAF != 0 || pmf == 0.0 {
                return pmf;
            }
            at = child as usize;
            trail >>= 2;
        }
    }

    /// Probability that [`LightTree::choose`] at `ctx` returns `None`: the
    /// mass the walk sends into nodes whose children the bounds all prove
    /// dark (a parent's looser bounds may not), so that
    /// `Σ pmf + dark_probability = 1`. Every path is walked: for tests.
    #[cfg(test)]
    pub(super) fn dark_probability(&self, ctx: &LightContext) -> f64 {
        fn walk(nodes: &[WideNode], at: usize, ctx: &LightContext, mass: f64) -> f64 {
            let Some((w, total)) = weights(&nodes[at], ctx) else {
                return mass;
            };
            let mut dark = 0.0;
            for (lane, &wk) in w.iter().enumerate() {
                let child = nodes[at].child[lane];
                if wk > 0.0 && child & LEAF == 0 {
                    dark += walk(nodes, child as usize, ctx, mass * f64::from(wk / total));
                }
            }
            dark
        }
        let tree_mass = f64::from(1.0 - self.p_infinite);
        if self.nodes.is_empty() {
            return if self.infinite.is_empty() { 1.0 } else { 0.0 };
        }
        walk(&self.nodes, 0, ctx, tree_mass)
    }
}
