//! `KHR_lights_punctual`: point, spot and directional lights in photometric
//! units, converted to Candela's radiometric ones.
//!
//! The extension gives point and spot intensity in candela (lm/sr) and
//! directional intensity in lux (lm/m²). Candela's lights are radiometric
//! (W/sr, W/m²), so both are divided by [`LUMENS_PER_WATT`], the luminous
//! efficacy at 555 nm that defines the candela. This is also how Blender's
//! exporter writes its lights (W → cd × 683 / 4π), so a Blender scene
//! round-trips to its own watts; emissive materials, which glTF gives no
//! unit, are taken as radiance as they are.

use super::Ctx;
use crate::desc::{LightDesc, LightKind, SpotEdge};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat4, Vec3};
use gltf::khr_lights_punctual::Kind;

/// Lumens per watt of 555 nm light: the photometric-to-radiometric factor.
pub(super) const LUMENS_PER_WATT: f32 = 683.0;

/// The light of node `node` under its world transform `m`.
pub(super) fn read_light(
    ctx: &Ctx,
    node: &gltf::Node,
    light: &gltf::khr_lights_punctual::Light,
    m: Mat4,
) -> Result<LightDesc, LoadError> {
    let at = format!("/extensions/KHR_lights_punctual/lights/{}", light.index());
    let power = Vec3::from(light.color()) * light.intensity() / LUMENS_PER_WATT;
    if !power.is_finite() || power.min_element() < 0.0 {
        return Err(ctx.err(
            at,
            ErrorKind::BadValue,
            format!("colour x intensity {power} is not finite and non-negative"),
        ));
    }
    if light.range().is_some() {
        ctx.warn(
            "light range",
            "the range cutoff is ignored; lights fall off as 1/r²",
        )?;
    }
    let position = m.transform_point3(Vec3::ZERO);
    let forward = || {
        m.transform_vector3(Vec3::NEG_Z)
            .try_normalize()
            .ok_or_else(|| {
                ctx.err(
                    format!("/nodes/{}", node.index()),
                    ErrorKind::BadValue,
                    "light direction is zero under the node transform".into(),
                )
            })
    };
    let kind = match light.kind() {
        Kind::Point => LightKind::Point {
            position,
            intensity: power,
        },
        Kind::Directional => LightKind::Directional {
            direction: forward()?,
            radiance: power,
        },
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let outer = outer_cone_angle.to_degrees();
            if !(outer > 0.0 && outer <= 90.0 + 1e-3) {
                return Err(ctx.err(
                    format!("{at}/spot/outerConeAngle"),
                    ErrorKind::BadValue,
                    format!("outer cone angle {outer} degrees is not in (0, 90]"),
                ));
            }
            // The extension's recommended smooth falloff between the cones;
            // an inner cone as wide as the outer one is a hard edge.
            let edge = if inner_cone_angle < outer_cone_angle {
                SpotEdge::SmoothInCosine {
                    inner_angle_deg: 2.0 * inner_cone_angle.max(0.0).to_degrees(),
                }
            } else {
                SpotEdge::Hard
            };
            LightKind::Spot {
                position,
                direction: forward()?,
                intensity: power,
                cone_angle_deg: 2.0 * outer,
                falloff_exponent: 0.0,
                edge,
            }
        }
    };
    Ok(LightDesc {
        name: light
            .name()
            .or(node.name())
            .map_or_else(|| format!("light {}", light.index()), str::to_string),
        kind,
        loc: Default::default(),
    })
}
