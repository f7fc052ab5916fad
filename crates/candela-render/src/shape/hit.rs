//! The record of a ray hitting a surface: what shading needs to know about
//! the point. It is made by the scene (which knows the primitives) and read
//! by materials and integrators, so it lives here, below both.

use super::{offset_ray_origin, PrimRef};
use crate::texture::TexturePoint;
use glam::{Vec2, Vec3, Vec4};

/// Everything the integrators need to know about a hit point.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// World position.
    pub p: Vec3,
    /// Bound on the absolute error of `p` per axis.
    pub p_error: Vec3,
    /// Unit geometric normal, flipped to the side the ray came from.
    pub ng: Vec3,
    /// Unit shading normal as the surface defines it (not flipped toward
    /// the ray): BSDF frames are built on it, so dielectrics can tell
    /// entering from leaving.
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// The mesh's vertex colour interpolated here (linear RGB); white
    /// ([`TexturePoint::NO_VERTEX_COLOR`]) where it has none.
    pub vertex_color: Vec3,
    /// The mesh's per-vertex tangent interpolated here (xyz not normalised,
    /// w = ±1 handedness), when the mesh has tangents; normal maps use it
    /// instead of the triangle's dp/du.
    pub tangent: Option<Vec4>,
    /// Material index.
    pub material: u32,
    /// The primitive hit.
    pub prim: PrimRef,
    /// Unit direction back toward the ray origin.
    pub wo: Vec3,
    /// Whether the ray arrived on the side the surface's own normal points
    /// to (the side an emitter emits on).
    pub front_face: bool,
    /// Ray parameter of the hit.
    pub t: f32,
}

impl SurfaceHit {
    /// Where the hit's textures are read: its uv and vertex colour.
    #[inline]
    pub fn texture_point(&self) -> TexturePoint {
        TexturePoint::new(self.uv, self.vertex_color)
    }

    /// The shading normal flipped to the side the ray came from.
    pub fn ns_facing(&self) -> Vec3 {
        if self.front_face {
            self.ns
        } else {
            -self.ns
        }
    }

    /// Origin for a ray leaving this point in direction `w`, offset past the
    /// error bound so that it cannot re-hit this surface. Inlined, like
    /// [`offset_ray_origin`], into the bounce and the shadow rays.
    #[inline(always)]
    pub fn spawn_origin(&self, w: Vec3) -> Vec3 {
        offset_ray_origin(self.p, self.p_error, self.ng, w)
    }
}
