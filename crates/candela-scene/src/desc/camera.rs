//! Cameras as a file describes them: a placement and a projection, each
//! projection with its own parameters.

use super::SourceLoc;
use glam::Mat4;

/// A camera: where it is and how it projects.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    /// Name of the node or camera element.
    pub name: String,
    /// Full world-from-camera transform (including the up-axis change). The
    /// camera sits at the local origin, looks down local -Z, local +Y is up.
    pub world_from_camera: Mat4,
    /// How the camera projects the world onto its image.
    pub projection: Projection,
    /// The file's near plane, if given, as read (glTF, COLLADA: a
    /// rasteriser's depth range, not applied; see [`CameraDesc::clip`]).
    pub znear: Option<f32>,
    /// The file's far plane, if given, as read (not applied either).
    pub zfar: Option<f32>,
    /// The depth range the renderer keeps: what lies nearer than
    /// `clip.near` or farther than `clip.far` is not seen by camera rays.
    /// `None` (every format but Mitsuba's) sees everything.
    pub clip: Option<ClipRange>,
    /// Where the camera was described.
    pub loc: SourceLoc,
}

/// Clip planes of a camera, as Mitsuba 3's `perspective` and `thinlens`
/// sensors apply `near_clip` and `far_clip`: two planes perpendicular to
/// the view axis at these distances in front of the eye (lens) plane. A
/// camera ray whose angle to the view axis is θ therefore starts
/// `near / cos θ` along itself and ends `far / cos θ` along itself; only
/// camera rays are clipped, later bounces see the whole scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipRange {
    /// Distance of the near plane along the view axis (> 0).
    pub near: f32,
    /// Distance of the far plane along the view axis (> `near`; may be
    /// infinite).
    pub far: f32,
}

/// The camera models a description can ask for. A renderer keeps square
/// pixels: when the image's aspect differs from the file's, a perspective
/// camera keeps its vertical field of view and an orthographic one its
/// width; the other extent follows the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A pinhole: every ray starts at the eye.
    Perspective {
        /// Horizontal field of view in degrees, in (0, 180).
        xfov_deg: f32,
        /// Vertical field of view in degrees, in (0, 180).
        yfov_deg: f32,
    },
    /// A thin lens: rays start on a disk of radius `aperture_radius` around
    /// the eye and meet the pinhole ray on the plane `focus_distance` in
    /// front of it (depth of field).
    ThinLens {
        /// Horizontal field of view in degrees, in (0, 180).
        xfov_deg: f32,
        /// Vertical field of view in degrees, in (0, 180).
        yfov_deg: f32,
        /// Lens radius in world units (>= 0; 0 is a pinhole).
        aperture_radius: f32,
        /// Distance to the plane in focus along the view direction (> 0).
        focus_distance: f32,
    },
    /// Parallel rays along the view direction through a rectangle of the
    /// given world-space width centred on the eye (its height follows the
    /// image's aspect).
    Orthographic {
        /// Full width of the view in world units (> 0).
        width: f32,
    },
}

impl CameraDesc {
    /// The (horizontal, vertical) fields of view in degrees of a perspective
    /// or thin-lens camera; `None` for an orthographic one.
    pub fn fov_deg(&self) -> Option<(f32, f32)> {
        match self.projection {
            Projection::Perspective { xfov_deg, yfov_deg }
            | Projection::ThinLens {
                xfov_deg, yfov_deg, ..
            } => Some((xfov_deg, yfov_deg)),
            Projection::Orthographic { .. } => None,
        }
    }
}
