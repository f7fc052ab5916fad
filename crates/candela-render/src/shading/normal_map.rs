//! Tangent-space normal maps, bump (height) maps, and the shading frame
//! they give. Where formats disagree the material's
//! [`candela_scene::PerturbationRules`] decide; both rule sets are below.
//!
//! A bump map h(u, v) (the slot's value times its scale, in scene units)
//! displaces the surface along its shading normal n: p' = p + h n, so
//! ∂p'/∂u ≈ t_u + (∂h/∂u) n, with t_u the part of ∂p/∂u orthogonal to n
//! (the term in ∂n/∂u is dropped, as pbrt and Mitsuba do for small
//! displacements), likewise for v, and the bumped normal is
//! ∂p'/∂u × ∂p'/∂v turned to the side of n (Blinn 1978, "Simulation of
//! Wrinkled Surfaces"). ∂h/∂u and ∂h/∂v are the exact derivatives of the
//! bilinear texture at the point (Mitsuba's `eval_1_grad`), so a constant
//! offset of the heights changes nothing.
//!
//! A texel (r, g, b) is the normal (2r − 1, 2g − 1, 2b − 1), normalised,
//! in the frame (T, B, N): N the interpolated shading normal, T a tangent
//! made orthogonal to N, B = ±N × T. Which T and which sign is the
//! material's [`candela_scene::TangentFrame`]:
//! - `VertexTangents` (glTF): T the mesh's per-vertex tangent (glTF
//!   `TANGENT`, or generated smooth from the UVs for a normal-mapped mesh)
//!   and B = w · N × T, exactly the frame a MikkTSpace baker used; a
//!   surface without them uses its own dp/du and turns B to the side of
//!   dp/dv (so mirrored UVs keep their handedness). +X right and +Y up in
//!   the image, the OpenGL / glTF / Blender convention (Candela's `v` runs
//!   bottom to top).
//! - `SurfaceDpDu` (Mitsuba): T the surface's own dp/du (a triangle's,
//!   from its corners and UVs) and B = N × T, right-handed whatever the
//!   UVs do: Mitsuba's shading frame `sh_frame`.
//!
//! The slot's scale multiplies X and Y (glTF's `normalTexture.scale`).
//!
//! # The shading-frame rules (no leaks)
//!
//! 1. **A normal facing away from the viewer** (the viewer on the other
//!    side of it than of the unperturbed normal), by the material's
//!    [`candela_scene::AwayFromViewer`]: either mirrored about the
//!    unperturbed normal ([`mirror_if_away`], Schüssler et al. 2017, as
//!    Mitsuba's `flip_invalid_normals`), or **bent toward the viewer**
//!    ([`keep_viewer_above`]): rotated toward `wo` in their common plane
//!    until cos(wo, n) = min(`MIN_COS_VIEW`, cos(wo, unmapped normal)), the
//!    minimal change that keeps the BSDF's view of the side (Keller et al.
//!    2017, "The Iray Light Transport Simulation and Rendering System",
//!    §A.3 bends shading normals the same way). Bending also guards the
//!    mirror, in the rare case where the mirrored normal still faces
//!    away. Without it a dielectric would believe the path is leaving the
//!    glass, and an opaque BSDF would see the viewer from behind.
//! 2. **The geometric normal decides reflection vs transmission**
//!    ([`super::scatter_allowed`]; pbrt-v3 §9.1's rule): a direction whose
//!    side of the geometric surface disagrees with its side of the shading
//!    frame carries nothing (in light sampling, BSDF sampling and the
//!    hemisphere estimator alike), so no reflected direction ever crosses
//!    the true surface and no transmission stays on the viewer's side.
//!    The estimators stay consistent with one another: both evaluate the
//!    same `f · [sides agree]`, and MIS keeps the full pdf of the rejected
//!    directions on both sides, which is exact. (Mitsuba asks the same of
//!    the unperturbed shading normal; on flat geometry the two agree.)
//!
//! The loss (directions rejected by 2) is the price: energy, never light
//! through walls. Microfacet-based normal mapping (Schüssler et al. 2017)
//! would recover it at the cost of a second facet per BSDF.
//!
//! # Bump shadowing (the terminator)
//!
//! Where the rules ask for it ([`Terminator`], Mitsuba's default), `f` is
//! multiplied by Estevez et al. 2019's shadowing G1 of a Beckmann-like
//! surface of α² = min(tan²θ_n / 8, 1), θ_n the angle the map tilted the
//! normal by, at the light direction's angle to the unperturbed normal:
//! 2 / (1 + √(1 + α² tan²θ_i)). It softens the hard terminator that
//! tilted normals draw on curved surfaces, and darkens grazing light. It
//! scales `f` only: sampling pdfs are unchanged.

use glam::Vec3;

/// The smallest cosine between `wo` and a bent normal (about 88.9°).
pub const MIN_COS_VIEW: f32 = 0.02;

/// The shading normal a tangent-space `texel` (stored, linear, in [0, 1])
/// gives at a point of shading normal `ns` and UV derivatives `dpdu`,
/// `dpdv`, with X and Y scaled by `scale`. A texel that leaves the normal
/// as it is ((0.5, 0.5, 1) up to scale) returns `ns` exactly.
pub fn mapped_normal(ns: Vec3, dpdu: Vec3, dpdv: Vec3, texel: Vec3, scale: f32) -> Vec3 {
    let t = texel * 2.0 - Vec3::ONE;
    let (x, y, z) = (t.x * scale, t.y * scale, t.z);
    if x == 0.0 && y == 0.0 && z > 0.0 {
        return ns;
    }
    let tangent = (dpdu - ns * ns.dot(dpdu))
        .try_normalize()
        .unwrap_or_else(|| crate::geometry::Frame::from_normal(ns).x);
    let mut bitangent = ns.cross(tangent);
    if bitangent.dot(dpdv) < 0.0 {
        bitangent = -bitangent;
    }
    (tangent * x + bitangent * y + ns * z)
        .try_normalize()
        .unwrap_or(ns)
}

/// The shading normal of a surface of normal `ns` and UV derivatives
/// `dpdu`, `dpdv` displaced along `ns` by a height of UV gradient
/// (`dhdu`, `dhdv`); `ns` itself, exactly, where the height is flat.
pub fn bumped_normal(ns: Vec3, dpdu: Vec3, dpdv: Vec3, dhdu: f32, dhdv: f32) -> Vec3 {
    if dhdu == 0.0 && dhdv == 0.0 {
        return ns;
    }
    let along = |d: Vec3, slope: f32| d + ns * (slope - ns.dot(d));
    let n = along(dpdu, dhdu).cross(along(dpdv, dhdv));
    match n.try_normalize() {
        Some(n) if n.dot(ns) < 0.0 => -n,
        Some(n) => n,
        None => ns,
    }
}

/// Rule 1 of the module docs, Mitsuba's way: `n` mirrored about the
/// unperturbed `ns` (its tangential part negated) when `wo` is on the other
/// side of it than of `ns` (or in its plane); else `n` as it is.
pub fn mirror_if_away(n: Vec3, ns: Vec3, wo: Vec3) -> Vec3 {
    if wo.dot(ns) * wo.dot(n) > 0.0 {
        return n;
    }
    (ns * (2.0 * n.dot(ns)) - n).normalize_or(ns)
}

/// The shadowing of bumps on light at a point whose normal a map tilted
/// (see the module docs): Estevez et al. 2019's G1 with α² from the tilt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Terminator {
    /// The unperturbed shading normal.
    normal: Vec3,
    /// α² of the equivalent rough surface; 0: no shadowing.
    alpha2: f32,
}

impl Terminator {
    /// No shadowing: a factor of 1 everywhere.
    pub const NONE: Self = Self {
        normal: Vec3::Z,
        alpha2: 0.0,
    };

    /// The shadowing at a point of unperturbed normal `ns` whose normal the
    /// map turned to `n` (both unit).
    pub fn new(ns: Vec3, n: Vec3) -> Self {
        let cos2 = ns.dot(n).powi(2);
        let alpha2 = (0.125 * tan2(cos2)).min(1.0);
        if alpha2 > 0.0 {
            Self { normal: ns, alpha2 }
        } else {
            Self::NONE
        }
    }

    /// The factor on `f` for light along the unit world direction `wi`
    /// (either way along it), in (0, 1]; 0 in the unperturbed plane.
    #[inline(always)]
    pub fn factor(&self, wi: Vec3) -> f32 {
        if self.alpha2 == 0.0 {
            return 1.0;
        }
        self.shadowed(wi)
    }

    /// [`Terminator::factor`] where there is shadowing. Out of line: inlined,
    /// the compiler evaluated it (a square root, two divisions) for every
    /// light sample of every surface and selected 1 without a map.
    #[cold]
    #[inline(never)]
    fn shadowed(&self, wi: Vec3) -> f32 {
        let t2 = tan2(wi.dot(self.normal).powi(2));
        2.0 / (1.0 + (1.0 + self.alpha2 * t2).sqrt())
    }
}

/// tan²θ from cos²θ (infinite at θ = 90°).
fn tan2(cos2: f32) -> f32 {
    (1.0 - cos2).max(0.0) / cos2
}

/// Rule 1 of the module docs: `n` rotated toward `wo` (no change when `wo`
/// already sees it at a cosine of at least min(`MIN_COS_VIEW`, cos(wo,
/// `ns`))), keeping `wo` on the side of `n` it is on of the unmapped `ns`.
pub fn keep_viewer_above(n: Vec3, ns: Vec3, wo: Vec3) -> Vec3 {
    let w = if wo.dot(ns) < 0.0 { -wo } else { wo };
    let floor = MIN_COS_VIEW.min(w.dot(ns)).max(0.0);
    let cos = w.dot(n);
    if cos >= floor {
        return n;
    }
    let Some(across) = (n - w * cos).try_normalize() else {
        return ns;
    };
    (w * floor + across * (1.0 - floor * floor).sqrt()).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::{ImageTexture, SlotTexture};
    use candela_image::RgbImage;
    use glam::Vec2;
    use std::sync::Arc;

    #[test]
    fn a_flat_texel_changes_nothing_and_a_tilted_one_follows_the_uvs() {
        let ns = Vec3::new(0.1, 0.2, 0.97).normalize();
        let (dpdu, dpdv) = (Vec3::X * 2.0, Vec3::Y * 0.5);
        assert_eq!(
            mapped_normal(ns, dpdu, dpdv, Vec3::new(0.5, 0.5, 1.0), 0.7),
            ns
        );
        // +X in the map tilts toward dp/du, +Y toward dp/dv, mirrored UVs too.
        let flat = Vec3::Z;
        let right = mapped_normal(flat, dpdu, dpdv, Vec3::new(1.0, 0.5, 0.5), 1.0);
        assert!((right - Vec3::X).length() < 1e-6, "{right}");
        let up = mapped_normal(flat, dpdu, -dpdv, Vec3::new(0.5, 1.0, 0.5), 1.0);
        assert!((up + Vec3::Y).length() < 1e-6, "{up}");
        // The scale shrinks the tilt.
        let half = mapped_normal(flat, dpdu, dpdv, Vec3::new(1.0, 0.5, 1.0), 0.5);
        assert!((half - Vec3::new(0.5, 0.0, 1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn a_height_ramp_tilts_the_normal_by_its_slope() {
        // h = a·u on the plane p = (u, v, 0): the surface z = a·x, whose
        // normal is (−a, 0, 1)/√(1 + a²).
        let a = 0.6;
        let n = bumped_normal(Vec3::Z, Vec3::X, Vec3::Y, a, 0.0);
        assert!(
            (n - Vec3::new(-a, 0.0, 1.0).normalize()).length() < 1e-6,
            "{n}"
        );
        // With UVs stretched (dp/du = 2x), the same height slope per unit u
        // is half as steep in space.
        let n = bumped_normal(Vec3::Z, 2.0 * Vec3::X, Vec3::Y, a, 0.0);
        assert!((n - Vec3::new(-a / 2.0, 0.0, 1.0).normalize()).length() < 1e-6);
        // Mirrored UVs (dp/dv = −y) keep the normal on the side of ns.
        let n = bumped_normal(Vec3::Z, Vec3::X, -Vec3::Y, 0.0, a);
        assert!(
            (n - Vec3::new(0.0, a, 1.0).normalize()).length() < 1e-6,
            "{n}"
        );
        assert_eq!(bumped_normal(Vec3::Z, Vec3::X, Vec3::Y, 0.0, 0.0), Vec3::Z);
        // Only the part of dp/du in the tangent plane counts (a shading
        // normal that differs from the geometric one).
        let n = bumped_normal(Vec3::Z, Vec3::X + 0.5 * Vec3::Z, Vec3::Y, a, 0.0);
        assert!(
            (n - Vec3::new(-a, 0.0, 1.0).normalize()).length() < 1e-6,
            "{n}"
        );
    }

    #[test]
    fn a_linear_height_texture_tilts_the_normal_by_the_analytic_angle() {
        // Texel centres (i + 0.5)/W hold c·(i + 0.5)/W, so between them the
        // bilinear height is c·u, times the slot's scale s: on a surface
        // with |dp/du| = L the normal tilts by atan(s·c / L) toward −dp/du,
        // and a flat texture does not tilt it at all.
        let (w, c, s, l) = (8, 0.6f32, 0.5f32, 0.4f32);
        let ramp = RgbImage::from_fn(w, 2, |i, _| [c * (i as f32 + 0.5) / w as f32; 3]).unwrap();
        let slot = |image: &RgbImage| SlotTexture {
            scale: s,
            ..SlotTexture::of_image(Arc::new(ImageTexture::from_image(image).unwrap()))
        };
        let (dpdu, dpdv) = (l * Vec3::X, 0.8 * Vec3::Y);
        for u in [0.2f32, 0.45, 0.8] {
            let g = slot(&ramp).gradient(Vec2::new(u, 0.3), 0);
            let n = bumped_normal(Vec3::Z, dpdu, dpdv, g.x, g.y);
            let tilt = n.z.clamp(-1.0, 1.0).acos();
            let expected = (s * c / l).atan();
            assert!(
                (tilt - expected).abs() < 1e-5,
                "{tilt} vs {expected} at u = {u}"
            );
            assert!(n.x < 0.0 && n.y.abs() < 1e-6, "{n}");
        }
        let flat = RgbImage::from_fn(w, 2, |_, _| [0.7; 3]).unwrap();
        let g = slot(&flat).gradient(Vec2::new(0.45, 0.3), 0);
        assert_eq!(bumped_normal(Vec3::Z, dpdu, dpdv, g.x, g.y), Vec3::Z);
    }

    #[test]
    fn a_normal_facing_away_is_mirrored_about_the_unperturbed_one() {
        // Mitsuba's flip: (x, y, z) → (−x, −y, z) in the unperturbed frame,
        // only when the viewer is behind the mapped normal.
        let ns = Vec3::Z;
        let n = Vec3::new(0.5, 0.3, 0.66f32.sqrt());
        let front = Vec3::new(0.6, 0.0, 0.8);
        assert_eq!(mirror_if_away(n, ns, front), n);
        let behind = Vec3::new(-0.9, 0.0, 0.19f32.sqrt());
        assert!(behind.dot(n) < 0.0);
        let m = mirror_if_away(n, ns, behind);
        assert!((m - Vec3::new(-n.x, -n.y, n.z)).length() < 1e-6, "{m}");
        assert!(behind.dot(m) > 0.0);
        // Seen from below the surface, the same on that side.
        assert_eq!(mirror_if_away(-n, -ns, -front), -n);
        let m = mirror_if_away(-n, -ns, -behind);
        assert!((m + Vec3::new(-n.x, -n.y, n.z)).length() < 1e-6, "{m}");
    }

    #[test]
    fn the_terminator_shadows_grazing_light_more_the_more_the_normal_tilts() {
        let ns = Vec3::Z;
        let tilted = |deg: f32| Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let toward = |deg: f32| Vec3::new(0.0, deg.to_radians().sin(), deg.to_radians().cos());
        // No tilt, no shadowing; light along the normal is never shadowed.
        assert_eq!(Terminator::new(ns, ns), Terminator::NONE);
        assert_eq!(Terminator::NONE.factor(toward(80.0)), 1.0);
        assert_eq!(Terminator::new(ns, tilted(30.0)).factor(ns), 1.0);
        // Estevez et al.'s G1 with α² = tan²(tilt)/8 at tan²θ_i.
        for (tilt, theta) in [(20.0f32, 40.0f32), (30.0, 75.0), (60.0, 85.0), (80.0, 60.0)] {
            let alpha2 = (tilt.to_radians().tan().powi(2) / 8.0).min(1.0);
            let expected = 2.0 / (1.0 + (1.0 + alpha2 * theta.to_radians().tan().powi(2)).sqrt());
            let t = Terminator::new(ns, tilted(tilt));
            // Either way along the direction.
            for wi in [toward(theta), -toward(theta)] {
                let got = t.factor(wi);
                assert!((got - expected).abs() < 1e-5, "{got} vs {expected}");
            }
        }
        // Monotone: more tilt or more grazing light shadows more, down to 0
        // in the plane.
        let t = Terminator::new(ns, tilted(40.0));
        let mut last = 1.0;
        for theta in [10.0f32, 30.0, 50.0, 70.0, 85.0, 89.0] {
            let f = t.factor(toward(theta));
            assert!(f < last && f > 0.0, "{f} after {last} at {theta}°");
            last = f;
        }
        assert_eq!(t.factor(Vec3::X), 0.0);
        assert!(Terminator::new(ns, tilted(60.0)).factor(toward(70.0)) < t.factor(toward(70.0)));
    }

    #[test]
    fn bending_keeps_the_viewer_above_and_leaves_visible_normals_alone() {
        let ns = Vec3::Z;
        let wo = Vec3::new(0.9, 0.0, 0.1).normalize();
        let visible = Vec3::new(0.3, 0.0, 0.95).normalize();
        assert_eq!(keep_viewer_above(visible, ns, wo), visible);
        let away = Vec3::new(-0.9, 0.0, 0.3).normalize();
        let bent = keep_viewer_above(away, ns, wo);
        assert!((bent.dot(wo) - MIN_COS_VIEW).abs() < 1e-5, "{bent}");
        assert!((bent.length() - 1.0).abs() < 1e-5);
        // From below the surface (inside glass), the same on that side.
        let bent = keep_viewer_above(-away, -ns, -wo);
        assert!((bent.dot(-wo) - MIN_COS_VIEW).abs() < 1e-5, "{bent}");
    }
}
