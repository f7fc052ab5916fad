//! Transport modes: the same BSDF used for radiance (paths traced from the
//! camera) or for importance (particles traced from the lights).
//!
//! Light tracing and bidirectional path tracing carry importance along
//! light subpaths, i.e. they evaluate the *adjoint* BSDF
//! f*(wo, wi) = f(wi, wo) (Veach 1997, §3.7 and ch. 5). Two of our
//! scattering models are not symmetric, and their adjoints differ:
//!
//! - **Refraction** (Veach §5.2): the radiance BSDF of a dielectric carries
//!   the factor 1/η² (η the relative IOR, far side over the side of `wo`;
//!   see the module docs of [`super`]); the adjoint does not. So
//!   [`Bsdf::f_mode`] and [`Bsdf::sample_mode`] multiply a transmitted pair
//!   by η² (of `wo`'s side) in importance mode, which is exactly the
//!   generalised reciprocity f(wo, wi)·η(wi)² = f(wi, wo)·η(wo)².
//! - **Shading normals** (Veach §5.3): with the BSDF evaluated around the
//!   shading normal `ns` but areas measured around the true normal `ng`, the
//!   scattering kernel is f(wo, wi)·|wi·ns| / |wi·ng| per unit projected
//!   solid angle of the geometry; its adjoint needs the extra factor
//!   [`shading_normal_correction`] = |wo·ns||wi·ng| / (|wo·ng||wi·ns|) in
//!   importance mode (pbrt-v4's `CorrectShadingNormal`, in our convention:
//!   `wo` toward where the particle came from, `wi` where it goes).
//!
//! - **Non-reciprocal models** (the glTF clear coat, which dims the layers
//!   beneath by the view alone, as the extension and Blender Cycles do):
//!   the adjoint is evaluated by its definition, f with `wo` and `wi`
//!   swapped, since no scalar factor relates the two values.
//!
//! All are checked by the adjoint relation
//! f_importance(wo, wi)·(kernel factors) = f_radiance(wi, wo)·(kernel
//! factors) in `transport_tests.rs`.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfSample};

/// Which quantity a path carries through a BSDF.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TransportMode {
    /// Radiance, on paths traced from the camera (the BSDF as it is).
    #[default]
    Radiance,
    /// Importance, on paths traced from the lights (the adjoint BSDF).
    Importance,
}

impl Bsdf {
    /// The squared relative index of refraction (far side over near side)
    /// of a refraction leaving direction `wo` (local frame): the factor
    /// `1/η²` the dielectric puts into a radiance sample's weight. 1 for
    /// every BSDF that does not change medium (a thin pane passes light
    /// straight through, back into the medium it came from).
    pub fn refraction_eta2(&self, wo: Vec3) -> f32 {
        let ior = match *self {
            Bsdf::Glass { ior, .. }
            | Bsdf::Refraction { ior, .. }
            | Bsdf::RoughGlass { ior, .. } => ior,
            Bsdf::MetallicRoughness(m) => m.ior(),
            Bsdf::Principled(p) => p.ior(),
            Bsdf::Blend(ref b) => return b.refraction_eta2(wo),
            Bsdf::Diffuse { .. }
            | Bsdf::Mirror { .. }
            | Bsdf::Microfacet { .. }
            | Bsdf::ThinGlass { .. }
            | Bsdf::Plastic(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::Conductor { .. } => return 1.0,
        };
        let eta = if wo.z > 0.0 { ior } else { 1.0 / ior };
        eta * eta
    }

    /// [`Bsdf::f`] for the given transport mode (cosine excluded).
    pub fn f_mode(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Vec3 {
        if let Bsdf::Blend(b) = self {
            return b.f_mode(wo, wi, mode); // each part its own factor
        }
        if self.evaluates_adjoint_swapped(mode) {
            return self.f(wi, wo);
        }
        self.f(wo, wi) * self.adjoint_scale(wo, wi, mode)
    }

    /// [`Bsdf::sample`] for the given transport mode: the same directions
    /// and densities, with `f` of the mode.
    pub fn sample_mode(
        &self,
        wo: Vec3,
        u1: f32,
        u2: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        if let Bsdf::Blend(b) = self {
            return b.sample_mode(wo, u1, u2, mode); // each part its own factor
        }
        let mut s = self.sample(wo, u1, u2)?;
        match self {
            Bsdf::MetallicRoughness(m) if self.evaluates_adjoint_swapped(mode) => {
                if s.is_specular() {
                    // A delta lobe has no value to swap: its weight's
                    // factors of the view, taken at the other direction.
                    s.f *= self.adjoint_scale(wo, s.wi, mode) * m.delta_adjoint_scale(wo, s.wi);
                } else {
                    s.f = self.f(s.wi, wo);
                }
            }
            _ => s.f *= self.adjoint_scale(wo, s.wi, mode),
        }
        Some(s)
    }

    /// Whether the adjoint in `mode` is the radiance BSDF with `wo` and
    /// `wi` swapped, f*(wo, wi) = f(wi, wo), evaluated as such: in
    /// importance mode, for a model whose value is not reciprocal (a glTF
    /// clear coat dims what lies beneath by the view alone), where no
    /// scalar factor turns f(wo, wi) into f(wi, wo). The swap includes
    /// refraction's η² by definition.
    fn evaluates_adjoint_swapped(&self, mode: TransportMode) -> bool {
        mode == TransportMode::Importance
            && matches!(self, Bsdf::MetallicRoughness(m) if !m.is_reciprocal())
    }

    /// The factor from the radiance BSDF to the mode's: η² for a
    /// transmitted pair in importance mode, else 1.
    fn adjoint_scale(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        match mode {
            TransportMode::Importance if wo.z * wi.z < 0.0 => self.refraction_eta2(wo),
            _ => 1.0,
        }
    }
}

/// The shading-normal correction of the adjoint BSDF (Veach 1997 §5.3):
/// |wo·ns||wi·ng| / (|wo·ng||wi·ns|) in importance mode, 1 in radiance
/// mode. World-space unit vectors; `wo` toward where the particle came
/// from, `wi` where it scatters to. Zero when either direction grazes the
/// true surface.
pub fn shading_normal_correction(
    mode: TransportMode,
    wo: Vec3,
    wi: Vec3,
    ns: Vec3,
    ng: Vec3,
) -> f32 {
    match mode {
        TransportMode::Radiance => 1.0,
        TransportMode::Importance => {
            let denom = wo.dot(ng).abs() * wi.dot(ns).abs();
            if denom == 0.0 {
                0.0
            } else {
                wo.dot(ns).abs() * wi.dot(ng).abs() / denom
            }
        }
    }
}
