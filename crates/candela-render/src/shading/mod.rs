//! From a hit and its material to what the integrators shade with: the
//! textured BSDF, the shading frame (normal maps), the emitted radiance,
//! and whether the surface is there at all (opacity cut-outs).
//!
//! - [`textures`]: every texture slot read at the hit's `uv`.
//! - [`normal_map`]: tangent-space normal maps, bump maps, the
//!   shading-frame rules that never let a sampled direction leak through
//!   the geometric surface (mirror or bend a mapped normal that faces away
//!   from the viewer; the geometric normal decides reflection vs
//!   transmission: [`scatter_allowed`]), and the bump shadowing
//!   ([`Terminator`]) a [`ShadingFrame`] carries, each as the material's
//!   `PerturbationRules` (its file format's conventions) say.
//! - [`opacity`]: cut-outs, applied by the visibility queries
//!   (`scene/visibility.rs`) to camera, bounce and shadow rays alike.

pub mod normal_map;
pub mod opacity;
pub mod textures;

#[cfg(test)]
mod blend_material_tests;
#[cfg(test)]
mod leak_tests;
#[cfg(test)]
mod sides_tests;

pub use normal_map::Terminator;
pub use textures::{LayerTextures, MaterialTextures};

use crate::bsdf::{Bsdf, BsdfSample};
use crate::geometry::Frame;
use crate::material::Material;
use crate::scene::Scene;
use crate::shape::{PrimKind, SurfaceHit};
use candela_scene::{AwayFromViewer, TangentFrame};
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// The frame a BSDF is evaluated in at a hit, and the shadowing the bumps
/// of its normal or bump map cast on light arriving there (none without a
/// map, or where the material's rules have no such term). Derefs to the
/// frame.
#[derive(Clone, Copy, Debug)]
pub struct ShadingFrame {
    /// The (perturbed) shading frame.
    pub frame: Frame,
    /// The bump shadowing, see [`Terminator`].
    pub terminator: Terminator,
}

impl ShadingFrame {
    /// The frame around `n`, without shadowing.
    #[inline]
    pub fn plain(n: Vec3) -> Self {
        Self {
            frame: Frame::from_normal(n),
            terminator: Terminator::NONE,
        }
    }

    /// The factor on `f` for light arriving from (or leaving toward) the
    /// world direction `wi`: 1 without a shadowing term.
    #[inline(always)]
    pub fn shadowing(&self, wi: Vec3) -> f32 {
        self.terminator.factor(wi)
    }
}

impl std::ops::Deref for ShadingFrame {
    type Target = Frame;
    #[inline(always)]
    fn deref(&self) -> &Frame {
        &self.frame
    }
}

/// The frame a BSDF is evaluated in at `hit`: around the shading normal,
/// perturbed by the normal or bump map of the material on the side the hit
/// sees ([`Material::facing`]), following its
/// [`candela_scene::PerturbationRules`] (see [`normal_map`]), with its +X
/// along dp/du when that material's BSDF is anisotropic (Mitsuba's shading
/// frame). Otherwise this is exactly `Frame::from_normal(hit.ns)`, inlined
/// into the caller.
#[inline]
pub fn shading_frame(scene: &Scene, hit: &SurfaceHit, material: &Material) -> ShadingFrame {
    let side = material.facing(hit).unwrap_or(material);
    let t = &side.textures;
    if t.normal.is_none() && t.bump.is_none() && !side.anisotropic {
        return ShadingFrame::plain(hit.ns);
    }
    perturbed_frame(scene, hit, side)
}

/// [`shading_frame`] of a material with a normal or bump map or an
/// anisotropic BSDF.
#[inline(never)]
fn perturbed_frame(scene: &Scene, hit: &SurfaceHit, material: &Material) -> ShadingFrame {
    let t = &material.textures;
    let rules = t.perturbation;
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
        let (tu, tv) = tangent_axes(rules.tangent_frame, hit, dpdu, dpdv);
        n = normal_map::mapped_normal(n, tu, tv, map.rgb(hit.texture_point()), map.scale);
    }
    if let Some(bump) = &t.bump {
        let slope = bump.gradient(hit.texture_point(), BUMP_CHANNEL);
        n = normal_map::bumped_normal(n, dpdu, dpdv, slope.x, slope.y);
    }
    if n == hit.ns {
        return ShadingFrame {
            frame: frame(hit.ns),
            terminator: Terminator::NONE,
        };
    }
    if rules.away_from_viewer == AwayFromViewer::MirrorTangent {
        n = normal_map::mirror_if_away(n, hit.ns, hit.wo);
    }
    // Bending is the guard of both rules: a no-op where the viewer sees n.
    let n = normal_map::keep_viewer_above(n, hit.ns, hit.wo);
    ShadingFrame {
        frame: frame(n),
        terminator: if rules.shadow_terminator {
            Terminator::new(hit.ns, n)
        } else {
            Terminator::NONE
        },
    }
}

/// The height channel of a bump map (grey images have it in every channel).
const BUMP_CHANNEL: u8 = 0;

/// The two directions a normal map's x and y are along at `hit` (made
/// orthogonal to the normal by `mapped_normal`, which also turns the
/// second to the side of the one given here).
fn tangent_axes(rule: TangentFrame, hit: &SurfaceHit, dpdu: Vec3, dpdv: Vec3) -> (Vec3, Vec3) {
    let n = hit.ns;
    match (rule, hit.tangent) {
        // With per-vertex tangents, (T, w · N × T) is the frame the map was
        // baked in; mapped_normal orthogonalises T against N and turns the
        // bitangent to the side of w · N × T, which is that frame exactly.
        (TangentFrame::VertexTangents, Some(tangent)) => {
            let tu = tangent.truncate();
            (tu, tangent.w * n.cross(tu))
        }
        (TangentFrame::VertexTangents, None) => (dpdu, dpdv),
        // Right-handed about N whatever the UVs' orientation.
        (TangentFrame::SurfaceDpDu, _) => (dpdu, n.cross(dpdu)),
    }
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
/// there is none (`ng` the geometric normal facing the viewer). The
/// sample's `f` does not include `frame`'s shadowing (the caller weighs
/// by [`ShadingFrame::shadowing`]).
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
