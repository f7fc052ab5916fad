//! The flat 32-byte node shared by build, traversal and validation.

use crate::Aabb;
use glam::Vec3;

/// One BVH node: a box and either two children or a range of primitives.
///
/// 32 bytes, aligned to 32, so a node never straddles a cache line and two
/// siblings usually share one. Nodes are stored depth first: an interior
/// node's first child is the next node, `offset` is the second child. A leaf
/// (`count > 0`) covers slots `offset .. offset + count` of
/// [`crate::Bvh::primitive_order`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct Node {
    /// Lower corner of the box.
    pub min: [f32; 3],
    /// Second child (interior) or first primitive slot (leaf).
    pub offset: u32,
    /// Upper corner of the box.
    pub max: [f32; 3],
    /// Number of primitives; zero marks an interior node.
    pub count: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

impl Node {
    /// A leaf over `count` slots starting at `first`.
    pub(crate) fn leaf(b: Aabb, first: u32, count: u32) -> Self {
        Self {
            min: b.min.to_array(),
            offset: first,
            max: b.max.to_array(),
            count,
        }
    }

    /// An interior node; `second` is patched once the first subtree is laid out.
    pub(crate) fn interior(b: Aabb, second: u32) -> Self {
        Self {
            min: b.min.to_array(),
            offset: second,
            max: b.max.to_array(),
            count: 0,
        }
    }

    /// True for a leaf.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The node's box.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(Vec3::from(self.min), Vec3::from(self.max))
    }
}
