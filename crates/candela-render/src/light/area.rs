//! Emitting surfaces: mesh triangles, spheres and CGL rectangles, each
//! one-sided, with constant radiance or an emission texture.
//!
//! Light sampling of triangles and rectangles is by the solid angle they
//! subtend where that is stable and worth it, else by area
//! (`area/solid_angle.rs`).
//!
//! A textured emitter is sampled like an untextured one (by solid angle,
//! or by area where that falls back): the density of a sampled point does not
//! depend on the radiance there, so evaluating the texture at the sampled
//! point (times the surface's opacity there, see `shading/opacity.rs`)
//! keeps the estimate unbiased; only its variance depends on how uneven the
//! texture is. The power used to choose among lights is the texture's mean
//! (an approximation is enough: any positive selection probability is
//! unbiased).

mod solid_angle;
pub(super) use solid_angle::LampSize;
#[cfg(test)]
pub(super) use solid_angle::MAX_SOLID_ANGLE;

use super::{luminance, LightSample};
use crate::geometry::Frame;
use crate::sampling::warp::{
    square_to_uniform_cone, square_to_uniform_sphere, square_to_uniform_triangle, uniform_cone_pdf,
    Parallelogram,
};
use crate::shading::MaterialTextures;
use crate::shape::{gamma, sphere_uv_in, SurfacePoint};
use crate::texture::TexturePoint;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::Arc;

/// The geometry of an area light.
#[derive(Clone, Debug, PartialEq)]
pub enum AreaShape {
    /// A triangle emitting on the side of `normal`.
    Triangle {
        /// Corners.
        v: [Vec3; 3],
        /// Unit normal of the emitting side.
        normal: Vec3,
    },
    /// A parallelogram `origin + s·edge0 + t·edge1` emitting on the side of `normal`.
    Rect {
        /// The parallelogram.
        shape: Parallelogram,
        /// Unit normal of the emitting side.
        normal: Vec3,
    },
    /// A sphere emitting outward, or inward when `inward`.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
        /// Emits toward its centre (normals flipped inward): seen and
        /// sampled from inside.
        inward: bool,
    },
}

/// A one-sided emitter of constant or textured radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    /// Where it emits from.
    pub shape: AreaShape,
    /// Emitted radiance (with a texture: its mean, for the light's power).
    pub radiance: Vec3,
    /// The emission and opacity textures of the emitting material, with
    /// the emitter's texture coordinates.
    pub textured: Option<TexturedEmission>,
}

/// Where a textured emitter reads its radiance.
#[derive(Clone, Debug, PartialEq)]
pub struct TexturedEmission {
    /// The material's textures (emission, opacity).
    pub textures: Arc<MaterialTextures>,
    /// A triangle's UVs at its three corners (the sphere's mapping is its
    /// own).
    pub uvs: [Vec2; 3],
    /// A triangle's vertex colours at its corners (white without them and
    /// on a sphere).
    pub colors: [Vec3; 3],
    /// A sphere's parameterisation axes (`SphereDesc::axes`; unused for a
    /// triangle).
    pub sphere_axes: Mat3,
    /// The constant radiance when there is no emission texture (an
    /// emitter with only a cut-out).
    pub radiance: Vec3,
}

impl TexturedEmission {
    /// Emitted radiance times opacity at a point (a sphere's: its uv).
    pub fn at(&self, at: impl Into<TexturePoint>) -> Vec3 {
        let at = at.into();
        self.textures.emission(at).unwrap_or(self.radiance) * self.textures.opacity(at)
    }

    /// [`TexturedEmission::at`] the point of corner weights `b` of a
    /// triangle: its UVs and vertex colours interpolated as `surface_hit`
    /// interpolates them.
    pub fn at_corners(&self, b: [f32; 3]) -> Vec3 {
        let uv = b[0] * self.uvs[0] + b[1] * self.uvs[1] + b[2] * self.uvs[2];
        let color = b[0] * self.colors[0] + b[1] * self.colors[1] + b[2] * self.colors[2];
        self.at(TexturePoint::new(uv, color))
    }
}

impl AreaShape {
    /// Surface area.
    pub fn area(&self) -> f32 {
        match self {
            AreaShape::Triangle { v, .. } => 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length(),
            AreaShape::Rect { shape, .. } => shape.area(),
            AreaShape::Sphere { radius, .. } => 4.0 * PI * radius * radius,
        }
    }
}

impl AreaLight {
    pub(super) fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        self.sample_li_with_size(p, u, &LampSize::of(&self.shape))
    }

    /// [`AreaLight::sample_li`] given `size = LampSize::of(&self.shape)`,
    /// which a caller sampling the light many times computes once. Left to
    /// the compiler's inlining: forced inline, it kept `LightSet::sample_li`
    /// and the point's sampling out of line instead, and callgrind counted
    /// 2% more instructions per render (BENCHMARKS.md, "Light samples
    /// outside their shadow rays").
    pub(super) fn sample_li_with_size(
        &self,
        p: Vec3,
        u: Vec2,
        size: &LampSize,
    ) -> Option<LightSample> {
        let area = size.area;
        let (q, normal, l) = match &self.shape {
            AreaShape::Sphere {
                center,
                radius,
                inward: false,
            } => return self.sample_sphere(p, *center, *radius, u),
            AreaShape::Sphere { .. } => {
                // Inward: a point by area, seen from its front (inside).
                let (point, l) = self.sample_point(u);
                (point.p, point.n, l)
            }
            shape => {
                if let Some(sampling) = solid_angle::choose(shape, p, size) {
                    return self.sample_solid_angle(p, u, sampling);
                }
                self.sample_planar_point(u)?
            }
        };
        let d = q - p;
        let dist2 = d.length_squared();
        let distance = dist2.sqrt();
        if distance == 0.0 {
            return None;
        }
        let wi = d / distance;
        let cos_light = -normal.dot(wi);
        if cos_light <= 0.0 {
            return None;
        }
        Some(LightSample {
            wi,
            l,
            distance,
            pdf: dist2 / (cos_light * area),
        })
    }

    /// [`AreaLight::sample_li`] for a planar lamp sampled by solid angle
    /// as `sampling` says: the point is where the direction meets the lamp.
    /// Out of line, as is [`AreaLight::sample_sphere`]: most light samples
    /// of a scene's planar lamps are by area, and inlined, these two made
    /// every call set up their stack frame.
    #[inline(never)]
    fn sample_solid_angle(
        &self,
        p: Vec3,
        u: Vec2,
        sampling: solid_angle::SolidAngleSampling,
    ) -> Option<LightSample> {
        let (wi, point) = solid_angle::sample(&self.shape, sampling, p, u)?;
        let (normal, corner) = match &self.shape {
            AreaShape::Triangle { v, normal } => (*normal, v[0]),
            AreaShape::Rect { shape, normal } => (*normal, shape.origin),
            AreaShape::Sphere { .. } => return None,
        };
        let cos_light = -normal.dot(wi);
        if cos_light <= 0.0 {
            return None;
        }
        let distance = match point {
            Some(q) => q.length(),
            // The plane through the lamp, met along wi.
            None => (p - corner).dot(normal) / cos_light,
        };
        if !(distance > 0.0 && distance.is_finite()) {
            return None;
        }
        let l = match (&self.shape, &self.textured) {
            (AreaShape::Triangle { v, normal }, Some(t)) => {
                let b = barycentric(v, *normal, p + distance * wi);
                t.at_corners(b)
            }
            _ => self.radiance,
        };
        Some(LightSample {
            wi,
            l,
            distance,
            pdf: 1.0 / sampling.solid_angle(),
        })
    }

    /// A point uniform by area on the surface, with its error bound and
    /// emitting normal, and the radiance it emits (textured: at its UV).
    /// Emission sampling and light sampling's fallback to sampling by area
    /// (triangles, rectangles) share it.
    pub(super) fn sample_point(&self, u: Vec2) -> (SurfacePoint, Vec3) {
        match &self.shape {
            AreaShape::Triangle { v, normal } => {
                let (b, p, l) = self.triangle_point(v, u);
                // Interpolation error, as `triangle.rs` bounds a hit's.
                let p_error =
                    gamma(7) * ((b[0] * v[0]).abs() + (b[1] * v[1]).abs() + (b[2] * v[2]).abs());
                (
                    SurfacePoint {
                        p,
                        p_error,
                        n: *normal,
                    },
                    l,
                )
            }
            AreaShape::Rect { shape, normal } => {
                let p = shape.sample(u);
                let p_error = gamma(5)
                    * (shape.origin.abs() + (u.x * shape.edge0).abs() + (u.y * shape.edge1).abs());
                (
                    SurfacePoint {
                        p,
                        p_error,
                        n: *normal,
                    },
                    self.radiance,
                )
            }
            AreaShape::Sphere {
                center,
                radius,
                inward,
            } => {
                let outward = square_to_uniform_sphere(u);
                let local = outward * *radius;
                let p = *center + local;
                let n = if *inward { -outward } else { outward };
                let p_error = gamma(5) * local.abs() + gamma(1) * p.abs();
                let l = match &self.textured {
                    Some(t) => {
                        let (su, sv) = sphere_uv_in(t.sphere_axes, *center, p);
                        t.at(Vec2::new(su, sv))
                    }
                    None => self.radiance,
                };
                (SurfacePoint { p, p_error, n }, l)
            }
        }
    }

    /// [`AreaLight::sample_point`] on a triangle or parallelogram without
    /// the error bound, which light sampling does not use (the shadow ray
    /// ends short of the lamp): the point, the emitting normal and the
    /// radiance; `None` for a sphere. Same points as `sample_point`.
    fn sample_planar_point(&self, u: Vec2) -> Option<(Vec3, Vec3, Vec3)> {
        match &self.shape {
            AreaShape::Triangle { v, normal } => {
                let (_, p, l) = self.triangle_point(v, u);
                Some((p, *normal, l))
            }
            AreaShape::Rect { shape, normal } => Some((shape.sample(u), *normal, self.radiance)),
            AreaShape::Sphere { .. } => None,
        }
    }

    /// A point of triangle `v` (this light's) uniform by area: its corner
    /// weights, the point, and the radiance it emits (textured: at its UV).
    #[inline(always)]
    fn triangle_point(&self, v: &[Vec3; 3], u: Vec2) -> ([f32; 3], Vec3, Vec3) {
        let b = square_to_uniform_triangle(u);
        let b2 = 1.0 - b.x - b.y;
        let l = match &self.textured {
            // The corner weights of q, as `surface_hit` interpolates UVs.
            Some(t) => t.at_corners([b.x, b.y, b2]),
            None => self.radiance,
        };
        let p = b.x * v[0] + b.y * v[1] + b2 * v[2];
        ([b.x, b.y, b2], p, l)
    }

    /// Spheres that emit outward, seen from outside, are sampled uniformly
    /// in the cone they subtend (no wasted samples on the far side); from
    /// inside they are dark. (Spheres that emit inward are sampled by area:
    /// from inside every point faces the receiver.)
    #[inline(never)]
    fn sample_sphere(&self, p: Vec3, center: Vec3, radius: f32, u: Vec2) -> Option<LightSample> {
        let to_center = center - p;
        let dc2 = to_center.length_squared();
        if dc2 <= radius * radius {
            return None;
        }
        let dc = dc2.sqrt();
        let axis = to_center / dc;
        let sin2_max = radius * radius / dc2;
        let cos_max = (1.0 - sin2_max).max(0.0).sqrt();
        let local = square_to_uniform_cone(u, cos_max);
        let wi = Frame::from_normal(axis).to_world(local);
        // Distance to the near intersection, with the discriminant clamped so
        // that directions on the cone's rim (tangent rays) still land on it.
        let b = wi.dot(to_center);
        let disc = (radius * radius - (dc2 - b * b)).max(0.0);
        let distance = b - disc.sqrt();
        let l = match &self.textured {
            Some(t) => {
                let (su, sv) = sphere_uv_in(t.sphere_axes, center, p + wi * distance);
                t.at(Vec2::new(su, sv))
            }
            None => self.radiance,
        };
        Some(LightSample {
            wi,
            l,
            distance,
            pdf: uniform_cone_pdf(local, cos_max),
        })
    }

    pub(super) fn pdf_li(&self, p: Vec3, wi: Vec3, p_light: Vec3) -> f32 {
        self.pdf_li_with_size(p, wi, p_light, &LampSize::of(&self.shape))
    }

    /// [`AreaLight::pdf_li`] given `size = LampSize::of(&self.shape)`.
    pub(super) fn pdf_li_with_size(
        &self,
        p: Vec3,
        wi: Vec3,
        p_light: Vec3,
        size: &LampSize,
    ) -> f32 {
        let normal = match &self.shape {
            AreaShape::Triangle { normal, .. } | AreaShape::Rect { normal, .. } => *normal,
            AreaShape::Sphere {
                center,
                radius,
                inward: false,
            } => {
                let to_center = *center - p;
                let dc2 = to_center.length_squared();
                if dc2 <= radius * radius {
                    return 0.0;
                }
                let cos_max = (1.0 - radius * radius / dc2).max(0.0).sqrt();
                let cos = wi.dot(to_center / dc2.sqrt());
                return uniform_cone_pdf(Vec3::new(0.0, 0.0, cos), cos_max);
            }
            // Inward: by area, the emitting normal toward the centre.
            AreaShape::Sphere { center, .. } => (*center - p_light).normalize_or_zero(),
        };
        let cos_light = -normal.dot(wi);
        if cos_light <= 0.0 {
            return 0.0;
        }
        if let Some(sampling) = solid_angle::choose(&self.shape, p, size) {
            return 1.0 / sampling.solid_angle();
        }
        (p_light - p).length_squared() / (cos_light * size.area)
    }

    pub(super) fn power(&self) -> f32 {
        PI * self.shape.area() * luminance(self.radiance)
    }
}

/// The corner weights of point `q` in the plane of triangle `v` (unit
/// `normal`), as `surface_hit` interpolates UVs: signed sub-triangle areas
/// over the whole.
fn barycentric(v: &[Vec3; 3], normal: Vec3, q: Vec3) -> [f32; 3] {
    let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).dot(normal);
    let total = area(v[0], v[1], v[2]);
    if total == 0.0 {
        return [1.0 / 3.0; 3];
    }
    let b0 = area(q, v[1], v[2]) / total;
    let b1 = area(v[0], q, v[2]) / total;
    [b0, b1, 1.0 - b0 - b1]
}
