//! One Cornell box, five file formats: `scenes/cornell/make.py` writes the
//! built-in demo's box (with the same 32×16 UV spheres everywhere) as
//! COLLADA, glTF, OBJ + MTL and Mitsuba 3 XML (which draws the PLY files).
//! Each loads to the same scene: equal triangle counts, the same emitted
//! light (radiance × area), the same materials, and the same image, checked
//! by a per-block z-test of independent batches of each format against the
//! `.dae` (Bonferroni-corrected over the blocks, `candela_image`'s z-test).
//! OBJ has no camera: it is given the `.dae`'s. The `.gltf` says
//! "Lambertian" as glTF can, with `KHR_materials_specular`'s
//! `specularFactor` 0 (exactly Lambert in Candela's glTF BSDF), and
//! "mirror" as a metal of roughness 0 (a delta lobe whose Schlick Fresnel
//! departs from the `.dae`'s constant 0.95 only at grazing angles, by at
//! most 0.05·(1 − cos θ)⁵).

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_scene::{load, BsdfDesc, LoadOptions, SceneDesc};
use glam::Vec3;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The formats compared with the reference, `cornell.dae`.
const OTHERS: [&str; 3] = ["cornell.gltf", "cornell.obj", "cornell.xml"];
/// Independent batches per format, and samples per pixel in each.
const BATCHES: u64 = 8;
const SPP: u32 = 16;
/// Chance that a correct loader fails one comparison.
const FALSE_ALARM: f64 = 1e-3;
const SIZE: (u32, u32) = (64, 48);

fn scene_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/cornell")
        .join(name)
}

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..LoadOptions::default()
    }
}

/// `name` loaded strictly (no warnings), with the `.dae`'s camera when the
/// format has none.
fn load_variant(name: &str, reference: &SceneDesc) -> SceneDesc {
    let mut desc = load(&scene_file(name), &strict())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .scene;
    if desc.cameras.is_empty() {
        desc.cameras = reference.cameras.clone();
    }
    desc
}

fn reference() -> SceneDesc {
    load(&scene_file("cornell.dae"), &strict()).unwrap().scene
}

/// Radiance × area summed over emissive triangles, in world space.
fn emitted(desc: &SceneDesc) -> Vec3 {
    let mut total = Vec3::ZERO;
    for inst in &desc.instances {
        let mesh = &desc.meshes[inst.mesh];
        let Some(le) = desc.materials[inst.material.unwrap_or(mesh.material)].emission else {
            continue;
        };
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| {
                inst.world_from_object
                    .transform_point3(mesh.positions[i as usize])
            });
            total += le * 0.5 * (b - a).cross(c - a).length();
        }
    }
    total
}

/// Every triangle drawn, as its world-space corners on a 1e-5 grid (corners
/// and triangles sorted, so grouping and corner order do not matter).
fn triangles_drawn(desc: &SceneDesc) -> Vec<[[i64; 3]; 3]> {
    let mut out = Vec::new();
    for inst in &desc.instances {
        let mesh = &desc.meshes[inst.mesh];
        for t in &mesh.triangles {
            let mut corners = t.map(|i| {
                let p = inst
                    .world_from_object
                    .transform_point3(mesh.positions[i as usize]);
                p.to_array().map(|c| (f64::from(c) * 1e5).round() as i64)
            });
            corners.sort();
            out.push(corners);
        }
    }
    out.sort();
    out
}

/// Triangles drawn per material (BSDF and emission): formats that group
/// meshes differently still draw each triangle with the same material.
fn materials_drawn(desc: &SceneDesc) -> BTreeMap<String, usize> {
    let mut out = BTreeMap::new();
    for inst in &desc.instances {
        let mesh = &desc.meshes[inst.mesh];
        let m = &desc.materials[inst.material.unwrap_or(mesh.material)];
        // A black diffuse BSDF reflects nothing, as `Black` does.
        let bsdf = match as_classic(&m.bsdf) {
            BsdfDesc::Diffuse { albedo } if albedo == Vec3::ZERO => BsdfDesc::Black,
            b => b,
        };
        *out.entry(format!("{bsdf:?} {:?}", m.emission)).or_default() += mesh.triangles.len();
    }
    out
}

/// The classic BSDF a glTF material stands for: Lambert when it is a
/// dielectric without a specular layer (exact), a mirror of its base colour
/// when it is a smooth metal (up to Schlick's grazing tail).
fn as_classic(bsdf: &BsdfDesc) -> BsdfDesc {
    match *bsdf {
        BsdfDesc::MetallicRoughness {
            base_color,
            metallic,
            transmission,
            specular,
            ..
        } if metallic == 0.0 && transmission == 0.0 && specular == 0.0 => {
            BsdfDesc::Diffuse { albedo: base_color }
        }
        BsdfDesc::MetallicRoughness {
            base_color,
            metallic,
            roughness,
            ..
        } if metallic == 1.0 && roughness == 0.0 => BsdfDesc::Mirror {
            reflectance: base_color,
        },
        ref other => other.clone(),
    }
}

#[test]
fn every_format_holds_the_same_geometry_light_and_materials() {
    let dae = reference();
    assert!(dae.spheres.is_empty(), "the spheres are tessellated");
    // 5 quads, the lamp, and two 32×16 UV spheres (2·32 + 14·32·2 each).
    assert_eq!(
        dae.instanced_triangle_count(),
        6 * 2 + 2 * (2 * 32 + 14 * 64)
    );
    // Radiance 10 over the 0.6 × 0.6 lamp.
    let light = emitted(&dae);
    assert!(
        (light - Vec3::splat(3.6)).abs().max_element() < 1e-4,
        "{light}"
    );
    for name in OTHERS {
        let other = load_variant(name, &dae);
        assert!(other.spheres.is_empty(), "{name}");
        assert_eq!(
            other.instanced_triangle_count(),
            dae.instanced_triangle_count(),
            "{name}"
        );
        let l = emitted(&other);
        assert!(
            (l - light).abs().max_element() < 1e-4,
            "{name}: {l} vs {light}"
        );
        assert_eq!(materials_drawn(&other), materials_drawn(&dae), "{name}");
        assert!(
            triangles_drawn(&other) == triangles_drawn(&dae),
            "{name}: the triangles differ"
        );
        let (c, d) = (&other.cameras[0], &dae.cameras[0]);
        assert!(
            c.world_from_camera.abs_diff_eq(d.world_from_camera, 1e-5),
            "{name}: camera {:?} vs {:?}",
            c.world_from_camera,
            d.world_from_camera
        );
        let (fc, fd) = (c.fov_deg().unwrap(), d.fov_deg().unwrap());
        assert!((fc.0 - fd.0).abs() < 1e-3, "{name}: fov {fc:?} vs {fd:?}");
    }
}

fn batches(desc: &SceneDesc, seed: u64) -> Vec<RgbImage> {
    common::file_camera_batches(desc, SIZE, SPP, BATCHES, 4, seed)
}

/// Mean colour of columns `x0..x1` over all batches.
fn column_mean(imgs: &[RgbImage], x0: usize, x1: usize) -> Vec3 {
    let mut s = Vec3::ZERO;
    for img in imgs {
        for y in 0..img.height() {
            for x in x0..x1 {
                s += Vec3::from(img.get(x, y).unwrap());
            }
        }
    }
    s
}

#[test]
fn every_format_renders_the_same_image() {
    let dae = reference();
    let imgs = batches(&dae, 1);
    // Not black, not mirrored: red wall on the left, green on the right.
    let (w, _) = SIZE;
    let (left, right) = (
        column_mean(&imgs, 0, 6),
        column_mean(&imgs, w as usize - 6, w as usize),
    );
    assert!(
        left.x > 2.0 * left.y && right.y > 2.0 * right.x,
        "left {left} right {right}"
    );
    let reference = BlockStats::from_batches(&imgs, 8).unwrap();
    for (k, name) in OTHERS.iter().enumerate() {
        let other = load_variant(name, &dae);
        let stats = BlockStats::from_batches(&batches(&other, 2 + k as u64), 8).unwrap();
        let summary = z_test(&stats, &reference, FALSE_ALARM).unwrap().summary();
        eprintln!("{name} vs cornell.dae: {summary:?}");
        assert!(summary.passed(), "{name} vs cornell.dae: {summary:?}");
    }
}
