//! Camera importance against ray generation: film points round-trip,
//! `pdf_we` is the density of `generate_ray`'s directions (chi-square),
//! `We` integrates to 1 over the film and to `1/(W·H)` over a pixel (Monte
//! Carlo, bounds from the variance), and `sample_wi` matches its density
//! (chi-square) and lands where `generate_ray` starts.

use super::*;
use crate::sampling::chi2::Chi2Test;
use crate::sampling::warp::{square_to_concentric_disk, square_to_uniform_hemisphere};
use crate::sampling::{Sampler, SamplerKind};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A wide, oblique camera on a small film (wide so that the chi-square
/// grid sees many cells of the film's solid angle).
fn pinhole() -> Camera {
    Camera::look_at(
        Vec3::new(0.4, 1.0, 3.0),
        Vec3::new(-0.2, 0.6, 0.0),
        Vec3::Y,
        100.0,
        80.0,
        8,
        6,
    )
}

fn thin_lens() -> Camera {
    Camera {
        lens_radius: 0.3,
        focal_distance: 2.5,
        ..pinhole()
    }
}

fn cameras() -> [(&'static str, Camera); 2] {
    [("pinhole", pinhole()), ("thin lens", thin_lens())]
}

fn lens_area(c: &Camera) -> f32 {
    if c.lens_radius > 0.0 {
        PI * c.lens_radius * c.lens_radius
    } else {
        1.0
    }
}

fn film_area(c: &Camera) -> f32 {
    4.0 * c.tan_half_width * c.tan_half_height
}

#[test]
fn generated_rays_map_back_to_their_film_point() {
    let mut sampler = Sampler::new(SamplerKind::Independent, 3);
    for (name, c) in cameras() {
        for i in 0..5000 {
            sampler.start_pixel_sample(0, 0, i);
            let film = sampler.next_2d() * Vec2::new(c.width as f32, c.height as f32);
            let ray = c.generate_ray(film, sampler.next_2d());
            let (we, back) = c
                .we(&ray)
                .unwrap_or_else(|| panic!("{name}: {film} not on the film"));
            assert!(
                (back - film).length() < 1e-3,
                "{name}: {film} came back as {back}"
            );
            let cos = ray.dir.dot(c.forward);
            let want = 1.0 / (film_area(&c) * lens_area(&c) * cos.powi(4));
            assert!((we.x - want).abs() <= 1e-4 * want && we.x == we.y && we.y == we.z);
            let (pos, dir) = c.pdf_we(&ray);
            assert_eq!(pos, 1.0 / lens_area(&c));
            let want_dir = 1.0 / (film_area(&c) * cos.powi(3));
            assert!(
                (dir - want_dir).abs() <= 1e-4 * want_dir,
                "{name}: {dir} vs {want_dir}"
            );
        }
        // Behind the camera and outside the film: no importance.
        let back = Ray::new(c.eye, -c.forward);
        assert!(c.we(&back).is_none() && c.pdf_we(&back) == (0.0, 0.0));
        let outside = c.generate_ray(Vec2::new(-0.5, 1.0), Vec2::splat(0.5));
        assert!(c.we(&outside).is_none(), "{name}");
    }
}

/// Film points uniform over the film (and a fixed lens point) give ray
/// directions whose solid-angle density is `pdf_we`'s.
#[test]
fn generated_directions_match_pdf_we() {
    for (name, c) in cameras() {
        let u_lens = Vec2::new(0.8, 0.3);
        let origin = c.generate_ray(Vec2::ZERO, u_lens).origin;
        let size = Vec2::new(c.width as f32, c.height as f32);
        let outcome = Chi2Test::sphere(&format!("generate_ray vs pdf_we: {name}"))
            .with_quadrature_panels(16)
            .run(
                |u| {
                    let ray = c.generate_ray(Vec2::new(u[0], u[1]) * size, u_lens);
                    Some((ray.dir, c.pdf_we(&ray).1))
                },
                |dir| c.pdf_we(&Ray::new(origin, dir)).1,
            );
        outcome.assert_ok();
    }
}

/// Uniform directions over the hemisphere in front of the camera (and,
/// for the thin lens, uniform lens points): the mean of
/// `We cos θ / (pdf_lens pdf_dir)` restricted to a film region estimates
/// that region's importance, 1 for the whole film and `1/(W·H)` for one
/// pixel (the splat factor the module docs state).
#[test]
fn importance_integrates_to_one_over_the_film() {
    const N: u32 = 400_000;
    let mut sampler = Sampler::new(SamplerKind::Independent, 5);
    for (name, c) in cameras() {
        let frame = crate::geometry::Frame::from_normal(c.forward);
        let pixels = [(0, 0), (3, 2), (7, 5)];
        let mut sums = [0f64; 4];
        let mut sums2 = [0f64; 4];
        for i in 0..N {
            sampler.start_pixel_sample(0, 0, i);
            let lens = square_to_concentric_disk(sampler.next_2d()) * c.lens_radius;
            let origin = c.eye + c.right * lens.x + c.up * lens.y;
            let dir = frame.to_world(square_to_uniform_hemisphere(sampler.next_2d()));
            let Some((we, film)) = c.we(&Ray::new(origin, dir)) else {
                continue;
            };
            // pdf_lens = 1 / lens area, pdf_dir = 1 / 2π.
            let v = f64::from(we.x * dir.dot(c.forward) * lens_area(&c) * 2.0 * PI);
            let pixel = (film.x as u32, film.y as u32);
            for (k, region) in std::iter::once(None).chain(pixels.map(Some)).enumerate() {
                if region.is_none() || region == Some(pixel) {
                    sums[k] += v;
                    sums2[k] += v * v;
                }
            }
        }
        let n = f64::from(N);
        let pixel_share = 1.0 / f64::from(c.width * c.height);
        for (k, want) in [1.0, pixel_share, pixel_share, pixel_share]
            .into_iter()
            .enumerate()
        {
            let mean = sums[k] / n;
            let std_err = ((sums2[k] / n - mean * mean).max(0.0) / n).sqrt();
            assert!(
                (mean - want).abs() <= 5.0 * std_err,
                "{name}, region {k}: ∫ We = {mean} vs {want} (± {std_err})"
            );
            assert!(std_err < 0.05 * want, "{name}: too few samples to tell");
        }
    }
}

/// Where the ray from `p` along `wi` crosses the lens disk, if it does.
fn lens_hit(c: &Camera, p: Vec3, wi: Vec3) -> Option<Vec3> {
    let denom = wi.dot(c.forward);
    if denom.abs() < 1e-9 {
        return None;
    }
    let t = (c.eye - p).dot(c.forward) / denom;
    let q = p + t * wi;
    (t > 0.0 && (q - c.eye).length() <= c.lens_radius).then_some(q)
}

#[test]
fn thin_lens_connections_match_their_density() {
    let c = thin_lens();
    for p in [
        c.eye + c.forward * 0.8 + c.right * 0.2,
        c.eye + c.forward * 0.5 - c.up * 0.1,
    ] {
        let outcome = Chi2Test::sphere(&format!("thin lens sample_wi from {p}"))
            .with_quadrature_panels(16)
            .run(
                |u| {
                    let s = c.sample_wi(p, Vec2::new(u[0], u[1]))?;
                    Some((s.wi, s.pdf))
                },
                // Independent of sample_wi: the lens point the direction
                // reaches, by area to solid angle, where the film sees p.
                |wi| match lens_hit(&c, p, wi) {
                    Some(q) if c.we(&Ray::new(q, -wi)).is_some() => {
                        (q - p).length_squared() / (wi.dot(c.forward).abs() * lens_area(&c))
                    }
                    _ => 0.0,
                },
            );
        outcome.assert_ok();
    }
}

#[test]
fn connections_land_where_generate_ray_starts() {
    let mut sampler = Sampler::new(SamplerKind::Independent, 9);
    for (name, c) in cameras() {
        let mut landed = 0;
        for i in 0..5000 {
            sampler.start_pixel_sample(0, 0, i);
            let p = c.eye + (sampler.next_2d() - 0.5).extend(0.0) * 6.0 + c.forward * 2.0;
            let u_lens = sampler.next_2d();
            let Some(s) = c.sample_wi(p, u_lens) else {
                continue;
            };
            landed += 1;
            assert!(((p + s.wi * s.distance) - s.p_lens).length() < 1e-4);
            let (we, film) = c.we(&Ray::new(s.p_lens, -s.wi)).unwrap();
            assert_eq!((we, film), (s.we, s.film));
            let cos = s.wi.dot(c.forward).abs();
            let want = s.distance * s.distance / (cos * lens_area(&c));
            assert!((s.pdf - want).abs() <= 1e-4 * want);
            // The camera's own ray for that film and lens point passes
            // through p.
            let ray = c.generate_ray(s.film, u_lens);
            assert!((ray.origin - s.p_lens).length() < 1e-5, "{name}");
            assert!(
                (ray.dir + s.wi).length() < 1e-3,
                "{name}: {} vs {}",
                ray.dir,
                -s.wi
            );
        }
        assert!(landed > 500, "{name}: {landed}");
    }
}

#[test]
fn orthographic_cameras_have_no_importance() {
    let c = Camera {
        orthographic: Some(Vec2::new(2.0, 1.5)),
        ..pinhole()
    };
    let ray = c.generate_ray(Vec2::new(4.0, 3.0), Vec2::ZERO);
    assert!(c.we(&ray).is_none());
    assert_eq!(c.pdf_we(&ray), (0.0, 0.0));
    assert!(c.sample_wi(c.eye + c.forward, Vec2::splat(0.5)).is_none());
}
