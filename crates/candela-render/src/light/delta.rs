//! Delta lights: point, spot and directional. They cannot be hit by rays,
//! only sampled; their "pdf" is 1 by convention.

use super::{luminance, LightSample};
use glam::Vec3;
use std::f32::consts::PI;

/// An isotropic point light: radiant intensity `I` (W/sr), irradiance
/// `I / r²` at distance `r` (the CS184 program dropped the falloff; physics
/// keeps it).
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// World position.
    pub position: Vec3,
    /// Radiant intensity per channel.
    pub intensity: Vec3,
}

impl PointLight {
    pub(super) fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        toward_point(self.position, self.intensity, p)
    }

    pub(super) fn power(&self) -> f32 {
        4.0 * PI * luminance(self.intensity)
    }
}

/// Light from an isotropic point of intensity `intensity` arriving at `p`:
/// the inverse-square law every point-like light shares.
fn toward_point(position: Vec3, intensity: Vec3, p: Vec3) -> Option<LightSample> {
    let d = position - p;
    let dist2 = d.length_squared();
    if dist2 == 0.0 {
        return None;
    }
    let distance = dist2.sqrt();
    Some(LightSample {
        wi: d / distance,
        l: intensity / dist2,
        distance,
        pdf: 1.0,
    })
}

/// A point light restricted to a cone around `direction`, with intensity
/// `I · cos(θ)^exponent · edge(θ)` inside the cone (COLLADA's falloff
/// exponent; the fade toward the edge of Mitsuba's and glTF's spots).
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    /// World position.
    pub position: Vec3,
    /// Unit cone axis.
    pub direction: Vec3,
    /// Intensity on the axis.
    pub intensity: Vec3,
    /// Cosine of the half cone angle.
    pub cos_cutoff: f32,
    /// Falloff exponent.
    pub exponent: f32,
    /// The fade toward the cone's edge.
    pub edge: SpotFade,
}

/// How a spot light fades toward the edge of its cone, `edge(θ)` in
/// [0, 1] (see `candela_scene::SpotEdge`, which it is made from).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpotFade {
    /// 1 up to the cutoff.
    Hard,
    /// Mitsuba 3: 1 inside the beam's half angle, then `(θc − θ) / (θc −
    /// θb)`, linear in the angle, down to 0 at the cutoff's half angle θc.
    LinearInAngle {
        /// Cosine of the beam's half angle θb.
        cos_beam: f32,
        /// The cutoff's half angle θc, radians.
        cutoff: f32,
        /// `1 / (θc − θb)`.
        inv_width: f32,
    },
    /// glTF: `t²` with `t = (cos θ − cos θo) / (cos θi − cos θo)` clamped
    /// to [0, 1], θi and θo the inner and outer half angles.
    SmoothInCosine {
        /// cos θo.
        cos_outer: f32,
        /// `1 / (cos θi − cos θo)`.
        scale: f32,
    },
}

impl SpotFade {
    /// Mitsuba's linear fade between half angles `beam` and `cutoff`
    /// (radians, `beam < cutoff`).
    pub fn linear_in_angle(beam: f32, cutoff: f32) -> Self {
        SpotFade::LinearInAngle {
            cos_beam: beam.cos(),
            cutoff,
            inv_width: 1.0 / (cutoff - beam),
        }
    }

    /// glTF's smooth fade between half angles `inner` and `outer`
    /// (radians, `inner < outer`); the difference of the cosines is taken
    /// at least 0.001, as the extension's sample code does.
    pub fn smooth_in_cosine(inner: f32, outer: f32) -> Self {
        SpotFade::SmoothInCosine {
            cos_outer: outer.cos(),
            scale: 1.0 / (inner.cos() - outer.cos()).max(1e-3),
        }
    }

    /// `edge(θ)` for `cos = cos θ` (inside the cone; 0 past the cutoff is
    /// the caller's test).
    pub fn at(self, cos: f32) -> f32 {
        match self {
            SpotFade::Hard => 1.0,
            SpotFade::LinearInAngle {
                cos_beam,
                cutoff,
                inv_width,
            } => {
                if cos >= cos_beam {
                    1.0
                } else {
                    ((cutoff - cos.clamp(-1.0, 1.0).acos()) * inv_width).clamp(0.0, 1.0)
                }
            }
            SpotFade::SmoothInCosine { cos_outer, scale } => {
                let t = ((cos - cos_outer) * scale).clamp(0.0, 1.0);
                t * t
            }
        }
    }
}

impl SpotLight {
    pub(super) fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        let mut sample = toward_point(self.position, self.intensity, p)?;
        let cos = (-sample.wi).dot(self.direction);
        if cos < self.cos_cutoff {
            return None;
        }
        sample.l *= self.intensity_scale(cos);
        Some(sample)
    }

    /// `cos^n`, or 1 without a falloff exponent: the part of the intensity
    /// emission sampling draws in proportion to.
    pub(super) fn falloff(&self, cos: f32) -> f32 {
        if self.exponent > 0.0 {
            cos.max(0.0).powf(self.exponent)
        } else {
            1.0
        }
    }

    /// The intensity along a direction at `cos` from the axis (inside the
    /// cone), relative to the axis: the falloff times the edge's fade.
    /// Light samples and emitted rays both carry it.
    pub(super) fn intensity_scale(&self, cos: f32) -> f32 {
        self.falloff(cos) * self.edge.at(cos)
    }

    pub(super) fn power(&self) -> f32 {
        // Solid angle of the cone; the falloff is ignored (an upper bound is
        // enough to choose among lights).
        2.0 * PI * (1.0 - self.cos_cutoff) * luminance(self.intensity)
    }
}

/// Light arriving from one direction with irradiance `E` on a surface that
/// faces it (sunlight).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub direction: Vec3,
    /// Irradiance on a surface facing the light.
    pub irradiance: Vec3,
}

impl DirectionalLight {
    pub(super) fn sample_li(&self) -> LightSample {
        LightSample {
            wi: -self.direction,
            l: self.irradiance,
            distance: f32::INFINITY,
            pdf: 1.0,
        }
    }

    pub(super) fn power(&self, scene_radius: f32) -> f32 {
        PI * scene_radius * scene_radius * luminance(self.irradiance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_light_falls_off_with_inverse_square() {
        let light = PointLight {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity: Vec3::splat(8.0),
        };
        let s = light.sample_li(Vec3::ZERO).unwrap();
        assert_eq!(s.wi, Vec3::Y);
        assert_eq!(s.distance, 2.0);
        assert_eq!(s.l, Vec3::splat(2.0));
    }

    /// A unit spot 1 above the origin pointing down, with a cutoff half
    /// angle of `cutoff_deg` and the fade `edge`.
    fn spot_down(cutoff_deg: f32, edge: SpotFade) -> SpotLight {
        SpotLight {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: -Vec3::Y,
            intensity: Vec3::ONE,
            cos_cutoff: cutoff_deg.to_radians().cos(),
            exponent: 0.0,
            edge,
        }
    }

    #[test]
    fn spot_light_is_dark_outside_its_cone() {
        let light = spot_down(30.0, SpotFade::Hard);
        assert!(light.sample_li(Vec3::ZERO).is_some());
        assert!(light.sample_li(Vec3::new(1.0, 0.0, 0.0)).is_none());
    }

    /// The intensity at `deg` degrees off the axis of a spot 1 above the
    /// origin pointing down, seen on the plane 1 below it (1/d² undone).
    fn intensity_at(light: &SpotLight, deg: f32) -> f32 {
        let p = Vec3::new(deg.to_radians().tan(), 0.0, 0.0);
        light
            .sample_li(p)
            .map_or(0.0, |s| s.l.x * s.distance * s.distance)
    }

    #[test]
    fn mitsubas_spot_fades_linearly_in_the_angle() {
        // Half angles: beam 15 degrees, cutoff 30.
        let light = spot_down(
            30.0,
            SpotFade::linear_in_angle(15f32.to_radians(), 30f32.to_radians()),
        );
        for (deg, want) in [
            (0.0, 1.0),
            (10.0, 1.0),
            (18.0, 0.8),
            (22.5, 0.5),
            (27.0, 0.2),
        ] {
            let got = intensity_at(&light, deg);
            assert!((got - want).abs() < 2e-4, "{deg} degrees: {got} vs {want}");
        }
        assert_eq!(intensity_at(&light, 31.0), 0.0);
    }

    #[test]
    fn gltfs_spot_fades_smoothly_in_the_cosine() {
        // Half angles: inner 20 degrees, outer 40.
        let (inner, outer) = (20f32.to_radians(), 40f32.to_radians());
        let light = spot_down(40.0, SpotFade::smooth_in_cosine(inner, outer));
        assert!((intensity_at(&light, 10.0) - 1.0).abs() < 1e-4);
        // Halfway in the cosine: t = 1/2, intensity 1/4.
        let mid = ((inner.cos() + outer.cos()) / 2.0).acos().to_degrees();
        assert!((intensity_at(&light, mid) - 0.25).abs() < 1e-3);
        assert_eq!(intensity_at(&light, 41.0), 0.0);
    }
}
