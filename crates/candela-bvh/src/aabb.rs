//! Axis-aligned bounding boxes, the only geometry the BVH knows about.

use glam::Vec3;

/// An axis-aligned box. The empty box has `min = +inf`, `max = -inf`, so that
/// growing it by any point or box yields that point or box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The identity for [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// A box from its two corners (as given; not reordered).
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box holding all `points`.
    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow(p))
    }

    /// This box grown to hold `p`.
    #[inline]
    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both boxes.
    #[inline]
    pub fn union(self, o: Aabb) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// True when no point lies inside (some `min > max`).
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Edge lengths, zero for an empty box.
    #[inline]
    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the surface area: the SAH only needs areas up to a constant factor.
    #[inline]
    pub fn half_area(&self) -> f32 {
        let e = self.extent();
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// Index of the longest axis (0 = x, 1 = y, 2 = z).
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// True when `inner` lies inside this box (an empty `inner` always does).
    pub fn contains(&self, inner: &Aabb) -> bool {
        inner.is_empty() || (self.min.cmple(inner.min).all() && self.max.cmpge(inner.max).all())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_is_identity_of_union() {
        let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 3.0, 4.0));
        assert_eq!(Aabb::EMPTY.union(b), b);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.half_area(), 0.0);
        assert!(b.contains(&Aabb::EMPTY));
    }

    #[test]
    fn half_area_and_axis() {
        let b = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(b.half_area(), 2.0 + 6.0 + 3.0);
        assert_eq!(b.longest_axis(), 2);
        assert_eq!(Aabb::from_points(&[Vec3::ONE, Vec3::ZERO]).max, Vec3::ONE);
    }
}
