//! `KHR_materials_clearcoat`: factors into the glTF model's description,
//! textures into their slots (red and green, scaled by the factors, with
//! `KHR_texture_transform`), the coat's normal map and broken references
//! reported by name, the extension itself no longer reported.

#[allow(dead_code)]
mod gltf;

use candela_scene::{load, BsdfDesc, LoadOptions, Loaded, TextureSlot};
use gltf::write;
use serde_json::{json, Value};

fn load_ok(path: &std::path::Path) -> Loaded {
    load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A document with one material per entry of `materials` and two
/// (unreadable) PNG textures ([`gltf::with_materials`]).
fn with_materials(name: &str, materials: Value) -> Loaded {
    let extensions = ["KHR_materials_clearcoat", "KHR_texture_transform"];
    load_ok(&write(name, &gltf::with_materials(&extensions, materials)))
}

fn coat_of(bsdf: &BsdfDesc) -> (f32, f32) {
    match bsdf {
        BsdfDesc::MetallicRoughness {
            clearcoat,
            clearcoat_roughness,
            ..
        } => (*clearcoat, *clearcoat_roughness),
        other => panic!("not the glTF model: {other:?}"),
    }
}

#[test]
fn clearcoat_factors_and_textures_arrive() {
    let l = with_materials(
        "clearcoat.gltf",
        json!([
            {"extensions": {"KHR_materials_clearcoat": {
                "clearcoatFactor": 0.7,
                "clearcoatRoughnessFactor": 0.3,
                "clearcoatTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2.0, 2.0]}}},
                "clearcoatRoughnessTexture": {"index": 1, "texCoord": 0},
                "clearcoatNormalTexture": {"index": 0}}}},
            {"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}},
            {"pbrMetallicRoughness": {"roughnessFactor": 0.4}}
        ]),
    );
    let m = &l.scene.materials;
    assert_eq!(coat_of(&m[0].bsdf), (0.7, 0.3));
    assert_eq!(coat_of(&m[1].bsdf), (1.0, 0.0), "the extension's defaults");
    assert_eq!(coat_of(&m[2].bsdf), (0.0, 0.0), "no extension, no coat");
    let t = &m[0].textures;
    let coat = t.get(TextureSlot::Clearcoat).expect("clearcoatTexture");
    let rough = t
        .get(TextureSlot::ClearcoatRoughness)
        .expect("clearcoatRoughnessTexture");
    assert_eq!((coat.channel, rough.channel), (Some(0), Some(1)));
    assert!((coat.scale - 0.7).abs() < 1e-6 && (rough.scale - 0.3).abs() < 1e-6);
    assert!(!coat.uv.is_identity() && rough.uv.is_identity());
    assert!(rough
        .image_path()
        .is_some_and(|p| p.ends_with("second texture.png")));
    assert!(m[1].textures.get(TextureSlot::Clearcoat).is_none());
    // Only the coat's normal map is reported, once, by name.
    assert!(
        !l.report.mentions("KHR_materials_clearcoat"),
        "{}",
        l.report
    );
    assert!(l.report.mentions("clearcoatNormalTexture"), "{}", l.report);
    assert_eq!(l.report.len(), 1, "{}", l.report);
}

#[test]
fn a_clearcoat_texture_naming_no_texture_is_reported_and_not_used() {
    let l = with_materials(
        "clearcoat-bad-index.gltf",
        json!([{"extensions": {"KHR_materials_clearcoat": {
            "clearcoatFactor": 0.5, "clearcoatTexture": {"index": 9}}}}]),
    );
    let m = &l.scene.materials[0];
    assert_eq!(coat_of(&m.bsdf), (0.5, 0.0));
    assert!(m.textures.get(TextureSlot::Clearcoat).is_none());
    assert!(l.report.mentions("KHR_materials_clearcoat"), "{}", l.report);
}
