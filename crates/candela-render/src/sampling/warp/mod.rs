//! Warps from the unit square to the domains the renderer samples.
//!
//! Each warp `square_to_x(u)` comes with `x_pdf`, the density of its output
//! (per unit solid angle for directions, per unit area for points; the
//! measure is named on each function), and where one exists an inverse
//! `x_to_square` with `square_to_x(x_to_square(p)) == p`. Inverses let tests
//! check bijectivity and let future code (e.g. path guiding or MLT) map
//! directions back to sample space.
//!
//! The spherical-polygon warps (`spherical_polygon.rs`) sample the solid
//! angle a triangle or rectangle subtends; their directions are in world
//! space, with corners given relative to the viewpoint.
//!
//! Other directions are in a local frame whose +Z is the pole (the normal for
//! hemispheres, the axis for cones).

mod planar;
mod spherical;
mod spherical_polygon;
#[cfg(test)]
mod spherical_polygon_tests;
#[cfg(test)]
mod tests;
mod trig;

pub use planar::{
    concentric_disk_to_square, square_to_concentric_disk, square_to_uniform_triangle,
    uniform_disk_pdf, uniform_triangle_pdf, uniform_triangle_to_square, Parallelogram,
};
pub use spherical::{
    cosine_hemisphere_pdf, cosine_hemisphere_to_square, square_to_cosine_hemisphere,
    square_to_uniform_cone, square_to_uniform_hemisphere, square_to_uniform_sphere,
    uniform_cone_pdf, uniform_cone_to_square, uniform_hemisphere_pdf, uniform_hemisphere_to_square,
    uniform_sphere_pdf, uniform_sphere_to_square,
};
pub use spherical_polygon::{
    rectangle_solid_angle, square_to_spherical_rectangle, square_to_spherical_triangle,
    triangle_solid_angle,
};
pub use trig::{sin_cos_turns, sin_cos_within_quarter_pi};
