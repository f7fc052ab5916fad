//! Random inputs for the crate's unit tests of the tree builders.

use crate::{Aabb, BuildOptions, Bvh};
use candela_testkit::SplitMix64 as Rng;
use glam::Vec3;

/// `n` boxes centred in [-10, 10]³ with half-extents in [0.01, `size`].
pub(crate) fn random_boxes(rng: &mut Rng, n: usize, size: f32) -> Vec<Aabb> {
    (0..n)
        .map(|_| {
            let c = rng.vec(-10.0, 10.0);
            let h = rng.vec(0.01, size);
            Aabb::new(c - h, c + h)
        })
        .collect()
}

/// The binary tree over `boxes`, their centres as centroids.
pub(crate) fn build(boxes: &[Aabb], opts: BuildOptions) -> Bvh {
    let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
    Bvh::build(boxes, &centroids, opts)
}
