//! Image textures in renders: a textured quad exactly filling the view,
//! lit by a uniform environment of radiance 1, reflects `albedo(uv)` at
//! every point (∫ albedo/π · cos dω = albedo). The quad faces the camera,
//! so film position maps affinely to `uv` and
//! - the image mean is the texture's mean over one period, which for
//!   wrap-around bilinear filtering is exactly the mean of its texels;
//! - each pixel's expected value is the texture at the pixel's centre
//!   (the texel-centre lines fall on pixel boundaries, and a bilinear
//!   patch averages over a box to its centre value).
//!
//! Both are checked against independent batches: the mean within a bound
//! from the batches' spread, the image by the block z-test against the
//! exact expected image. A missing texture file is reported once and
//! falls back to the flat colour.

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::{write_exr, ExrLayers, RgbImage};
use candela_render::camera::framing::CameraMode;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::light::{EnvironmentMap, EnvironmentOptions};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_render::texture::ImageTexture;
use candela_scene::{
    BsdfDesc, ColorSpace, MaterialDesc, MeshDesc, SceneDesc, TextureRef, TextureWrap,
};
use glam::{Vec2, Vec3};
use std::path::Path;
use std::sync::Arc;

const SIZE: u32 = 32;
const BATCHES: u64 = 16;

/// A 4 × 4 texture with no symmetry, values in [0.05, 0.95].
fn texture_image() -> RgbImage {
    RgbImage::from_fn(4, 4, |x, y| {
        let k = (x * 7 + y * 13 + x * y * 5) % 16;
        let f = |s: usize| 0.05 + 0.9 * ((k + s) % 16) as f32 / 15.0;
        [f(0), f(5), f(11)]
    })
    .expect("texture")
}

/// A quad at depth 1 facing the camera, exactly filling a square view of
/// half-angle `atan(half)`, with `uv` (0, 0) at its bottom left.
fn textured_quad(half: f32, material: MaterialDesc) -> SceneDesc {
    let mesh = MeshDesc {
        name: "quad".into(),
        positions: vec![
            Vec3::new(-half, -half, -1.0),
            Vec3::new(half, -half, -1.0),
            Vec3::new(half, half, -1.0),
            Vec3::new(-half, half, -1.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        normals: vec![Vec3::Z],
        normal_indices: vec![[0; 3]; 2],
        uvs: vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ],
        uv_indices: vec![[0, 1, 2], [0, 2, 3]],
        material: 0,
        ..Default::default()
    };
    SceneDesc {
        source: "textured quad".into(),
        cameras: vec![common::camera_at(Vec3::ZERO)],
        meshes: vec![mesh],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        materials: vec![material],
        ..Default::default()
    }
}

fn textured(name: &str, path: &Path) -> MaterialDesc {
    let mut m = common::material(
        name,
        BsdfDesc::Diffuse {
            albedo: Vec3::splat(0.5),
        },
        None,
    );
    m.textures.color = Some(TextureRef::new(path, ColorSpace::of_image_file(path)));
    m
}

fn build(desc: &SceneDesc) -> Scene {
    let white = RgbImage::from_fn(8, 4, |_, _| [1.0; 3]).expect("white sky");
    let opts = SceneOptions {
        width: SIZE,
        height: SIZE,
        camera_mode: CameraMode::File,
        environment: Some(Arc::new(
            EnvironmentMap::from_image(&white, &EnvironmentOptions::default()).expect("sky"),
        )),
        ..Default::default()
    };
    Scene::build(desc, &opts).expect("scene builds")
}

fn batches(scene: &Scene) -> Vec<RgbImage> {
    (0..BATCHES)
        .map(|seed| {
            let settings = RenderSettings {
                spp: 16,
                seed: 500 + seed,
                integrator: IntegratorSettings {
                    max_depth: 1,
                    lighting: LightingMode::Mis,
                    roulette: false,
                    ..Default::default()
                },
                ..Default::default()
            };
            let out = render(scene, &settings, &|_| {}).expect("render");
            assert_eq!(out.stats.invalid_samples, 0);
            out.film.resolve()
        })
        .collect()
}

fn image_mean(image: &RgbImage) -> [f64; 3] {
    let mut sum = [0.0f64; 3];
    for p in image.pixels() {
        for c in 0..3 {
            sum[c] += f64::from(p[c]);
        }
    }
    sum.map(|s| s / image.pixels().len() as f64)
}

#[test]
fn a_textured_quad_renders_the_texture() {
    let dir = candela_testkit::TempDir::new("textured-quad");
    let path = dir.join("albedo.exr");
    write_exr(&path, &ExrLayers::beauty(texture_image())).expect("write texture");
    let texture = ImageTexture::load(&path).expect("texture loads");
    let half = 30f32.to_radians().tan();
    let scene = build(&textured_quad(half, textured("checker", &path)));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert!((scene.camera.tan_half_width - half).abs() < 1e-6);
    assert!((scene.camera.tan_half_height - half).abs() < 1e-6);
    let images = batches(&scene);

    // The image mean against the texel mean, bound from the batches.
    let means: Vec<[f64; 3]> = images.iter().map(image_mean).collect();
    let expected = texture.mean();
    for c in 0..3 {
        let k = means.len() as f64;
        let m = means.iter().map(|v| v[c]).sum::<f64>() / k;
        let var = means.iter().map(|v| (v[c] - m).powi(2)).sum::<f64>() / (k - 1.0);
        let se = (var / k).sqrt();
        let e = f64::from(expected[c]);
        eprintln!("channel {c}: image mean {m:.5} ± {se:.5}, texel mean {e:.5}");
        assert!(se < 0.01 * e, "the test needs a tight estimate");
        // 4.5 standard errors (t with 15 dof: ~5e-4 two-sided per channel).
        assert!((m - e).abs() < 4.5 * se, "channel {c}: {m} vs {e} ± {se}");
    }

    // Orientation, independently of `lookup`: pixel (8i + 4, 8j + 4)
    // (y down) has its centre 1/16 texel right of and below the centre of
    // texel (i, j) of the file (row 0 at the top), so its value is the
    // bilinear mix 15/16 : 1/16 with the next texel right and down
    // (wrapping).
    let file = texture_image();
    let texel = |i: usize, j: usize| file.get(i % 4, j % 4).expect("texel");
    for j in 0..4 {
        for i in 0..4 {
            let (a, b) = (15.0 / 16.0, 1.0 / 16.0);
            let want: [f64; 3] = std::array::from_fn(|c| {
                let t = |i, j| f64::from(texel(i, j)[c]);
                a * a * t(i, j)
                    + b * a * t(i + 1, j)
                    + a * b * t(i, j + 1)
                    + b * b * t(i + 1, j + 1)
            });
            let values: Vec<[f32; 3]> = images
                .iter()
                .map(|img| img.get(8 * i + 4, 8 * j + 4).expect("pixel"))
                .collect();
            for c in 0..3 {
                let k = values.len() as f64;
                let m = values.iter().map(|v| f64::from(v[c])).sum::<f64>() / k;
                let var = values
                    .iter()
                    .map(|v| (f64::from(v[c]) - m).powi(2))
                    .sum::<f64>()
                    / (k - 1.0);
                let se = (var / k).sqrt();
                // 6 standard errors over 48 tests (t, 15 dof): ~1e-3.
                assert!(
                    (m - want[c]).abs() < 6.0 * se + 1e-6,
                    "pixel at texel ({i}, {j}) channel {c}: rendered {m:.4} ± {se:.4}, expected {:.4}",
                    want[c]
                );
            }
        }
    }

    // Every 8 × 8 block against the exact image.
    let exact = RgbImage::from_fn(SIZE as usize, SIZE as usize, |x, y| {
        let uv = Vec2::new(
            (x as f32 + 0.5) / SIZE as f32,
            1.0 - (y as f32 + 0.5) / SIZE as f32,
        );
        texture.lookup(uv, TextureWrap::REPEAT).to_array()
    })
    .expect("exact image");
    let zero = RgbImage::new(SIZE as usize, SIZE as usize).expect("zeros");
    let reference = BlockStats::from_pixel_errors(&exact, &zero, 8).expect("reference");
    let rendered = BlockStats::from_batches(&images, 8).expect("render stats");
    let summary = z_test(&rendered, &reference, 1e-3)
        .expect("z-test")
        .summary();
    eprintln!("textured quad vs exact: {summary:?}");
    assert!(summary.passed(), "{summary:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_missing_texture_is_reported_once_and_the_flat_colour_used() {
    let dir = candela_testkit::TempDir::new("missing-texture");
    let path = dir.join("nowhere.png");
    let mut desc = textured_quad(30f32.to_radians().tan(), textured("a", &path));
    desc.materials.push(textured("b", &path));
    let scene = build(&desc);
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].contains("nowhere.png"));
    assert!(scene.materials.iter().all(|m| m.textures.color.is_none()));
    // Flat grey 0.5 under a white sky: every pixel converges to 0.5.
    let images = batches(&scene);
    let means: Vec<f64> = images.iter().map(|i| image_mean(i)[1]).collect();
    let k = means.len() as f64;
    let m = means.iter().sum::<f64>() / k;
    let se = (means.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (k - 1.0) / k).sqrt();
    eprintln!("flat fallback: {m:.5} ± {se:.5}");
    assert!((m - 0.5).abs() < 4.5 * se, "{m} ± {se}");
    std::fs::remove_dir_all(&dir).ok();
}
