//! `<transform name="to_world">`: a sequence of `translate`, `rotate`,
//! `scale`, `matrix` and `lookat` elements. Mitsuba applies each one after
//! the ones before it, so the result is M = T_last · … · T_first.

use super::doc::{elements, Doc, XNode};
use super::values::{exactly, number, numbers, xyz};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4, Vec3};

/// The matrix of a `<transform>` element.
pub(super) fn transform(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    let mut m = Mat4::IDENTITY;
    for step in elements(node) {
        let t = match step.tag_name().name() {
            "translate" => Mat4::from_translation(xyz(doc, step, 0.0)?),
            "scale" => Mat4::from_scale(xyz(doc, step, 1.0)?),
            "rotate" => rotate(doc, step)?,
            "matrix" => matrix(doc, step)?,
            "lookat" => lookat(doc, step)?,
            other => {
                return Err(doc.err(
                    step,
                    ErrorKind::BadValue,
                    format!("unknown transform step <{other}> (expected translate, rotate, scale, matrix or lookat)"),
                ))
            }
        };
        m = t * m;
    }
    Ok(m)
}

/// The `to_world` transform of a plugin element (identity if it has none).
pub(super) fn to_world(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    match doc.prop(node, "to_world")? {
        Some(t) if t.tag_name().name() == "transform" => transform(doc, t),
        Some(t) => Err(doc.err(t, ErrorKind::BadValue, "to_world must be a <transform>")),
        None => Ok(Mat4::IDENTITY),
    }
}

fn rotate(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    let axis = xyz(doc, node, 0.0)?;
    let angle = number(doc, node, &doc.required(node, "angle")?)?;
    let Some(axis) = axis.try_normalize() else {
        return Err(doc.err(node, ErrorKind::BadValue, "rotation axis is zero"));
    };
    Ok(Mat4::from_axis_angle(axis, angle.to_radians()))
}

/// 16 numbers (or 9, a 3×3 linear part), row by row.
fn matrix(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    let text = doc.required(node, "value")?;
    let v = numbers(doc, node, &text)?;
    match v.len() {
        16 => Ok(Mat4::from_cols_slice(&v).transpose()),
        9 => Ok(Mat4::from_mat3(Mat3::from_cols_slice(&v).transpose())),
        _ => exactly(doc, node, &text, 16).map(|_| Mat4::IDENTITY),
    }
}

/// Mitsuba's look-at: local +Z toward the target, +Y toward `up`, +X to
/// the left (x = up × dir), the origin at the eye.
fn lookat(doc: &Doc, node: XNode) -> Result<Mat4, LoadError> {
    let vec = |key: &str| -> Result<Option<Vec3>, LoadError> {
        match doc.attr(node, key)? {
            Some(t) => Ok(Some(Vec3::from_slice(&exactly(doc, node, &t, 3)?))),
            None => Ok(None),
        }
    };
    let need = |key: &str, v: Option<Vec3>| {
        v.ok_or_else(|| {
            doc.err(
                node,
                ErrorKind::MissingElement,
                format!("missing attribute \"{key}\""),
            )
        })
    };
    let origin = need("origin", vec("origin")?)?;
    let target = need("target", vec("target")?)?;
    let dir = (target - origin)
        .try_normalize()
        .ok_or_else(|| doc.err(node, ErrorKind::BadValue, "target and origin coincide"))?;
    let up = match vec("up")? {
        Some(u) => u,
        None => dir.any_orthonormal_vector(),
    };
    let left = up.cross(dir).try_normalize().ok_or_else(|| {
        doc.err(
            node,
            ErrorKind::BadValue,
            "up is zero or parallel to the view direction",
        )
    })?;
    let new_up = dir.cross(left);
    Ok(Mat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        origin.extend(1.0),
    ))
}
