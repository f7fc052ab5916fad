//! Choosing a light by walking the tree, and the probability of a given
//! light by retracing its trail: one branch rule ([`branch`]) serves both,
//! so [`LightTree::pmf`] returns exactly the probability
//! [`LightTree::choose`] reports.

use super::{LightContext, LightTree, Node};

/// The largest `f32` below 1: a remapped random number must stay in [0, 1).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// The probability of taking the first child of interior node `at` at
/// `ctx` (its importance over the pair's), or `None` when neither child
/// can reach the point.
fn branch(nodes: &[Node], at: usize, ctx: &LightContext) -> Option<f32> {
    let second = nodes[at].second_or_light as usize;
    let i0 = nodes[at + 1].bounds.importance(ctx);
    let i1 = nodes[second].bounds.importance(ctx);
    let total = i0 + i1;
    if total.is_nan() || total <= 0.0 || total.is_infinite() {
        return None;
    }
    Some(i0 / total)
}

/// Whether a tree that is a single leaf can reach the point at all (a
/// leaf below the root was already vouched for by its parent's branch).
fn root_leaf_reaches(nodes: &[Node], ctx: &LightContext) -> bool {
    nodes[0].bounds.importance(ctx) > 0.0
}

/// The number of branches from the root down to the leaf of `trail`.
pub(super) fn leaf_depth(nodes: &[Node], mut trail: u64) -> u32 {
    let (mut at, mut depth) = (0usize, 0u32);
    while !nodes[at].leaf {
        at = if trail & 1 == 0 {
            at + 1
        } else {
            nodes[at].second_or_light as usize
        };
        trail >>= 1;
        depth += 1;
    }
    depth
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
        if self.nodes[0].leaf && !root_leaf_reaches(&self.nodes, ctx) {
            return None;
        }
        while !self.nodes[at].leaf {
            let p0 = branch(&self.nodes, at, ctx)?;
            if u < p0 {
                pmf *= p0;
                u = (u / p0).min(ONE_MINUS_EPSILON);
                at += 1;
            } else {
                let p1 = 1.0 - p0;
                pmf *= p1;
                u = ((u - p0) / p1).min(ONE_MINUS_EPSILON);
                at = self.nodes[at].second_or_light as usize;
            }
        }
        Some((self.nodes[at].second_or_light, pmf))
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
        if self.nodes[0].leaf && !root_leaf_reaches(&self.nodes, ctx) {
            return 0.0;
        }
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0usize;
        while !self.nodes[at].leaf {
            let Some(p0) = branch(&self.nodes, at, ctx) else {
                return 0.0;
            };
            if trail & 1 == 0 {
                pmf *= p0;
                at += 1;
            } else {
                pmf *= 1.0 - p0;
                at = self.nodes[at].second_or_light as usize;
            }
            trail >>= 1;
        }
        pmf
    }

    /// Probability that [`LightTree::choose`] at `ctx` returns `None`: the
    /// mass the walk sends into nodes whose children the bounds both prove
    /// dark (a parent's looser bounds may not), so that
    /// `Σ pmf + dark_probability = 1`. Every path is walked: for tests.
    #[cfg(test)]
    pub(super) fn dark_probability(&self, ctx: &LightContext) -> f64 {
        fn walk(nodes: &[Node], at: usize, ctx: &LightContext, mass: f64) -> f64 {
            if nodes[at].leaf {
                return 0.0;
            }
            match branch(nodes, at, ctx) {
                None => mass,
                Some(p0) => {
                    let second = nodes[at].second_or_light as usize;
                    walk(nodes, at + 1, ctx, mass * f64::from(p0))
                        + walk(nodes, second, ctx, mass * f64::from(1.0 - p0))
                }
            }
        }
        let tree_mass = f64::from(1.0 - self.p_infinite);
        if self.nodes.is_empty() {
            return if self.infinite.is_empty() { 1.0 } else { 0.0 };
        }
        if self.nodes[0].leaf && !root_leaf_reaches(&self.nodes, ctx) {
            return tree_mass;
        }
        walk(&self.nodes, 0, ctx, tree_mass)
    }
}
