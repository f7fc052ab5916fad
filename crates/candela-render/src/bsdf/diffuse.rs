//! Lambertian reflection.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::{same_hemisphere, BsdfFlags, BsdfSample};
use crate::sampling::warp::square_to_cosine_hemisphere;

/// The lobe's flags.
pub(super) const FLAGS: BsdfFlags = BsdfFlags::REFLECTION.union(BsdfFlags::DIFFUSE);

/// f = albedo / π on the side of `wo`, zero across the surface.
pub(super) fn f(albedo: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if same_hemisphere(wo, wi) {
        albedo * FRAC_1_PI
    } else {
        Vec3::ZERO
    }
}

/// Cosine-weighted sampling on the side of `wo`; the weight f·cos/pdf is
/// exactly `albedo`.
pub(super) fn sample(albedo: Vec3, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
    let mut wi = square_to_cosine_hemisphere(u);
    if wo.z < 0.0 {
        wi.z = -wi.z;
    }
    // `pdf` and `f` with their one hemisphere test made once.
    if !same_hemisphere(wo, wi) {
        return None;
    }
    let pdf = wi.z.abs() * FRAC_1_PI;
    (pdf > 0.0).then(|| BsdfSample {
        wi,
        f: albedo * FRAC_1_PI,
        pdf,
        flags: FLAGS,
    })
}

/// |cos θi| / π on the side of `wo`.
pub(super) fn pdf(wo: Vec3, wi: Vec3) -> f32 {
    if same_hemisphere(wo, wi) {
        wi.z.abs() * FRAC_1_PI
    } else {
        0.0
    }
}
