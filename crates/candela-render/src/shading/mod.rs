//! From a hit and its material to what the integrators shade with: the
//! textured BSDF, the shading frame (normal maps), the emitted radiance,
//! and whether the surface is there at all (opacity cut-outs).
//!
//! - [`textures`]: every texture slot read at the hit's `uv`.
//! - [`normal_map`]: tangent-space normal maps and the shading-frame rule
//!   that never lets a sampled direction leak through the geometric
//!   surface (bend the mapped normal toward the viewer; the geometric
//!   normal decides reflection vs transmission: [`scatter_allowed`]).
//! - [`opacity`]: cut-outs, applied by the visibility queries
//!   (`scene/visibility.rs`) to camera, bounce and shadow rays alike.

pub mod normal_map;
pub mod opacity;
pub mod textures;

#[cfg(test)]
mod leak_tests;
#[cfg(test)]
mod sides_tests;

pub use textures::MaterialTextures;

use crate::bsdf::{Bsdf, BsdfSample};
use crate::geometry::Frame;
use crate::material::Material;
use crate::scene::Scene;
use crate::shape::{PrimKind, SurfaceHit};
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// The frame a BSDF is evaluated in at `hit`: around the shading normal,
/// perturbed by the normal or bump map of the material on the side the hit
/// sees ([`Material::facing`]) (and bent by the rule of [`normal_map`])
/// when it has one, with its +X along dp/du when that material's BSDF is
/// anisotropic (Mitsuba's shading frame). Otherwise this is exactly
/// `Frame::from_normal(hit.ns)`, inlined into the caller.
#[inline]
pub fn shading_frame(scene: &Scene, hit: &SurfaceHit, material: &Material) -> Frame {
    let side = material.facing(hit).unwrap_or(material);
    let t = &side.textures;
    if t.normal.is_none() && t.bump.is_none() && !side.anisotropic {
        return Frame::from_normal(hit.ns);
    }
    perturbed_frame(scene, hit, side)
}

/// [`shading_frame`] of a material with a normal or bump map or an
/// anisotropic BSDF.
#[inline(never)]
fn perturbed_frame(scene: &Scene, hit: &SurfaceHit, material: &Material) -> Frame {
    let t = &material.textures;
    let (dpdu, dpdv) = uv_derivatives(scene, hit);
    let frame = |n: Vec3| {
        if material.anisotropic {
            Frame::from_normal_and_tangent(n, dpdu)
        } else {
            Frame::from_normal(n)
        }
    };
    let mut n = hit.ns;
    if let Some(map) = &t.normal {
        // With per-vertex tangents, (T, w · N × T) is the frame the map was
        // baked in; mapped_normal orthogonalises T against N and turns the
        // bitangent to the side of w · N × T, which is that frame exactly.
        let (tu, tv) = match hit.tangent {
            Some(tangent) => {
                let tu = tangent.truncate();
                (tu, tangent.w * n.cross(tu))
            }
            None => (dpdu, dpdv),
        };
        n = normal_map::mapped_normal(n, tu, tv, map.image.lookup(hit.uv), map.scale);
    }
    if let Some(bump) = &t.bump {
        let (w, h) = bump.image.size();
        let (du, dv) = (0.5 / w as f32, 0.5 / h as f32);
        let height = |u: f32, v: f32| bump.value(hit.uv + Vec2::new(u, v), 0);
        let dhdu = (height(du, 0.0) - height(-du, 0.0)) / (2.0 * du);
        let dhdv = (height(0.0, dv) - height(0.0, -dv)) / (2.0 * dv);
        n = normal_map::bumped_normal(n, dpdu, dpdv, dhdu, dhdv);
    }
    if n == hit.ns {
        return frame(hit.ns);
    }
    frame(normal_map::keep_viewer_above(n, hit.ns, hit.wo))
}

/// Rule 2 of [`normal_map`]: a scattered direction `wi` counts only if its
/// side of the geometric surface (normal `ng`, facing `wo`) agrees with its
/// side in the shading frame (`wo_local`, `wi_local`): reflection stays on
/// the viewer's side of the true surface, transmission crosses it.
pub fn scatter_allowed(ng: Vec3, wi: Vec3, wo_local: Vec3, wi_local: Vec3) -> bool {
    scatter_allowed_given(wi.dot(ng), wo_local, wi_local)
}

/// [`scatter_allowed`] given `wi · ng`, for a caller that needs the dot
/// product again (a light sample's shadow ray takes its side from it).
#[inline(always)]
pub fn scatter_allowed_given(wi_dot_ng: f32, wo_local: Vec3, wi_local: Vec3) -> bool {
    let geometric_reflection = wi_dot_ng > 0.0;
    let shading_reflection = wo_local.z * wi_local.z > 0.0;
    geometric_reflection == shading_reflection
}

/// Why [`sample_scatter`] gave no direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoScatter {
    /// The BSDF sampled nothing (or a zero density).
    NoSample,
    /// Rule 2 rejected the sampled direction.
    WrongSide,
}

/// Samples the BSDF in `frame` for `wo_local` (the direction toward the
/// viewer in `frame`'s coordinates, which the caller has for its light
/// samples too) and returns the world direction with the sample, or why
/// there is none (`ng` the geometric normal facing the viewer).
#[inline]
pub fn sample_scatter(
    bsdf: &Bsdf,
    frame: &Frame,
    ng: Vec3,
    wo_local: Vec3,
    u1: f32,
    u2: Vec2,
) -> Result<(Vec3, BsdfSample), NoScatter> {
    let s = bsdf
        .sample(wo_local, u1, u2)
        .filter(|s| s.pdf > 0.0)
        .ok_or(NoScatter::NoSample)?;
    let wi = frame.to_world(s.wi);
    if scatter_allowed(ng, wi, wo_local, s.wi) {
        Ok((wi, s))
    } else {
        Err(NoScatter::WrongSide)
    }
}

/// dp/du and dp/dv at `hit`: a triangle's from its corners and UVs (its
/// barycentric parametrisation when it has no UVs or they are
/// degenerate), a sphere's from its (u, v) = (φ/2π, θ/π) mapping in its
/// own axes.
pub fn uv_derivatives(scene: &Scene, hit: &SurfaceHit) -> (Vec3, Vec3) {
    let i = hit.prim.index() as usize;
    match hit.prim.kind() {
        PrimKind::Triangle => {
            let tris = &scene.geometry.triangles;
            let [p0, p1, p2] = tris.corners(i);
            let (e1, e2) = (p1 - p0, p2 - p0);
            let ti = tris.uv_indices[i];
            let uv = if ti[0] == u32::MAX {
                [Vec2::ZERO, Vec2::X, Vec2::Y]
            } else {
                ti.map(|k| tris.uvs[k as usize])
            };
            let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
            let det = d1.x * d2.y - d1.y * d2.x;
            if det.abs() < 1e-12 || !det.is_finite() {
                return (e1, e2);
            }
            let inv = 1.0 / det;
            ((d2.y * e1 - d1.y * e2) * inv, (d1.x * e2 - d2.x * e1) * inv)
        }
        PrimKind::Sphere => {
            // In the sphere's axes q = (sin θ cos φ, sin θ sin φ, cos θ),
            // u = φ/2π, v = θ/π.
            let s = &scene.geometry.spheres[i];
            let q = s.axes.transpose() * (hit.p - s.center).normalize_or(s.axes.z_axis);
            let (cos_t, sin_t) = (q.z, (1.0 - q.z * q.z).max(0.0).sqrt());
            let (sin_p, cos_p) = q.y.atan2(q.x).sin_cos();
            (
                s.axes * Vec3::new(-sin_p, cos_p, 0.0) * (TAU * s.radius * sin_t),
                s.axes * Vec3::new(cos_t * cos_p, cos_t * sin_p, -sin_t) * (PI * s.radius),
            )
        }
    }
}
