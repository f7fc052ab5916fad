//! Emission sampling: every light's direction and position distributions
//! against their densities (chi-square), `pdf_le` against what `sample_le`
//! reports, the estimate of each light's power against its analytic value,
//! and the choice of the emitting light.

use super::*;
use crate::sampling::chi2::{integrate_2d, Chi2Test};
use crate::sampling::warp::Parallelogram;
use crate::sampling::{Sampler, SamplerKind};
use crate::shading::MaterialTextures;
use crate::texture::{ImageTexture, SlotTexture};
use candela_image::RgbImage;
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::PI;
use std::sync::Arc;

const BOUNDS: SceneSphere = SceneSphere {
    center: Vec3::new(0.3, 0.5, -0.2),
    radius: 2.0,
};

fn triangle_corners() -> [Vec3; 3] {
    [
        Vec3::new(-0.5, 1.0, -0.3),
        Vec3::new(0.6, 1.1, -0.2),
        Vec3::new(0.1, 1.2, 0.7),
    ]
}

fn triangle(radiance: Vec3, textured: Option<TexturedEmission>) -> AreaLight {
    let v = triangle_corners();
    AreaLight {
        shape: AreaShape::Triangle {
            v,
            normal: (v[1] - v[0]).cross(v[2] - v[0]).normalize(),
        },
        radiance,
        textured,
    }
}

fn rect() -> AreaLight {
    AreaLight {
        shape: AreaShape::Rect {
            shape: Parallelogram {
                origin: Vec3::new(-0.3, 1.0, -0.4),
                edge0: Vec3::new(0.6, 0.1, 0.0),
                edge1: Vec3::new(0.0, 0.0, 0.8),
            },
            normal: -Vec3::new(0.6, 0.1, 0.0).cross(Vec3::Z).normalize(),
        },
        radiance: Vec3::new(2.0, 1.0, 0.5),
        textured: None,
    }
}

fn sphere(textured: Option<TexturedEmission>) -> AreaLight {
    AreaLight {
        shape: AreaShape::Sphere {
            center: Vec3::new(0.2, 1.0, -0.1),
            radius: 0.4,
            inward: false,
        },
        radiance: Vec3::new(0.5, 1.0, 3.0),
        textured,
    }
}

/// An emission texture that varies along u only (two texel columns,
/// wrapped bilinearly): its mean over any band of full u periods is the
/// mean of its texels, which makes a textured sphere's power analytic.
fn striped_emission() -> TexturedEmission {
    let image = RgbImage::from_pixels(2, 1, vec![[4.0, 1.0, 0.5], [0.5, 2.0, 6.0]]).unwrap();
    let textures = MaterialTextures {
        emission: Some(SlotTexture::of_image(Arc::new(
            ImageTexture::from_image(&image).unwrap(),
        ))),
        ..MaterialTextures::default()
    };
    TexturedEmission {
        textures: Arc::new(textures),
        uvs: [Vec2::ZERO, Vec2::X, Vec2::Y],
        colors: [crate::texture::TexturePoint::NO_VERTEX_COLOR; 3],
        sphere_axes: candela_scene::SphereDesc::Y_POLE,
        radiance: Vec3::ONE,
    }
}

fn spot(cone_deg: f32, exponent: f32) -> SpotLight {
    SpotLight {
        position: Vec3::new(0.1, 2.0, 0.3),
        direction: Vec3::new(0.2, -1.0, 0.1).normalize(),
        intensity: Vec3::new(3.0, 2.0, 1.0),
        cos_cutoff: (cone_deg.to_radians() * 0.5).cos(),
        exponent,
        edge: SpotFade::Hard,
    }
}

fn env_image() -> RgbImage {
    RgbImage::from_fn(16, 8, |x, y| {
        if (x, y) == (5, 2) {
            [40.0, 30.0, 20.0]
        } else {
            [0.1 + 0.05 * x as f32, 0.2, 0.1 + 0.1 * y as f32]
        }
    })
    .unwrap()
}

fn environment() -> EnvironmentLight {
    let opts = EnvironmentOptions {
        scale: 1.0,
        rotate_y_deg: 30.0,
        ..Default::default()
    };
    EnvironmentLight {
        map: Arc::new(EnvironmentMap::from_image(&env_image(), &opts).unwrap()),
    }
}

/// Every kind of light, named, with the flux its emission estimate must
/// have (per channel, computed here independently of the light's code).
fn lights_with_power() -> Vec<(&'static str, Light, DVec3)> {
    let area_power = |l: &AreaLight| l.radiance.as_dvec3() * PI * f64::from(l.shape.area());
    let tri = triangle(Vec3::new(1.0, 2.0, 3.0), None);
    let rect = rect();
    let sph = sphere(None);
    // Texture mean (the two texels' average) over the whole sphere.
    let textured_sphere = sphere(Some(striped_emission()));
    let mean = DVec3::new(2.25, 1.5, 3.25);
    let textured_sphere_power = mean * PI * f64::from(textured_sphere.shape.area());
    let textured_tri = triangle(Vec3::ONE, Some(striped_emission()));
    let textured_tri_power = textured_triangle_power(&textured_tri);
    let spot_power = |s: &SpotLight| {
        let k = f64::from(s.exponent) + 1.0;
        let c0 = f64::from(if s.exponent > 0.0 {
            s.cos_cutoff.max(0.0)
        } else {
            s.cos_cutoff
        });
        s.intensity.as_dvec3() * 2.0 * PI * (1.0 - c0.powf(k)) / k
    };
    let spots = [spot(40.0, 0.0), spot(70.0, 3.0), spot(250.0, 0.0)];
    // Faded edges (half angles): Mitsuba's, linear in the angle from 20° to
    // 35°; glTF's, t² in the cosine from 15° to 40°. Their flux, with b and
    // c the half angles: 2π I [1 − cos b + (sin b − sin c + (c − b) cos b) /
    // (c − b)] (∫ (c − θ) sin θ dθ by parts), and 2π I [1 − cos b + (cos b
    // − cos c) / 3] (∫ t² dcos θ).
    let (b, c) = (20f64.to_radians(), 35f64.to_radians());
    let mut mitsuba = spot(70.0, 0.0);
    mitsuba.edge = SpotFade::linear_in_angle(b as f32, c as f32);
    let mitsuba_power = mitsuba.intensity.as_dvec3()
        * (2.0 * PI * (1.0 - b.cos() + (b.sin() - c.sin() + (c - b) * b.cos()) / (c - b)));
    let (bi, co) = (15f64.to_radians(), 40f64.to_radians());
    let mut gltf = spot(80.0, 0.0);
    gltf.edge = SpotFade::smooth_in_cosine(bi as f32, co as f32);
    let gltf_power =
        gltf.intensity.as_dvec3() * (2.0 * PI * (1.0 - bi.cos() + (bi.cos() - co.cos()) / 3.0));
    let r2 = f64::from(BOUNDS.radius).powi(2);
    let env = environment();
    let env_power = environment_radiance_integral(&env_image()) * PI * r2;
    vec![
        ("triangle", Light::Area(tri.clone()), area_power(&tri)),
        ("rect", Light::Area(rect.clone()), area_power(&rect)),
        ("sphere", Light::Area(sph.clone()), area_power(&sph)),
        (
            "textured sphere",
            Light::Area(textured_sphere),
            textured_sphere_power,
        ),
        (
            "textured triangle",
            Light::Area(textured_tri),
            textured_tri_power,
        ),
        (
            "point",
            Light::Point(PointLight {
                position: Vec3::new(0.0, 1.5, 0.2),
                intensity: Vec3::new(1.0, 0.5, 2.0),
            }),
            DVec3::new(1.0, 0.5, 2.0) * 4.0 * PI,
        ),
        (
            "spot 40°",
            Light::Spot(spots[0].clone()),
            spot_power(&spots[0]),
        ),
        (
            "spot 70° cos³",
            Light::Spot(spots[1].clone()),
            spot_power(&spots[1]),
        ),
        (
            "spot 250°",
            Light::Spot(spots[2].clone()),
            spot_power(&spots[2]),
        ),
        ("spot, Mitsuba's fade", Light::Spot(mitsuba), mitsuba_power),
        ("spot, glTF's fade", Light::Spot(gltf), gltf_power),
        (
            "directional",
            Light::Directional(DirectionalLight {
                direction: Vec3::new(0.3, -1.0, 0.2).normalize(),
                irradiance: Vec3::new(2.0, 1.5, 1.0),
            }),
            DVec3::new(2.0, 1.5, 1.0) * PI * r2,
        ),
        (
            "ambient",
            Light::Ambient(AmbientLight {
                radiance: Vec3::new(0.5, 0.7, 1.0),
            }),
            // Upper hemisphere (2π sr) through the disk (π r²).
            DVec3::new(0.5, 0.7, 1.0) * 2.0 * PI * PI * r2,
        ),
        ("environment", Light::Environment(env), env_power),
    ]
}

/// ∫ L dω of an equirectangular image, pixel by pixel (each pixel is
/// constant over its patch: Δφ · (cos θ₀ − cos θ₁)).
fn environment_radiance_integral(image: &RgbImage) -> DVec3 {
    let (w, h) = image.size();
    let mut sum = DVec3::ZERO;
    for y in 0..h {
        let cos0 = (PI * y as f64 / h as f64).cos();
        let cos1 = (PI * (y + 1) as f64 / h as f64).cos();
        for x in 0..w {
            let p = image.pixels()[y * w + x];
            sum += Vec3::from_array(p).as_dvec3() * (2.0 * PI / w as f64) * (cos0 - cos1);
        }
    }
    sum
}

/// π ∫ L dA over the textured triangle, by quadrature over its
/// barycentric parameters (`s`, and `t = (1 − s) w` to keep the domain a
/// rectangle), each channel apart.
fn textured_triangle_power(light: &AreaLight) -> DVec3 {
    let t = light.textured.as_ref().unwrap();
    let area = f64::from(light.shape.area());
    let channel = |c: usize| {
        // Barycentric density of uniform area sampling: 2 on the triangle.
        integrate_2d(
            |s, w| {
                let b0 = s as f32;
                let b1 = ((1.0 - s) * w) as f32;
                let uv = b0 * t.uvs[0] + b1 * t.uvs[1] + (1.0 - b0 - b1) * t.uvs[2];
                f64::from(t.at(uv)[c]) * (1.0 - s)
            },
            (0.0, 1.0),
            (0.0, 1.0),
        ) * 2.0
    };
    DVec3::new(channel(0), channel(1), channel(2)) * PI * area
}

/// The position sample `u_pos` used when testing directions.
const U_POS: Vec2 = Vec2::new(0.37, 0.61);

/// Chi-square of the emitted directions of the lights `which` selects,
/// at a fixed position sample, against `pdf_le`.
fn check_directions(which: impl Fn(&Light) -> bool) {
    let mut checked = 0;
    for (name, light, _) in lights_with_power() {
        if !which(&light) {
            continue;
        }
        let origin_sample = light.sample_le(U_POS, Vec2::splat(0.5), &BOUNDS).unwrap();
        let (origin, normal) = (origin_sample.ray.origin, origin_sample.normal);
        let outcome = Chi2Test::sphere(&format!("sample_le direction: {name}"))
            .with_quadrature_panels(8)
            .with_samples(300_000)
            .run(
                |u| {
                    let e = light.sample_le(U_POS, Vec2::new(u[0], u[1]), &BOUNDS)?;
                    // The position does not depend on the direction's numbers
                    // (except at infinity, where the disk turns with it).
                    let fixed = (e.ray.origin - origin).length() < 1e-5;
                    assert!(fixed || light.is_infinite(), "{name}");
                    Some((e.ray.dir, e.pdf_dir))
                },
                |dir| light.pdf_le(origin, normal, dir, &BOUNDS).1,
            );
        outcome.assert_ok();
        checked += 1;
    }
    assert!(checked > 0);
}

#[test]
fn area_light_directions_match_pdf_le() {
    check_directions(|l| matches!(l, Light::Area(_)));
}

#[test]
fn point_and_spot_directions_match_pdf_le() {
    check_directions(|l| matches!(l, Light::Point(_) | Light::Spot(_)));
}

/// The directional light's direction is a delta: only its position is
/// tested (below).
#[test]
fn sky_directions_match_pdf_le() {
    check_directions(|l| matches!(l, Light::Ambient(_) | Light::Environment(_)));
}

/// Coordinates of an emitted origin in which its density is simple, the
/// chi-square domain, and that density.
type PositionCheck = (
    Chi2Test,
    Box<dyn Fn(Vec3, Vec3) -> Vec3>,
    Box<dyn Fn(Vec3) -> f32>,
);

fn position_check(name: &str, light: &Light) -> Option<PositionCheck> {
    let test = |n: &str, lo: f32, hi: f32| {
        Chi2Test::plane(
            &format!("sample_le position: {n}"),
            Vec2::splat(lo),
            Vec2::splat(hi),
        )
        .with_quadrature_panels(16)
    };
    match light {
        Light::Area(a) => match a.shape.clone() {
            AreaShape::Triangle { v, normal } => Some((
                test(name, 0.0, 1.0),
                // Barycentric weights of v[1] and v[2], by the dual basis.
                Box::new(move |p, _| {
                    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
                    let n = e1.cross(e2);
                    let d = p - v[0];
                    assert!(d.dot(normal).abs() < 1e-4, "{p} is off the triangle");
                    Vec3::new(d.dot(e2.cross(n)), d.dot(n.cross(e1)), 0.0) / n.length_squared()
                }),
                Box::new(|b| if b.x + b.y <= 1.0 { 2.0 } else { 0.0 }),
            )),
            AreaShape::Rect { shape, normal } => Some((
                test(name, 0.0, 1.0),
                Box::new(move |p, _| {
                    assert!((p - shape.origin).dot(normal).abs() < 1e-4);
                    shape.to_square(p).extend(0.0)
                }),
                Box::new(|_| 1.0),
            )),
            AreaShape::Sphere { center, radius, .. } => Some((
                Chi2Test::sphere(&format!("sample_le position: {name}")),
                Box::new(move |p, _| {
                    assert!(((p - center).length() - radius).abs() < 1e-4);
                    (p - center).normalize()
                }),
                Box::new(|_| 1.0 / (4.0 * std::f32::consts::PI)),
            )),
        },
        Light::Point(_) | Light::Spot(_) => None,
        Light::Directional(_) | Light::Ambient(_) | Light::Environment(_) => Some((
            test(name, -1.0, 1.0),
            // The disk through the centre perpendicular to the ray, moved
            // back by the radius; coordinates in units of the radius (any
            // orthonormal basis of the disk: its density is isotropic).
            Box::new(|p, dir| {
                let rel = p - BOUNDS.center;
                assert!(
                    (rel.dot(dir) + BOUNDS.radius).abs() < 1e-4,
                    "{p} is off the disk"
                );
                let frame = crate::geometry::Frame::from_normal(dir);
                Vec3::new(rel.dot(frame.x), rel.dot(frame.y), 0.0) / BOUNDS.radius
            }),
            Box::new(|p| {
                if p.truncate().length_squared() <= 1.0 {
                    std::f32::consts::FRAC_1_PI
                } else {
                    0.0
                }
            }),
        )),
    }
}

#[test]
fn emitted_origins_are_uniform_on_the_light() {
    let mut checked = 0;
    for (name, light, _) in lights_with_power() {
        if name.starts_with("textured") {
            continue; // same positions as the untextured shapes
        }
        let Some((test, coords, pdf)) = position_check(name, &light) else {
            continue;
        };
        let outcome = test.with_samples(300_000).run(
            |u| {
                let e = light.sample_le(Vec2::new(u[0], u[1]), Vec2::new(u[2], 0.3), &BOUNDS)?;
                let c = coords(e.ray.origin, e.ray.dir);
                // Claimed density per unit area, in the test's coordinates.
                let scale = match &light {
                    Light::Area(a) => match a.shape {
                        // Barycentric coordinates cover half the unit square.
                        AreaShape::Triangle { .. } => 2.0 * a.shape.area(),
                        AreaShape::Rect { .. } => a.shape.area(),
                        AreaShape::Sphere { radius, .. } => radius * radius,
                    },
                    _ => BOUNDS.radius * BOUNDS.radius,
                };
                Some((c, e.pdf_pos * scale))
            },
            pdf,
        );
        outcome.assert_ok();
        checked += 1;
    }
    assert_eq!(checked, 6, "three area shapes and three lights at infinity");
}

#[test]
fn pdf_le_agrees_with_sample_le() {
    let mut sampler = Sampler::new(SamplerKind::Independent, 7);
    for (name, light, _) in lights_with_power() {
        let mut emitted = 0;
        for i in 0..2000 {
            sampler.start_pixel_sample(0, 0, i);
            let (u_pos, u_dir) = (sampler.next_2d(), sampler.next_2d());
            let Some(e) = light.sample_le(u_pos, u_dir, &BOUNDS) else {
                continue;
            };
            emitted += 1;
            assert!(
                (e.ray.dir.length() - 1.0).abs() < 1e-5,
                "{name}: unit direction"
            );
            match &light {
                Light::Area(_) => {
                    assert!(e.normal.dot(e.ray.dir) > 0.0, "{name}: emits on its side")
                }
                Light::Point(_) | Light::Spot(_) => assert_eq!(e.normal, Vec3::ZERO),
                _ => assert_eq!(e.normal, e.ray.dir, "{name}: normal of a light at infinity"),
            }
            let (pos, dir) = light.pdf_le(e.ray.origin, e.normal, e.ray.dir, &BOUNDS);
            let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(b.abs());
            assert!(
                close(pos, e.pdf_pos),
                "{name}: pdf_pos {pos} vs {}",
                e.pdf_pos
            );
            assert!(
                close(dir, e.pdf_dir),
                "{name}: pdf_dir {dir} vs {}",
                e.pdf_dir
            );
            assert!(e.pdf_pos > 0.0 && e.pdf_dir > 0.0 && e.le.is_finite());
        }
        assert!(
            emitted > 1900,
            "{name}: only {emitted} of 2000 samples emitted"
        );
    }
}

/// The emission estimate `le |cos| / (pdf_pos pdf_dir)` (no cosine for
/// point and spot lights) has the light's analytic power as its mean, per
/// channel, within five standard errors of the sample mean.
#[test]
fn emission_estimates_the_lights_power() {
    const N: u32 = 200_000;
    let mut sampler = Sampler::new(SamplerKind::Independent, 11);
    for (name, light, power) in lights_with_power() {
        let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
        let mut inverse_pdf_pos = 0.0f64;
        let mut emitted = 0u32;
        for i in 0..N {
            sampler.start_pixel_sample(0, 0, i);
            let (u_pos, u_dir) = (sampler.next_2d(), sampler.next_2d());
            let Some(e) = light.sample_le(u_pos, u_dir, &BOUNDS) else {
                continue;
            };
            let cos = if e.normal == Vec3::ZERO {
                1.0
            } else {
                e.normal.dot(e.ray.dir).abs()
            };
            let v = (e.le * cos / (e.pdf_pos * e.pdf_dir)).as_dvec3();
            sum += v;
            sum2 += v * v;
            inverse_pdf_pos += 1.0 / f64::from(e.pdf_pos);
            emitted += 1;
        }
        let n = f64::from(N);
        let mean = sum / n;
        let std_err = ((sum2 / n - mean * mean).max(DVec3::ZERO) / n).powf(0.5);
        let bound = 5.0 * std_err + 1e-5 * power.abs();
        assert!(
            (mean - power).abs().cmple(bound).all(),
            "{name}: power {mean} vs {power} (bound {bound})"
        );
        // Position densities integrate to the area they cover (over the
        // samples that emit: the environment map loses a few whose direction
        // rounds onto a pole, where its density is zero).
        let area = match &light {
            Light::Area(a) => f64::from(a.shape.area()),
            Light::Point(_) | Light::Spot(_) => 1.0,
            _ => PI * f64::from(BOUNDS.radius).powi(2),
        };
        assert!(emitted >= N - 20, "{name}: {emitted} of {N} emitted");
        let measured = inverse_pdf_pos / f64::from(emitted);
        assert!(
            (measured - area).abs() <= 1e-5 * area,
            "{name}: area {measured} vs {area}"
        );
        eprintln!("{name}: power {mean:.5} vs {power:.5} (± {std_err:.3})");
    }
}

#[test]
fn lights_at_infinity_do_not_emit_in_an_empty_scene() {
    let empty = SceneSphere {
        center: Vec3::ZERO,
        radius: 0.0,
    };
    for (name, light, _) in lights_with_power() {
        let e = light.sample_le(U_POS, Vec2::splat(0.3), &empty);
        assert_eq!(e.is_none(), light.is_infinite(), "{name}");
    }
}

#[test]
fn emitters_are_chosen_by_power_delta_lights_included() {
    let lights: Vec<Light> = lights_with_power().into_iter().map(|(_, l, _)| l).collect();
    let set = LightSet::new(lights.clone(), &[], BOUNDS.radius);
    let total: f32 = lights.iter().map(|l| l.power(BOUNDS.radius)).sum();
    let n = 100_000;
    let mut counts = vec![0u32; lights.len()];
    for k in 0..n {
        let (i, pmf) = set.choose_emitter((k as f32 + 0.5) / n as f32).unwrap();
        assert_eq!(pmf, set.emitter_pmf(i));
        counts[i as usize] += 1;
    }
    for (i, light) in lights.iter().enumerate() {
        let want = light.power(BOUNDS.radius) / total;
        assert!((set.emitter_pmf(i as u32) - want).abs() < 1e-5 * want.max(1e-3));
        // Stratified choices: the count is the pmf to within one.
        let expected = f64::from(want) * f64::from(n);
        assert!(
            (f64::from(counts[i]) - expected).abs() <= 2.0,
            "{i}: {} vs {expected}",
            counts[i]
        );
    }
    assert!(LightSet::new(Vec::new(), &[], 1.0)
        .choose_emitter(0.5)
        .is_none());
}

/// Light sampling a textured triangle by solid angle finds the point where
/// the sampled direction meets the triangle, and reads the texture there
/// (the barycentrics solved here independently, by least squares).
#[test]
fn textured_triangle_light_samples_read_the_texture_where_they_land() {
    let light = triangle(Vec3::ONE, Some(striped_emission()));
    let (AreaShape::Triangle { v, normal }, Some(t)) = (&light.shape, &light.textured) else {
        unreachable!()
    };
    let p = (v[0] + v[1] + v[2]) / 3.0 + 0.7 * *normal + Vec3::new(0.2, 0.0, -0.1);
    let (e1, e2) = ((v[1] - v[0]).as_dvec3(), (v[2] - v[0]).as_dvec3());
    let mut checked = 0;
    for i in 0..64 {
        let u = Vec2::new((i as f32 + 0.5) / 64.0, (i as f32 * 0.618_034) % 1.0);
        let s = Light::Area(light.clone())
            .sample_li(p, u)
            .expect("front side");
        let omega = crate::sampling::warp::triangle_solid_angle(v[0] - p, v[1] - p, v[2] - p);
        assert!(
            (s.pdf * omega - 1.0).abs() < 1e-4,
            "not sampled by solid angle"
        );
        let d = (p + s.distance * s.wi - v[0]).as_dvec3();
        // Normal equations of d = a·e1 + b·e2.
        let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let det = g11 * g22 - g12 * g12;
        let a = (g22 * d.dot(e1) - g12 * d.dot(e2)) / det;
        let b = (g11 * d.dot(e2) - g12 * d.dot(e1)) / det;
        assert!(
            a >= -1e-4 && b >= -1e-4 && a + b <= 1.0 + 1e-4,
            "{a} {b} off the triangle"
        );
        let uv = (1.0 - a - b) as f32 * t.uvs[0] + a as f32 * t.uvs[1] + b as f32 * t.uvs[2];
        let want = t.at(uv);
        assert!(
            (s.l - want).abs().max_element() <= 1e-3 * want.max_element(),
            "{:?} vs {want:?}",
            s.l
        );
        checked += 1;
    }
    assert_eq!(checked, 64);
}

/// A triangle lamp whose emission is its vertex colours: each light sample
/// carries the colour interpolated at the point it landed on, Σ bₖ cₖ
/// (the corner weights of that point, found from the point itself), as a
/// hit there reads it.
#[test]
fn a_vertex_coloured_lamp_emits_its_interpolated_colour_where_sampled() {
    let colors = [
        Vec3::new(3.0, 0.5, 0.0),
        Vec3::new(0.0, 2.0, 1.0),
        Vec3::new(0.5, 0.0, 4.0),
    ];
    let textures = MaterialTextures {
        emission: Some(SlotTexture {
            source: crate::texture::SlotSource::VertexColor,
            ..striped_emission().textures.emission.clone().unwrap()
        }),
        ..MaterialTextures::default()
    };
    let light = triangle(
        Vec3::ONE,
        Some(TexturedEmission {
            textures: Arc::new(textures),
            colors,
            ..striped_emission()
        }),
    );
    let v = triangle_corners();
    let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
    let p = Vec3::new(0.1, 0.2, 0.0);
    let mut sampler = Sampler::new(SamplerKind::Independent, 0x7e57);
    let mut checked = 0;
    for i in 0..500 {
        sampler.start_pixel_sample(0, 0, i);
        let Some(s) = light.sample_li(p, sampler.next_2d()) else {
            continue;
        };
        checked += 1;
        let q = p + s.distance * s.wi;
        let area = |a: Vec3, b: Vec3, c: Vec3| (b - a).cross(c - a).dot(n);
        let total = area(v[0], v[1], v[2]);
        let b = [
            area(q, v[1], v[2]) / total,
            area(v[0], q, v[2]) / total,
            area(v[0], v[1], q) / total,
        ];
        let want = b[0] * colors[0] + b[1] * colors[1] + b[2] * colors[2];
        assert!(
            (s.l - want).abs().max_element() < 1e-4 * want.max_element(),
            "at {b:?}: {} vs {want}",
            s.l
        );
    }
    // The lamp faces p: every sample lands.
    assert_eq!(checked, 500);
}
