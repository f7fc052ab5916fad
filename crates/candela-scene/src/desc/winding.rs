//! Reversing a mesh's winding, which turns its front faces round: Candela
//! takes a triangle's front (glass or medium side, the side a one-sided
//! lamp lights) from the order of its corners.

use super::MeshDesc;

impl MeshDesc {
    /// Swaps the second and third corner of every triangle, and of its
    /// normal and uv indices (which name the same corners). Normals are
    /// left as they are: the shading side follows them, not the winding.
    pub fn reverse_winding(&mut self) {
        for t in self
            .triangles
            .iter_mut()
            .chain(self.normal_indices.iter_mut())
            .chain(self.uv_indices.iter_mut())
        {
            t.swap(1, 2);
        }
    }
}
