//! Every texture slot in renders, each against what it must give:
//!
//! - **colour on a mirror**: a mirror quad filling the view under a uniform
//!   sky of radiance 1 shows its reflectance, so the image mean is the
//!   texture's texel mean (wrap-around bilinear filtering preserves it);
//! - **cut-outs**: a black quad filling the view in front of the same sky
//!   shows the sky exactly where it is cut out, so the image mean is the
//!   open fraction: 2/3 for a (1, 0, 0) stripe mask with cutoff 1/2, 1 −
//!   mean(alpha) for stochastic opacity;
//! - **a textured lamp seen through a cut-out**: every estimator agrees on
//!   it in the estimator-agreement suite (`agreement_suite.rs`, scene
//!   `common::agreement_scenes::textured_lamp_through_a_cut_out_screen`);
//! - **a flat normal map** ((0.5, 0.5, 1) everywhere) renders the image bit
//!   for bit as without one, with the triangles' own tangent frames and
//!   with per-vertex tangents alike;
//! - **a constant opacity** (glTF's alpha without a texture): 0.25 blended
//!   lets 0.75 of the sky through, below a mask's cutoff all of it; 0.3
//!   (Mitsuba's `mask`) lets 0.7 of the shadow rays that cross it through
//!   (a binomial bound).
//!
//! Means are checked against independent batches (4.5 standard errors,
//! ~5e-4 two-sided with 15 degrees of freedom).

mod common;

use candela_bvh::TraversalStats;
use candela_image::{write_exr, ExrLayers, RgbImage};
use candela_render::camera::framing::CameraMode;
use candela_render::geometry::Ray;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::light::{EnvironmentMap, EnvironmentOptions};
use candela_render::render::{render, RenderSettings};
use candela_render::sampling::{Sampler, SamplerKind};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{
    BsdfDesc, ColorSpace, InstanceDesc, MaterialDesc, MeshDesc, SceneDesc, TextureRef,
};
use glam::Vec3;
use std::sync::Arc;

const SIZE: u32 = 32;
const BATCHES: u64 = 16;

/// A scene of `meshes` and `materials` seen by the camera at the origin
/// looking down −Z (60°).
fn scene_of(meshes: Vec<MeshDesc>, materials: Vec<MaterialDesc>) -> SceneDesc {
    SceneDesc {
        source: "texture slots".into(),
        cameras: vec![common::camera_at(Vec3::ZERO)],
        instances: (0..meshes.len())
            .map(|i| InstanceDesc::identity(i, Default::default()))
            .collect(),
        meshes,
        materials,
        ..Default::default()
    }
}

/// One quad at depth 1 exactly filling the view.
fn view_filling(material: MaterialDesc) -> SceneDesc {
    let h = 30f32.to_radians().tan();
    let q = common::textured_quad(
        Vec3::new(-h, -h, -1.0),
        Vec3::X * 2.0 * h,
        Vec3::Y * 2.0 * h,
        0,
    );
    scene_of(vec![q], vec![material])
}

fn build(desc: &SceneDesc, sky: bool) -> Scene {
    let white = RgbImage::from_fn(8, 4, |_, _| [1.0; 3]).expect("white sky");
    let opts = SceneOptions {
        width: SIZE,
        height: SIZE,
        camera_mode: CameraMode::File,
        environment: sky.then(|| {
            Arc::new(
                EnvironmentMap::from_image(&white, &EnvironmentOptions::default()).expect("sky"),
            )
        }),
        ..Default::default()
    };
    let scene = Scene::build(desc, &opts).expect("scene builds");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert!(scene.unsupported.is_empty(), "{:?}", scene.unsupported);
    scene
}

fn render_batch(scene: &Scene, seed: u64, max_depth: u32) -> RgbImage {
    let settings = RenderSettings {
        spp: 16,
        seed,
        integrator: IntegratorSettings {
            max_depth,
            lighting: LightingMode::Mis,
            roulette: false,
            ..Default::default()
        },
        ..Default::default()
    };
    let out = render(scene, &settings, &|_| {}).expect("render");
    assert_eq!(out.stats.invalid_samples, 0);
    out.film.resolve()
}

/// Asserts the mean of channel 0 over the batches' image means is within
/// 4.5 standard errors of `expected` (plus rounding when the spread is 0).
fn assert_image_mean(label: &str, scene: &Scene, max_depth: u32, expected: f64) {
    let means: Vec<f64> = (0..BATCHES)
        .map(|b| {
            let image = render_batch(scene, 900 + b, max_depth);
            let n = image.pixels().len() as f64;
            image.pixels().iter().map(|p| f64::from(p[0])).sum::<f64>() / n
        })
        .collect();
    let k = means.len() as f64;
    let m = means.iter().sum::<f64>() / k;
    let se = (means.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (k - 1.0) / k).sqrt();
    eprintln!("{label}: {m:.5} ± {se:.5}, expected {expected:.5}");
    assert!(
        (m - expected).abs() < 4.5 * se + 1e-5,
        "{label}: {m} ± {se} vs {expected}"
    );
}

/// Writes a one-channel (grey) EXR of `w × h` values, row 0 at the top.
fn black() -> MaterialDesc {
    common::material("black", BsdfDesc::Diffuse { albedo: Vec3::ZERO }, None)
}

#[test]
fn a_textured_mirror_reflects_its_texture() {
    let dir = candela_testkit::TempDir::new("textured-mirror");
    let path = dir.join("tint.exr");
    let values: Vec<f32> = (0..16)
        .map(|k| 0.05 + 0.9 * ((k * 7) % 16) as f32 / 15.0)
        .collect();
    common::grey_exr(&path, 4, 4, &values);
    let mut mirror = common::material(
        "mirror",
        BsdfDesc::Mirror {
            reflectance: Vec3::ONE,
        },
        None,
    );
    mirror.textures.color = Some(TextureRef::new(&path, ColorSpace::Linear));
    let scene = build(&view_filling(mirror), true);
    let expected = values.iter().map(|&v| f64::from(v)).sum::<f64>() / 16.0;
    assert_image_mean("textured mirror", &scene, 1, expected);
}

#[test]
fn cut_outs_let_the_open_fraction_through() {
    let dir = candela_testkit::TempDir::new("cut-outs");
    // A 3 × 1 mask (1, 0, 0): bilinear values reach the cutoff 1/2 within
    // half a texel of the opaque texel's centre, so one third is opaque.
    let stripes = dir.join("stripes.exr");
    common::grey_exr(&stripes, 3, 1, &[1.0, 0.0, 0.0]);
    let mut masked = black();
    masked.textures.opacity = Some(TextureRef::new(&stripes, ColorSpace::Linear));
    masked.textures.opacity_cutoff = Some(0.5);
    assert_image_mean("mask", &build(&view_filling(masked), true), 1, 2.0 / 3.0);
    // Stochastic opacity: open with probability 1 − alpha.
    let alphas = [0.1f32, 0.9, 0.5, 0.3, 0.7, 0.2, 1.0, 0.0, 0.6];
    let coverage = dir.join("coverage.exr");
    common::grey_exr(&coverage, 3, 3, &alphas);
    let mut blended = black();
    blended.textures.opacity = Some(TextureRef::new(&coverage, ColorSpace::Linear));
    let open = 1.0 - alphas.iter().map(|&a| f64::from(a)).sum::<f64>() / 9.0;
    assert_image_mean("stochastic", &build(&view_filling(blended), true), 1, open);
}

#[test]
fn a_constant_opacity_lets_its_complement_through() {
    // glTF BLEND with a constant alpha 0.25: open with probability 0.75.
    let mut blended = black();
    blended.textures.opacity_constant = Some(0.25);
    assert_image_mean(
        "constant blend",
        &build(&view_filling(blended), true),
        1,
        0.75,
    );
    // glTF MASK with the alpha below the cutoff: not there at all (exactly
    // the sky, so the spread is 0 and the bound is rounding).
    let mut masked = black();
    masked.textures.opacity_constant = Some(0.3);
    masked.textures.opacity_cutoff = Some(0.5);
    assert_image_mean("constant mask", &build(&view_filling(masked), true), 1, 1.0);
}

#[test]
fn a_flat_normal_map_renders_bit_for_bit_as_none() {
    let dir = candela_testkit::TempDir::new("flat-normal-map");
    let flat = dir.join("flat.exr");
    let image = RgbImage::from_fn(2, 2, |_, _| [0.5, 0.5, 1.0]).unwrap();
    write_exr(&flat, &ExrLayers::beauty(image)).unwrap();
    let plain = common::material(
        "plastic",
        BsdfDesc::MetallicRoughness {
            base_color: Vec3::new(0.7, 0.4, 0.2),
            metallic: 0.3,
            roughness: 0.4,
            transmission: 0.0,
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            sheen_color: Vec3::ZERO,
            sheen_roughness: 0.0,
        },
        None,
    );
    let mut mapped = plain.clone();
    mapped.textures.normal = Some(TextureRef::new(&flat, ColorSpace::Linear));
    let render_with = |m: MaterialDesc, tangents: bool| {
        let h = 30f32.to_radians().tan();
        let mut q = common::textured_quad(
            Vec3::new(-h, -h, -1.3),
            Vec3::new(2.0 * h, 0.0, -0.4),
            Vec3::Y * 2.0 * h,
            0,
        );
        if tangents {
            // Any frame: a flat texel must ignore it.
            q.tangents = vec![Vec3::new(0.3, 0.9, 0.1).normalize().extend(-1.0)];
        }
        render_batch(&build(&scene_of(vec![q], vec![m]), true), 5, 3)
    };
    let a = render_with(plain, false);
    assert!(a.pixels().iter().any(|p| p[0] > 0.0), "the quad is lit");
    assert_eq!(a.pixels(), render_with(mapped.clone(), false).pixels());
    assert_eq!(a.pixels(), render_with(mapped, true).pixels());
}

#[test]
fn a_constant_opacity_lets_its_complement_of_shadow_rays_through() {
    // Mitsuba's `mask` with a constant opacity p (glTF's constant alpha
    // too): each shadow ray that crosses the quad passes with probability
    // 1 − p, decided per ray. Binomial bound: 4.5 standard errors.
    let p = 0.3f64;
    let mut thin = black();
    thin.textures.opacity_constant = Some(p as f32);
    let scene = build(&view_filling(thin), false);
    // Segments from in front of the quad (z = −0.5) to behind it
    // (z = −1.5), crossing it well inside its edges (|x|, |y| < 0.58).
    let half = 0.25;
    let mut sampler = Sampler::new(SamplerKind::Independent, 29);
    let n = 20_000u32;
    let mut passed = 0u32;
    for k in 0..n {
        sampler.start_pixel_sample(0, 0, k);
        let (a, b) = (sampler.next_2d(), sampler.next_2d());
        let from = Vec3::new(half * (2.0 * a.x - 1.0), half * (2.0 * a.y - 1.0), -0.5);
        let to = Vec3::new(half * (2.0 * b.x - 1.0), half * (2.0 * b.y - 1.0), -1.5);
        let mut ray = Ray::new(from, (to - from).normalize());
        ray.t_max = (to - from).length();
        if !scene.occluded_visible(&ray, &mut TraversalStats::default()) {
            passed += 1;
        }
    }
    let fraction = f64::from(passed) / f64::from(n);
    let sigma = (p * (1.0 - p) / f64::from(n)).sqrt();
    assert!(
        (fraction - (1.0 - p)).abs() < 4.5 * sigma,
        "{fraction} of shadow rays passed, expected {} ± {}",
        1.0 - p,
        4.5 * sigma
    );
}
