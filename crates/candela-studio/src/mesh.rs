//! The scene's surfaces as the page's WebGL view draws them.
//!
//! One flat array of world-space triangles (three `f32` vertices each,
//! little-endian): the render scene's triangles in primitive order, then
//! each sphere tessellated into [`SPHERE_TRIANGLES`] triangles. Primitive
//! `i < triangles` is triangle `i`; sphere `j` is triangles
//! `triangles + j * SPHERE_TRIANGLES ..`, so the page can highlight the
//! primitives of a BVH node by id.

use candela_render::scene::Geometry;
use glam::Vec3;
use std::f32::consts::PI;

/// Segments around a tessellated sphere.
const SPHERE_SEGMENTS: u32 = 16;
/// Rings from pole to pole.
const SPHERE_RINGS: u32 = 8;
/// Triangles per tessellated sphere.
pub const SPHERE_TRIANGLES: u32 = 2 * SPHERE_SEGMENTS * SPHERE_RINGS;

/// Every surface as triangle soup, in primitive order.
pub fn triangles(geometry: &Geometry) -> Vec<[Vec3; 3]> {
    let tris = &geometry.triangles;
    let mut out: Vec<[Vec3; 3]> = tris
        .triangles
        .iter()
        .map(|t| {
            t.map(|i| {
                tris.positions
                    .get(i as usize)
                    .copied()
                    .unwrap_or(Vec3::ZERO)
            })
        })
        .collect();
    for s in &geometry.spheres {
        out.extend(sphere_triangles(s.center, s.radius.abs()));
    }
    out
}

/// The triangles as little-endian `f32` bytes (nine per triangle).
pub fn to_bytes(triangles: &[[Vec3; 3]]) -> Vec<u8> {
    triangles
        .iter()
        .flat_map(|t| t.iter().flat_map(|v| v.to_array()))
        .flat_map(f32::to_le_bytes)
        .collect()
}

/// A latitude-longitude sphere of [`SPHERE_TRIANGLES`] triangles (the
/// ones at the poles are degenerate, which keeps the count fixed).
fn sphere_triangles(center: Vec3, radius: f32) -> Vec<[Vec3; 3]> {
    let point = |ring: u32, seg: u32| {
        let theta = PI * ring as f32 / SPHERE_RINGS as f32;
        let phi = 2.0 * PI * seg as f32 / SPHERE_SEGMENTS as f32;
        center
            + radius
                * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                )
    };
    let mut out = Vec::with_capacity(SPHERE_TRIANGLES as usize);
    for ring in 0..SPHERE_RINGS {
        for seg in 0..SPHERE_SEGMENTS {
            let (a, b) = (point(ring, seg), point(ring, seg + 1));
            let (c, d) = (point(ring + 1, seg), point(ring + 1, seg + 1));
            out.push([a, c, b]);
            out.push([b, c, d]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sphere_has_its_fixed_count_on_its_surface() {
        let c = Vec3::new(1.0, 2.0, 3.0);
        let tris = sphere_triangles(c, 0.5);
        assert_eq!(tris.len() as u32, SPHERE_TRIANGLES);
        for v in tris.iter().flatten() {
            assert!(((*v - c).length() - 0.5).abs() < 1e-5);
        }
        assert_eq!(to_bytes(&tris).len(), tris.len() * 36);
    }
}
