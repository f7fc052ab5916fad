//! Emission sampling: rays leaving the lights, for methods that trace
//! paths from the lights (light tracing, bidirectional path tracing).
//!
//! [`Light::sample_le`] draws a ray leaving a light with the radiance it
//! carries, and the densities of its origin (per unit area) and of its
//! direction (per unit solid angle); [`Light::pdf_le`] gives those two
//! densities for a ray found some other way (a camera path that hits an
//! emitter), as bidirectional MIS needs (Veach 1997, ch. 10; pbrt-v4's
//! `Light::SampleLe`/`PDF_Le`, whose conventions these follow).
//!
//! | light | origin (pdf_pos) | direction (pdf_dir) |
//! |---|---|---|
//! | area (triangle, rect, sphere) | uniform by area: 1 / area | cosine-weighted about the emitting normal: cos θ / π |
//! | point | its position: 1 (delta) | uniform sphere: 1 / 4π |
//! | spot | its position: 1 (delta) | ∝ the falloff `cos^n` inside the cone |
//! | directional | uniform on a disk of the scene's radius, perpendicular to the direction, on the side the light comes from: 1 / (π r²) | its direction: 1 (delta) |
//! | ambient sky | the same disk, perpendicular to the sampled direction | uniform over the upper hemisphere: 1 / 2π |
//! | environment map | the same disk | the map's importance distribution (the one `sample_li` uses) |
//!
//! Delta components report 1 (in `pdf_le` too, whatever the argument: ask
//! only about rays the light can emit). The estimate of a light's power,
//! `le · |cos θ| / (pdf_pos · pdf_dir)` with `cos θ` between the ray and
//! [`LightEmission::normal`] (taken as 1 for point and spot lights, whose
//! normal is zero), is unbiased for the flux the light sends out (for
//! lights at infinity: the flux crossing the scene's bounding disk); the
//! tests check it against each light's analytic power.

use super::{area::AreaLight, Light};
use crate::geometry::{Frame, Ray};
use crate::sampling::warp::{sin_cos_turns, square_to_concentric_disk, square_to_uniform_sphere};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A sphere bounding the scene. Lights at infinity emit from a disk of
/// its radius through its centre, perpendicular to the emitted direction
/// and moved back along it by the radius (pbrt-v4), so every ray from them
/// crosses the whole scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneSphere {
    /// Centre.
    pub center: Vec3,
    /// Radius (0 for an empty scene: lights at infinity then emit nothing).
    pub radius: f32,
}

/// A ray leaving a light, with its radiance and densities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightEmission {
    /// Origin on the light (for emitting surfaces pushed off the surface by
    /// its rounding-error bound, as `shape::spawn_ray` does, so the ray
    /// cannot re-hit its own emitter), unit direction.
    pub ray: Ray,
    /// Radiance leaving along the ray; for point and spot lights the
    /// intensity (W/sr) in that direction, for a directional light its
    /// irradiance.
    pub le: Vec3,
    /// Surface normal at the origin for area lights (the emitting side),
    /// the ray direction for lights at infinity, zero for point and spot
    /// lights.
    pub normal: Vec3,
    /// Density of the origin per unit area (1 for point and spot lights).
    pub pdf_pos: f32,
    /// Density of the direction per unit solid angle (1 for a directional
    /// light).
    pub pdf_dir: f32,
}

impl Light {
    /// Draws a ray leaving the light: `u_pos` chooses the origin, `u_dir`
    /// the direction (see the module's table). `None` when the light
    /// cannot emit (zero area or cone, a light at infinity in an empty
    /// scene, a sample of zero density).
    pub fn sample_le(
        &self,
        u_pos: Vec2,
        u_dir: Vec2,
        bounds: &SceneSphere,
    ) -> Option<LightEmission> {
        match self {
            Light::Area(l) => l.sample_le(u_pos, u_dir),
            Light::Point(l) => {
                let dir = square_to_uniform_sphere(u_dir);
                Some(LightEmission {
                    ray: Ray::new(l.position, dir),
                    le: l.intensity,
                    normal: Vec3::ZERO,
                    pdf_pos: 1.0,
                    pdf_dir: 1.0 / (4.0 * PI),
                })
            }
            Light::Spot(l) => l.sample_le(u_dir),
            Light::Directional(l) => {
                let (origin, pdf_pos) = disk_origin(l.direction, u_pos, bounds)?;
                Some(LightEmission {
                    ray: Ray::new(origin, l.direction),
                    le: l.irradiance,
                    normal: l.direction,
                    pdf_pos,
                    pdf_dir: 1.0,
                })
            }
            Light::Ambient(_) | Light::Environment(_) => {
                // The direction toward the sky, as light sampling draws it;
                // the ray travels the other way.
                let s = self.sample_li(Vec3::ZERO, u_dir)?;
                if s.pdf <= 0.0 {
                    return None;
                }
                let dir = -s.wi;
                let (origin, pdf_pos) = disk_origin(dir, u_pos, bounds)?;
                Some(LightEmission {
                    ray: Ray::new(origin, dir),
                    le: s.l,
                    normal: dir,
                    pdf_pos,
                    pdf_dir: s.pdf,
                })
            }
        }
    }

    /// Densities `(pdf_pos, pdf_dir)` with which [`Light::sample_le`]
    /// would emit the ray leaving `origin` along unit `dir`, where `normal`
    /// is the light's surface normal at `origin` (area lights; ignored by
    /// the others). Zero when the light cannot emit that ray (the back of
    /// a one-sided emitter, outside a spot's cone, below the ambient sky's
    /// horizon); delta components are 1 (see the module docs).
    pub fn pdf_le(
        &self,
        origin: Vec3,
        normal: Vec3,
        dir: Vec3,
        bounds: &SceneSphere,
    ) -> (f32, f32) {
        let _ = origin; // every position density here is uniform
        match self {
            Light::Area(l) => (1.0 / l.shape.area(), normal.dot(dir).max(0.0) / PI),
            Light::Point(_) => (1.0, 1.0 / (4.0 * PI)),
            Light::Spot(l) => (1.0, l.pdf_dir(dir)),
            Light::Directional(_) => (disk_pdf(bounds), 1.0),
            Light::Ambient(_) | Light::Environment(_) => {
                (disk_pdf(bounds), self.pdf_li(Vec3::ZERO, -dir, Vec3::ZERO))
            }
        }
    }
}

impl super::SpotLight {
    /// The lowest cosine the spot emits at: its cutoff, and not below the
    /// horizon when a falloff `cos^n` (zero there) is applied.
    fn cos_lowest(&self) -> f32 {
        if self.exponent > 0.0 {
            self.cos_cutoff.max(0.0)
        } else {
            self.cos_cutoff.max(-1.0)
        }
    }

    /// Directions are drawn in proportion to the intensity, `cos^n θ` inside
    /// the cone (uniform in the cone when `n = 0`): with `k = n + 1` and
    /// `c0` the lowest cosine, `P(cos θ ≤ c) = (c^k − c0^k) / (1 − c0^k)`,
    /// inverted in closed form.
    fn sample_le(&self, u: Vec2) -> Option<LightEmission> {
        let c0 = self.cos_lowest();
        let cos = if self.exponent > 0.0 {
            let k = self.exponent + 1.0;
            let a = c0.powf(k);
            (a + u.x * (1.0 - a)).powf(1.0 / k).min(1.0)
        } else {
            c0 + u.x * (1.0 - c0)
        };
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let (s, c) = sin_cos_turns(u.y);
        let dir = Frame::from_normal(self.direction).to_world(Vec3::new(sin * c, sin * s, cos));
        let pdf_dir = self.pdf_dir(dir);
        if pdf_dir <= 0.0 {
            return None;
        }
        // The edge's fade is a weight on the sample (the density follows
        // `cos^n` only), as `sample_li` applies it.
        Some(LightEmission {
            ray: Ray::new(self.position, dir),
            le: self.intensity * self.intensity_scale(cos),
            normal: Vec3::ZERO,
            pdf_pos: 1.0,
            pdf_dir,
        })
    }

    /// Solid-angle density of emitting along `dir`:
    /// `k cos^n θ / (2π (1 − c0^k))` inside the cone.
    fn pdf_dir(&self, dir: Vec3) -> f32 {
        let cos = dir.dot(self.direction);
        let c0 = self.cos_lowest();
        if cos < self.cos_cutoff || cos < c0 || c0 >= 1.0 {
            return 0.0;
        }
        let k = self.exponent.max(0.0) + 1.0;
        k * self.falloff(cos) / (2.0 * PI * (1.0 - c0.powf(k)))
    }
}

impl AreaLight {
    /// A point uniform on the surface, a direction cosine-weighted about
    /// its emitting normal.
    fn sample_le(&self, u_pos: Vec2, u_dir: Vec2) -> Option<LightEmission> {
        let area = self.shape.area();
        if area.is_nan() || area <= 0.0 {
            return None;
        }
        let (point, le) = self.sample_point(u_pos);
        let local = crate::sampling::warp::square_to_cosine_hemisphere(u_dir);
        let pdf_dir = crate::sampling::warp::cosine_hemisphere_pdf(local);
        if pdf_dir <= 0.0 {
            return None;
        }
        let dir = Frame::from_normal(point.n).to_world(local);
        Some(LightEmission {
            ray: crate::shape::spawn_ray(&point, dir),
            le,
            normal: point.n,
            pdf_pos: 1.0 / area,
            pdf_dir,
        })
    }
}

/// The origin of a ray along `dir` from a light at infinity: uniform on
/// the disk of the scene's radius perpendicular to `dir` through the
/// centre, moved back by the radius; with its density per unit area.
fn disk_origin(dir: Vec3, u: Vec2, bounds: &SceneSphere) -> Option<(Vec3, f32)> {
    let pdf = disk_pdf(bounds);
    if pdf <= 0.0 {
        return None;
    }
    let d = square_to_concentric_disk(u) * bounds.radius;
    let frame = Frame::from_normal(dir);
    let origin = bounds.center + frame.x * d.x + frame.y * d.y - dir * bounds.radius;
    Some((origin, pdf))
}

/// 1 / (π r²), zero for an empty (or malformed) scene sphere.
fn disk_pdf(bounds: &SceneSphere) -> f32 {
    let r = bounds.radius;
    if r > 0.0 && r.is_finite() {
        1.0 / (PI * r * r)
    } else {
        0.0
    }
}
