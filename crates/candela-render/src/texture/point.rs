//! Where a texture is read: the surface's uv and its vertex colour there.

use glam::{Vec2, Vec3};

/// What a texture slot reads at a surface point: the texture coordinates
/// (images, patterns) and the mesh's vertex colour interpolated there
/// (`candela_scene::TextureSource::VertexColor`, and textures multiplied
/// by it). A point given by its uv alone (`From<Vec2>`) has the vertex
/// colour of a mesh without colours: white.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexturePoint {
    /// Texture coordinates.
    pub uv: Vec2,
    /// Linear RGB vertex colour; white where the mesh has none.
    pub vertex_color: Vec3,
}

impl TexturePoint {
    /// The vertex colour of a surface without colours.
    pub const NO_VERTEX_COLOR: Vec3 = Vec3::ONE;

    /// The point at `uv` with vertex colour `vertex_color`.
    #[inline]
    pub fn new(uv: Vec2, vertex_color: Vec3) -> Self {
        Self { uv, vertex_color }
    }
}

impl From<Vec2> for TexturePoint {
    #[inline]
    fn from(uv: Vec2) -> Self {
        Self::new(uv, Self::NO_VERTEX_COLOR)
    }
}
