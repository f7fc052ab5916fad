//! The Mitsuba loader's textures read into the description: bitmaps with
//! their filter and `to_uv`, checkerboards (as a colour and as one value),
//! wrap modes, an area emitter's radiance, and what is still unsupported
//! (a mesh attribute other than the vertex colours) reported once by name.

use candela_scene::{
    load, LoadOptions, Loaded, MaterialDesc, TextureFilter, TextureRef, TextureSlot, TextureSource,
    TextureWrap, WrapMode,
};
use glam::{Vec2, Vec3};

mod beside_image;

/// Loads `body` (a scene) beside a copy of the conformance scenes' image.
fn load_scene(name: &str, body: &str) -> Loaded {
    let (_dir, path) = beside_image::write_scene(name, body);
    load(&path, &LoadOptions::default()).unwrap()
}

fn material<'a>(l: &'a Loaded, name: &str) -> &'a MaterialDesc {
    l.scene
        .materials
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no material {name}"))
}

fn slot(m: &MaterialDesc, slot: TextureSlot) -> &TextureRef {
    m.textures.get(slot).expect("a texture in the slot")
}

/// Where `t` reads at Candela's `uv`, against where Mitsuba reads at the
/// same surface point, `mitsuba(u, v_m)` with v_m = 1 − v, brought back
/// into Candela's v.
fn assert_reads_like(t: &TextureRef, mitsuba: impl Fn(Vec2) -> Vec2) {
    for uv in [
        Vec2::new(0.1, 0.2),
        Vec2::new(0.8, 0.35),
        Vec2::new(0.45, 0.9),
    ] {
        let m = mitsuba(Vec2::new(uv.x, 1.0 - uv.y));
        let expected = Vec2::new(m.x, 1.0 - m.y);
        let got = t.uv.apply(uv);
        assert!(
            (got - expected).abs().max_element() < 1e-5,
            "{got} vs {expected} at {uv}"
        );
    }
}

const SCENE: &str = r#"<scene version="3.0.0">
    <texture type="checkerboard" id="shared">
        <rgb name="color0" value="0.8, 0.1, 0.1"/>
        <rgb name="color1" value="0.1, 0.1, 0.8"/>
        <transform name="to_uv"><scale x="4" y="2"/></transform>
    </texture>
    <bsdf type="diffuse" id="bitmap">
        <texture type="bitmap" name="reflectance">
            <string name="filename" value="t.png"/>
            <string name="filter_type" value="nearest"/>
            <transform name="to_uv">
                <scale x="2" y="3"/>
                <translate x="0.25" y="0.5"/>
            </transform>
        </texture>
    </bsdf>
    <bsdf type="diffuse" id="checker">
        <ref name="reflectance" id="shared"/>
    </bsdf>
    <bsdf type="roughconductor" id="rough">
        <texture type="checkerboard" name="alpha">
            <float name="color0" value="0.05"/>
            <float name="color1" value="0.3"/>
        </texture>
    </bsdf>
    <shape type="rectangle"><ref id="bitmap"/></shape>
    <shape type="rectangle"><ref id="checker"/></shape>
    <shape type="rectangle"><ref id="rough"/></shape>
</scene>"#;

#[test]
fn bitmaps_keep_their_filter_and_to_uv() {
    let l = load_scene("mitsuba-tex-bitmap", SCENE);
    assert!(l.report.is_empty(), "{}", l.report);
    let t = slot(material(&l, "bitmap"), TextureSlot::Color);
    assert!(matches!(&t.source, TextureSource::Image(p) if p.ends_with("t.png")));
    assert_eq!(t.filter, TextureFilter::Nearest);
    // Mitsuba composes later steps after earlier ones: scale, then shift.
    assert_reads_like(t, |m| Vec2::new(2.0 * m.x + 0.25, 3.0 * m.y + 0.5));
}

#[test]
fn checkerboards_keep_their_colours_cells_and_to_uv() {
    let l = load_scene("mitsuba-tex-checker", SCENE);
    let t = slot(material(&l, "checker"), TextureSlot::Color);
    assert_reads_like(t, |m| Vec2::new(4.0 * m.x, 2.0 * m.y));
    // Mitsuba reads color0 at its uv (0.05, 0.1) (to_uv: (0.2, 0.2), in
    // its cell [0, ½]²): Candela's uv (0.05, 0.9).
    assert_eq!(colour_at(t, Vec2::new(0.05, 0.9)), Vec3::new(0.8, 0.1, 0.1));
    assert_eq!(colour_at(t, Vec2::new(0.2, 0.9)), Vec3::new(0.1, 0.1, 0.8));
    // Read as one value Mitsuba swaps its colours (eval_1): at its uv
    // (0.2, 0.2) the roughness is color1's 0.3.
    let r = slot(material(&l, "rough"), TextureSlot::Roughness);
    assert_eq!(colour_at(r, Vec2::new(0.2, 0.8)), Vec3::splat(0.3));
    assert_eq!(colour_at(r, Vec2::new(0.7, 0.8)), Vec3::splat(0.05));
}

/// The description's checkerboard `t` at Candela's `uv`.
fn colour_at(t: &TextureRef, uv: Vec2) -> Vec3 {
    let TextureSource::Checkerboard { color0, color1 } = t.source else {
        panic!("{:?}", t.source)
    };
    if TextureSource::checker_cell_is_even(t.uv.apply(uv)) {
        color0
    } else {
        color1
    }
}

#[test]
fn wrap_modes_are_kept_for_both_axes_and_unsupported_types_reported_once_by_name() {
    let bitmap = |id: &str, mode: &str| {
        format!(
            r#"<bsdf type="diffuse" id="{id}">
        <texture type="bitmap" name="reflectance">
            <string name="filename" value="t.png"/>
            <string name="wrap_mode" value="{mode}"/>
        </texture>
    </bsdf>
    <shape type="rectangle"><ref id="{id}"/></shape>"#
        )
    };
    let l = load_scene(
        "mitsuba-tex-unsupported",
        &format!(
            r#"<scene version="3.0.0">
    {}{}{}
    <bsdf type="diffuse" id="b">
        <texture type="mesh_attribute" name="reflectance">
            <string name="name" value="face_color"/>
        </texture>
    </bsdf>
    <shape type="rectangle"><ref id="b"/></shape>
</scene>"#,
            bitmap("m", "mirror"),
            bitmap("c", "clamp"),
            bitmap("r", "repeat")
        ),
    );
    assert_eq!(l.report.len(), 1, "{}", l.report);
    // Vertex colours are read; another mesh attribute is named.
    assert!(l.report.mentions("\"face_color\""), "{}", l.report);
    for (id, mode) in [
        ("m", WrapMode::Mirror),
        ("c", WrapMode::Clamp),
        ("r", WrapMode::Repeat),
    ] {
        let t = slot(material(&l, id), TextureSlot::Color);
        assert_eq!(t.wrap, TextureWrap::both(mode), "{id}");
    }
    let dir = candela_testkit::TempDir::new("mitsuba-tex-bad-wrap");
    std::fs::write(dir.join("t.png"), b"not read").unwrap();
    let path = dir.join("scene.xml");
    std::fs::write(
        &path,
        format!(r#"<scene version="3.0.0">{}</scene>"#, bitmap("x", "wrap")),
    )
    .unwrap();
    let err = load(&path, &LoadOptions::default()).unwrap_err();
    assert!(
        err.to_string().contains("unknown wrap_mode \"wrap\""),
        "{err}"
    );
}

#[test]
fn a_textured_area_emitter_puts_its_radiance_in_the_emission_slot() {
    let l = load_scene(
        "mitsuba-tex-emitter",
        r#"<scene version="3.0.0">
    <shape type="sphere" id="lamp">
        <emitter type="area">
            <texture type="bitmap" name="radiance">
                <string name="filename" value="t.png"/>
                <string name="filter_type" value="nearest"/>
            </texture>
        </emitter>
    </shape>
</scene>"#,
    );
    // Read, not replaced by a constant (which was reported before).
    assert!(l.report.is_empty(), "{}", l.report);
    let m = &l.scene.materials[l.scene.spheres[0].material];
    assert!(m.emission.is_some(), "the material emits");
    let t = slot(m, TextureSlot::Emission);
    assert!(matches!(&t.source, TextureSource::Image(p) if p.ends_with("t.png")));
    assert_eq!(t.filter, TextureFilter::Nearest);
}
