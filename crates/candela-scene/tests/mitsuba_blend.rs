//! The Mitsuba loader's `blendbsdf`: the description it gives (its two
//! parts with their own textures and sides, nested blends, a weight
//! texture in its slot), what `twosided` around it does, and bad input (a
//! missing or wrong weight, a wrong number of parts, a part's maps).

use candela_scene::{
    load, BlendDesc, BsdfDesc, ErrorKind, LoadError, LoadOptions, Loaded, MaterialDesc, Sides,
    TextureSlot, TextureSource,
};
use glam::Vec3;

mod beside_image;

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..LoadOptions::default()
    }
}

/// Loads a scene of the given elements beside a copy of the conformance
/// scenes' image.
fn try_load(name: &str, body: &str, options: &LoadOptions) -> Result<Loaded, LoadError> {
    let scene = format!(r#"<scene version="3.0.0">{body}</scene>"#);
    let (_dir, path) = beside_image::write_scene(name, &scene);
    load(&path, options)
}

fn blend_of(m: &MaterialDesc) -> &BlendDesc {
    match &m.bsdf {
        BsdfDesc::Blend(b) => b,
        other => panic!("not a blend: {other:?}"),
    }
}

#[test]
fn a_blend_describes_both_parts_with_their_textures_and_sides() {
    let l = try_load(
        "mitsuba-blend",
        r#"
    <bsdf type="roughconductor" id="gold"><string name="material" value="Au"/>
        <float name="alpha" value="0.2"/></bsdf>
    <shape type="sphere"><bsdf type="blendbsdf" id="mix">
        <float name="weight" value="0.3"/>
        <bsdf type="diffuse"><texture type="bitmap" name="reflectance">
            <string name="filename" value="t.png"/></texture></bsdf>
        <ref id="gold"/>
    </bsdf></shape>
    <shape type="sphere"><bsdf type="blendbsdf" id="textured">
        <texture type="bitmap" name="weight"><string name="filename" value="t.png"/>
            <boolean name="raw" value="true"/></texture>
        <bsdf type="dielectric"/>
        <bsdf type="blendbsdf"><float name="weight" value="1"/>
            <bsdf type="diffuse"/><bsdf type="plastic"/></bsdf>
    </bsdf></shape>"#,
        &strict(),
    )
    .unwrap();
    let m = &l.scene.materials;
    let mix = blend_of(&m[0]);
    assert_eq!(mix.weight, 0.3);
    assert_eq!(m[0].sides, Sides::Both, "the parts decide their sides");
    let [diffuse, gold] = &mix.parts;
    assert!(matches!(diffuse.bsdf, BsdfDesc::Diffuse { .. }));
    assert!(
        diffuse.textures.get(TextureSlot::Color).is_some(),
        "the part keeps its texture"
    );
    assert_eq!(diffuse.sides, Sides::Front);
    assert!(matches!(gold.bsdf, BsdfDesc::Conductor { alpha, .. } if alpha.u == 0.2));
    assert_eq!(gold.sides, Sides::Front);

    let textured = blend_of(&m[1]);
    let weight = m[1]
        .textures
        .get(TextureSlot::Weight)
        .expect("the weight's texture");
    assert!(matches!(&weight.source, TextureSource::Image(p) if p.ends_with("t.png")));
    assert!(matches!(textured.parts[0].bsdf, BsdfDesc::Glass { .. }));
    assert_eq!(textured.parts[0].sides, Sides::Both, "glass transmits");
    let inner = blend_of(&textured.parts[1]);
    assert_eq!(inner.weight, 1.0);
    assert!(matches!(inner.parts[1].bsdf, BsdfDesc::Plastic { alpha, .. } if alpha == 0.0));
}

#[test]
fn twosided_around_a_blend_makes_its_parts_two_sided() {
    let l = try_load(
        "mitsuba-blend-twosided",
        r#"<shape type="rectangle"><bsdf type="twosided"><bsdf type="blendbsdf">
        <float name="weight" value="0.5"/>
        <bsdf type="diffuse"/>
        <bsdf type="blendbsdf"><float name="weight" value="0.5"/>
            <bsdf type="roughconductor"/><bsdf type="roughplastic"/></bsdf>
    </bsdf></bsdf></shape>"#,
        &strict(),
    )
    .unwrap();
    let outer = blend_of(&l.scene.materials[0]);
    assert_eq!(outer.parts[0].sides, Sides::Both);
    let inner = blend_of(&outer.parts[1]);
    assert!(inner.parts.iter().all(|p| p.sides == Sides::Both));
}

#[test]
fn a_checkerboard_weight_is_read_as_mitsuba_reads_one_value() {
    // Mitsuba's one-value checkerboard swaps the colours, which in
    // Candela's mirrored v keeps them in the description's order (as for
    // roughness, `mitsuba/textures.rs`), and reads an RGB colour by the
    // mean of its channels (0.5 here; its luminance would be 0.39).
    let l = try_load(
        "mitsuba-blend-checker",
        r#"<shape type="sphere"><bsdf type="blendbsdf">
        <texture type="checkerboard" name="weight">
            <rgb name="color0" value="0.2, 0.4, 0.9"/><float name="color1" value="0.1"/></texture>
        <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf></shape>"#,
        &strict(),
    )
    .unwrap();
    let t = l.scene.materials[0]
        .textures
        .get(TextureSlot::Weight)
        .unwrap();
    let TextureSource::Checkerboard { color0, color1 } = t.source else {
        panic!("{t:?}");
    };
    assert_eq!((color0, color1), (Vec3::splat(0.5), Vec3::splat(0.1)));
}

#[test]
fn bad_blends_are_errors_naming_the_element() {
    for (body, says) in [
        (
            r#"<bsdf type="blendbsdf" id="b"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "no \"weight\"",
        ),
        (
            r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="0.5"/><bsdf type="diffuse"/></bsdf>"#,
            "exactly two inner BSDFs",
        ),
        (
            r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="0.5"/>
                <bsdf type="diffuse"/><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "exactly two inner BSDFs",
        ),
        (
            r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="0.5"/>
                <bsdf type="diffuse"/><bsdf type="velvet"/></bsdf>"#,
            "unknown BSDF type \"velvet\"",
        ),
        (
            r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="nan"/>
                <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
            "not finite",
        ),
    ] {
        let err = try_load("mitsuba-blend-bad", body, &LoadOptions::default()).unwrap_err();
        let text = err.to_string();
        assert!(text.contains(says) && text.contains("scene.xml"), "{text}");
        assert!(err.loc.is_some() && !text.contains('\n'), "{text}");
        assert!(
            matches!(
                err.kind,
                ErrorKind::BadValue | ErrorKind::MissingElement | ErrorKind::NonFinite
            ),
            "{err:?}"
        );
    }
}

#[test]
fn a_weight_outside_the_unit_interval_and_a_parts_maps_are_reported() {
    let l = try_load(
        "mitsuba-blend-reported",
        r#"<shape type="sphere"><bsdf type="blendbsdf">
        <float name="weight" value="1.5"/>
        <bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="t.png"/>
            <boolean name="raw" value="true"/></texture><bsdf type="diffuse"/></bsdf>
        <bsdf type="diffuse"/></bsdf></shape>"#,
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(l.report.mentions("outside [0, 1]"), "{}", l.report);
    assert!(
        l.report.mentions("bump map of its first BSDF"),
        "{}",
        l.report
    );
    let m = &l.scene.materials[0];
    let blend = blend_of(m);
    assert_eq!(blend.weight, 1.0, "clamped, as Mitsuba clamps it");
    assert!(blend.parts[0].textures.get(TextureSlot::Bump).is_none());
    // Strict loading refuses what it would report.
    assert!(try_load(
        "mitsuba-blend-reported-strict",
        r#"<bsdf type="blendbsdf" id="b"><float name="weight" value="-0.1"/>
        <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>"#,
        &strict(),
    )
    .is_err());
}
