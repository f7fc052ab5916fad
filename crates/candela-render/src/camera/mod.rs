//! Cameras: where primary rays come from.
//!
//! [`Camera`] is a pinhole (or, with a lens radius, thin-lens) perspective
//! camera described by an eye point, an orthonormal basis and the tangents of
//! its half fields of view, or an orthographic one (parallel rays through a
//! rectangle of half extents [`Camera::orthographic`] around the eye). How it is placed is decided in [`framing`]: the
//! CS184 orbit rule (the default for `.dae` files, so users see the images
//! they know) or the literal camera of the file.
//!
//! Its importance (`We`, its densities, and connecting a point to the
//! lens), which light tracing and bidirectional methods need, is in
//! `importance.rs`: [`Camera::we`], [`Camera::pdf_we`], [`Camera::sample_wi`].

mod filter;
mod filter_table;
#[cfg(test)]
mod filter_tests;
pub mod framing;
mod importance;
#[cfg(test)]
mod importance_tests;
mod view;

pub use filter::{PixelFilter, FILTER_HELP, MAX_FILTER_RADIUS};
pub use filter_table::FilmFilter;
pub use importance::CameraWiSample;
pub use view::CameraView;

use crate::geometry::Ray;
use crate::sampling::warp::square_to_concentric_disk;
pub use candela_scene::ClipRange;
use glam::{Vec2, Vec3};

/// A perspective camera for a `width` × `height` image.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye point (centre of the lens).
    pub eye: Vec3,
    /// Unit vector to the right of the image, in world space.
    pub right: Vec3,
    /// Unit vector toward the top of the image, in world space.
    pub up: Vec3,
    /// Unit viewing direction, in world space.
    pub forward: Vec3,
    /// tan(hfov / 2).
    pub tan_half_width: f32,
    /// tan(vfov / 2).
    pub tan_half_height: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Lens radius; 0 is a pinhole.
    pub lens_radius: f32,
    /// Distance to the plane in focus (used when `lens_radius > 0`).
    pub focal_distance: f32,
    /// Half width and half height of the view in world units for an
    /// orthographic camera (whose rays all run along `forward`); `None` for
    /// a perspective one.
    pub orthographic: Option<Vec2>,
    /// The pixel reconstruction filter: where in the film a pixel's
    /// samples come from (`filter.rs`); the one-pixel box by default.
    pub filter: FilmFilter,
    /// Clip planes across the view axis (Mitsuba's `near_clip` and
    /// `far_clip`, see [`ClipRange`]); `None` sees everything.
    pub clip: Option<ClipRange>,
}

impl Camera {
    /// A pinhole camera at `eye` looking at `target`, with `up` as the
    /// approximate up direction and the given full fields of view in degrees.
    pub fn look_at(
        eye: Vec3,
        target: Vec3,
        up: Vec3,
        hfov_deg: f32,
        vfov_deg: f32,
        width: u32,
        height: u32,
    ) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let up = right.cross(forward);
        Self {
            eye,
            right,
            up,
            forward,
            tan_half_width: (hfov_deg.to_radians() * 0.5).tan(),
            tan_half_height: (vfov_deg.to_radians() * 0.5).tan(),
            width,
            height,
            lens_radius: 0.0,
            focal_distance: (target - eye).length(),
            orthographic: None,
            filter: FilmFilter::default(),
            clip: None,
        }
    }

    /// Whether rays are parallel (see [`Camera::orthographic`]).
    pub fn is_orthographic(&self) -> bool {
        self.orthographic.is_some()
    }

    /// Horizontal field of view in degrees.
    pub fn hfov_deg(&self) -> f32 {
        2.0 * self.tan_half_width.atan().to_degrees()
    }

    /// Vertical field of view in degrees.
    pub fn vfov_deg(&self) -> f32 {
        2.0 * self.tan_half_height.atan().to_degrees()
    }

    /// Whether [`Camera::generate_ray`] reads its lens sample: only a thin
    /// lens does (a pinhole or an orthographic camera ignores it), so the
    /// caller skips the sample's two dimensions rather than drawing them
    /// (a 2-D draw is about 110 instructions, 1% of an equal-error sample).
    pub fn uses_lens_sample(&self) -> bool {
        self.orthographic.is_none() && self.lens_radius > 0.0
    }

    /// The ray through film position `film` (in pixels, x to the right, y
    /// down from the top-left corner) and lens sample `u_lens` in [0,1)².
    /// An orthographic camera has no lens: `u_lens` is not used. With clip
    /// planes the ray starts on the near plane and ends on the far one
    /// ([`Camera::clipped`]).
    pub fn generate_ray(&self, film: Vec2, u_lens: Vec2) -> Ray {
        let ray = self.unclipped_ray(film, u_lens);
        self.clipped(ray)
    }

    /// `ray` (leaving the lens plane) cut to the clip range, as Mitsuba's
    /// sensors do: its origin moves to the near plane and its end to the
    /// far one. The planes lie across the view axis, so along a ray at
    /// angle θ to it the distances are `near / cos θ` and `far / cos θ`.
    /// The start moves rather than a minimum distance being kept, so
    /// every consumer of the ray (traversal, the path tracer, BDPT's
    /// first vertex) sees the clip without knowing of it.
    pub fn clipped(&self, mut ray: Ray) -> Ray {
        let Some(clip) = self.clip else {
            return ray;
        };
        let inv_cos = 1.0 / ray.dir.dot(self.forward);
        let (near_t, far_t) = (clip.near * inv_cos, clip.far * inv_cos);
        ray.origin += ray.dir * near_t;
        ray.t_max = far_t - near_t;
        ray
    }

    /// Where `ray`, which may have been moved forward by
    /// [`Camera::clipped`], left the lens plane (the plane through the eye
    /// across the view axis).
    pub fn lens_point(&self, ray: &Ray) -> Vec3 {
        let depth = (ray.origin - self.eye).dot(self.forward);
        if depth == 0.0 {
            return ray.origin;
        }
        ray.origin - ray.dir * (depth / ray.dir.dot(self.forward))
    }

    /// Whether point `p` lies between the clip planes (always without).
    pub fn in_clip_range(&self, p: Vec3) -> bool {
        self.clip.is_none_or(|c| {
            let depth = (p - self.eye).dot(self.forward);
            depth >= c.near && depth <= c.far
        })
    }

    fn unclipped_ray(&self, film: Vec2, u_lens: Vec2) -> Ray {
        let nx = 2.0 * film.x / self.width as f32 - 1.0;
        let ny = 1.0 - 2.0 * film.y / self.height as f32;
        if let Some(half) = self.orthographic {
            let origin = self.eye + self.right * (nx * half.x) + self.up * (ny * half.y);
            return Ray::new(origin, self.forward);
        }
        let sx = nx * self.tan_half_width;
        let sy = ny * self.tan_half_height;
        let dir_cam = Vec3::new(sx, sy, 1.0);
        if self.lens_radius <= 0.0 {
            let dir = self.to_world(dir_cam).normalize();
            return Ray::new(self.eye, dir);
        }
        // Thin lens: every ray through the lens point meets the pinhole ray on
        // the plane of focus.
        let focus = dir_cam * self.focal_distance;
        let lens = square_to_concentric_disk(u_lens) * self.lens_radius;
        let origin_cam = Vec3::new(lens.x, lens.y, 0.0);
        let dir = self.to_world(focus - origin_cam).normalize();
        Ray::new(self.eye + self.right * lens.x + self.up * lens.y, dir)
    }

    fn to_world(&self, v: Vec3) -> Vec3 {
        self.right * v.x + self.up * v.y + self.forward * v.z
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A 640 × 480 camera at z = 5 looking at the origin: the camera
    /// module's tests share it.
    pub(crate) fn camera() -> Camera {
        Camera::look_at(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::Y,
            60.0,
            45.0,
            640,
            480,
        )
    }

    #[test]
    fn centre_pixel_looks_at_target() {
        let c = camera();
        let r = c.generate_ray(Vec2::new(320.0, 240.0), Vec2::ZERO);
        assert!((r.dir - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
    }

    #[test]
    fn image_corners_span_the_field_of_view() {
        let c = camera();
        let left = c.generate_ray(Vec2::new(0.0, 240.0), Vec2::ZERO);
        let angle = left.dir.dot(c.forward).acos().to_degrees();
        assert!((angle - 30.0).abs() < 1e-3, "{angle}");
        assert!(left.dir.x < 0.0, "x = 0 is the left edge");
        let top = c.generate_ray(Vec2::new(320.0, 0.0), Vec2::ZERO);
        let angle = top.dir.dot(c.forward).acos().to_degrees();
        assert!((angle - 22.5).abs() < 1e-3, "{angle}");
        assert!(top.dir.y > 0.0, "y = 0 is the top edge");
    }

    #[test]
    fn only_a_thin_lens_reads_the_lens_sample() {
        // The render loop skips drawing the lens sample when this says no:
        // the ray must then be the same whatever the sample.
        let mut ortho = camera();
        ortho.orthographic = Some(Vec2::new(2.0, 1.5));
        let mut lens = camera();
        lens.lens_radius = 0.3;
        lens.focal_distance = 4.0;
        let film = Vec2::new(100.0, 50.0);
        for c in [camera(), ortho] {
            assert!(!c.uses_lens_sample());
            let at = |u| c.generate_ray(film, u);
            for u in [Vec2::new(0.1, 0.9), Vec2::new(0.99, 0.0)] {
                assert_eq!(
                    (at(u).origin, at(u).dir),
                    (at(Vec2::ZERO).origin, at(Vec2::ZERO).dir)
                );
            }
        }
        assert!(lens.uses_lens_sample());
        let (a, b) = (
            lens.generate_ray(film, Vec2::new(0.1, 0.9)),
            lens.generate_ray(film, Vec2::ZERO),
        );
        assert_ne!(a.origin, b.origin);
    }

    #[test]
    fn clip_planes_lie_across_the_view_axis() {
        // Mitsuba's rule: the planes are at depth near and far along the
        // view axis, so an off-axis ray (angle θ) starts near / cos θ and
        // ends far / cos θ along itself, for a pinhole and a thin lens.
        let (near, far) = (1.5, 7.0);
        let mut lens = camera();
        lens.lens_radius = 0.3;
        lens.focal_distance = 4.0;
        for mut c in [camera(), lens] {
            c.clip = Some(ClipRange { near, far });
            for (film, u) in [
                (Vec2::new(320.0, 240.0), Vec2::new(0.5, 0.5)),
                (Vec2::new(0.0, 0.0), Vec2::new(0.1, 0.8)),
                (Vec2::new(640.0, 130.0), Vec2::new(0.9, 0.3)),
            ] {
                let r = c.generate_ray(film, u);
                let start = c.lens_point(&r);
                let cos = r.dir.dot(c.forward);
                let depth = |p: Vec3| (p - c.eye).dot(c.forward);
                assert!(depth(start).abs() < 1e-5, "starts from the lens plane");
                assert!(((r.origin - start).length() - near / cos).abs() < 1e-4);
                assert!((depth(r.origin) - near).abs() < 1e-4);
                assert!((depth(r.at(r.t_max)) - far).abs() < 1e-3);
                assert!((r.t_max - (far - near) / cos).abs() < 1e-3);
                if film.x == 0.0 {
                    assert!(cos < 0.85, "the corner ray is off axis ({cos})");
                }
                // The same ray without clipping leaves the same lens point.
                let mut open = c.clone();
                open.clip = None;
                let o = open.generate_ray(film, u);
                assert!((o.origin - start).length() < 1e-5);
                assert!((o.dir - r.dir).length() < 1e-6);
            }
        }
    }

    #[test]
    fn the_clip_range_bounds_connections_to_the_camera() {
        let mut c = camera();
        c.clip = Some(ClipRange {
            near: 2.0,
            far: 4.0,
        });
        // The camera at z = 5 looks down -z: depth 5 - z.
        assert!(!c.in_clip_range(Vec3::new(0.0, 0.0, 4.0)));
        assert!(c.in_clip_range(Vec3::new(0.3, 0.0, 2.0)));
        assert!(!c.in_clip_range(Vec3::new(0.0, 0.0, 0.5)));
        assert!(c.sample_wi(Vec3::new(0.0, 0.0, 4.0), Vec2::ZERO).is_none());
        assert!(c.sample_wi(Vec3::new(0.0, 0.0, 2.0), Vec2::ZERO).is_some());
    }

    #[test]
    fn thin_lens_rays_meet_on_the_focal_plane() {
        let mut c = camera();
        c.lens_radius = 0.3;
        c.focal_distance = 4.0;
        let film = Vec2::new(100.0, 50.0);
        let pinhole = {
            let mut p = c.clone();
            p.lens_radius = 0.0;
            p.generate_ray(film, Vec2::ZERO)
        };
        let t_focus = 4.0 / pinhole.dir.dot(c.forward);
        let focus = pinhole.at(t_focus);
        for u in [
            Vec2::new(0.1, 0.9),
            Vec2::new(0.7, 0.2),
            Vec2::new(0.5, 0.5),
        ] {
            let r = c.generate_ray(film, u);
            let t = (focus - r.origin).dot(c.forward) / r.dir.dot(c.forward);
            assert!((r.at(t) - focus).length() < 1e-4);
        }
    }
}
