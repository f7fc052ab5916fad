//! `<instance_light>`: the light's technique (CGL, then `technique_common`,
//! then `blender`) and its placement by the node transform.

use super::builder::Builder;
use super::lenient::{cgl_technique, color, float_or, Color};
use super::numbers::float;
use super::xml::{child, elements, require, technique, text, Ctx, XNode};
use crate::desc::{LightDesc, LightKind, SpotEdge};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};

/// Reads one light instance under the world-from-node transform `m`.
pub(crate) fn instance(ctx: &Ctx, b: &mut Builder, inst: XNode, m: Mat4) -> Result<(), LoadError> {
    let Some(light) = ctx.resolve(inst, "url", &["light"])? else {
        return Ok(());
    };
    let name = light
        .attribute("name")
        .or(light.attribute("id"))
        .unwrap_or("light")
        .to_string();
    let cgl = cgl_technique(ctx, light)?;
    let kind = if let Some(t) = cgl.or_else(|| child(light, "technique_common")) {
        let Some(model) = elements(t).next() else {
            return ctx.warn(t, "light technique without a light type; ignored");
        };
        standard(ctx, model, m)?
    } else if let Some(t) = technique(light, "blender") {
        blender(ctx, t, m)?
    } else {
        return ctx.warn(
            light,
            "light without a CGL, common or blender technique; ignored",
        );
    };
    if let Some(kind) = kind {
        b.scene.lights.push(LightDesc {
            name,
            kind,
            loc: ctx.loc(inst),
        });
    }
    Ok(())
}

/// A CGL or `technique_common` light whose type is the element `model`.
fn standard(ctx: &Ctx, model: XNode, m: Mat4) -> Result<Option<LightKind>, LoadError> {
    let color = || color(ctx, require(ctx, model, "color")?, Color::Emitted);
    let position = m.transform_point3(Vec3::ZERO);
    Ok(Some(match model.tag_name().name() {
        "point" => LightKind::Point {
            position,
            intensity: color()?,
        },
        "directional" => LightKind::Directional {
            direction: forward(ctx, model, m)?,
            radiance: color()?,
        },
        "spot" => LightKind::Spot {
            position,
            direction: forward(ctx, model, m)?,
            intensity: color()?,
            cone_angle_deg: float_or(ctx, child(model, "falloff_angle"), 180.0)?,
            falloff_exponent: float_or(ctx, child(model, "falloff_exponent"), 0.0)?,
            edge: SpotEdge::Hard,
        },
        "ambient" => LightKind::Ambient { radiance: color()? },
        "area" => area(ctx, model, m, color()?)?,
        other => {
            ctx.warn(
                model,
                format!("light type <{other}> not supported; ignored"),
            )?;
            return Ok(None);
        }
    }))
}

/// Blender's own light description: `type` (0 point, 1 sun, 2 spot, 3 hemi)
/// and colour `energy` x (`red`, `green`, `blue`).
fn blender(ctx: &Ctx, t: XNode, m: Mat4) -> Result<Option<LightKind>, LoadError> {
    let num = |name: &str| float(ctx, require(ctx, t, name)?);
    let color = num("energy")? * Vec3::new(num("red")?, num("green")?, num("blue")?);
    let ty = require(ctx, t, "type")?;
    let position = m.transform_point3(Vec3::ZERO);
    Ok(Some(match text(ty).trim() {
        "0" => LightKind::Point {
            position,
            intensity: color,
        },
        "1" => LightKind::Directional {
            direction: forward(ctx, t, m)?,
            radiance: color,
        },
        "2" => LightKind::Spot {
            position,
            direction: forward(ctx, t, m)?,
            intensity: color,
            cone_angle_deg: child(t, "spotsize").map_or(Ok(180.0), |n| float(ctx, n))?,
            falloff_exponent: 0.0,
            edge: SpotEdge::Hard,
        },
        "3" => LightKind::Ambient { radiance: color },
        other => {
            ctx.warn(
                ty,
                format!("blender light type {other} not supported; ignored"),
            )?;
            return Ok(None);
        }
    }))
}

/// The node's local -Z in world space, normalised.
fn forward(ctx: &Ctx, at: XNode, m: Mat4) -> Result<Vec3, LoadError> {
    m.transform_vector3(Vec3::NEG_Z)
        .try_normalize()
        .ok_or_else(|| {
            ctx.err(
                at,
                ErrorKind::BadValue,
                "light direction is zero under the node transform",
            )
        })
}

/// CGL area light: a unit square in the node's local XY plane, emitting
/// towards local -Z. The normal uses the inverse transpose so it stays
/// perpendicular to the rectangle under non-uniform scale.
fn area(ctx: &Ctx, model: XNode, m: Mat4, radiance: Vec3) -> Result<LightKind, LoadError> {
    let linear = Mat3::from_mat4(m);
    let normal = (linear.inverse().transpose() * Vec3::NEG_Z).try_normalize();
    let normal = normal
        .filter(|_| linear.determinant().abs() > 1e-20)
        .ok_or_else(|| {
            ctx.err(
                model,
                ErrorKind::BadValue,
                "area light under a singular transform",
            )
        })?;
    Ok(LightKind::Area {
        center: m.transform_point3(Vec3::ZERO),
        edge_x: linear * Vec3::X,
        edge_y: linear * Vec3::Y,
        normal,
        radiance,
    })
}
