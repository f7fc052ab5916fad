//! Smooth (delta) interfaces: the mirror, glass, refraction alone, and a
//! thin pane of glass.
//!
//! All three scatter into single directions, so `f` and `pdf` are zero for
//! any given pair and only `sample` is meaningful (see the module docs of
//! [`super`] for how delta samples encode their weight).

use glam::Vec3;

use super::fresnel::{fresnel_dielectric, refract};
use super::{BsdfFlags, BsdfSample};

/// Flags of a perfect mirror.
pub(super) const MIRROR_FLAGS: BsdfFlags = BsdfFlags::REFLECTION.union(BsdfFlags::SPECULAR);
/// Flags of refraction alone.
pub(super) const REFRACTION_FLAGS: BsdfFlags = BsdfFlags::TRANSMISSION.union(BsdfFlags::SPECULAR);
/// Flags of glass: both.
pub(super) const GLASS_FLAGS: BsdfFlags = MIRROR_FLAGS.union(REFRACTION_FLAGS);

/// The mirror direction of `wo` about the normal +Z.
pub(crate) fn reflect_local(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

/// A delta sample with the given weight and discrete probability.
pub(super) fn delta_sample(
    wi: Vec3,
    weight: Vec3,
    probability: f32,
    flags: BsdfFlags,
) -> Option<BsdfSample> {
    let cos = wi.z.abs();
    (cos > 0.0 && probability > 0.0).then(|| BsdfSample {
        wi,
        f: weight * (probability / cos),
        pdf: probability,
        flags,
    })
}

/// Perfect specular reflection; the weight is `reflectance`.
pub(super) fn sample_mirror(reflectance: Vec3, wo: Vec3) -> Option<BsdfSample> {
    delta_sample(reflect_local(wo), reflectance, 1.0, MIRROR_FLAGS)
}

/// The refracted direction of `wo` and the relative IOR η (far side over
/// near side), entering when `wo.z > 0`, leaving when `wo.z < 0`.
pub(super) fn refract_local(wo: Vec3, ior: f32) -> Option<(Vec3, f32)> {
    let (normal, eta) = if wo.z > 0.0 {
        (Vec3::Z, ior)
    } else {
        (-Vec3::Z, 1.0 / ior)
    };
    refract(wo, normal, eta).map(|wi| (wi, eta))
}

/// Smooth glass: reflects with the exact dielectric Fresnel probability F
/// (chosen by `u1 < F`; F = 1 under total internal reflection), refracts
/// otherwise. Weights: `reflectance` on reflection, `transmittance / η²` on
/// refraction (radiance compression into the denser medium).
pub(super) fn sample_glass(
    reflectance: Vec3,
    transmittance: Vec3,
    ior: f32,
    wo: Vec3,
    u1: f32,
) -> Option<BsdfSample> {
    let fresnel = fresnel_dielectric(wo.z, ior);
    if u1 < fresnel {
        return delta_sample(reflect_local(wo), reflectance, fresnel, MIRROR_FLAGS);
    }
    let (wi, eta) = refract_local(wo, ior)?;
    delta_sample(
        wi,
        transmittance / (eta * eta),
        1.0 - fresnel,
        REFRACTION_FLAGS,
    )
}

/// Refraction alone (CS184's `RefractionBSDF`): always refracts, with
/// weight `transmittance / η²` and no Fresnel factor. Under total internal
/// reflection there is no refracted direction, so the sample fails (`None`)
/// and the path ends: that light is lost, as in CS184.
pub(super) fn sample_refraction(transmittance: Vec3, ior: f32, wo: Vec3) -> Option<BsdfSample> {
    let (wi, eta) = refract_local(wo, ior)?;
    delta_sample(wi, transmittance / (eta * eta), 1.0, REFRACTION_FLAGS)
}

/// The reflectance of a thin slab (a window pane) of relative IOR `ior`
/// seen at `cos_i`, counting every internal bounce: with R the Fresnel
/// reflectance of one face and T = 1 − R, the light reflects R, or enters and
/// leaves after 2k + 1 internal reflections, adding
/// T² R Σₖ R²ᵏ = T² R / (1 − R²). In total 2R / (1 + R) (absorption-free
/// slab; Mitsuba's `thindielectric`). The same from both sides, since the
/// slab has the same medium on both.
pub(crate) fn thin_slab_reflectance(cos_i: f32, ior: f32) -> f32 {
    let single = fresnel_dielectric(cos_i.abs(), ior);
    2.0 * single / (1.0 + single)
}

/// A thin pane: reflects with probability R = [`thin_slab_reflectance`]
/// (chosen by `u1 < R`), else passes straight through (`wi = −wo`): the two
/// parallel faces undo each other's refraction, so the ray leaves in its
/// original direction, into the same medium, without any η² scaling.
/// Weights: `reflectance` and `transmittance`.
pub(super) fn sample_thin_glass(
    reflectance: Vec3,
    transmittance: Vec3,
    ior: f32,
    wo: Vec3,
    u1: f32,
) -> Option<BsdfSample> {
    let r = thin_slab_reflectance(wo.z, ior);
    if u1 < r {
        delta_sample(reflect_local(wo), reflectance, r, MIRROR_FLAGS)
    } else {
        delta_sample(-wo, transmittance, 1.0 - r, REFRACTION_FLAGS)
    }
}

/// A smooth conductor: the mirror direction with the exact conductor
/// Fresnel reflectance of complex IOR `eta + i k` as its weight, so metals
/// brighten toward grazing angles (Mitsuba's `conductor`).
pub(super) fn sample_conductor(eta: Vec3, k: Vec3, wo: Vec3) -> Option<BsdfSample> {
    let reflectance = super::fresnel::fresnel_conductor(wo.z.abs(), eta, k);
    delta_sample(reflect_local(wo), reflectance, 1.0, MIRROR_FLAGS)
}
