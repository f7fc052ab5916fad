//! The typed reference to one primitive of a scene: which kind of shape and
//! which one of that kind. It is the only place that knows how the two are
//! packed into a `u32`; everything else asks [`PrimRef::kind`] and
//! [`PrimRef::index`] and matches on [`PrimKind`], so the compiler lists
//! every place a new shape must be handled.

use std::fmt;

/// The kinds of primitive the renderer intersects. Adding a shape adds a
/// variant here (and to [`PrimKind::ALL`]), its intersection in its own file
/// in this folder, and an arm wherever a `match` on the kind now fails to
/// compile (the BVH leaf test, the hit's surface, the emitter's shape).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PrimKind {
    /// A triangle of the scene's (flattened) meshes.
    Triangle = 0,
    /// An analytic sphere.
    Sphere = 1,
}

impl PrimKind {
    /// Every kind, in tag order.
    pub const ALL: [PrimKind; 2] = [PrimKind::Triangle, PrimKind::Sphere];
    /// Number of kinds.
    pub const COUNT: usize = Self::ALL.len();
}

/// A primitive: a kind and an index among the primitives of that kind.
/// Four bytes (kind in the top [`PrimRef::KIND_BITS`] bits), so it can be
/// stored per BVH slot and compared cheaply in leaf loops.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct PrimRef(u32);

impl PrimRef {
    /// Bits used by the kind tag (room for four kinds).
    pub const KIND_BITS: u32 = 2;
    const INDEX_BITS: u32 = 32 - Self::KIND_BITS;
    /// Largest index a reference can hold (about a billion per kind).
    pub const MAX_INDEX: u32 = (1 << Self::INDEX_BITS) - 1;

    /// Primitive `index` of `kind`; `None` if the index does not fit.
    #[inline]
    pub const fn new(kind: PrimKind, index: u32) -> Option<Self> {
        if index > Self::MAX_INDEX {
            return None;
        }
        Some(Self(((kind as u32) << Self::INDEX_BITS) | index))
    }

    /// Triangle `index` (which must be at most [`PrimRef::MAX_INDEX`]:
    /// the scene builder checks the counts once).
    #[inline]
    pub const fn triangle(index: u32) -> Self {
        Self((PrimKind::Triangle as u32) << Self::INDEX_BITS | (index & Self::MAX_INDEX))
    }

    /// Sphere `index` (at most [`PrimRef::MAX_INDEX`]).
    #[inline]
    pub const fn sphere(index: u32) -> Self {
        Self((PrimKind::Sphere as u32) << Self::INDEX_BITS | (index & Self::MAX_INDEX))
    }

    /// The kind of shape.
    #[inline(always)]
    pub const fn kind(self) -> PrimKind {
        match self.0 >> Self::INDEX_BITS {
            0 => PrimKind::Triangle,
            _ => PrimKind::Sphere,
        }
    }

    /// The index among primitives of its kind.
    #[inline(always)]
    pub const fn index(self) -> u32 {
        self.0 & Self::MAX_INDEX
    }

    /// Whether this is a triangle (the common case in leaf loops).
    #[inline(always)]
    pub const fn is_triangle(self) -> bool {
        self.0 >> Self::INDEX_BITS == PrimKind::Triangle as u32
    }
}

impl fmt::Debug for PrimRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}({})", self.kind(), self.index())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kind_and_index_round_trip() {
        for kind in PrimKind::ALL {
            for index in [0, 1, 12345, PrimRef::MAX_INDEX] {
                let p = PrimRef::new(kind, index).unwrap();
                assert_eq!((p.kind(), p.index()), (kind, index));
                assert_eq!(p.is_triangle(), kind == PrimKind::Triangle);
            }
        }
        assert_eq!(PrimRef::new(PrimKind::Sphere, PrimRef::MAX_INDEX + 1), None);
        assert_eq!(
            PrimRef::triangle(7),
            PrimRef::new(PrimKind::Triangle, 7).unwrap()
        );
        assert_eq!(
            PrimRef::sphere(7),
            PrimRef::new(PrimKind::Sphere, 7).unwrap()
        );
        assert_eq!(format!("{:?}", PrimRef::sphere(3)), "Sphere(3)");
    }
}
