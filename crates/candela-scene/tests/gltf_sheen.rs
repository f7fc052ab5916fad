//! `KHR_materials_sheen`: factors into the glTF model's description (black
//! and 0 by default), textures into their slots (the colour's RGB in sRGB
//! scaled by the factor, the roughness's alpha scaled by its factor, with
//! `KHR_texture_transform`), a coloured factor on a texture, a malformed
//! colour and a broken reference reported by name, the extension itself no
//! longer reported (nor refused when required).

#[allow(dead_code)]
mod gltf;

use candela_scene::{load, BsdfDesc, ColorSpace, LoadOptions, Loaded, TextureSlot};
use glam::Vec3;
use gltf::write;
use serde_json::{json, Value};

fn load_ok(path: &std::path::Path) -> Loaded {
    load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// [`gltf::with_materials`] with the sheen (and texture transforms), the
/// sheen also required, loaded.
fn with_materials(name: &str, materials: Value) -> Loaded {
    let text = gltf::with_materials(&["KHR_materials_sheen", "KHR_texture_transform"], materials);
    let mut doc: Value = serde_json::from_slice(&text).expect("the test's own JSON");
    doc["extensionsRequired"] = json!(["KHR_materials_sheen"]);
    load_ok(&write(name, &serde_json::to_vec(&doc).expect("JSON")))
}

fn sheen_of(bsdf: &BsdfDesc) -> (Vec3, f32) {
    match bsdf {
        BsdfDesc::MetallicRoughness {
            sheen_color,
            sheen_roughness,
            ..
        } => (*sheen_color, *sheen_roughness),
        other => panic!("not the glTF model: {other:?}"),
    }
}

#[test]
fn sheen_factors_and_textures_arrive() {
    let l = with_materials(
        "sheen.gltf",
        json!([
            {"extensions": {"KHR_materials_sheen": {
                "sheenColorFactor": [0.6, 0.6, 0.6],
                "sheenRoughnessFactor": 0.3,
                "sheenColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2.0, 2.0]}}},
                "sheenRoughnessTexture": {"index": 1, "texCoord": 0}}}},
            {"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.5, 0.25]}}},
            {"extensions": {"KHR_materials_sheen": {}}},
            {"pbrMetallicRoughness": {"roughnessFactor": 0.4}}
        ]),
    );
    let m = &l.scene.materials;
    assert_eq!(sheen_of(&m[0].bsdf), (Vec3::splat(0.6), 0.3));
    assert_eq!(
        sheen_of(&m[1].bsdf),
        (Vec3::new(1.0, 0.5, 0.25), 0.0),
        "roughness defaults to 0"
    );
    assert_eq!(
        sheen_of(&m[2].bsdf),
        (Vec3::ZERO, 0.0),
        "the extension's defaults"
    );
    assert_eq!(
        sheen_of(&m[3].bsdf),
        (Vec3::ZERO, 0.0),
        "no extension, no sheen"
    );
    let t = &m[0].textures;
    let color = t.get(TextureSlot::SheenColor).expect("sheenColorTexture");
    let rough = t
        .get(TextureSlot::SheenRoughness)
        .expect("sheenRoughnessTexture");
    assert_eq!(
        (color.channel, rough.channel),
        (None, Some(3)),
        "RGB; alpha"
    );
    assert_eq!(
        (color.color_space, rough.color_space),
        (ColorSpace::Srgb, ColorSpace::Linear)
    );
    // The colour factor is the colour texture's tint (scale 1), the
    // roughness factor the roughness texture's scale.
    assert_eq!((color.tint, color.scale), (Vec3::splat(0.6), 1.0));
    assert!((rough.scale - 0.3).abs() < 1e-6);
    assert!(!color.uv.is_identity() && rough.uv.is_identity());
    assert!(rough
        .image_path()
        .is_some_and(|p| p.ends_with("second texture.png")));
    assert!(m[1].textures.get(TextureSlot::SheenColor).is_none());
    // Nothing reported: neither the extension nor a grey factor.
    assert!(l.report.is_empty(), "{}", l.report);
}

#[test]
fn a_coloured_sheen_factor_tints_its_texture_exactly() {
    let l = with_materials(
        "sheen-coloured-factor.gltf",
        json!([{"extensions": {"KHR_materials_sheen": {
            "sheenColorFactor": [0.9, 0.3, 0.3], "sheenColorTexture": {"index": 0}}}}]),
    );
    let m = &l.scene.materials[0];
    let color = m.textures.get(TextureSlot::SheenColor).expect("texture");
    assert_eq!((color.tint, color.scale), (Vec3::new(0.9, 0.3, 0.3), 1.0));
    assert!(!l.report.mentions("sheenColorFactor"), "{}", l.report);
}

#[test]
fn a_malformed_sheen_colour_and_a_texture_naming_no_texture_are_reported() {
    let l = with_materials(
        "sheen-bad.gltf",
        json!([{"extensions": {"KHR_materials_sheen": {
            "sheenColorFactor": [1.0, "red"], "sheenRoughnessFactor": 0.5,
            "sheenRoughnessTexture": {"index": 9}}}}]),
    );
    let m = &l.scene.materials[0];
    assert_eq!(sheen_of(&m.bsdf), (Vec3::ZERO, 0.5));
    assert!(m.textures.get(TextureSlot::SheenRoughness).is_none());
    assert!(l.report.mentions("sheenColorFactor"), "{}", l.report);
    assert!(l.report.mentions("KHR_materials_sheen"), "{}", l.report);
}
