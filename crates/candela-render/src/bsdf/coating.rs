//! The energy a rough dielectric coating lets through, tabulated once per
//! (distribution, IOR) for the rough plastic (see `rough_plastic.rs`).
//!
//! A rough coating seen at μ = cos θ reflects the directional albedo
//! E(μ) = ∫ F(wo·m) D(m) G2(wo, wi) / (4 cos θo) dωi (the reflection lobe of
//! the rough dielectric, Fresnel included) and transmits the energy T(μ) of
//! the rough dielectric's refraction lobe into the layer; E + T < 1 by what
//! masking removes (single scattering). Light scattered back up from the
//! base meets the coating from inside, whose albedo for diffuse light is
//! F_int = 2 ∫₀¹ E_inside(μ) μ dμ (mostly total internal reflection), or,
//! as the description's [`InternalReflectance`] says, Mitsuba's plain mean
//! of 2 E_inside(μ) μ at 64 evenly spaced μ, ends included, which is
//! (63/64) F_int + E_inside(1)/64. These are Mitsuba 3's `roughplastic`
//! precomputations (`eval_transmittance` and `eval_reflectance`; Weidlich &
//! Wilkie 2007).
//!
//! Both albedos are integrated over the visible normals: E(μ) = E_u[F ·
//! G2(wo, wi) / G1(wo) · [wi above]] and T(μ) = E_u[(1 − F) · G2(wo, wt) /
//! G1(wo) · [wt below]], wi and wt the reflected and refracted directions of
//! the visible normal m for u on a regular midpoint grid of the unit square,
//! which is smooth where the lobe is narrow and never misses it. Anisotropic distributions are tabulated at
//! azimuth 0 (Mitsuba refuses them for `roughplastic`).
//!
//! Tables are interned: one per distinct (distribution, masking, F_int
//! rule, IOR) for the whole
//! process, leaked so that [`super::RoughPlastic`] stays a small `Copy`
//! value holding a `&'static` reference. Their number is the number of
//! distinct rough-plastic parameter sets in the scenes loaded, so a caller
//! that varies α per hit (a roughness texture) must quantise α first.

use std::sync::Mutex;

use glam::{Vec2, Vec3};

use super::distribution::{Masking, MicrofacetDistribution};
use super::fresnel::{fresnel_dielectric, refract};
pub use candela_scene::InternalReflectance;

/// Entries of T(μ), at μ = j / (N − 1).
pub(super) const TABLE_SIZE: usize = 64;
/// Grid side of the visible-normal quadrature per direction. From inside
/// it needs the full side too: the edge of total internal reflection cuts
/// the grid, and at 32 F_int was 0.0035 too high for GGX α = 0.1.
const GRID: usize = 64;
/// Cosines at which E_inside is averaged for F_int (midpoints).
const INTERNAL_NODES: usize = 64;
/// Cosines of [`InternalReflectance::EvenSampleMean`] (Mitsuba's table
/// size): j / (N − 1) for j = 0..N.
const EVEN_SAMPLES: usize = 64;
/// The smallest cosine tabulated (μ = 0 exactly has no visible normals).
const MIN_COSINE: f32 = 1e-4;

/// T(μ) from outside and F_int from inside, for one coating.
#[derive(Debug, PartialEq)]
pub(crate) struct CoatingTable {
    dist: MicrofacetDistribution,
    masking: Masking,
    internal: InternalReflectance,
    ior: f32,
    transmittance: [f32; TABLE_SIZE],
    internal_reflectance: f32,
}

impl CoatingTable {
    fn compute(
        dist: MicrofacetDistribution,
        masking: Masking,
        internal: InternalReflectance,
        ior: f32,
    ) -> Self {
        let mut transmittance = [0.0; TABLE_SIZE];
        for (j, t) in transmittance.iter_mut().enumerate() {
            let mu = (j as f32 / (TABLE_SIZE - 1) as f32).max(MIN_COSINE);
            *t = transmission_albedo(dist, masking, ior, mu, GRID).clamp(0.0, 1.0);
        }
        let internal_reflectance = internal_reflectance(dist, masking, internal, 1.0 / ior, GRID);
        Self {
            dist,
            masking,
            internal,
            ior,
            transmittance,
            internal_reflectance: internal_reflectance.clamp(0.0, 1.0),
        }
    }

    /// T(μ): the energy the coating lets in from outside at cosine `mu`
    /// (either side; linear interpolation in μ).
    pub(crate) fn transmittance(&self, mu: f32) -> f32 {
        let x = mu.abs().min(1.0) * (TABLE_SIZE - 1) as f32;
        let i = (x as usize).min(TABLE_SIZE - 2);
        let w = x - i as f32;
        self.transmittance[i] * (1.0 - w) + self.transmittance[i + 1] * w
    }

    /// F_int: the coating's albedo for diffuse light from inside.
    pub(crate) fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }
}

/// F_int: the albedo for diffuse light of a rough interface of relative
/// IOR `eta` (far side over near side), E(μ) on a `grid` × `grid` rule,
/// averaged over μ as `rule` says.
pub(crate) fn internal_reflectance(
    dist: MicrofacetDistribution,
    masking: Masking,
    rule: InternalReflectance,
    eta: f32,
    grid: usize,
) -> f32 {
    let cosines: Vec<f32> = match rule {
        // The midpoint rule: 2 E(μ) μ is smooth but for the edge of total
        // internal reflection.
        InternalReflectance::Integral => (0..INTERNAL_NODES)
            .map(|j| (j as f32 + 0.5) / INTERNAL_NODES as f32)
            .collect(),
        InternalReflectance::EvenSampleMean => (0..EVEN_SAMPLES)
            .map(|j| j as f32 / (EVEN_SAMPLES - 1) as f32)
            .collect(),
    };
    let sum: f32 = cosines
        .iter()
        // μ = 0 has no visible normals; its term is 0 (μ E(μ) → 0).
        .filter(|&&mu| mu > 0.0)
        .map(|&mu| 2.0 * mu * reflection_albedo(dist, masking, eta, mu, grid))
        .sum();
    sum / cosines.len() as f32
}

/// The directional albedo E(μ) of the reflection lobe of a rough interface
/// of relative IOR `eta` (far side over near side) seen at cosine `mu`,
/// by a `grid` × `grid` midpoint rule over the visible normals.
pub(crate) fn reflection_albedo(
    dist: MicrofacetDistribution,
    masking: Masking,
    eta: f32,
    mu: f32,
    grid: usize,
) -> f32 {
    visible_normal_mean(dist, mu, grid, |wo, m, cos_om| {
        let wi = 2.0 * cos_om * m - wo;
        (wi.z > 0.0).then(|| fresnel_dielectric(cos_om, eta) * dist.masking(masking, wo, wi))
    })
}

/// The energy T(μ) that a rough interface of relative IOR `eta` transmits
/// from cosine `mu`, by the same rule as [`reflection_albedo`].
pub(crate) fn transmission_albedo(
    dist: MicrofacetDistribution,
    masking: Masking,
    eta: f32,
    mu: f32,
    grid: usize,
) -> f32 {
    visible_normal_mean(dist, mu, grid, |wo, m, cos_om| {
        // None at total internal reflection on this microfacet.
        let wt = refract(wo, m, eta)?;
        (wt.z < 0.0)
            .then(|| (1.0 - fresnel_dielectric(cos_om, eta)) * dist.masking(masking, wo, wt))
    })
}

/// The mean over the visible normals m of `lobe(wo, m, wo·m) / G1(wo)` for
/// the direction `wo` at cosine `mu`, by a `grid` × `grid` midpoint rule
/// (`None`, a direction on the wrong side, counts 0). The radial coordinate
/// of the visible-normal disk is u = 1 − s³ with s on the midpoint grid
/// (weight 3s²): the steep microfacets, whose reflections the masking and
/// the horizon cut, sit in a band of width about α² at u → 1, which plain
/// midpoints never reach for a smooth lobe (the white GGX albedo at α =
/// 0.065 seen from the normal came out 0.9999 instead of 0.9953).
pub(super) fn visible_normal_mean(
    dist: MicrofacetDistribution,
    mu: f32,
    grid: usize,
    lobe: impl Fn(Vec3, Vec3, f32) -> Option<f32>,
) -> f32 {
    let wo = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    let g1 = dist.g1(wo);
    let mut sum = 0.0f64;
    for a in 0..grid {
        let s = (a as f64 + 0.5) / grid as f64;
        let (radial, weight) = (1.0 - s * s * s, 3.0 * s * s);
        for b in 0..grid {
            let u = Vec2::new(radial as f32, (b as f32 + 0.5) / grid as f32);
            let m = dist.sample_visible_normal(wo, u);
            let cos_om = wo.dot(m);
            if cos_om <= 0.0 {
                continue;
            }
            if let Some(value) = lobe(wo, m, cos_om) {
                sum += weight * f64::from(value / g1);
            }
        }
    }
    (sum / (grid * grid) as f64) as f32
}

/// Every table made so far.
static TABLES: Mutex<Vec<&'static CoatingTable>> = Mutex::new(Vec::new());

/// The table for a coating of distribution `dist` and IOR `ior` (inside
/// over outside), its masking and F_int as the description says, computed
/// on first use.
pub(crate) fn coating_table(
    dist: MicrofacetDistribution,
    masking: Masking,
    internal: InternalReflectance,
    ior: f32,
) -> &'static CoatingTable {
    // A poisoned lock only means another thread panicked while pushing a
    // finished table: the list is still valid.
    let mut tables = TABLES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(t) = tables
        .iter()
        .find(|t| t.dist == dist && t.masking == masking && t.internal == internal && t.ior == ior)
    {
        return t;
    }
    let table: &'static CoatingTable = Box::leak(Box::new(CoatingTable::compute(
        dist, masking, internal, ior,
    )));
    tables.push(table);
    table
}
