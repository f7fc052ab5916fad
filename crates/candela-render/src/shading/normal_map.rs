//! Tangent-space normal maps, bump (height) maps, and the shading frame
//! they give.
//!
//! A bump map h(u, v) (the slot's value times its scale, in scene units)
//! displaces the surface along its shading normal n: p' = p + h n, so
//! ∂p'/∂u ≈ ∂p/∂u + (∂h/∂u) n (the term in ∂n/∂u is dropped, as pbrt
//! does for small displacements), likewise for v, and the bumped normal is
//! ∂p'/∂u × ∂p'/∂v turned to the side of n (Blinn 1978, "Simulation of
//! Wrinkled Surfaces"). ∂h/∂u and ∂h/∂v are central differences of the
//! bilinear texture half a texel either side.
//!
//! A texel (r, g, b) is the normal (2r − 1, 2g − 1, 2b − 1) in the frame
//! (T, B, N): N the interpolated shading normal, T the surface's dp/du made
//! orthogonal to N, B = N × T turned to the side of dp/dv (so mirrored UVs
//! keep their handedness). +X right and +Y up in the image, the OpenGL /
//! glTF / Blender convention (Candela's `v` runs bottom to top). The slot's
//! scale multiplies X and Y (glTF's `normalTexture.scale`). dp/du and dp/dv
//! are the triangle's own (pbrt's, from its positions and UVs; a triangle
//! without UVs uses its barycentric parametrisation) unless the mesh has
//! per-vertex tangents (glTF `TANGENT`, or generated smooth from the UVs for
//! a normal-mapped mesh): `shading_frame` then passes the interpolated T as
//! dp/du and w · N × T as dp/dv, which this construction turns into exactly
//! the frame (T ⊥ N, w · N × T) a MikkTSpace baker used, without the
//! per-triangle frame's facets on smooth meshes.
//!
//! # The shading-frame rule (no leaks)
//!
//! Two parts, both cheap and both documented in `shading/mod.rs`:
//! 1. **Bend toward the viewer** ([`keep_viewer_above`]): a mapped normal
//!    that would put `wo` below (or within [`MIN_COS_VIEW`] of) its
//!    horizon is rotated toward `wo` in their common plane until
//!    cos(wo, n) = min(`MIN_COS_VIEW`, cos(wo, unmapped normal)), the minimal
//!    change that keeps the BSDF's view of the side (Keller et al. 2017,
//!    "The Iray Light Transport Simulation and Rendering System", §A.3
//!    bends shading normals the same way). Without it a dielectric would
//!    believe the path is leaving the glass, and an opaque BSDF would see
//!    the viewer from behind.
//! 2. **The geometric normal decides reflection vs transmission**
//!    ([`super::scatter_allowed`]; pbrt-v3 §9.1's rule): a direction whose
//!    side of the geometric surface disagrees with its side of the shading
//!    frame carries nothing (in light sampling, BSDF sampling and the
//!    hemisphere estimator alike), so no reflected direction ever crosses
//!    the true surface and no transmission stays on the viewer's side.
//!    The estimators stay consistent with one another: both evaluate the
//!    same `f · [sides agree]`, and MIS keeps the full pdf of the rejected
//!    directions on both sides, which is exact.
//!
//! The loss (directions rejected by 2) is the price: energy, never light
//! through walls. Microfacet-based normal mapping (Schüssler et al. 2017)
//! would recover it at the cost of a second facet per BSDF.

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
    let n = (dpdu + ns * dhdu).cross(dpdv + ns * dhdv);
    match n.try_normalize() {
        Some(n) if n.dot(ns) < 0.0 => -n,
        Some(n) => n,
        None => ns,
    }
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
