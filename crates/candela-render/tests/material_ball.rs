//! The project's material test ball (`scenes/materials/ball.xml`, written by
//! `scenes/materials/make.py`): every material it offers loads strictly
//! (nothing reported, nothing unsupported), the ball wears the BSDF its id
//! names, and a small render of each is finite and lit.

mod common;

use candela_render::bsdf::Bsdf;
use candela_render::material::Material;
use candela_render::texture::TextureCache;
use candela_scene::{load, LoadOptions, SceneDesc};
use std::path::PathBuf;

fn ball(material: &str) -> SceneDesc {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/materials/ball.xml");
    let options = LoadOptions {
        strict: true,
        defines: vec![("material".into(), material.into())],
        ..LoadOptions::default()
    };
    let loaded = load(&path, &options).unwrap_or_else(|e| panic!("{material}: {e}"));
    assert!(loaded.report.is_empty(), "{material}: {}", loaded.report);
    loaded.scene
}

/// The BSDF of the sphere called "ball".
fn ball_bsdf(desc: &SceneDesc) -> Bsdf {
    let sphere = desc
        .spheres
        .iter()
        .find(|s| s.name == "ball")
        .expect("a ball");
    let (m, unsupported) =
        Material::from_desc(&desc.materials[sphere.material], &mut TextureCache::new());
    assert!(unsupported.is_empty(), "{unsupported:?}");
    m.bsdf.expect("a BSDF")
}

/// Whether a BSDF is of the kind a material id names.
type IsExpected = fn(&Bsdf) -> bool;

#[test]
fn every_ball_material_loads_and_maps_to_its_bsdf() {
    let expect: [(&str, IsExpected); 8] = [
        ("roughglass", |b| matches!(b, Bsdf::RoughGlass { .. })),
        ("glass", |b| matches!(b, Bsdf::Glass { .. })),
        ("roughplastic", |b| matches!(b, Bsdf::RoughPlastic(_))),
        ("plastic", |b| matches!(b, Bsdf::Plastic(_))),
        ("smooth_Au", |b| matches!(b, Bsdf::Conductor { .. })),
        ("Au", |b| matches!(b, Bsdf::Microfacet { .. })),
        ("Fe", |b| matches!(b, Bsdf::Microfacet { .. })),
        ("Ti", |b| matches!(b, Bsdf::Microfacet { .. })),
    ];
    for (id, is_expected) in expect {
        let bsdf = ball_bsdf(&ball(id));
        assert!(is_expected(&bsdf), "{id}: {bsdf:?}");
    }
    for metal in ["Ag", "Al", "Cu", "Cr", "Ni", "W"] {
        assert!(
            matches!(ball_bsdf(&ball(metal)), Bsdf::Microfacet { .. }),
            "{metal}"
        );
    }
}

#[test]
fn a_small_render_of_the_rough_plastic_ball_is_finite_and_lit() {
    let desc = ball("roughplastic");
    // Finite samples are asserted by the helper.
    let image = common::file_camera_batches(&desc, (40, 30), 4, 1, 6, 1).remove(0);
    let pixels = image.pixels();
    assert!(pixels
        .iter()
        .all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)));
    // The ball fills the middle of the frame and is blue (its base colour).
    let centre = pixels[15 * 40 + 20];
    assert!(centre[2] > centre[0] && centre[2] > 0.02, "{centre:?}");
}
