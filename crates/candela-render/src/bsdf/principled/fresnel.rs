//! The principled BSDF's Fresnel terms: Schlick's approximation as Mitsuba's
//! `principled` evaluates it (with the refracted angle when the relative
//! IOR is below 1), and the main specular lobe's blend of the exact
//! dielectric term with Schlick's for the metallic part and the tint.

use glam::Vec3;

/// (1 − cos)⁵, Schlick's weight.
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's weight at `cos_i` (cosine with the microfacet normal, on the
/// outside when positive) for an interface of relative IOR `eta` (inside
/// over outside): from the incident angle when the light goes into the
/// denser side, else from the refracted angle (Schlick's rule for η < 1;
/// 1 under total internal reflection).
pub(super) fn interface_weight(cos_i: f32, eta: f32) -> f32 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    if eta_it > 1.0 {
        return schlick_weight(cos_i.abs());
    }
    let cos_t2 = 1.0 - (1.0 - cos_i * cos_i) * eta_it.recip().powi(2);
    schlick_weight(cos_t2.max(0.0).sqrt())
}

/// Schlick's Fresnel of normal-incidence reflectance `r0` (per channel).
pub(super) fn schlick(r0: Vec3, cos_i: f32, eta: f32) -> Vec3 {
    let w = interface_weight(cos_i, eta);
    r0 + (Vec3::ONE - r0) * w
}

/// ((η − 1)/(η + 1))², the normal-incidence reflectance of a dielectric.
pub(super) fn r0_of_eta(eta: f32) -> f32 {
    ((eta - 1.0) / (eta + 1.0)).powi(2)
}

/// Luminance of a linear sRGB colour with Mitsuba's weights (the tints are
/// the base colour divided by it).
pub(super) fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.212671, 0.715160, 0.072169))
}

/// The base colour's hue at luminance 1 (white when it is black).
pub(super) fn tint(base_color: Vec3) -> Vec3 {
    let lum = luminance(base_color);
    if lum > 0.0 {
        base_color / lum
    } else {
        Vec3::ONE
    }
}

/// The main specular reflection's Fresnel on the outside (Mitsuba's
/// `principled_fresnel`): the exact dielectric term `dielectric` for the
/// untinted dielectric share (1 − metallic)(1 − spec_tint), Schlick's with
/// F0 = base colour for the metallic share, and Schlick's with the tinted
/// F0 = tint · r0(η) for the tinted dielectric share.
pub(super) fn main_reflection(
    dielectric: f32,
    cos_i: f32,
    eta: f32,
    base_color: Vec3,
    metallic: f32,
    spec_tint: f32,
) -> Vec3 {
    let mut f = Vec3::splat((1.0 - metallic) * (1.0 - spec_tint) * dielectric);
    if metallic > 0.0 {
        f += metallic * schlick(base_color, cos_i, eta);
    }
    if spec_tint > 0.0 {
        let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
        let r0 = tint(base_color) * r0_of_eta(eta_it);
        f += (1.0 - metallic) * spec_tint * schlick(r0, cos_i, eta);
    }
    f
}
