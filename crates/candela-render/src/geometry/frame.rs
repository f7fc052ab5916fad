use glam::Vec3;

/// An orthonormal frame; BSDFs work in its local coordinates, where the
/// shading normal is +Z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Local +X in world space.
    pub x: Vec3,
    /// Local +Y in world space.
    pub y: Vec3,
    /// Local +Z (the normal) in world space.
    pub z: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n`, built without branches on a
    /// division by a small number (Duff et al. 2017, "Building an
    /// Orthonormal Basis, Revisited").
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let x = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let y = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { x, y, z: n }
    }

    /// A frame around the unit vector `n` whose +X is `tangent` made
    /// orthogonal to `n` (Gram-Schmidt) and normalised: the shading frame of
    /// an anisotropic BSDF, whose roughness follows the surface's dp/du.
    /// Falls back to [`Frame::from_normal`] when `tangent` is (nearly)
    /// parallel to `n` or not finite.
    pub fn from_normal_and_tangent(n: Vec3, tangent: Vec3) -> Self {
        match (tangent - n * n.dot(tangent)).try_normalize() {
            Some(x) => Self {
                x,
                y: n.cross(x),
                z: n,
            },
            None => Self::from_normal(n),
        }
    }

    /// World to local coordinates.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// Local to world coordinates.
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_round_trips() {
        let dirs = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
            Vec3::new(1e-8, 0.0, -1.0).normalize(),
        ];
        for n in dirs {
            let f = Frame::from_normal(n);
            for (a, b) in [(f.x, f.y), (f.y, f.z), (f.x, f.z)] {
                assert!(a.dot(b).abs() < 1e-6, "{n:?}");
            }
            for v in [f.x, f.y, f.z] {
                assert!((v.length() - 1.0).abs() < 1e-6, "{n:?}");
            }
            assert!(f.x.cross(f.y).dot(f.z) > 0.999, "right-handed for {n:?}");
            let w = Vec3::new(0.2, 0.7, -0.4);
            assert!((f.to_world(f.to_local(w)) - w).length() < 1e-6);
        }
    }
}
