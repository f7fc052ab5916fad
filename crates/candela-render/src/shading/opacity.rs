//! Opacity cut-outs: whether a ray meets the surface at a hit or passes
//! through it.
//!
//! A mask (glTF `MASK`, a cutoff on the opacity slot) is deterministic:
//! opaque where the value reaches the cutoff. A coverage fraction (glTF
//! `BLEND`, OBJ `map_d`, Mitsuba opacity) is stochastic opacity: the surface
//! is there with probability a, decided by a hash of the ray (pbrt-v4's
//! alpha test, `HashFloat(ray.o, ray.d)`), so the decision needs no sampler
//! dimension, is the same for a ray however often it is traced, and works
//! for shadow rays, which have no sampler. The expected transmittance of a
//! point is then exactly 1 − a, which the estimators average to the blended
//! look without sorting transparent surfaces.
//!
//! Emission follows the surface: a cut-out point neither blocks nor emits,
//! and light sampling weights an emitter's radiance by its opacity
//! (`light/area.rs`), so both estimators see a · Le.
//!
//! An invisible surface (Mitsuba's `null` BSDF) is passed by every ray, yet
//! emits in full: the closest-hit query stops at one that emits so that the
//! integrator can add its emission before going on past it
//! (`scene/visibility.rs`).

use crate::geometry::Ray;
use crate::material::Material;
use crate::sampling::hash::{mix64, unit_f32};
use crate::shape::SurfaceHit;

/// Whether `ray` passes through `material` at `hit`: always through an
/// invisible one ([`Material::invisible`]).
pub fn passes_through(material: &Material, hit: &SurfaceHit, ray: &Ray) -> bool {
    if material.invisible {
        return true;
    }
    if !material.textures.has_opacity() {
        return false;
    }
    let a = material.textures.opacity(hit.texture_point());
    if a >= 1.0 {
        return false;
    }
    if a <= 0.0 {
        return true;
    }
    ray_hash(ray) >= a
}

/// A uniform number in [0, 1) from the ray's origin and direction bits.
fn ray_hash(ray: &Ray) -> f32 {
    let bits = [ray.origin, ray.dir]
        .iter()
        .flat_map(|v| v.to_array())
        .fold(0x2545_f491_4f6c_dd1d_u64, |h, c| {
            mix64(h ^ u64::from(c.to_bits()))
        });
    unit_f32((bits >> 32) as u32)
}
