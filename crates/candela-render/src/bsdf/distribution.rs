//! Distributions of microfacet normals, shared by the rough conductor and
//! the rough dielectric: a closed enum (Beckmann | GGX), each isotropic or
//! anisotropic, with
//! - D(m): microfacet area per unit solid angle of normals, per unit
//!   macro-surface area, so that ∫ D(m) cos θm dωm = 1;
//! - Smith's Λ(w), from which G1 = 1 / (1 + Λ) and the *height-correlated*
//!   masking-shadowing G2 = 1 / (1 + Λ(wo) + Λ(wi)) (Heitz 2014,
//!   "Understanding the Masking-Shadowing Function"), which, unlike the
//!   separable product G1·G1, does not double-count shadowing by the same
//!   heights;
//! - sampling of the normals visible from a direction, with density
//!   D_wo(m) = G1(wo)·max(0, wo·m)·D(m) / cos θo: the weight f·cos/pdf of a
//!   perfect reflector is then G2/G1 ≤ 1, without the fireflies of plain
//!   D(m)·cos θm sampling at grazing angles.
//!
//! Directions here are in the upper hemisphere (`z > 0`); the BSDFs flip
//! the side of `wo` before asking. Both distributions are symmetric under
//! m → (−m.x, −m.y, m.z), which the dielectric relies on when it views the
//! surface from below.

use glam::{Vec2, Vec3};

use super::{beckmann, ggx};

/// Roughness below this is clamped: a smaller α makes D overflow `f32`
/// and the lobe is indistinguishable from a mirror anyway.
pub const MIN_ALPHA: f32 = 1e-3;

/// How the masking of the two directions of a pair combines into G2 (the
/// scene description's choice, by the file's renderer).
pub use candela_scene::Masking;

/// A distribution of microfacet normals with roughness α along the tangent
/// (x) and bitangent (y) axes of the shading frame (equal: isotropic).
/// Values below [`MIN_ALPHA`] are clamped where used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MicrofacetDistribution {
    /// Beckmann: Gaussian slopes, RMS slope α (α/√2 per axis); the
    /// distribution of CS184's `<microfacet>` and of Walter et al.'s paper.
    Beckmann {
        /// Roughness along x.
        alpha_x: f32,
        /// Roughness along y.
        alpha_y: f32,
    },
    /// GGX / Trowbridge-Reitz: the normals of an ellipsoid of radii
    /// (α_x, α_y, 1); a longer tail (a glow around highlights) than
    /// Beckmann at the same α.
    Ggx {
        /// Roughness along x.
        alpha_x: f32,
        /// Roughness along y.
        alpha_y: f32,
    },
}

impl MicrofacetDistribution {
    /// Isotropic Beckmann of roughness α.
    pub fn beckmann(alpha: f32) -> Self {
        Self::Beckmann {
            alpha_x: alpha,
            alpha_y: alpha,
        }
    }

    /// Isotropic GGX of roughness α.
    pub fn ggx(alpha: f32) -> Self {
        Self::Ggx {
            alpha_x: alpha,
            alpha_y: alpha,
        }
    }

    /// (α_x, α_y), clamped to [`MIN_ALPHA`] (NaN becomes the minimum too).
    pub fn alphas(&self) -> (f32, f32) {
        let (Self::Beckmann { alpha_x, alpha_y } | Self::Ggx { alpha_x, alpha_y }) = *self;
        (alpha_x.max(MIN_ALPHA), alpha_y.max(MIN_ALPHA))
    }

    /// D(m); zero for `m.z ≤ 0`.
    pub(crate) fn d(&self, m: Vec3) -> f32 {
        let (ax, ay) = self.alphas();
        match self {
            Self::Beckmann { .. } => beckmann::d(ax, ay, m),
            Self::Ggx { .. } => ggx::d(ax, ay, m),
        }
    }

    /// Smith's Λ(w) (either side: only |w.z| matters).
    pub(crate) fn lambda(&self, w: Vec3) -> f32 {
        let (ax, ay) = self.alphas();
        let cos = f64::from(w.z.abs());
        // α(φ)·sin θ, then divided by cos θ: α(φ)·tan θ.
        let alpha_sin = (f64::from(ax * w.x).powi(2) + f64::from(ay * w.y).powi(2)).sqrt();
        let alpha_tan = if cos == 0.0 {
            f64::INFINITY
        } else {
            alpha_sin / cos
        };
        match self {
            Self::Beckmann { .. } => beckmann::lambda(alpha_tan),
            Self::Ggx { .. } => ggx::lambda(alpha_tan),
        }
    }

    /// Smith's masking G1(w) = 1 / (1 + Λ(w)).
    pub(crate) fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing G2(wo, wi).
    pub(crate) fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Masking-shadowing of the pair combined as `masking` says.
    pub(crate) fn masking(&self, masking: Masking, wo: Vec3, wi: Vec3) -> f32 {
        match masking {
            Masking::HeightCorrelated => self.g2(wo, wi),
            Masking::Separable => self.g1(wo) * self.g1(wi),
        }
    }

    /// A normal visible from `wo` (`wo.z > 0`), with density
    /// [`Self::visible_pdf`].
    pub(crate) fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Vec3 {
        let (ax, ay) = self.alphas();
        match self {
            Self::Beckmann { .. } => beckmann::sample_visible_normal(ax, ay, wo, u),
            Self::Ggx { .. } => ggx::sample_visible_normal(ax, ay, wo, u),
        }
    }

    /// D_wo(m) = G1(wo)·max(0, wo·m)·D(m) / cos θo for `wo.z > 0`.
    pub(crate) fn visible_pdf(&self, wo: Vec3, m: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * wo.dot(m).max(0.0) * self.d(m) / wo.z
    }
}
