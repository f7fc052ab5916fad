//! Deterministic samplers and warps from the unit square to the domains we sample.
//!
//! Every random number the renderer uses comes from a [`Sampler`], whose values
//! are a pure function of (seed, pixel, sample index, dimension), as pbrt-v4's
//! `StartPixelSample`. Renders are then identical for any thread count or
//! machine split, and one sample of one pixel can be replayed for debugging.
//! Warps ([`warp`]) turn those numbers into directions and points, each with
//! the density it produces and, where one exists, its inverse.

pub(crate) mod hash;
pub mod piecewise;
mod sampler;
mod sobol;
pub mod warp;

#[cfg(test)]
pub(crate) mod chi2;
#[cfg(test)]
mod sampler_tests;

pub use sampler::{Sampler, SamplerKind, SkippedDimension};
