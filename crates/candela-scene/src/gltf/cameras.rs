//! Cameras: perspective (`yfov`, optional `aspectRatio`) and orthographic
//! (`xmag`, `ymag`), placed by their node.

use super::Ctx;
use crate::desc::{CameraDesc, Projection};
use crate::error::{ErrorKind, LoadError};
use glam::{Mat3, Mat4};

/// Aspect used for the horizontal field of view when the file gives none;
/// the renderer keeps `yfov` and takes the width from the image anyway.
const DEFAULT_ASPECT: f32 = 4.0 / 3.0;

/// The camera of node `node` under its world transform `m`.
pub(super) fn read_camera(
    ctx: &Ctx,
    node: &gltf::Node,
    cam: &gltf::Camera,
    m: Mat4,
) -> Result<CameraDesc, LoadError> {
    let at = format!("/cameras/{}", cam.index());
    let det = Mat3::from_mat4(m).determinant();
    // NaN fails the comparison: singular.
    if det.abs() <= 1e-12 || det.is_nan() {
        return Err(ctx.err(
            format!("/nodes/{}", node.index()),
            ErrorKind::DegenerateCamera,
            "camera node transform is singular".into(),
        ));
    }
    let degenerate = |field: &str, msg: String| {
        ctx.err(format!("{at}/{field}"), ErrorKind::DegenerateCamera, msg)
    };
    let (projection, znear, zfar) = match cam.projection() {
        gltf::camera::Projection::Perspective(p) => {
            let yfov = p.yfov().to_degrees();
            if !(yfov > 0.0 && yfov < 180.0) {
                return Err(degenerate(
                    "perspective/yfov",
                    format!("field of view {yfov} degrees is not in (0, 180)"),
                ));
            }
            let aspect = p.aspect_ratio().unwrap_or(DEFAULT_ASPECT);
            if !(aspect > 0.0 && aspect.is_finite()) {
                return Err(degenerate(
                    "perspective/aspectRatio",
                    format!("aspect ratio {aspect} is not positive"),
                ));
            }
            let xfov = crate::collada::xfov_from_yfov(yfov, aspect);
            let proj = Projection::Perspective {
                xfov_deg: xfov,
                yfov_deg: yfov,
            };
            (proj, p.znear(), p.zfar())
        }
        gltf::camera::Projection::Orthographic(o) => {
            let (xmag, ymag) = (o.xmag(), o.ymag());
            if !(xmag.abs() > 0.0 && xmag.is_finite() && ymag.abs() > 0.0 && ymag.is_finite()) {
                return Err(degenerate(
                    "orthographic",
                    format!("magnifications {xmag} x {ymag} must be non-zero and finite"),
                ));
            }
            let proj = Projection::Orthographic {
                width: 2.0 * xmag.abs(),
            };
            (proj, o.znear(), Some(o.zfar()))
        }
    };
    Ok(CameraDesc {
        name: cam
            .name()
            .or(node.name())
            .map_or_else(|| format!("camera {}", cam.index()), str::to_string),
        world_from_camera: m,
        projection,
        znear: Some(znear),
        zfar,
        // glTF's znear (required) and zfar are the planes of a
        // rasteriser's projection matrix (depth precision; zfar absent
        // means an infinite projection), not a request to hide geometry.
        clip: None,
        loc: Default::default(),
    })
}
