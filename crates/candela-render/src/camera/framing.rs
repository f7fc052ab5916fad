//! Where the camera goes.
//!
//! The CS184 course program never renders from the file's camera: it orbits a
//! camera around the scene's bounding box along the file camera's direction
//! and keeps a fixed focal length in pixels, so the field of view follows the
//! render size. Its users' images are made that way, so it is our default for
//! `.dae` files; [`CameraMode::File`] uses the literal COLLADA camera. The rule,
//! step by step, is in the project's scene notes (shared/scenes/README.md).
//!
//! The file camera's projection is honoured in both modes: a thin lens
//! brings its aperture and focus distance, an orthographic camera its width
//! (placed by the orbit rule in [`CameraMode::Cs184`], which only decides
//! where the eye is for it).

use super::Camera;
use candela_scene::{CameraDesc, ClipRange, Projection, SceneDesc};
use glam::{Vec2, Vec3, Vec4};

/// How to place the camera. Written `cs184`, `file` or a number `N` (on
/// the command line, in JSON also as a number).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "CameraModeValue", into = "CameraModeValue")]
pub enum CameraMode {
    /// The CS184 orbit rule (default).
    #[default]
    Cs184,
    /// The file's camera as written: node transform, local -Z, xfov/yfov;
    /// the first when the file has several.
    File,
    /// The file's camera number `N`, counting from 0 in file order (glTF:
    /// camera nodes in node order; Mitsuba: sensors in document order).
    Numbered(usize),
}

impl CameraMode {
    /// The index of the file camera this mode renders from, if any.
    pub fn file_camera_index(self) -> Option<usize> {
        match self {
            CameraMode::Cs184 => None,
            CameraMode::File => Some(0),
            CameraMode::Numbered(n) => Some(n),
        }
    }
}

impl std::fmt::Display for CameraMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CameraMode::Cs184 => f.write_str("cs184"),
            CameraMode::File => f.write_str("file"),
            CameraMode::Numbered(n) => write!(f, "{n}"),
        }
    }
}

impl std::str::FromStr for CameraMode {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "cs184" => Ok(CameraMode::Cs184),
            "file" => Ok(CameraMode::File),
            n => n.parse().map(CameraMode::Numbered).map_err(|_| {
                format!("'{s}': expected cs184, file, or a camera number (0 is the file's first)")
            }),
        }
    }
}

/// A camera mode on the wire: a name or a number.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(untagged)]
enum CameraModeValue {
    Number(usize),
    Name(String),
}

impl TryFrom<CameraModeValue> for CameraMode {
    type Error = String;

    fn try_from(v: CameraModeValue) -> Result<Self, Self::Error> {
        match v {
            CameraModeValue::Number(n) => Ok(CameraMode::Numbered(n)),
            CameraModeValue::Name(s) => s.parse(),
        }
    }
}

impl From<CameraMode> for CameraModeValue {
    fn from(m: CameraMode) -> Self {
        match m {
            CameraMode::Numbered(n) => CameraModeValue::Number(n),
            named => CameraModeValue::Name(named.to_string()),
        }
    }
}

/// Field of view used when a file has no camera (the course program's
/// defaults).
const DEFAULT_XFOV_DEG: f32 = 50.0;
const DEFAULT_YFOV_DEG: f32 = 35.0;

/// Why no camera could be made.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FramingError {
    /// The scene has no geometry to frame.
    #[error("the scene has no geometry to frame")]
    EmptyScene,
    /// `--camera file` was asked for but the scene has no camera.
    #[error("the scene has no camera (use the default framing instead of --camera file)")]
    NoFileCamera,
    /// `--camera N` names a camera the file does not have.
    #[error("--camera {index}: the file has {count} camera(s), numbered from 0")]
    NoSuchCamera {
        /// The number asked for.
        index: usize,
        /// How many cameras the file has.
        count: usize,
    },
    /// The resulting camera is degenerate.
    #[error("degenerate camera: {0}")]
    Degenerate(&'static str),
}

/// Builds the camera for a `width` × `height` render of `scene`.
pub fn frame_scene(
    scene: &SceneDesc,
    mode: CameraMode,
    width: u32,
    height: u32,
) -> Result<Camera, FramingError> {
    if width == 0 || height == 0 {
        return Err(FramingError::Degenerate("image has zero size"));
    }
    let file = match mode {
        CameraMode::Numbered(index) => {
            Some(scene.cameras.get(index).ok_or(FramingError::NoSuchCamera {
                index,
                count: scene.cameras.len(),
            })?)
        }
        _ => scene.cameras.first(),
    };
    let mut camera = match mode {
        CameraMode::Cs184 => cs184_orbit(scene, file, width, height)?,
        CameraMode::File | CameraMode::Numbered(_) => {
            file_camera(file.ok_or(FramingError::NoFileCamera)?, width, height)?
        }
    };
    if let Some(desc) = file {
        apply_projection(&mut camera, desc.projection)?;
        // Planes measured from the file's eye mean nothing for the orbit's.
        if mode != CameraMode::Cs184 {
            camera.clip = checked_clip(desc.clip)?;
        }
    }
    let finite = camera.eye.is_finite()
        && camera.forward.is_finite()
        && camera.right.is_finite()
        && camera.up.is_finite()
        && camera.tan_half_width.is_finite()
        && camera.tan_half_height.is_finite();
    if !finite || camera.tan_half_width <= 0.0 || camera.tan_half_height <= 0.0 {
        return Err(FramingError::Degenerate("non-finite camera"));
    }
    Ok(camera)
}

/// The CS184 rule: orbit placement around the bounds, fixed focal length.
fn cs184_orbit(
    scene: &SceneDesc,
    file_camera: Option<&CameraDesc>,
    width: u32,
    height: u32,
) -> Result<Camera, FramingError> {
    let (lo, hi) = scene.bounds().ok_or(FramingError::EmptyScene)?;
    let target = (lo + hi) * 0.5;
    let r = 1.5 * (hi - lo).length();
    if r <= 0.0 {
        return Err(FramingError::Degenerate("scene bounds have zero size"));
    }
    // The point one unit in front of the file camera, normalised as if it
    // were a direction: the course program's quirk, kept on purpose.
    let (d, (xfov, yfov)) = match file_camera {
        Some(c) => {
            let p = c.world_from_camera * Vec4::new(0.0, 0.0, -1.0, 1.0);
            let fov = c.fov_deg().unwrap_or((DEFAULT_XFOV_DEG, DEFAULT_YFOV_DEG));
            (p.truncate(), fov)
        }
        None => (Vec3::Z, (DEFAULT_XFOV_DEG, DEFAULT_YFOV_DEG)),
    };
    let d = d.try_normalize().unwrap_or(Vec3::Z);
    let phi = d.y.clamp(-1.0, 1.0).acos();
    let theta = d.x.atan2(d.z);
    let dir = Vec3::new(phi.sin() * theta.sin(), phi.cos(), phi.sin() * theta.cos());
    let eye = target + r * dir;
    // Straight above or below the target the orbit's up vector vanishes; any
    // horizontal up then gives a valid view.
    let up = if phi.sin() > 1e-6 { Vec3::Y } else { -Vec3::Z };
    let (hfov, vfov) = cs184_fov(xfov, yfov, width, height);
    Ok(Camera::look_at(eye, target, up, hfov, vfov, width, height))
}

/// Fits the file's fields of view to the course program's 800×600 window,
/// fixes the focal length in pixels there, and returns the (horizontal,
/// vertical) fields of view in degrees for a `width` × `height` render.
pub fn cs184_fov(xfov_deg: f32, yfov_deg: f32, width: u32, height: u32) -> (f32, f32) {
    let tan_x = (xfov_deg.to_radians() * 0.5).tan();
    let tan_y = (yfov_deg.to_radians() * 0.5).tan();
    // Keep whichever field is the binding one at a 4:3 aspect.
    let tan_y = if tan_x / tan_y < 4.0 / 3.0 {
        tan_y
    } else {
        tan_x * 0.75
    };
    let focal_px = 600.0 / (2.0 * tan_y);
    let hfov = 2.0 * (width as f32 / (2.0 * focal_px)).atan();
    let vfov = 2.0 * (height as f32 / (2.0 * focal_px)).atan();
    (hfov.to_degrees(), vfov.to_degrees())
}

/// The file's lens or orthographic extent on a placed camera (a pinhole
/// perspective camera needs nothing more).
fn apply_projection(camera: &mut Camera, projection: Projection) -> Result<(), FramingError> {
    match projection {
        Projection::Perspective { .. } => {}
        Projection::ThinLens {
            aperture_radius,
            focus_distance,
            ..
        } => {
            if !(aperture_radius.is_finite() && aperture_radius >= 0.0) {
                return Err(FramingError::Degenerate("lens aperture is negative"));
            }
            if !(focus_distance.is_finite() && focus_distance > 0.0) {
                return Err(FramingError::Degenerate("focus distance is not positive"));
            }
            camera.lens_radius = aperture_radius;
            camera.focal_distance = focus_distance;
        }
        Projection::Orthographic { width } => {
            if !(width.is_finite() && width > 0.0) {
                return Err(FramingError::Degenerate(
                    "orthographic width is not positive",
                ));
            }
            let half_width = 0.5 * width;
            let half_height = half_width * camera.height as f32 / camera.width as f32;
            camera.orthographic = Some(Vec2::new(half_width, half_height));
        }
    }
    Ok(())
}

/// A clip range the renderer can apply: 0 ≤ near < far (far may be
/// infinite).
fn checked_clip(clip: Option<ClipRange>) -> Result<Option<ClipRange>, FramingError> {
    match clip {
        Some(c) if !(c.near >= 0.0 && c.near.is_finite() && c.far > c.near) => {
            Err(FramingError::Degenerate("clip range is empty"))
        }
        _ => Ok(clip),
    }
}

/// The literal file camera: node origin, local -Z, local +Y up. The file's
/// vertical field of view is kept; the horizontal one follows the render's
/// aspect ratio, so pixels stay square. (An orthographic camera gets its
/// extent from [`apply_projection`]; the default field of view set here is
/// not used by it.)
fn file_camera(desc: &CameraDesc, width: u32, height: u32) -> Result<Camera, FramingError> {
    let m = desc.world_from_camera;
    let eye = m.transform_point3(Vec3::ZERO);
    let forward = m.transform_vector3(-Vec3::Z);
    let up = m.transform_vector3(Vec3::Y);
    if forward.length_squared() == 0.0 || up.cross(forward).length_squared() == 0.0 {
        return Err(FramingError::Degenerate("camera transform is singular"));
    }
    let (_, yfov_deg) = desc
        .fov_deg()
        .unwrap_or((DEFAULT_XFOV_DEG, DEFAULT_YFOV_DEG));
    let tan_y = (yfov_deg.to_radians() * 0.5).tan();
    let tan_x = tan_y * width as f32 / height as f32;
    let hfov = 2.0 * tan_x.atan().to_degrees();
    Ok(Camera::look_at(
        eye,
        eye + forward,
        up,
        hfov,
        yfov_deg,
        width,
        height,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fov_follows_the_render_size_at_fixed_focal_length() {
        // A 4:3 file camera at 800x600 keeps its own field of view.
        let (h, v) = cs184_fov(50.0, 38.5, 800, 600);
        let expect_v = 2.0
            * ((50f32.to_radians() / 2.0).tan() * 0.75)
                .atan()
                .to_degrees();
        assert!((v - expect_v).abs() < 1e-3, "{v} vs {expect_v}");
        assert!((h - 50.0).abs() < 1e-3, "{h}");
        // Half the pixels in each direction: tan of the half angle halves.
        let (h2, v2) = cs184_fov(50.0, 38.5, 400, 300);
        let t = |deg: f32| (deg.to_radians() / 2.0).tan();
        assert!((t(h2) - t(h) / 2.0).abs() < 1e-5);
        assert!((t(v2) - t(v) / 2.0).abs() < 1e-5);
    }

    #[test]
    fn narrow_file_fov_widens_x_to_four_thirds() {
        // tan(x/2)/tan(y/2) < 4/3: y binds, x is widened.
        let (h, v) = cs184_fov(30.0, 40.0, 800, 600);
        assert!((v - 40.0).abs() < 1e-3, "{v}");
        let expect_h = 2.0 * ((20f32.to_radians()).tan() * 4.0 / 3.0).atan().to_degrees();
        assert!((h - expect_h).abs() < 1e-3, "{h}");
    }

    #[test]
    fn empty_scene_is_an_error() {
        let scene = SceneDesc::default();
        assert_eq!(
            frame_scene(&scene, CameraMode::Cs184, 8, 8),
            Err(FramingError::EmptyScene)
        );
        assert_eq!(
            frame_scene(&scene, CameraMode::Cs184, 0, 8),
            Err(FramingError::Degenerate("image has zero size"))
        );
    }
}
