//! Points that no light sample can light: behind every lamp.
//!
//! Planar emitters (triangles, CGL parallelograms) emit on one side only, so
//! a light sample from a point behind a lamp's plane ends on its back and is
//! rejected (`AreaLight::sample_li_with_size` returns `None` when the lamp's
//! cosine is not positive). In a scene whose sampled lights are all planar, a
//! point behind every one of them (the ceiling above a Cornell box's lamp:
//! 15% of the CS184 benchmark's light samples) gets nothing from any light
//! sample, and the vertex can pass over its light samples' random numbers
//! instead of drawing them, choosing a light and sampling a point on it.
//!
//! The test must never skip a sample that would have found light, so it
//! asks for a margin that covers the rounding of the sampled point and of
//! its direction (see [`BEHIND_MARGIN`]); within the margin the samples are
//! taken as before. The image is then the same, bit for bit.

use super::{AreaShape, Light};
use glam::Vec3;

/// More sampled lights than this and the test is not made: it costs a dot
/// product per light and vertex, and with many lamps a point behind all of
/// them is rare.
const MAX_PLANES: usize = 8;

/// The margin behind a lamp's plane, relative to the size of the
/// coordinates involved (`|p|₁` plus the lamp's corner and edges), beyond
/// which every light sample's lamp cosine is certainly not positive. The
/// sampled cosine is `h / d` up to rounding, `h` the point's signed height
/// over the plane and `d` its distance to the sampled point; the rounding of
/// the sampled point, of `q − p`, of the normalisation and of the dot
/// products is a few tens of ε = 2⁻²³ of those coordinates. 10⁻⁴ is
/// about 800 ε: a point that close to a lamp's plane samples as before.
const BEHIND_MARGIN: f32 = 1e-4;

/// The plane of one planar lamp.
#[derive(Clone, Copy, Debug, PartialEq)]
struct LampPlane {
    /// A corner of the lamp.
    corner: Vec3,
    /// Unit normal of the emitting side.
    normal: Vec3,
    /// `|corner|₁` plus the lamp's extent (`|edges|₁`): with `|p|₁` it
    /// bounds the coordinates the margin scales with.
    size: f32,
}

impl LampPlane {
    fn of(light: &Light) -> Option<Self> {
        let Light::Area(area) = light else {
            return None;
        };
        let (corner, normal, extent) = match &area.shape {
            AreaShape::Triangle { v, normal } => {
                (v[0], *normal, (v[1] - v[0]).abs() + (v[2] - v[0]).abs())
            }
            AreaShape::Rect { shape, normal } => {
                (shape.origin, *normal, shape.edge0.abs() + shape.edge1.abs())
            }
            AreaShape::Sphere { .. } => return None,
        };
        Some(Self {
            corner,
            normal,
            size: corner.abs().element_sum() + extent.element_sum(),
        })
    }

    /// Whether `p` lies behind the lamp by more than the margin.
    #[inline(always)]
    fn is_behind(&self, p: Vec3) -> bool {
        let height = (p - self.corner).dot(self.normal);
        height < -BEHIND_MARGIN * (p.abs().element_sum() + self.size)
    }
}

/// The planes of a scene's sampled lights when all of them are planar
/// lamps (and at most [`MAX_PLANES`]); empty otherwise, and then no point
/// is said to be behind them.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct LampBacks {
    planes: Vec<LampPlane>,
}

impl LampBacks {
    /// The planes of `sampled` (indices into `lights`).
    pub(super) fn new(lights: &[Light], sampled: &[u32]) -> Self {
        if sampled.len() > MAX_PLANES {
            return Self::default();
        }
        let planes: Option<Vec<LampPlane>> = sampled
            .iter()
            .map(|&i| LampPlane::of(&lights[i as usize]))
            .collect();
        Self {
            planes: planes.unwrap_or_default(),
        }
    }

    /// Whether `p` is behind every sampled lamp, so that every light
    /// sample from it is rejected (false when not sure).
    #[inline]
    pub(super) fn all_behind(&self, p: Vec3) -> bool {
        !self.planes.is_empty() && self.planes.iter().all(|plane| plane.is_behind(p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{AmbientLight, AreaLight, LightSet};
    use crate::sampling::warp::Parallelogram;
    use glam::Vec2;

    fn lamp(shape: AreaShape) -> Light {
        Light::Area(AreaLight {
            shape,
            radiance: Vec3::ONE,
            textured: None,
        })
    }

    /// A Cornell-box lamp: two triangles facing down at height 1.49 and a
    /// parallelogram beside them.
    fn lamps() -> Vec<Light> {
        let down = Vec3::NEG_Y;
        let c = [
            Vec3::new(0.4, 1.49, -0.3),
            Vec3::new(0.4, 1.49, 0.3),
            Vec3::new(-0.4, 1.49, 0.3),
            Vec3::new(-0.4, 1.49, -0.3),
        ];
        vec![
            lamp(AreaShape::Triangle {
                v: [c[0], c[1], c[2]],
                normal: down,
            }),
            lamp(AreaShape::Triangle {
                v: [c[0], c[2], c[3]],
                normal: down,
            }),
            lamp(AreaShape::Rect {
                shape: Parallelogram {
                    origin: Vec3::new(0.5, 1.3, -0.2),
                    edge0: Vec3::new(0.3, 0.0, 0.0),
                    edge1: Vec3::new(0.0, 0.0, 0.3),
                },
                normal: down,
            }),
        ]
    }

    /// Where the test says "behind every lamp", every light sample of every
    /// lamp is rejected; and it says so for points clearly behind them.
    #[test]
    fn a_point_behind_every_lamp_gets_no_light_sample() {
        let lights = lamps();
        let set = LightSet::new(lights.clone(), &[], 2.0);
        let backs = LampBacks::new(&lights, &[0, 1, 2]);
        let mut points = Vec::new();
        for k in 0..400 {
            // Points around both lamp planes, some within the margin.
            let x = (k % 20) as f32 * 0.11 - 1.0;
            let y = 1.25 + (k / 20) as f32 * 0.025 + if k % 3 == 0 { 1e-6 } else { 0.0 };
            points.push(Vec3::new(x, y, 0.1 * (k % 7) as f32 - 0.3));
        }
        // And just past the margin over the triangles' plane.
        for k in 0..40 {
            let q = Vec3::new((k % 8) as f32 * 0.3 - 1.2, 1.49, 0.2 * (k / 8) as f32 - 0.4);
            let size = q.abs().element_sum() + lights_size(&backs);
            let p = q + Vec3::Y * (1.01 * BEHIND_MARGIN * size);
            points.push(p);
        }
        let mut behind = 0;
        for p in points {
            if !backs.all_behind(p) {
                continue;
            }
            behind += 1;
            for i in 0..3 {
                for s in 0..64 {
                    let u = Vec2::new((s % 8) as f32 / 8.0 + 0.06, (s / 8) as f32 / 8.0 + 0.01);
                    assert_eq!(set.sample_li(i, p, u), None, "light {i} from {p:?}");
                }
            }
        }
        // y > 1.49 (the rect at 1.3 is behind them too): 10 rows of 20,
        // and those just past the margin.
        assert_eq!(behind, 240);
        assert!(backs.all_behind(Vec3::new(0.0, 1.5, 0.0)));
        assert!(
            !backs.all_behind(Vec3::new(0.0, 1.4, 0.0)),
            "in front of the triangles"
        );
        assert!(
            !backs.all_behind(Vec3::new(0.0, 1.49 + 1e-6, 0.0)),
            "within the margin"
        );
    }

    /// The largest `size` of the planes (the margin's scale beside `|p|₁`).
    fn lights_size(backs: &LampBacks) -> f32 {
        backs
            .planes
            .iter()
            .map(|plane| plane.size)
            .fold(0.0, f32::max)
    }

    /// A sphere, a sky or too many lamps: no point is said to be behind.
    #[test]
    fn only_planar_lamps_have_backs() {
        let mut lights = lamps();
        lights.push(Light::Ambient(AmbientLight {
            radiance: Vec3::ONE,
        }));
        let above = Vec3::new(0.0, 2.0, 0.0);
        assert!(LampBacks::new(&lights, &[0, 1, 2]).all_behind(above));
        assert!(!LampBacks::new(&lights, &[0, 1, 2, 3]).all_behind(above));
        let sphere = lamp(AreaShape::Sphere {
            center: Vec3::ZERO,
            radius: 0.1,
            inward: false,
        });
        assert!(!LampBacks::new(&[sphere], &[0]).all_behind(above));
        let many: Vec<Light> = (0..=MAX_PLANES).map(|k| lamps()[k % 2].clone()).collect();
        let all: Vec<u32> = (0..many.len() as u32).collect();
        assert!(!LampBacks::new(&many, &all).all_behind(above));
        assert!(LampBacks::new(&many, &all[..MAX_PLANES]).all_behind(above));
        assert!(!LampBacks::new(&lights, &[]).all_behind(above));
    }
}
