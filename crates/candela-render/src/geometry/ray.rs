use glam::Vec3;

/// A ray `origin + t * dir` for `t` in `(0, t_max)`.
///
/// Spawned rays are offset from their surface by the intersection's error
/// bound (see [`crate::shape::offset_ray_origin`]), so `t` starts at zero and
/// no epsilon is needed at traversal time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start point.
    pub origin: Vec3,
    /// Direction; unit length for camera and scattered rays.
    pub dir: Vec3,
    /// Upper end of the parametric interval.
    pub t_max: f32,
}

impl Ray {
    /// A ray with an unbounded interval.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir,
            t_max: f32::INFINITY,
        }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}
