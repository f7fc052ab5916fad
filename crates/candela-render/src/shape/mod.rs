//! Ray–shape intersection: triangles and spheres, and the surface points
//! with error bounds from which new rays are spawned without self-hits.
//! [`PrimRef`] names one primitive of a scene by kind and index.

mod generate;
mod hit;
mod prim;
mod sphere;
mod surface;
mod triangle;
mod triangle4;

pub use generate::icosphere;
pub use hit::SurfaceHit;
pub use prim::{PrimKind, PrimRef};
pub use sphere::{intersect_sphere, sphere_surface_point, sphere_uv, sphere_uv_in};
pub use surface::{gamma, offset_ray_origin, spawn_ray, SurfacePoint};
pub use triangle::{
    intersect_triangle, triangle_normal, triangle_surface_point,
    triangle_surface_point_with_normal, TriangleHit, TriangleRay,
};
pub use triangle4::{intersect_triangle4, occluded_triangle4, TrianglePacket, TriangleRay4};

#[cfg(test)]
mod fan_watertight_tests;
#[cfg(test)]
mod near_hit_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod watertight_tests;
