//! `<instance_camera>`: the perspective optics and the camera's world transform.

use super::builder::Builder;
use super::numbers::float;
use super::xml::{child, require, Ctx, XNode};
use crate::desc::{CameraDesc, Projection};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4};

/// Aspect assumed when a file gives one field of view and no aspect ratio:
/// the CS184 program's 800x600 window.
const DEFAULT_ASPECT: f32 = 4.0 / 3.0;

/// Reads one camera instance under the world-from-node transform `m`.
pub(crate) fn instance(ctx: &Ctx, b: &mut Builder, inst: XNode, m: Mat4) -> Result<(), LoadError> {
    let Some(camera) = ctx.resolve(inst, "url", &["camera"])? else {
        return Ok(());
    };
    let tc = require(ctx, require(ctx, camera, "optics")?, "technique_common")?;
    let Some(persp) = child(tc, "perspective") else {
        return ctx.warn(tc, "non-perspective camera not supported; ignored");
    };
    let get = |name: &str| {
        child(persp, name)
            .map(|n| float(ctx, n).map(|v| (v, n)))
            .transpose()
    };
    let (xfov, yfov, aspect) = (get("xfov")?, get("yfov")?, get("aspect_ratio")?);
    for (v, n) in [xfov, yfov].into_iter().flatten() {
        if !(v > 0.0 && v < 180.0) {
            return Err(ctx.err(
                n,
                ErrorKind::DegenerateCamera,
                format!("field of view {v} degrees is not in (0, 180)"),
            ));
        }
    }
    if let Some((a, n)) = aspect.filter(|(a, _)| *a <= 0.0) {
        return Err(ctx.err(
            n,
            ErrorKind::DegenerateCamera,
            format!("aspect ratio {a} is not positive"),
        ));
    }
    let aspect_or_default = |at: XNode| -> Result<f32, LoadError> {
        match aspect {
            Some((a, _)) => Ok(a),
            None => {
                ctx.warn(at, "one field of view and no aspect_ratio; 4:3 assumed")?;
                Ok(DEFAULT_ASPECT)
            }
        }
    };
    let (x, y) = match (xfov, yfov) {
        (Some((x, _)), Some((y, _))) => (x, y),
        (Some((x, n)), None) => (x, yfov_from_xfov(x, aspect_or_default(n)?)),
        (None, Some((y, n))) => (xfov_from_yfov(y, aspect_or_default(n)?), y),
        (None, None) => {
            return Err(ctx.err(
                persp,
                ErrorKind::MissingElement,
                "perspective needs <xfov> or <yfov>",
            ))
        }
    };
    let det = Mat3::from_mat4(m).determinant();
    if det.is_nan() || det.abs() <= 1e-12 || !m.is_finite() {
        return Err(ctx.err(
            inst,
            ErrorKind::DegenerateCamera,
            "camera node transform is singular",
        ));
    }
    b.scene.cameras.push(CameraDesc {
        name: camera
            .attribute("name")
            .or(camera.attribute("id"))
            .unwrap_or("camera")
            .to_string(),
        world_from_camera: m,
        projection: Projection::Perspective {
            xfov_deg: x,
            yfov_deg: y,
        },
        znear: get("znear")?.map(|(v, _)| v),
        zfar: get("zfar")?.map(|(v, _)| v),
        // COLLADA requires znear/zfar for its rasterising viewers' depth
        // buffer (exporters write 0.1/100 or 0.01/10000); the CS184 orbit
        // moves the eye anyway, so planes measured from the file's eye
        // would cut arbitrary slices. Not a request to clip.
        clip: None,
        loc: ctx.loc(inst),
    });
    Ok(())
}

/// Vertical field of view from the horizontal one: `2 atan(tan(x/2) / aspect)`.
pub(crate) fn yfov_from_xfov(xfov_deg: f32, aspect: f32) -> f32 {
    2.0 * ((xfov_deg.to_radians() / 2.0).tan() / aspect)
        .atan()
        .to_degrees()
}

/// Horizontal field of view from the vertical one: `2 atan(tan(y/2) * aspect)`.
pub(crate) fn xfov_from_yfov(yfov_deg: f32, aspect: f32) -> f32 {
    2.0 * ((yfov_deg.to_radians() / 2.0).tan() * aspect)
        .atan()
        .to_degrees()
}
