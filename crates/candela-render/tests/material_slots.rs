//! The description's texture slots through the material build: every slot
//! is read in its declared colour space, channel and scale, and a slot the
//! material's BSDF has no parameter for is reported by name, not dropped.

use candela_image::{write_png, RgbImage, ToneMap};
use candela_render::bsdf::Bsdf;
use candela_render::material::Material;
use candela_render::shape::{PrimRef, SurfaceHit};
use candela_render::texture::TextureCache;
use candela_scene::{BsdfDesc, ColorSpace, MaterialDesc, TextureRef, TextureSlot};
use glam::{Vec2, Vec3};

/// A hit whose only meaningful field is its texture coordinate.
fn hit_at(uv: Vec2) -> SurfaceHit {
    SurfaceHit {
        p: Vec3::ZERO,
        p_error: Vec3::ZERO,
        ng: Vec3::Z,
        ns: Vec3::Z,
        uv,
        vertex_color: Vec3::ONE,
        tangent: None,
        material: 0,
        prim: PrimRef::triangle(0),
        wo: Vec3::Z,
        front_face: true,
        t: 1.0,
    }
}

fn albedo(m: &Material) -> Vec3 {
    match m.bsdf_at(&hit_at(Vec2::new(0.5, 0.5))) {
        Some(candela_render::bsdf::Bsdf::Diffuse { albedo }) => albedo,
        other => panic!("not diffuse: {other:?}"),
    }
}

#[test]
fn every_texture_slot_is_read_or_reported_by_name() {
    let dir = std::env::temp_dir().join(format!("candela-slots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // One flat 8-bit PNG: linear 0.2 is stored as sRGB code 124 (0.486).
    let png = dir.join("flat.png");
    let flat = RgbImage::from_fn(2, 2, |_, _| [0.2; 3]).unwrap();
    write_png(&png, &flat, &ToneMap::default()).unwrap();
    let stored = 124.0 / 255.0;

    let mut desc = MaterialDesc::default_grey();
    desc.name = "everything".into();
    for slot in TextureSlot::ALL {
        desc.textures
            .set(slot, TextureRef::new(&png, slot.default_color_space()));
    }
    desc.textures.color.as_mut().unwrap().scale = 0.5;
    let mut cache = TextureCache::new();
    let (m, unsupported) = Material::from_desc(&desc, &mut cache);
    assert!(cache.problems().is_empty(), "{:?}", cache.problems());
    // sRGB colour, decoded, then scaled: 0.2 x 0.5 (8-bit rounding aside).
    assert!(
        (albedo(&m) - Vec3::splat(0.1)).abs().max_element() < 2e-3,
        "{}",
        albedo(&m)
    );
    // A Lambertian surface has no roughness, metalness, blend weight,
    // clear coat, sheen, transmission or specular layer; every other slot
    // drives something.
    let names: Vec<&str> = unsupported.iter().map(|u| u.0.as_str()).collect();
    let lambert_lacks = [
        TextureSlot::Roughness,
        TextureSlot::Metalness,
        TextureSlot::Weight,
        TextureSlot::Clearcoat,
        TextureSlot::ClearcoatRoughness,
        TextureSlot::Transmission,
        TextureSlot::Specular,
        TextureSlot::SpecularColor,
        TextureSlot::SheenColor,
        TextureSlot::SheenRoughness,
    ];
    assert_eq!(names.len(), lambert_lacks.len(), "{names:?}");
    for slot in lambert_lacks {
        assert!(
            names
                .iter()
                .any(|n| n.contains(slot.name()) && n.contains("'everything'")),
            "{} not reported: {names:?}",
            slot.name()
        );
    }

    // The same file declared linear: its stored values, unscaled.
    let mut linear = MaterialDesc::default_grey();
    linear.textures.color = Some(TextureRef::new(&png, ColorSpace::Linear));
    let (m, unsupported) = Material::from_desc(&linear, &mut cache);
    assert!(unsupported.is_empty());
    assert!(
        (albedo(&m) - Vec3::splat(stored)).abs().max_element() < 1e-5,
        "{}",
        albedo(&m)
    );

    // A colour texture on a mirror is its reflectance.
    let mut mirror = linear.clone();
    mirror.bsdf = BsdfDesc::Mirror {
        reflectance: Vec3::ONE,
    };
    let (m, unsupported) = Material::from_desc(&mirror, &mut cache);
    assert!(unsupported.is_empty(), "{unsupported:?}");
    match m.bsdf_at(&hit_at(Vec2::new(0.5, 0.5))) {
        Some(Bsdf::Mirror { reflectance }) => {
            assert!((reflectance - Vec3::splat(stored)).abs().max_element() < 1e-6)
        }
        other => panic!("{other:?}"),
    }

    // The glTF model takes every slot but a blend's weight; a pure emitter
    // only emission and opacity.
    let mut gltf = desc.clone();
    gltf.bsdf = BsdfDesc::MetallicRoughness {
        base_color: Vec3::ONE,
        metallic: 0.0,
        roughness: 0.5,
        transmission: 0.0,
        ior: 1.5,
        specular: 1.0,
        specular_color: Vec3::ONE,
        clearcoat: 0.0,
        clearcoat_roughness: 0.0,
        sheen_color: Vec3::ZERO,
        sheen_roughness: 0.0,
    };
    let (m, unsupported) = Material::from_desc(&gltf, &mut cache);
    assert!(
        unsupported.len() == 1 && unsupported[0].0.contains(TextureSlot::Weight.name()),
        "{unsupported:?}"
    );
    // The sheen's colour is an sRGB colour (decoded), its roughness a
    // linear value (the stored one).
    match m.bsdf_at(&hit_at(Vec2::new(0.5, 0.5))) {
        Some(Bsdf::MetallicRoughness(mr)) => {
            let (color, roughness) = mr.sheen();
            assert!(
                (color - Vec3::splat(0.2)).abs().max_element() < 2e-3,
                "{color}"
            );
            assert!((roughness - stored).abs() < 2e-5, "{roughness}"); // 16-bit storage
        }
        other => panic!("{other:?}"),
    }
    let mut lamp = desc.clone();
    lamp.bsdf = BsdfDesc::Black;
    let (m, unsupported) = Material::from_desc(&lamp, &mut cache);
    assert_eq!(
        unsupported.len(),
        TextureSlot::ALL.len() - 2,
        "all but emission and opacity: {unsupported:?}"
    );
    assert!(m.emission.is_some(), "the emission texture makes it a lamp");
    std::fs::remove_dir_all(&dir).ok();
}
