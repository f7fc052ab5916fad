//! The Mitsuba loader's sides and roughness axes: which sides of a surface
//! scatter (one-sided BSDFs, `twosided` with one or two BSDFs, the
//! dielectrics, a shape's default BSDF), anisotropic `alpha_u`/`alpha_v`,
//! and a sphere's parameterisation axes from its `to_world`.

use candela_scene::{load, Alpha, BsdfDesc, LoadOptions, Loaded, MaterialDesc, Sides, SphereDesc};
use glam::{Mat3, Vec3};

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..LoadOptions::default()
    }
}

/// Loads a scene of the given shapes (strictly: nothing may be reported).
fn load_shapes(name: &str, shapes: &str) -> Loaded {
    let dir = candela_testkit::TempDir::new(name);
    let path = dir.join("scene.xml");
    std::fs::write(&path, format!(r#"<scene version="3.0.0">{shapes}</scene>"#)).unwrap();
    load(&path, &strict()).unwrap()
}

fn albedo(m: &MaterialDesc) -> Vec3 {
    match m.bsdf {
        BsdfDesc::Diffuse { albedo } => albedo,
        ref other => panic!("not diffuse: {other:?}"),
    }
}

#[test]
fn opaque_bsdfs_are_one_sided_unless_twosided_and_a_second_bsdf_is_the_back() {
    let l = load_shapes(
        "mitsuba-sides",
        r#"
    <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.1"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="twosided"><bsdf type="diffuse">
        <rgb name="reflectance" value="0.2"/></bsdf></bsdf></shape>
    <shape type="rectangle"><bsdf type="twosided">
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.4"/></bsdf></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughconductor"/></shape>
    <shape type="rectangle"><bsdf type="roughplastic"/></shape>
    <shape type="rectangle"><bsdf type="dielectric"/></shape>
    <shape type="rectangle"><bsdf type="roughdielectric"/></shape>
    <shape type="rectangle"><bsdf type="thindielectric"/></shape>
    <shape type="rectangle"/>"#,
    );
    let m = &l.scene.materials;
    assert_eq!(m.len(), 9);
    assert_eq!(
        (albedo(&m[0]), &m[0].sides),
        (Vec3::splat(0.1), &Sides::Front)
    );
    assert_eq!(
        (albedo(&m[1]), &m[1].sides),
        (Vec3::splat(0.2), &Sides::Both)
    );
    assert_eq!(albedo(&m[2]), Vec3::splat(0.3));
    let Sides::Back(back) = &m[2].sides else {
        panic!("twosided with two BSDFs: {:?}", m[2].sides)
    };
    assert_eq!(
        (albedo(back), &back.sides),
        (Vec3::splat(0.4), &Sides::Both)
    );
    assert_eq!(m[3].sides, Sides::Front, "roughconductor");
    assert_eq!(m[4].sides, Sides::Front, "roughplastic");
    for (i, name) in [
        (5, "dielectric"),
        (6, "roughdielectric"),
        (7, "thindielectric"),
    ] {
        assert_eq!(m[i].sides, Sides::Both, "{name}");
    }
    // A shape without a BSDF gets Mitsuba's one-sided diffuse 0.5.
    assert_eq!(
        (albedo(&m[8]), &m[8].sides),
        (Vec3::splat(0.5), &Sides::Front)
    );
}

#[test]
fn a_shared_bsdf_keeps_its_sides_and_an_emitter_keeps_its_bsdfs() {
    let l = load_shapes(
        "mitsuba-sides-ref",
        r#"
    <bsdf type="twosided" id="both"><bsdf type="diffuse"/></bsdf>
    <bsdf type="diffuse" id="front"/>
    <shape type="rectangle"><ref id="both"/></shape>
    <shape type="rectangle"><ref id="front"/>
        <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"#,
    );
    let m = &l.scene.materials;
    assert_eq!(m[0].sides, Sides::Both);
    assert_eq!(m[1].sides, Sides::Front);
    assert_eq!(m[1].emission, Some(Vec3::ONE));
}

#[test]
fn a_lamp_without_a_bsdf_is_black_and_a_plain_shape_grey() {
    let l = load_shapes(
        "mitsuba-lamp-default",
        r#"
    <shape type="rectangle">
        <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
    <shape type="rectangle"/>"#,
    );
    let m = &l.scene.materials;
    let lamp = m.iter().find(|m| m.emission.is_some()).unwrap();
    let plain = m.iter().find(|m| m.emission.is_none()).unwrap();
    assert_eq!(lamp.bsdf, BsdfDesc::Black);
    assert_eq!(lamp.emission, Some(Vec3::splat(2.0)));
    assert_eq!(plain.sides, Sides::Front);
    assert!(
        matches!(plain.bsdf, BsdfDesc::Diffuse { albedo } if albedo == Vec3::splat(0.5)),
        "{:?}",
        plain.bsdf
    );
}

#[test]
fn twosided_around_a_dielectric_is_reported_and_the_dielectric_kept() {
    let dir = candela_testkit::TempDir::new("mitsuba-sides-glass");
    let path = dir.join("scene.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0"><shape type="rectangle">
        <bsdf type="twosided"><bsdf type="dielectric"/></bsdf></shape></scene>"#,
    )
    .unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert!(matches!(l.scene.materials[0].bsdf, BsdfDesc::Glass { .. }));
    assert_eq!(l.scene.materials[0].sides, Sides::Both);
    assert_eq!(l.report.len(), 1, "{}", l.report);
    assert!(l.report.mentions("twosided"), "{}", l.report);
    assert!(load(&path, &strict()).is_err());
}

#[test]
fn anisotropic_roughness_keeps_both_alphas() {
    let l = load_shapes(
        "mitsuba-alphas",
        r#"
    <shape type="rectangle"><bsdf type="roughconductor">
        <float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughdielectric"><string name="distribution" value="ggx"/>
        <float name="alpha_u" value="0.3"/><float name="alpha_v" value="0.1"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="roughconductor">
        <float name="alpha" value="0.25"/></bsdf></shape>"#,
    );
    let m = &l.scene.materials;
    let alpha = |i: usize| match m[i].bsdf {
        BsdfDesc::Conductor { alpha, .. } | BsdfDesc::RoughDielectric { alpha, .. } => alpha,
        ref other => panic!("{other:?}"),
    };
    assert_eq!(alpha(0), Alpha { u: 0.05, v: 0.4 });
    assert_eq!(alpha(1), Alpha { u: 0.3, v: 0.1 });
    assert_eq!(alpha(2), Alpha::isotropic(0.25));
    assert!(alpha(0).is_anisotropic() && !alpha(2).is_anisotropic());
}

#[test]
fn a_spheres_axes_are_its_to_world_rotation_with_the_pole_on_local_z_reversed_for_v() {
    let l = load_shapes(
        "mitsuba-sphere-axes",
        r#"
    <shape type="sphere"><float name="radius" value="0.5"/></shape>
    <shape type="sphere"><transform name="to_world">
        <rotate x="1" angle="90"/><scale value="2"/><translate x="1"/></transform></shape>"#,
    );
    let s = &l.scene.spheres;
    let flip_z = Mat3::from_diagonal(Vec3::new(1.0, 1.0, -1.0));
    assert_eq!(s[0].axes, flip_z);
    // Rotating +90° about x takes local +z to world −y and +y to +z; the
    // parameterisation's pole axis is the reverse of local +z.
    let a = s[1].axes;
    let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() < 1e-6;
    assert!(close(a.z_axis, Vec3::Y) && close(a.y_axis, Vec3::Z) && close(a.x_axis, Vec3::X));
    assert!((s[1].radius - 2.0).abs() < 1e-6);
    // In those axes v = θ/π from the pole is 1 − Mitsuba's v (θ from local
    // +z), the flip every Mitsuba uv gets into Candela's image rows, and u
    // = φ/2π is Mitsuba's: a point at Mitsuba's (u, v) = (0.125, 0.25).
    let (theta, phi) = (0.25 * std::f32::consts::PI, 0.125 * std::f32::consts::TAU);
    let local = Vec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    );
    let q = s[0].axes.transpose() * local;
    let v = q.z.acos() / std::f32::consts::PI;
    let u = q.y.atan2(q.x) / std::f32::consts::TAU;
    assert!(
        (u - 0.125).abs() < 1e-6 && (v - 0.75).abs() < 1e-6,
        "u {u} v {v}"
    );
    // Candela's own convention differs: the pole on +Y.
    assert_eq!(SphereDesc::Y_POLE.z_axis, Vec3::Y);
}

#[test]
fn flip_normals_turns_a_spheres_front_and_emission_inward() {
    let l = load_shapes(
        "mitsuba-flipped-sphere",
        r#"
    <shape type="sphere"><boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
    <shape type="sphere"><bsdf type="diffuse"/></shape>"#,
    );
    let s = &l.scene.spheres;
    let m = &l.scene.materials;
    // The sphere's front is its inside: the material stays as written
    // (one-sided diffuse, emitting), nothing reported.
    assert!(s[0].inward && !s[1].inward);
    let flipped = &m[s[0].material];
    assert_eq!(flipped.sides, Sides::Front);
    assert_eq!(albedo(flipped), Vec3::splat(0.6));
    assert_eq!(flipped.emission, Some(Vec3::splat(2.0)));
}
