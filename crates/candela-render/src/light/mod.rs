//! Light sources: sampling the light arriving at a point, and the density of
//! having sampled a given direction (for multiple importance sampling).
//!
//! Every light answers two questions (pbrt's `Light::SampleLi`/`PDF_Li`):
//! - [`Light::sample_li`]: pick a direction `wi` toward the light from a
//!   point, with the radiance `L` arriving along it, the distance to the
//!   light, and the density of `wi` per unit **solid angle** at the point
//!   (delta lights report 1 and are flagged by [`Light::is_delta`]);
//! - [`Light::pdf_li`]: that density for a direction found some other way
//!   (a BSDF sample that happened to hit the light).
//!
//! Emissive geometry (mesh triangles, spheres) and CGL area rectangles are
//! sampled uniformly in the solid angle they subtend: spheres seen from
//! outside in their cone, triangles and rectangles as spherical polygons
//! (`area/solid_angle.rs`), which fall back to sampling by area converted
//! to solid angle (`pdf_A · d² / |cos θ_l|`) when the lamp looks tiny or
//! fills nearly a hemisphere. Emitters are one-sided: they emit on the side
//! of their normal.
//!
//! Methods that start paths at the lights (light tracing, BDPT) sample
//! rays leaving them with [`Light::sample_le`] and [`Light::pdf_le`]
//! (`emission.rs`), and choose the light with [`LightSet::choose_emitter`].
//!
//! Light samples choose among the non-delta lights through
//! [`LightSet::selector`] (`select.rs`): uniformly, by power, or by the
//! light tree (`tree/`), which weighs each light by a bound on what it can
//! contribute at the shading point.
//!
//! Lights at infinity that rays can escape to (the ambient sky, the
//! environment map) also answer [`Light::le`], the radiance an escaping ray
//! sees, so the path tracer handles all of them in one place.

mod area;
mod backs;
mod delta;
mod emission;
#[cfg(test)]
mod emission_tests;
mod envmap;
mod envmap_bilinear;
#[cfg(test)]
mod envmap_bilinear_tests;
#[cfg(test)]
mod envmap_tests;
mod infinite;
mod select;
#[cfg(test)]
mod select_tests;
mod set;
mod sky;
#[cfg(test)]
mod tests;
mod tree;

use area::LampSize;
pub use area::{AreaLight, AreaShape, TexturedEmission};
pub use delta::{DirectionalLight, PointLight, SpotFade, SpotLight};
pub use emission::{LightEmission, SceneSphere};
pub use envmap::{EnvironmentLight, EnvironmentLookup, EnvironmentMap, EnvironmentOptions};
pub use infinite::AmbientLight;
pub use select::{LightSelection, LightSelector, AUTO_TREE_ABOVE, MIN_REUSED_SHARE};
pub use set::LightSet;
pub use sky::ProceduralSky;
pub use tree::{LightBounds, LightContext, LightTree};

use glam::{Vec2, Vec3};

/// The largest `f32` below 1: a remapped random number must stay in [0, 1).
pub(crate) const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// A sampled direction toward a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light.
    pub wi: Vec3,
    /// Radiance arriving along `wi` (for delta lights: the irradiance-like
    /// quantity that makes `f · L · cos / pdf` with `pdf = 1` correct).
    pub l: Vec3,
    /// Distance to the sampled point on the light (infinite for lights at
    /// infinity).
    pub distance: f32,
    /// Density of `wi` per unit solid angle; 1 for delta lights.
    pub pdf: f32,
}

/// Every kind of light.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Isotropic point light.
    Point(PointLight),
    /// Point light within a cone.
    Spot(SpotLight),
    /// Light from one direction.
    Directional(DirectionalLight),
    /// Emitting surface: triangle, sphere or rectangle.
    Area(AreaLight),
    /// Uniform radiance from the upper hemisphere.
    Ambient(AmbientLight),
    /// Radiance from every direction, given by an equirectangular map.
    Environment(EnvironmentLight),
}

impl Light {
    /// Whether the light is a delta distribution (position or direction):
    /// only light sampling can find it.
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point(_) | Light::Spot(_) | Light::Directional(_)
        )
    }

    /// Whether the light sits at infinity (hit by rays that escape the scene).
    pub fn is_infinite(&self) -> bool {
        matches!(
            self,
            Light::Directional(_) | Light::Ambient(_) | Light::Environment(_)
        )
    }

    /// Radiance seen by a ray that escapes the scene in direction `dir`:
    /// the sky of the lights at infinity that rays can hit, zero for every
    /// other light (delta lights are never hit; emitting surfaces are found
    /// by intersection instead).
    pub fn le(&self, dir: Vec3) -> Vec3 {
        match self {
            Light::Ambient(l) => l.le(dir),
            Light::Environment(l) => l.le(dir),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Area(_) => Vec3::ZERO,
        }
    }

    /// Whether rays can hit the light (emissive geometry, lights at
    /// infinity). A CGL area rectangle is not geometry: only light sampling
    /// finds it, so its light samples take the full MIS weight.
    pub fn is_hittable(&self) -> bool {
        match self {
            Light::Area(l) => !matches!(l.shape, AreaShape::Rect { .. }),
            Light::Ambient(_) | Light::Environment(_) => true,
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) => false,
        }
    }

    /// Samples the light as seen from point `p`.
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        match self {
            Light::Point(l) => l.sample_li(p),
            Light::Spot(l) => l.sample_li(p),
            Light::Directional(l) => Some(l.sample_li()),
            Light::Area(l) => l.sample_li(p, u),
            Light::Ambient(l) => l.sample_li(u),
            Light::Environment(l) => l.sample_li(u),
        }
    }

    /// Solid-angle density with which [`Light::sample_li`] from `p` picks
    /// direction `wi`, given that the ray along `wi` reaches the light at
    /// point `p_light` (ignored by lights at infinity). Zero for delta lights.
    pub fn pdf_li(&self, p: Vec3, wi: Vec3, p_light: Vec3) -> f32 {
        match self {
            Light::Area(l) => l.pdf_li(p, wi, p_light),
            Light::Ambient(l) => l.pdf_li(wi),
            Light::Environment(l) => l.pdf_li(wi),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) => 0.0,
        }
    }

    /// Total emitted power (luminance-weighted), used to choose among lights.
    /// `scene_radius` bounds the scene, for lights at infinity.
    pub fn power(&self, scene_radius: f32) -> f32 {
        match self {
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Directional(l) => l.power(scene_radius),
            Light::Area(l) => l.power(),
            Light::Ambient(l) => l.power(scene_radius),
            Light::Environment(l) => l.power(scene_radius),
        }
    }
}

/// Luminance of a linear RGB colour, used for light power.
pub(crate) fn luminance(c: Vec3) -> f32 {
    crate::film::luminance(c)
}
