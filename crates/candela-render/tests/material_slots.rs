//! The description's texture slots through the material build: the colour
//! slot's texture is read in its declared colour space and scaled, and
//! every slot no BSDF uses yet is reported by name, not dropped.

use candela_image::{write_png, RgbImage, ToneMap};
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
    let names: Vec<&str> = unsupported.iter().map(|u| u.0.as_str()).collect();
    assert_eq!(names.len(), 5, "{names:?}");
    for slot in TextureSlot::ALL.into_iter().skip(1) {
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

    // A colour texture on a mirror is reported, not used.
    let mut mirror = linear.clone();
    mirror.bsdf = BsdfDesc::Mirror {
        reflectance: Vec3::ONE,
    };
    let (m, unsupported) = Material::from_desc(&mirror, &mut cache);
    assert!(m.diffuse_texture.is_none());
    assert_eq!(unsupported.len(), 1);
    assert!(
        unsupported[0].0.contains("colour texture"),
        "{unsupported:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
