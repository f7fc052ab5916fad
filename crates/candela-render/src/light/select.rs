//! Which non-delta light a light sample goes to: the strategies of the
//! `light_selection` setting and the one interface the integrators use,
//! [`LightSelector::choose`] and [`LightSelector::pmf`], both functions of
//! the receiving point ([`LightContext`]) so that a BSDF sample that finds
//! an emitter weighs it with the probability the choice there would have
//! had.

use super::tree::{LightContext, LightTree};
use super::{LightSet, ONE_MINUS_EPSILON};
use glam::Vec2;

/// The smallest share of [0, 1) from which [`LightSelector::choose_with_point`]
/// reuses the choosing number for the point: rescaled from a share of
/// 2^-8, a number of 24 bits (the sampler's) keeps 16, finer than any
/// lamp's texture or shape needs.
pub const MIN_REUSED_SHARE: f32 = 1.0 / 256.0;

/// Scenes with more sampled (non-delta) lights than this use the light
/// tree under [`LightSelection::Auto`]; others choose by power. With a few
/// dozen lights a choice by power is already close to the tree's (its
/// distance and orientation terms matter once lights are many and spread
/// out), the tree's walk costs a few importance evaluations per level, and
/// the scenes of the CS184 course (at most a handful of emitting
/// triangles) keep the images they always had, bit for bit.
pub const AUTO_TREE_ABOVE: usize = 64;

/// How the light of each light sample is chosen among the non-delta lights
/// (delta lights are each sampled once per vertex whatever this says).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum LightSelection {
    /// The light tree when the scene has more than 64 sampled lights
    /// (emitting triangles, spheres, area lights, skies), power otherwise.
    #[default]
    Auto,
    /// Every light equally likely.
    Uniform,
    /// In proportion to each light's power, wherever the point is; lights
    /// at infinity as a group get at most n/(n + 1) of the choices (n of
    /// them), as their power figure grows with the scene's size.
    Power,
    /// By the light tree: in proportion to a bound of each light's
    /// contribution at the point (power, distance, orientation; Conty
    /// Estevez and Kulla 2018). Best with many lights.
    Bvh,
}

/// A selection strategy resolved for one scene.
#[derive(Clone, Copy, Debug)]
enum Strategy<'a> {
    Uniform,
    Power,
    Tree(&'a LightTree),
}

/// The light set with a strategy: chooses lights and says how likely a
/// choice was.
#[derive(Clone, Copy, Debug)]
pub struct LightSelector<'a> {
    set: &'a LightSet,
    strategy: Strategy<'a>,
}

impl LightSet {
    /// The selector for `how` (`Auto` resolved by the number of sampled
    /// lights; the tree is built on first use and kept).
    pub fn selector(&self, how: LightSelection) -> LightSelector<'_> {
        let tree = || Strategy::Tree(self.tree());
        let strategy = match how {
            LightSelection::Uniform => Strategy::Uniform,
            LightSelection::Power => Strategy::Power,
            LightSelection::Bvh => tree(),
            LightSelection::Auto if self.sampled_count() > AUTO_TREE_ABOVE => tree(),
            LightSelection::Auto => Strategy::Power,
        };
        LightSelector {
            set: self,
            strategy,
        }
    }
}

impl LightSelector<'_> {
    /// Chooses a non-delta light for a sample at `ctx` with the uniform
    /// number `u`: (light index, probability), or `None` when there is no
    /// such light or none can reach the point.
    pub fn choose(&self, ctx: &LightContext, u: f32) -> Option<(u32, f32)> {
        match self.strategy {
            Strategy::Uniform => self.set.choose_uniformly(u),
            Strategy::Power => self.set.choose_by_power(u),
            Strategy::Tree(tree) => tree.choose(ctx, u),
        }
    }

    /// Chooses a non-delta light for a light sample at `ctx` together with
    /// the two numbers for the point on it: (light index, probability,
    /// the point's numbers).
    ///
    /// `u` is the sample's 2-D number. Choosing by power or uniformly, its
    /// first coordinate makes the choice and is then reused, rescaled from
    /// the chosen light's share of [0, 1) to all of it (pbrt-v4's
    /// `SampleDiscrete` remapping): given the choice it is still uniform and
    /// independent of the second coordinate, and the choice and the point
    /// are stratified together. That saves a draw per light sample; the
    /// sampler was the largest cost of a light sample outside its shadow
    /// ray (BENCHMARKS.md). `u_choose` (the sample's own one-dimensional
    /// number) is called only when reuse would leave too few bits: a share
    /// under [`MIN_REUSED_SHARE`], or the light tree, whose walk rescales
    /// at every level.
    pub fn choose_with_point(
        &self,
        ctx: &LightContext,
        u: Vec2,
        u_choose: impl FnOnce() -> f32,
    ) -> Option<(u32, f32, Vec2)> {
        let (index, pmf, share) = match self.strategy {
            Strategy::Tree(tree) => {
                let (index, pmf) = tree.choose(ctx, u_choose())?;
                return Some((index, pmf, u));
            }
            Strategy::Power => self.set.choose_by_power_within(u.x)?,
            Strategy::Uniform => self.set.choose_uniformly_within(u.x)?,
        };
        let width = share.end - share.start;
        let x = if width >= MIN_REUSED_SHARE {
            ((u.x - share.start) / width).clamp(0.0, ONE_MINUS_EPSILON)
        } else {
            u_choose()
        };
        Some((index, pmf, Vec2::new(x, u.y)))
    }

    /// Probability that [`LightSelector::choose`] at `ctx` picks light `i`
    /// (0 for delta lights).
    pub fn pmf(&self, ctx: &LightContext, i: u32) -> f32 {
        match self.strategy {
            Strategy::Uniform => self.set.uniform_pmf(i),
            Strategy::Power => self.set.power_pmf(i),
            Strategy::Tree(tree) => tree.pmf(ctx, i),
        }
    }

    /// Whether the strategy depends on the point (the tree).
    pub fn uses_tree(&self) -> bool {
        matches!(self.strategy, Strategy::Tree(_))
    }
}
