//! The principled BSDF's base: Burley's diffuse with retro-reflection (and
//! the Hanrahan-Krueger-like "flatness" blend) and the sheen, on the
//! outside only (cosines positive, h the half vector of the pair).

use std::f32::consts::FRAC_1_PI;

use glam::Vec3;

use super::fresnel::{schlick_weight, tint};

/// Burley's diffuse shape (cosine excluded, before base colour / π):
/// (1 − F_o/2)(1 − F_i/2) + R_R (F_o + F_i + F_o F_i (R_R − 1)) with
/// R_R = 2 roughness cos²θd (the 2015 notes' split of the 2012 form
/// (1 + (F_D90 − 1) F_o)(1 + (F_D90 − 1) F_i), F_D90 = 1/2 + R_R), blended
/// toward the flattened "subsurface" shape by `flatness`.
pub(super) fn diffuse_shape(
    cos_o: f32,
    cos_i: f32,
    cos_d: f32,
    roughness: f32,
    flatness: f32,
) -> f32 {
    let (fo, fi) = (schlick_weight(cos_o), schlick_weight(cos_i));
    let lambert = (1.0 - 0.5 * fo) * (1.0 - 0.5 * fi);
    let rr = 2.0 * roughness * cos_d * cos_d;
    let retro = rr * (fo + fi + fo * fi * (rr - 1.0));
    let diffuse = lambert + retro;
    if flatness <= 0.0 {
        return diffuse;
    }
    let fss90 = 0.5 * rr;
    let fss = (1.0 + (fss90 - 1.0) * fo) * (1.0 + (fss90 - 1.0) * fi);
    let subsurface = 1.25 * (fss * (1.0 / (cos_o + cos_i) - 0.5) + 0.5);
    diffuse + flatness * (subsurface - diffuse)
}

/// The diffuse lobe's value: weight · base colour / π · shape.
pub(super) fn diffuse(weight: f32, base_color: Vec3, shape: f32) -> Vec3 {
    base_color * (weight * FRAC_1_PI * shape)
}

/// The sheen: sheen · (1 − metallic) · (1 − cos θd)⁵, tinted toward the
/// base colour's hue by `sheen_tint`.
pub(super) fn sheen(
    sheen: f32,
    sheen_tint: f32,
    metallic: f32,
    base_color: Vec3,
    cos_d: f32,
) -> Vec3 {
    let color = Vec3::ONE + sheen_tint * (tint(base_color) - Vec3::ONE);
    color * (sheen * (1.0 - metallic) * schlick_weight(cos_d.abs()))
}
