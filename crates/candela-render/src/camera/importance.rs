//! Camera importance: the camera as the source of paths' other end, for
//! methods that connect paths from the lights to the camera (light
//! tracing, bidirectional path tracing; Veach 1997, §4.4 and ch. 10).
//!
//! Following pbrt-v4 (`PerspectiveCamera::We`, `PDF_We`, `SampleWi`), the
//! importance of the perspective camera, for a ray leaving the lens at
//! angle θ to the viewing direction through a point of the film, is
//!
//! ```text
//! We = 1 / (A · A_lens · cos⁴θ)
//! ```
//!
//! with `A = 4 tan(hfov/2) tan(vfov/2)` the film's area on the plane at
//! distance 1 and `A_lens = π r²` the lens area (1 for a pinhole, whose
//! position is a delta). It is zero outside the film and behind the camera.
//! Since `dω = cos³θ dA₁` on that plane, `∫_lens ∫_film We cos θ dω dA = 1`:
//! the importance of the whole film is 1.
//!
//! # Splatting
//! A pixel of a `W × H` film (box filter, pixel = the mean of its samples)
//! covers `1/(W·H)` of that importance. So for `N` light paths, the value
//! of pixel `j` is `(W·H / N) · Σ c`, summed over the contributions `c`
//! (`We · throughput · … / pdf`, as each technique computes them) whose
//! film point [`Camera::we`] / [`CameraWiSample::film`] returns falls in
//! pixel `j`. A film that divides each pixel's sums by its own sample count
//! `n` (Candela's) gets exactly that from unscaled splats when the renderer
//! traces `N = n·W·H` light paths, one per camera sample; in general each
//! splat must be multiplied by `W·H·n / N`.
//!
//! With a wider reconstruction filter (`filter.rs`) a contribution at film
//! point `x` belongs to every pixel `p` whose filter covers it, weighted by
//! `f_n(x − c_p)` (normalised, integral 1: the box's weight is 1 in its
//! pixel), and "the film" extends by the filter's margin
//! ([`super::FilmFilter::margin`]) beyond the frame, where the edge pixels'
//! camera samples also reach: `We` keeps its formula there (`A` stays the
//! frame's area), so the same splat scale holds.
//!
//! The orthographic camera has no finite importance density on directions
//! (its rays are parallel): light tracing and BDPT do not support it, and
//! every function here returns `None` (or zero densities) for it.

use super::Camera;
use crate::geometry::Ray;
use crate::sampling::warp::square_to_concentric_disk;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A direction from a point toward the camera's lens, for connecting a
/// path vertex to the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraWiSample {
    /// Unit direction from the point toward the lens point.
    pub wi: Vec3,
    /// Importance of the ray leaving the lens point toward the point.
    pub we: Vec3,
    /// Density of `wi` per unit solid angle at the point
    /// (`distance² / (|cos θ| · A_lens)`; for a pinhole a delta, reported
    /// with `A_lens = 1` as pbrt does).
    pub pdf: f32,
    /// The point on the lens (the eye for a pinhole).
    pub p_lens: Vec3,
    /// Distance from the point to `p_lens`.
    pub distance: f32,
    /// Film position the connection lands on, in the coordinates
    /// [`Camera::generate_ray`] takes (pixels, y down from the top).
    pub film: Vec2,
}

impl Camera {
    /// Film area on the plane at distance 1 in front of the eye.
    fn film_area_at_unit_distance(&self) -> f32 {
        4.0 * self.tan_half_width * self.tan_half_height
    }

    /// Lens area; 1 for a pinhole (its position is a delta).
    fn lens_area(&self) -> f32 {
        if self.lens_radius > 0.0 {
            PI * self.lens_radius * self.lens_radius
        } else {
            1.0
        }
    }

    /// The film position (pixels, as [`Camera::generate_ray`] takes them)
    /// of a ray leaving the lens, with the cosine of its angle to the
    /// viewing direction; `None` behind the camera or outside the film.
    /// For a pinhole the origin is taken to be the eye; for a thin lens it
    /// is the lens point, and the film point is the one whose pinhole ray
    /// meets this ray on the plane in focus.
    fn film_point(&self, ray: &Ray) -> Option<(Vec2, f32)> {
        if self.orthographic.is_some() {
            return None;
        }
        let dir = ray.dir.normalize_or_zero();
        let cos = dir.dot(self.forward);
        if cos.is_nan() || cos <= 0.0 {
            return None;
        }
        let d = Vec2::new(dir.dot(self.right), dir.dot(self.up)) / cos;
        // Slopes (x/z, y/z) of the pinhole ray through the same film point.
        let slope = if self.lens_radius > 0.0 {
            let o = self.lens_point(ray) - self.eye;
            let lens = Vec2::new(o.dot(self.right), o.dot(self.up));
            (lens + d * self.focal_distance) / self.focal_distance
        } else {
            d
        };
        let nx = slope.x / self.tan_half_width;
        let ny = slope.y / self.tan_half_height;
        let film = Vec2::new(
            (nx + 1.0) * 0.5 * self.width as f32,
            (1.0 - ny) * 0.5 * self.height as f32,
        );
        // The frame and, for filters wider than a pixel, the margin whose
        // film points still count for the edge pixels (`filter.rs`).
        let m = self.filter.margin();
        let inside = film.x >= -m
            && film.y >= -m
            && film.x < self.width as f32 + m
            && film.y < self.height as f32 + m;
        inside.then_some((film, cos))
    }

    /// Importance `We` carried by `ray`, leaving the lens (see the module
    /// docs for its normalisation), and the film position it comes from in
    /// [`Camera::generate_ray`]'s coordinates (pixels): a ray generated for
    /// film point `f` maps back to `f`. `None` outside the film, behind the
    /// camera, or for an orthographic camera.
    pub fn we(&self, ray: &Ray) -> Option<(Vec3, Vec2)> {
        let (film, cos) = self.film_point(ray)?;
        let cos2 = cos * cos;
        let we = 1.0 / (self.film_area_at_unit_distance() * self.lens_area() * cos2 * cos2);
        Some((Vec3::splat(we), film))
    }

    /// Densities `(pdf_pos, pdf_dir)` with which [`Camera::generate_ray`],
    /// fed a film point uniform over the whole film and a uniform lens
    /// sample, produces `ray`: `1 / A_lens` per unit lens area (1 for a
    /// pinhole) and `1 / (A cos³θ)` per unit solid angle. Zero outside the
    /// film, behind the camera, or for an orthographic camera.
    pub fn pdf_we(&self, ray: &Ray) -> (f32, f32) {
        match self.film_point(ray) {
            Some((_, cos)) => (
                1.0 / self.lens_area(),
                1.0 / (self.film_area_at_unit_distance() * cos * cos * cos),
            ),
            None => (0.0, 0.0),
        }
    }

    /// Connects point `p` to the camera: a lens point from `u_lens` (the
    /// concentric disk, as [`Camera::generate_ray`] maps it; the eye for a
    /// pinhole), the direction toward it and the importance of the ray from
    /// it to `p`. `None` when `p` is outside the view or the clip range,
    /// at the lens point, or the camera is orthographic.
    pub fn sample_wi(&self, p: Vec3, u_lens: Vec2) -> Option<CameraWiSample> {
        if self.orthographic.is_some() || !self.in_clip_range(p) {
            return None;
        }
        let lens = square_to_concentric_disk(u_lens) * self.lens_radius.max(0.0);
        let p_lens = self.eye + self.right * lens.x + self.up * lens.y;
        let to_lens = p_lens - p;
        let dist2 = to_lens.length_squared();
        if dist2.is_nan() || dist2 <= 0.0 {
            return None;
        }
        let distance = dist2.sqrt();
        let wi = to_lens / distance;
        let (we, film) = self.we(&Ray::new(p_lens, -wi))?;
        let cos = wi.dot(self.forward).abs();
        let pdf = dist2 / (cos * self.lens_area());
        Some(CameraWiSample {
            wi,
            we,
            pdf,
            p_lens,
            distance,
            film,
        })
    }
}
