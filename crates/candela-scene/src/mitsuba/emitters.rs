//! Emitters: `area` (inside a shape: its radiance, a constant or a
//! texture, becomes the material's emission), `point`, `spot`,
//! `directional`, `envmap` and `constant` (the scene's [`EnvironmentDesc`]).
//!
//! Mitsuba's spot light fades smoothly from `beam_width` to
//! `cutoff_angle`; Candela's is a hard cone of half-angle `cutoff_angle`
//! (the fade is reported when the two differ).

use super::doc::{Doc, XNode};
use super::transform::to_world;
use super::values::{float, point};
use super::Builder;
use crate::desc::{EnvironmentDesc, EnvironmentLookup, LightDesc, LightKind, SpotEdge, TextureRef};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};

/// The radiance of a shape's `<emitter type="area">`: a constant, or a
/// texture for the material's emission slot (which the renderer reads
/// wherever the lamp is hit or sampled).
pub(super) fn area_radiance(
    b: &mut Builder,
    doc: &Doc,
    node: XNode,
) -> Result<(Vec3, Option<TextureRef>), LoadError> {
    let kind = doc.plugin_type(node)?;
    if kind != "area" {
        return Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("a shape's emitter must be \"area\", not \"{kind}\""),
        ));
    }
    b.color(doc, node, "radiance", Vec3::ONE)
}

/// A top-level `<emitter>`.
pub(super) fn emitter(b: &mut Builder, doc: &Doc, node: XNode) -> Result<(), LoadError> {
    let kind = doc.plugin_type(node)?;
    let name = doc.attr(node, "id")?.unwrap_or_else(|| kind.clone());
    let m = to_world(doc, node)?;
    let light = match kind.as_str() {
        "point" => LightKind::Point {
            position: point(doc, node, "position")?
                .unwrap_or_else(|| m.transform_point3(Vec3::ZERO)),
            intensity: b.constant(doc, node, "intensity", Vec3::ONE)?,
        },
        "spot" => {
            let cutoff = float(doc, node, "cutoff_angle", 20.0)?;
            let beam = float(doc, node, "beam_width", 0.75 * cutoff)?;
            if !(cutoff > 0.0 && cutoff <= 90.0) {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("cutoff_angle {cutoff} is not in (0, 90]"),
                ));
            }
            if !(beam > 0.0 && beam.is_finite()) {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("beam_width {beam} is not a positive angle"),
                ));
            }
            if let Some(t) = doc.prop(node, "texture")? {
                b.warn(
                    doc,
                    t,
                    "a spot light's projected texture is not supported (its intensity is used)",
                )?;
            }
            // Mitsuba fades linearly in the angle from beam_width (full)
            // to cutoff_angle (none); a beam at least as wide is a hard cone.
            let edge = if beam < cutoff {
                SpotEdge::LinearInAngle {
                    beam_angle_deg: 2.0 * beam,
                }
            } else {
                SpotEdge::Hard
            };
            LightKind::Spot {
                position: m.transform_point3(Vec3::ZERO),
                direction: forward(doc, node, m)?,
                intensity: b.constant(doc, node, "intensity", Vec3::ONE)?,
                cone_angle_deg: 2.0 * cutoff,
                falloff_exponent: 0.0,
                edge,
            }
        }
        "directional" => {
            let direction = match point(doc, node, "direction")? {
                Some(d) => d
                    .try_normalize()
                    .ok_or_else(|| doc.err(node, ErrorKind::BadValue, "direction is zero"))?,
                None => forward(doc, node, m)?,
            };
            LightKind::Directional {
                direction,
                radiance: b.constant(doc, node, "irradiance", Vec3::ONE)?,
            }
        }
        "envmap" => {
            let path = b.existing_file(doc, node)?;
            let scale = float(doc, node, "scale", 1.0)?;
            let to_world = match rotation_of(m) {
                Some(r) => r,
                None => {
                    b.warn(
                        doc,
                        node,
                        "an environment map's to_world with a shear, a mirror or an uneven \
                         scale: only its rotation is used",
                    )?;
                    nearest_rotation(m)
                }
            };
            return set_environment(
                b,
                doc,
                node,
                EnvironmentDesc::Map {
                    path,
                    scale,
                    // Mitsuba's envmap reads its bitmap bilinearly with
                    // rows from pole to pole (its `eval_spectrum`).
                    lookup: EnvironmentLookup::BilinearPoleRows,
                    to_world,
                },
            );
        }
        "constant" => {
            let radiance = b.constant(doc, node, "radiance", Vec3::ONE)?;
            return set_environment(b, doc, node, EnvironmentDesc::Constant { radiance });
        }
        "area" => {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                "an area emitter belongs inside a <shape>",
            ))
        }
        "projector" | "directionalarea" | "sunsky" => {
            return b.warn(
                doc,
                node,
                format!("emitter type \"{kind}\" is not supported (skipped)"),
            )
        }
        other => {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("unknown emitter type \"{other}\""),
            ))
        }
    };
    b.scene.lights.push(LightDesc {
        name,
        kind: light,
        loc: doc.loc(node),
    });
    Ok(())
}

/// Mitsuba lights shine along their local +Z.
fn forward(doc: &Doc, node: XNode, m: Mat4) -> Result<Vec3, LoadError> {
    m.transform_vector3(Vec3::Z)
        .try_normalize()
        .ok_or_else(|| doc.err(node, ErrorKind::BadValue, "to_world maps +Z to zero"))
}

fn set_environment(
    b: &mut Builder,
    doc: &Doc,
    node: XNode,
    env: EnvironmentDesc,
) -> Result<(), LoadError> {
    if b.scene.environment.is_some() {
        b.warn(doc, node, "a second environment emitter replaces the first")?;
    }
    b.scene.environment = Some(env);
    Ok(())
}

/// The rotation of an environment map's `to_world`: its linear part when
/// that is a rotation times a uniform scale (directions are normalised, so
/// the scale and any translation change nothing), else `None`.
fn rotation_of(m: Mat4) -> Option<Mat3> {
    let a = Mat3::from_mat4(m);
    let scale = a.x_axis.length();
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let r = a * (1.0 / scale);
    let off = (r.transpose() * r - Mat3::IDENTITY).to_cols_array();
    let orthonormal = off.iter().all(|e| e.abs() < 1e-4);
    (orthonormal && r.determinant() > 0.0).then_some(r)
}

/// A rotation near `m`'s linear part (its axes made orthonormal, x first,
/// then y), for a `to_world` that is not a rotation; the identity if even
/// that fails.
fn nearest_rotation(m: Mat4) -> Mat3 {
    let a = Mat3::from_mat4(m);
    let Some(x) = a.x_axis.try_normalize() else {
        return Mat3::IDENTITY;
    };
    let Some(z) = x.cross(a.y_axis).try_normalize() else {
        return Mat3::IDENTITY;
    };
    Mat3::from_cols(x, z.cross(x), z)
}
