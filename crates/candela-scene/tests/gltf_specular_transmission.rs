//! The textures of `KHR_materials_transmission` and
//! `KHR_materials_specular`: each in its slot with its factor (the
//! transmitted fraction in red, the specular strength in alpha, both
//! linear; the specular colour sRGB, its factor a per-channel tint), with
//! `KHR_texture_transform`; the extensions' defaults when a factor is
//! absent; nothing reported.

#[allow(dead_code)]
mod gltf;

use candela_scene::{load, ColorSpace, LoadOptions, Loaded, TextureSlot};
use glam::Vec3;
use gltf::write;
use serde_json::{json, Value};

fn load_ok(path: &std::path::Path) -> Loaded {
    load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A document with one material per entry of `materials` and two
/// (unreadable) PNG textures ([`gltf::with_materials`]).
fn with_materials(name: &str, materials: Value) -> Loaded {
    let extensions = [
        "KHR_materials_transmission",
        "KHR_materials_specular",
        "KHR_texture_transform",
    ];
    load_ok(&write(name, &gltf::with_materials(&extensions, materials)))
}

#[test]
fn transmission_and_specular_textures_arrive_with_their_factors_and_channels() {
    let l = with_materials(
        "specular-transmission.gltf",
        json!([
            {"extensions": {
                "KHR_materials_transmission": {
                    "transmissionFactor": 0.6,
                    "transmissionTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2.0, 2.0]}}}},
                "KHR_materials_specular": {
                    "specularFactor": 0.4,
                    "specularTexture": {"index": 1},
                    "specularColorFactor": [1.0, 0.5, 0.25],
                    "specularColorTexture": {"index": 0}}}},
            {"extensions": {
                "KHR_materials_transmission": {"transmissionFactor": 0.3},
                "KHR_materials_specular": {"specularFactor": 0.2}}}
        ]),
    );
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    let m = &l.scene.materials;
    let t = &m[0].textures;
    let transmission = t
        .get(TextureSlot::Transmission)
        .expect("transmissionTexture");
    assert_eq!(transmission.channel, Some(0), "red");
    assert_eq!(transmission.color_space, ColorSpace::Linear);
    assert!((transmission.scale - 0.6).abs() < 1e-6);
    assert!(!transmission.uv.is_identity(), "its KHR_texture_transform");

    let specular = t.get(TextureSlot::Specular).expect("specularTexture");
    assert_eq!(specular.channel, Some(3), "alpha");
    assert_eq!(specular.color_space, ColorSpace::Linear);
    assert!((specular.scale - 0.4).abs() < 1e-6);
    assert!(specular
        .image_path()
        .is_some_and(|p| p.ends_with("second texture.png")));

    let tint = t
        .get(TextureSlot::SpecularColor)
        .expect("specularColorTexture");
    assert_eq!(tint.channel, None, "a colour");
    assert_eq!(tint.color_space, ColorSpace::Srgb);
    assert_eq!(
        tint.tint,
        Vec3::new(1.0, 0.5, 0.25),
        "the factor, per channel"
    );
    assert_eq!(tint.scale, 1.0);

    // Factors without textures fill no slot.
    for slot in [
        TextureSlot::Transmission,
        TextureSlot::Specular,
        TextureSlot::SpecularColor,
    ] {
        assert!(m[1].textures.get(slot).is_none(), "{}", slot.name());
    }
}

#[test]
fn absent_factors_take_the_extensions_defaults() {
    // transmissionFactor 0 (a texture alone transmits nothing, as the
    // extension says), specularFactor 1, specularColorFactor white.
    let l = with_materials(
        "specular-transmission-defaults.gltf",
        json!([
            {"extensions": {
                "KHR_materials_transmission": {"transmissionTexture": {"index": 0}},
                "KHR_materials_specular": {
                    "specularTexture": {"index": 0},
                    "specularColorTexture": {"index": 1}}}},
            {"pbrMetallicRoughness": {"roughnessFactor": 0.4}}
        ]),
    );
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    let t = &l.scene.materials[0].textures;
    let scale = |slot| t.get(slot).map(|t| t.scale);
    assert_eq!(scale(TextureSlot::Transmission), Some(0.0));
    assert_eq!(scale(TextureSlot::Specular), Some(1.0));
    let tint = t
        .get(TextureSlot::SpecularColor)
        .expect("specularColorTexture");
    assert_eq!((tint.tint, tint.scale), (Vec3::ONE, 1.0));
    // No extension, no slots.
    let plain = &l.scene.materials[1].textures;
    assert!(plain.iter().next().is_none(), "{plain:?}");
}

#[test]
fn a_texture_reference_naming_no_texture_is_an_error_not_a_panic() {
    let text = gltf::with_materials(
        &["KHR_materials_specular"],
        json!([{"extensions": {"KHR_materials_specular": {
            "specularColorTexture": {"index": 9}}}}]),
    );
    let path = write("specular-bad-index.gltf", &text);
    let e = load(&path, &LoadOptions::default()).expect_err("index 9 of 2 textures");
    assert!(e.to_string().contains("specularColorTexture"), "{e}");
}
