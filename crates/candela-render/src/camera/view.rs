//! An explicit camera placement: eye, look-at point, up and field of view.
//!
//! The settings' `eye`/`look_at`/`up`/`fov` (the CLI's `--eye`, `--look-at`,
//! `--up`, `--fov`, Python's keywords, the viewer's orbiting camera) become a
//! [`CameraView`], and [`Camera::with_view`] is the one place that turns it
//! into a camera. It replaces only the placement of the framed camera: image
//! size, lens and orthographic extent stay as framed.

use super::framing::FramingError;
use super::Camera;
use glam::Vec3;

/// Where the camera is and where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraView {
    /// Eye point (centre of the lens).
    pub eye: Vec3,
    /// The point the camera looks at (also the plane in focus of a thin
    /// lens, unless a focal distance is given).
    pub target: Vec3,
    /// Approximate up direction; the image's up is its part orthogonal to
    /// the view direction.
    pub up: Vec3,
    /// Vertical field of view in degrees; `None` keeps the framed camera's.
    /// The horizontal one follows the image's aspect ratio (square pixels).
    pub vfov_deg: Option<f32>,
}

impl Camera {
    /// This camera moved to `view`: same image size, lens radius and
    /// orthographic extent; the vertical field of view from the view (or
    /// kept), the horizontal one from the aspect ratio; the plane in focus
    /// through the look-at point.
    pub fn with_view(&self, view: &CameraView) -> Result<Camera, FramingError> {
        let finite = view.eye.is_finite() && view.target.is_finite() && view.up.is_finite();
        if !finite {
            return Err(FramingError::Degenerate("the view is not finite"));
        }
        let distance = (view.target - view.eye).length();
        if distance <= 0.0 {
            return Err(FramingError::Degenerate("the eye is at the look-at point"));
        }
        let forward = (view.target - view.eye) / distance;
        if forward.cross(view.up).length_squared() <= 1e-12 {
            return Err(FramingError::Degenerate(
                "the up direction is parallel to the view direction",
            ));
        }
        let vfov = view.vfov_deg.unwrap_or_else(|| self.vfov_deg());
        if !(vfov > 0.0 && vfov < 180.0) {
            return Err(FramingError::Degenerate(
                "the field of view must be between 0 and 180 degrees",
            ));
        }
        let tan_y = (vfov.to_radians() * 0.5).tan();
        let tan_x = tan_y * self.width as f32 / self.height as f32;
        let hfov = 2.0 * tan_x.atan().to_degrees();
        let placed = Camera::look_at(
            view.eye,
            view.target,
            view.up,
            hfov,
            vfov,
            self.width,
            self.height,
        );
        Ok(Camera {
            lens_radius: self.lens_radius,
            orthographic: self.orthographic,
            filter: self.filter.clone(),
            clip: self.clip,
            ..placed
        })
    }

    /// The view that places this camera: its eye, the point at its focal
    /// distance straight ahead, its up vector and its vertical field of
    /// view (what a viewer starts its orbit from).
    pub fn view(&self) -> CameraView {
        CameraView {
            eye: self.eye,
            target: self.eye + self.forward * self.focal_distance,
            up: self.up,
            vfov_deg: Some(self.vfov_deg()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::camera;

    #[test]
    fn a_view_looks_where_it_says() {
        let view = CameraView {
            eye: Vec3::new(3.0, 1.0, 0.0),
            target: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            vfov_deg: Some(40.0),
        };
        let c = camera().with_view(&view).unwrap();
        let centre = c.generate_ray(glam::Vec2::new(320.0, 240.0), glam::Vec2::ZERO);
        assert!((centre.dir - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-6);
        assert!((c.vfov_deg() - 40.0).abs() < 1e-4);
        let aspect = c.tan_half_width / c.tan_half_height;
        assert!((aspect - 640.0 / 480.0).abs() < 1e-5, "square pixels");
        assert!((c.focal_distance - 3.0).abs() < 1e-6);
    }

    #[test]
    fn the_view_of_a_camera_places_it_again() {
        let c = camera();
        let again = c.with_view(&c.view()).unwrap();
        assert!((again.eye - c.eye).length() < 1e-6);
        assert!((again.forward - c.forward).length() < 1e-6);
        assert!((again.up - c.up).length() < 1e-6);
        assert!((again.tan_half_height - c.tan_half_height).abs() < 1e-6);
    }

    #[test]
    fn degenerate_views_are_errors() {
        let good = camera().view();
        let bad = [
            CameraView {
                target: good.eye,
                ..good
            },
            CameraView {
                up: good.target - good.eye,
                ..good
            },
            CameraView {
                vfov_deg: Some(180.0),
                ..good
            },
            CameraView {
                eye: Vec3::NAN,
                ..good
            },
        ];
        for view in bad {
            assert!(camera().with_view(&view).is_err(), "{view:?}");
        }
    }
}
