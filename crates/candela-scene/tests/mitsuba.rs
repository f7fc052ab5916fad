//! The Mitsuba 3 XML loader: the shared research scenes (golden counts,
//! lights, cameras), a hand-written base file that uses one of everything
//! (`tests/mitsuba/base.xml` with `part.xml` included), caller overrides of
//! `<default>`s, the camera's handedness, and mutated files (never a panic).
//! Malformed files are in `tests/malformed/` (`*-mitsuba-*.xml`).

use candela_scene::{
    load, Alpha, BsdfDesc, ClipRange, ColorSpace, EnvironmentDesc, EnvironmentLookup, FilterHint,
    LightKind, LoadOptions, Loaded, MicrofacetModel, PerturbationRules, PrincipledParameters,
    Projection, SpotEdge,
};
use glam::Vec3;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn shared(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared")
        .join(rel)
}

fn base_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/mitsuba")
}

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..LoadOptions::default()
    }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() <= 1e-4 * (1.0 + b.abs().max_element())
}

/// The radiance of the scene's only emissive material.
fn lamp(l: &Loaded) -> Vec3 {
    let lamps: Vec<Vec3> = l
        .scene
        .materials
        .iter()
        .filter_map(|m| m.emission)
        .collect();
    assert_eq!(lamps.len(), 1, "{lamps:?}");
    lamps[0]
}

fn eye(l: &Loaded) -> Vec3 {
    l.scene.cameras[0]
        .world_from_camera
        .transform_point3(Vec3::ZERO)
}

#[test]
fn the_mitsuba_cornell_box_loads() {
    let l = load(&shared("scenes/formats/mitsuba/cbox/cbox.xml"), &strict()).unwrap();
    let s = &l.scene;
    assert_eq!((s.meshes.len(), s.instances.len()), (8, 8));
    assert_eq!(s.triangle_count(), 38);
    // The lamp's spectrum 400:0, 500:8, 600:15.6, 700:18.4 as light in
    // linear sRGB, Mitsuba 3.9's figure (its area emitter's `eval`).
    assert!(
        close(lamp(&l), Vec3::new(20.7108, 10.8546, 2.77115)),
        "{:?}",
        lamp(&l)
    );
    assert!(close(eye(&l), Vec3::new(278.0, 273.0, -800.0)));
    assert_eq!(l.hints.spp, Some(128));
    assert_eq!(l.hints.resolution, Some((256, 256)));
    assert_eq!(l.hints.max_depth, Some(5)); // Mitsuba's 6 segments
    assert!(l.hints.file_camera);
    assert_eq!(l.hints.filter, Some(FilterHint::Gaussian { stddev: 0.5 }));
    let Projection::Perspective { xfov_deg, yfov_deg } = s.cameras[0].projection else {
        panic!("{:?}", s.cameras[0].projection)
    };
    assert!((xfov_deg - 39.3077).abs() < 1e-3 && (yfov_deg - 39.3077).abs() < 1e-3);
    assert!(l.report.is_empty(), "{}", l.report);
}

#[test]
fn the_cs184_bunny_and_spheres_load() {
    let bunny = load(&shared("bench/mitsuba/CBbunny.xml"), &strict()).unwrap();
    assert_eq!(bunny.scene.meshes.len(), 7);
    assert_eq!(bunny.scene.triangle_count(), 28_588);
    assert!(close(lamp(&bunny), Vec3::splat(10.0)));
    assert!(close(eye(&bunny), Vec3::new(0.0, -4.802_344, 0.75)));
    let spheres = load(&shared("bench/mitsuba/CBspheres_lambertian.xml"), &strict()).unwrap();
    let s = &spheres.scene;
    assert_eq!(
        (s.meshes.len(), s.triangle_count(), s.spheres.len()),
        (6, 12, 2)
    );
    assert!(close(s.spheres[0].center, Vec3::new(-0.4, 0.3, 0.3)));
    assert!((s.spheres[1].radius - 0.3).abs() < 1e-6);
    assert!(close(lamp(&spheres), Vec3::splat(10.0)));
    assert!(close(eye(&spheres), Vec3::new(0.0, 4.802_344, 0.75)));
    for l in [&bunny, &spheres] {
        assert_eq!(l.hints.spp, Some(64));
        assert_eq!(l.hints.resolution, Some((480, 360)));
        // max_depth -1: unlimited.
        assert!(l.hints.max_depth.unwrap() >= 1000);
        let (x, y) = l.scene.cameras[0].fov_deg().unwrap();
        assert!((x - 30.676_4).abs() < 1e-3, "{x}");
        let want_y = 2.0
            * ((x.to_radians() / 2.0).tan() * 360.0 / 480.0)
                .atan()
                .to_degrees();
        assert!((y - want_y).abs() < 1e-3, "{y} {want_y}");
    }
}

fn base() -> Loaded {
    load(&base_dir().join("base.xml"), &LoadOptions::default()).unwrap()
}

#[test]
fn the_base_file_loads_every_element() {
    let l = base();
    let s = &l.scene;
    // floor (2), lamp rectangle (2), cube (12, drawn twice), disk (64
    // segments of 16 rings, the innermost a fan: 64 × 31).
    let disk = 64 * 31;
    assert_eq!(s.meshes.len(), 4);
    assert_eq!(s.triangle_count(), 2 + 2 + 12 + disk);
    assert_eq!(s.instances.len(), 5);
    assert_eq!(s.instanced_triangle_count(), 2 + 2 + 24 + disk);
    // The ball, and the group's sphere in both instances: the second
    // scales by 2 and then moves by +x.
    assert_eq!(s.spheres.len(), 3);
    assert!(close(s.spheres[2].center, Vec3::new(1.0, 1.0, 0.0)));
    assert!((s.spheres[2].radius - 0.2).abs() < 1e-6);
    assert!(close(s.spheres[1].center, Vec3::new(-1.0, 0.5, 0.0)));
    assert_eq!((l.hints.spp, l.hints.max_depth), (Some(16), Some(3)));
    assert_eq!(l.hints.resolution, Some((64, 48)));
    let by_bsdf = |f: &dyn Fn(&BsdfDesc) -> bool| s.materials.iter().any(|m| f(&m.bsdf));
    assert!(by_bsdf(
        &|b| matches!(b, BsdfDesc::Glass { ior, .. } if (ior - 1.5046).abs() < 1e-6)
    ));
    assert!(by_bsdf(
        &|b| matches!(b, BsdfDesc::Conductor { distribution: MicrofacetModel::Ggx, alpha, eta, .. }
        if *alpha == Alpha::isotropic(0.2) && (eta.x - 0.143).abs() < 1e-3)
    ));
    assert!(by_bsdf(
        &|b| matches!(b, BsdfDesc::Plastic { alpha, .. } if *alpha == 0.0)
    ));
    assert!(by_bsdf(
        &|b| matches!(b, BsdfDesc::Diffuse { albedo } if close(*albedo, Vec3::splat(0.5)))
    ));
    // `<spectrum value="5">` in an emitter: equal-energy light of 5, which
    // Mitsuba 3.9's RGB variants give as (2.40959, 1.89658, 1.81783) for 2.
    assert!(close(lamp(&l), Vec3::new(2.40959, 1.89658, 1.81783) * 2.5));
    assert_eq!(
        s.environment,
        Some(EnvironmentDesc::Constant {
            radiance: Vec3::splat(0.1)
        })
    );
    assert!(
        matches!(s.lights[0].kind, LightKind::Point { position, intensity }
        if close(position, Vec3::new(1.0, 2.0, 3.0)) && close(intensity, Vec3::new(1.0, 2.0, 3.0)))
    );
    assert!(l.report.is_empty(), "{}", l.report);
}

#[test]
fn a_spot_lights_texture_is_reported_not_dropped() {
    let dir = candela_testkit::TempDir::new("mitsuba-spot-texture");
    let path = dir.join("spot.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0"><emitter type="spot">
        <texture name="texture" type="checkerboard"/></emitter><shape type="sphere"/></scene>"#,
    )
    .unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert!(
        l.report
            .to_string()
            .contains("projected texture is not supported"),
        "{}",
        l.report
    );
    assert!(load(&path, &strict()).is_err(), "strict mode refuses it");
}

#[test]
fn hide_emitters_is_a_hint_of_the_integrator() {
    let dir = candela_testkit::TempDir::new("mitsuba-hide-emitters");
    let load = |integrator: &str| {
        let path = dir.join("hide.xml");
        let text = format!(r#"<scene version="3.0.0">{integrator}<shape type="sphere"/></scene>"#);
        std::fs::write(&path, text).unwrap();
        load(&path, &strict()).unwrap()
    };
    let hidden = load(
        r#"<integrator type="path"><boolean name="hide_emitters" value="true"/></integrator>"#,
    );
    assert!(hidden.hints.hide_emitters);
    assert!(!load(r#"<integrator type="path"/>"#).hints.hide_emitters);
    assert!(!load("").hints.hide_emitters);
}

#[test]
fn an_orthographic_sensor_is_as_wide_as_twice_its_x_scale() {
    let dir = candela_testkit::TempDir::new("mitsuba-orthographic");
    let load_with = |scale: &str| {
        let path = dir.join("ortho.xml");
        let text = format!(
            r#"<scene version="3.0.0"><sensor type="orthographic"><transform name="to_world">
            <scale {scale}/><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/>
            </transform></sensor><shape type="sphere"/></scene>"#
        );
        std::fs::write(&path, text).unwrap();
        load(&path, &LoadOptions::default()).unwrap()
    };
    let l = load_with(r#"value="1.4""#);
    assert!(l.report.is_empty(), "{}", l.report);
    assert!(l.hints.file_camera);
    let Projection::Orthographic { width } = l.scene.cameras[0].projection else {
        panic!("{:?}", l.scene.cameras[0].projection)
    };
    assert!((width - 2.8).abs() < 1e-5, "width {width}");
    // A squashed view cannot keep the image's aspect: said once.
    let squashed = load_with(r#"x="1" y="2""#);
    assert!(squashed
        .report
        .to_string()
        .contains("orthographic view scaled unevenly"));
}

#[test]
fn transforms_compose_in_mitsubas_order() {
    let l = base();
    let s = &l.scene;
    let facing = |name: &str| {
        let i = s
            .instances
            .iter()
            .find(|i| s.meshes[i.mesh].name == name)
            .unwrap();
        let m = &s.meshes[i.mesh];
        let p = m.triangles[0].map(|k| {
            i.world_from_object
                .transform_point3(m.positions[k as usize])
        });
        ((p[1] - p[0]).cross(p[2] - p[0]).normalize(), p[0])
    };
    // The floor: scale 2, then a -90 degree turn about x: facing +y, 2 wide.
    let (n, p) = facing("floor");
    assert!(close(n, Vec3::Y), "{n}");
    assert!((p.x.abs() - 2.0).abs() < 1e-5 && p.y.abs() < 1e-5, "{p}");
    // The lamp: turned to face +y, flipped (-y), then lifted to y = 3.
    let (n, p) = facing("lamp");
    assert!(close(n, -Vec3::Y), "{n}");
    assert!((p.y - 3.0).abs() < 1e-5, "{p}");
}

#[test]
fn the_camera_is_not_mirrored() {
    // The base camera sits at z = 5 looking toward -z with +y up: world +x
    // must be the image's right (Candela's camera +x), -z straight ahead.
    let c = &base().scene.cameras[0];
    let m = c.world_from_camera;
    assert!(close(m.transform_vector3(Vec3::X), Vec3::X));
    assert!(close(m.transform_vector3(Vec3::Y), Vec3::Y));
    assert!(close(m.transform_vector3(-Vec3::Z), -Vec3::Z));
    assert!(m.determinant() > 0.0);
}

#[test]
fn caller_defines_override_the_files_defaults() {
    let opts = LoadOptions {
        defines: vec![("spp".into(), "3".into()), ("depth".into(), "-1".into())],
        ..LoadOptions::default()
    };
    let l = load(&base_dir().join("base.xml"), &opts).unwrap();
    assert_eq!(l.hints.spp, Some(3));
    assert!(l.hints.max_depth.unwrap() >= 1000);
}

#[test]
fn unsupported_plugins_warn_once_or_fail_in_strict_mode() {
    let dir = candela_testkit::TempDir::new("mitsuba-warn");
    let path = dir.join("warn.xml");
    let body = r#"<scene version="3.0.0">
    <shape type="cube"><bsdf type="principledthin"/></shape>
    <shape type="cube"><bsdf type="principledthin"/></shape>
    <shape type="bsplinecurve"/>
</scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(l.report.len(), 2, "{}", l.report);
    assert_eq!(l.report.warnings[0].count, 2, "{}", l.report);
    assert!(l.report.mentions("bsplinecurve"));
    let err = load(&path, &strict()).unwrap_err();
    assert_eq!(err.kind, candela_scene::ErrorKind::Unsupported, "{err}");
}

#[test]
fn principled_reads_every_parameter_and_mitsubas_ior_rules() {
    let dir = candela_testkit::TempDir::new("mitsuba-principled");
    std::fs::write(dir.join("rough.png"), []).unwrap();
    let path = dir.join("principled.xml");
    let body = r#"<scene version="3.0.0">
    <shape type="cube"><bsdf type="principled">
        <rgb name="base_color" value="0.7, 0.2, 0.1"/>
        <texture type="bitmap" name="roughness"><string name="filename" value="rough.png"/></texture>
        <float name="anisotropic" value="0.3"/><float name="metallic" value="0.4"/>
        <float name="spec_trans" value="0.5"/><float name="specular" value="0"/>
        <float name="spec_tint" value="0.6"/><float name="sheen" value="0.7"/>
        <float name="sheen_tint" value="0.8"/><float name="flatness" value="0.9"/>
        <float name="clearcoat" value="0.25"/><float name="clearcoat_gloss" value="0.35"/>
        <float name="clearcoat_sampling_rate" value="2"/>
    </bsdf></shape>
    <shape type="cube"><bsdf type="principled"><float name="specular" value="1"/>
        <texture type="bitmap" name="sheen"><string name="filename" value="rough.png"/></texture>
    </bsdf></shape>
    <shape type="cube"><bsdf type="principled"><float name="eta" value="1"/>
        <float name="spec_trans" value="1"/></bsdf></shape>
</scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    let BsdfDesc::Principled(PrincipledParameters {
        base_color,
        roughness,
        anisotropic,
        metallic,
        spec_trans,
        eta,
        spec_tint,
        sheen,
        sheen_tint,
        flatness,
        clearcoat,
        clearcoat_gloss,
    }) = l.scene.materials[0].bsdf
    else {
        panic!("{:?}", l.scene.materials[0].bsdf)
    };
    assert!(close(base_color, Vec3::new(0.7, 0.2, 0.1)));
    assert_eq!(
        roughness, 0.5,
        "a textured roughness keeps Mitsuba's default"
    );
    assert!(l.scene.materials[0].textures.roughness.is_some());
    assert_eq!(
        [
            anisotropic,
            metallic,
            spec_trans,
            spec_tint,
            sheen,
            sheen_tint,
            flatness
        ],
        [0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9]
    );
    assert_eq!([clearcoat, clearcoat_gloss], [0.25, 0.35]);
    // specular 0 on a transmitting material is 0.001, as Mitsuba: η ≈ 1.0036.
    let expected = 2.0 / (1.0 - (0.08f32 * 1e-3).sqrt()) - 1.0;
    assert!((eta - expected).abs() < 1e-6 && eta > 1.0, "{eta}");
    // specular 1 is η = 2/(1 − √0.08) − 1; eta 1 on a transmitting one is 1.001.
    let etas: Vec<f32> = l.scene.materials[1..]
        .iter()
        .map(|m| match m.bsdf {
            BsdfDesc::Principled(p) => p.eta,
            _ => f32::NAN,
        })
        .collect();
    assert!(
        (etas[0] - (2.0 / (1.0 - 0.08f32.sqrt()) - 1.0)).abs() < 1e-6,
        "{etas:?}"
    );
    assert_eq!(etas[1], 1.001);
    assert!(l.report.mentions("clearcoat_sampling_rate"), "{}", l.report);
    assert!(l.report.mentions("sheen"), "{}", l.report);
    assert_eq!(l.report.len(), 2, "{}", l.report);
    // Both eta and specular is an error, as in Mitsuba.
    std::fs::write(
        &path,
        r#"<scene version="3.0.0"><shape type="cube"><bsdf type="principled">
        <float name="eta" value="1.4"/><float name="specular" value="0.3"/></bsdf></shape></scene>"#,
    )
    .unwrap();
    let err = load(&path, &LoadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("either"), "{err}");
}

#[test]
fn a_smooth_none_conductor_takes_its_specular_reflectance() {
    // Fresnel is 1 for "none", so Mitsuba's BSDF is the factor itself: a
    // mirror. Elsewhere Candela's conductor has no such factor: reported.
    let dir = std::env::temp_dir().join(format!("candela-mitsuba-mirror-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("mirror.xml");
    let body = r#"<scene version="3.0.0">
    <shape type="cube"><bsdf type="conductor">
        <rgb name="specular_reflectance" value="0.95, 0.9, 0.85"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughconductor"><string name="material" value="Au"/>
        <rgb name="specular_reflectance" value="0.5"/></bsdf></shape>
</scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    let BsdfDesc::Mirror { reflectance } = l.scene.materials[0].bsdf else {
        panic!("{:?}", l.scene.materials[0].bsdf)
    };
    assert!(
        close(reflectance, Vec3::new(0.95, 0.9, 0.85)),
        "{reflectance}"
    );
    assert!(matches!(
        l.scene.materials[1].bsdf,
        BsdfDesc::Conductor { .. }
    ));
    assert_eq!(l.report.len(), 1, "{}", l.report);
    assert!(l.report.mentions("specular_reflectance"), "{}", l.report);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn named_metals_and_rough_plastic_load() {
    // Every metal the issue names (Fe and Ti from Johnson & Christy, Ni the
    // data Mitsuba calls "Ni_palik"), on smooth and rough conductors, and a
    // rough plastic with its distribution and `nonlinear`.
    let dir = std::env::temp_dir().join(format!("candela-mitsuba-metals-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let names = ["Ag", "Al", "Au", "Cu", "Cr", "Fe", "Ni", "Ti", "W"];
    let mut body = String::from(r#"<scene version="3.0.0">"#);
    for (i, name) in names.iter().enumerate() {
        let kind = if i % 2 == 0 {
            "conductor"
        } else {
            "roughconductor"
        };
        body += &format!(
            r#"<shape type="cube"><bsdf type="{kind}"><string name="material" value="{name}"/></bsdf></shape>"#
        );
    }
    body += r#"<shape type="cube"><bsdf type="roughplastic">
        <string name="distribution" value="ggx"/><float name="alpha" value="0.3"/>
        <boolean name="nonlinear" value="true"/><float name="int_ior" value="1.6"/>
        <rgb name="diffuse_reflectance" value="0.8, 0.2, 0.1"/></bsdf></shape>
    <shape type="cube"><bsdf type="plastic"/></shape></scene>"#;
    let path = dir.join("metals.xml");
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &strict()).unwrap();
    let m = &l.scene.materials;
    assert_eq!(m.len(), names.len() + 2);
    for (i, name) in names.iter().enumerate() {
        let BsdfDesc::Conductor { alpha, eta, k, .. } = m[i].bsdf else {
            panic!("{name}: {:?}", m[i].bsdf)
        };
        assert_eq!(alpha.is_rough(), i % 2 == 1, "{name}");
        // Metals: all channels positive, absorbing (k > 1).
        assert!(
            eta.min_element() > 0.0 && k.min_element() > 1.0,
            "{name}: {eta} {k}"
        );
    }
    // Gold: Mitsuba 3.9.1's scalar_rgb value (data/metals/README.md).
    let BsdfDesc::Conductor { eta, k, .. } = m[2].bsdf else {
        panic!()
    };
    assert!(close(eta, Vec3::new(0.143036, 0.375307, 1.44205)), "{eta}");
    assert!(close(k, Vec3::new(3.983, 2.38556, 1.60336)), "{k}");
    assert!(matches!(
        m[names.len()].bsdf,
        BsdfDesc::Plastic { distribution: MicrofacetModel::Ggx, alpha, nonlinear: true, ior, .. }
            if (alpha - 0.3).abs() < 1e-6 && (ior - 1.6 / 1.000277).abs() < 1e-5
    ));
    assert!(matches!(
        m[names.len() + 1].bsdf,
        BsdfDesc::Plastic { alpha, nonlinear: false, .. } if alpha == 0.0
    ));
    // An unknown name is a located error that lists the known ones.
    std::fs::write(
        &path,
        r#"<scene version="3.0.0"><shape type="cube"><bsdf type="conductor">
        <string name="material" value="Unobtainium"/></bsdf></shape></scene>"#,
    )
    .unwrap();
    let err = load(&path, &strict()).unwrap_err().to_string();
    assert!(err.contains("Unobtainium") && err.contains("Fe, "), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A mutation of the base file: replace, cut, or insert a token that
/// matters to the loader.
#[derive(Clone, Debug)]
enum Mutation {
    Replace(usize, u8),
    Truncate(usize),
    Insert(usize, &'static str),
}

const TOKENS: &[&str] = &[
    "<",
    ">",
    "\"",
    "$",
    "$spp",
    "nan",
    "-1",
    "0",
    "1e40",
    "=",
    "/",
    " ",
    ",",
    "<shape type=\"cube\">",
    "<ref id=\"pair\"/>",
    "<include filename=\"base.xml\"/>",
];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Replace(i, b)),
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), proptest::sample::select(TOKENS))
            .prop_map(|(i, t)| Mutation::Insert(i, t)),
    ]
}

fn mutate(mut bytes: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let n = bytes.len().max(1);
        match m {
            Mutation::Replace(i, b) => {
                if let Some(x) = bytes.get_mut(i % n) {
                    *x = *b;
                }
            }
            Mutation::Truncate(i) => bytes.truncate(i % n),
            Mutation::Insert(i, t) => {
                let at = (i % n).min(bytes.len());
                bytes.splice(at..at, t.bytes());
            }
        }
    }
    bytes
}

/// A scratch copy of the base files, the mutated scene written over `base.xml`.
fn scratch() -> candela_testkit::TempDir {
    let dir = candela_testkit::TempDir::new("mitsuba-fuzz");
    for f in ["quad.obj", "part.xml"] {
        std::fs::copy(base_dir().join(f), dir.join(f)).unwrap();
    }
    dir
}

fn loads_or_fails(path: &Path, bytes: &[u8]) {
    std::fs::write(path, bytes).unwrap();
    if let Err(e) = load(path, &LoadOptions::default()) {
        assert!(!e.to_string().contains('\n'), "{e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenes_never_panic(ms in proptest::collection::vec(mutation(), 1..4)) {
        let dir = scratch();
        let text = std::fs::read(base_dir().join("base.xml")).unwrap();
        loads_or_fails(&dir.join("base.xml"), &mutate(text, &ms));
    }
}

#[test]
fn built_in_shapes_and_ply_read_images_from_the_top_as_mitsuba_does() {
    // Mitsuba's rectangle has uv (0, 0) at its corner (-1, -1), and Mitsuba
    // reads uv v = 0 on an image's top row; Candela's v = 0 is the bottom
    // row, so that corner must carry Candela uv (0, 1). Upside down, a
    // bitmap on a rectangle was +17% / -6.5% (G / B) against Mitsuba in
    // benches/mitsuba_conformance/tex-diffuse.xml. OBJ files are left alone
    // (Mitsuba's OBJ reader flips v itself); PLY files are flipped.
    let dir = candela_testkit::TempDir::new("mitsuba-uv");
    let path = dir.join("uv.xml");
    std::fs::write(
        dir.join("t.ply"),
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nproperty float u\nproperty float v\nelement face 1\n\
         property list uchar int vertex_indices\nend_header\n\
         0 0 0 0 0.2\n1 0 0 1 0.2\n0 1 0 0 0.9\n3 0 1 2\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("t.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0.2\nvt 1 0.2\nvt 0 0.9\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let body = r#"<scene version="3.0.0">
    <shape type="rectangle"/>
    <shape type="ply"><string name="filename" value="t.ply"/></shape>
    <shape type="obj"><string name="filename" value="t.obj"/></shape>
</scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    let uv_at = |mesh: usize, p: Vec3| {
        let m = &l.scene.meshes[mesh];
        let (t, c) = m
            .triangles
            .iter()
            .enumerate()
            .find_map(|(t, tri)| {
                tri.iter()
                    .position(|&v| close(m.positions[v as usize], p))
                    .map(|c| (t, c))
            })
            .unwrap();
        m.uvs[m.uv_indices[t][c] as usize]
    };
    let corner = uv_at(0, Vec3::new(-1.0, -1.0, 0.0));
    assert!(
        (corner - glam::Vec2::new(0.0, 1.0)).length() < 1e-6,
        "{corner}"
    );
    let ply = uv_at(1, Vec3::new(0.0, 1.0, 0.0));
    assert!((ply - glam::Vec2::new(0.0, 0.1)).length() < 1e-6, "{ply}");
    let obj = uv_at(2, Vec3::new(0.0, 1.0, 0.0));
    assert!((obj - glam::Vec2::new(0.0, 0.9)).length() < 1e-6, "{obj}");
}

#[test]
fn a_cylinder_is_placed_from_p0_to_p1_with_mitsubas_normals_and_uv() {
    // Mitsuba's cylinder from p0 = (1, 0, 0) to p1 = (1, 2, 0), radius 0.5:
    // its axis frame (Duff et al.'s basis of +Y) puts u = 0 toward +X and
    // u = 1/4 toward -Z; v runs from p0 (0) to p1 (1). Read from Mitsuba 3
    // by ray queries: (1, 1, 0.5) has uv (0.75, 0.5), (1, 1, -0.5) has
    // (0.25, 0.5), normals point away from the axis.
    let dir = candela_testkit::TempDir::new("mitsuba-cylinder");
    let path = dir.join("c.xml");
    let body = r#"<scene version="3.0.0"><shape type="cylinder">
        <point name="p0" x="1" y="0" z="0"/><point name="p1" x="1" y="2" z="0"/>
        <float name="radius" value="0.5"/></shape></scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &strict()).unwrap();
    let m = &l.scene.meshes[0];
    let axis_point = |p: Vec3| Vec3::new(1.0, p.y, 0.0);
    for (t, tri) in m.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| m.positions[v as usize]);
        let face = (b - a).cross(c - a).normalize();
        let centre = (a + b + c) / 3.0;
        // Wound counter-clockwise seen from outside.
        assert!(face.dot(centre - axis_point(centre)) > 0.0, "triangle {t}");
        for (k, &v) in tri.iter().enumerate() {
            let p = m.positions[v as usize];
            let n = m.normals[m.normal_indices[t][k] as usize];
            let radial = p - axis_point(p);
            assert!((radial.length() - 0.5).abs() < 1e-5, "{p}");
            assert!((-1e-5..=2.0 + 1e-5).contains(&p.y), "{p}");
            assert!((n - radial / 0.5).length() < 1e-5, "{n} at {p}");
        }
    }
    // Candela's v is Mitsuba's 1 - v (images are read from the top there).
    let uv_near = |p: Vec3| {
        let (t, k) = (0..m.triangles.len())
            .flat_map(|t| (0..3).map(move |k| (t, k)))
            .min_by(|&(t, k), &(u, j)| {
                let d = |t: usize, k: usize| (m.positions[m.triangles[t][k] as usize] - p).length();
                d(t, k).total_cmp(&d(u, j))
            })
            .unwrap();
        m.uvs[m.uv_indices[t][k] as usize]
    };
    let quarter = uv_near(Vec3::new(1.0, 0.0, -0.5));
    assert!(
        (quarter - glam::Vec2::new(0.25, 1.0)).length() < 1e-5,
        "{quarter}"
    );
    let three_quarters = uv_near(Vec3::new(1.0, 2.0, 0.5));
    assert!(
        (three_quarters - glam::Vec2::new(0.75, 0.0)).length() < 1e-5,
        "{three_quarters}"
    );
    let half = uv_near(Vec3::new(0.5, 2.0, 0.0));
    assert!((half - glam::Vec2::new(0.5, 0.0)).length() < 1e-5, "{half}");
}

/// A scene whose sensor's film has `film_body` inside.
fn with_film(dir: &candela_testkit::TempDir, name: &str, film_body: &str) -> PathBuf {
    let path = dir.join(name);
    let body = format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <film type="hdrfilm">
            <integer name="width" value="8"/>
            <integer name="height" value="6"/>
            {film_body}
        </film>
    </sensor>
    <shape type="cube"/>
</scene>"#
    );
    std::fs::write(&path, body).unwrap();
    path
}

#[test]
fn the_films_reconstruction_filter_becomes_a_hint() {
    let dir = candela_testkit::TempDir::new("mitsuba-rfilter");
    let cases = [
        ("", FilterHint::Gaussian { stddev: 0.5 }),
        (r#"<rfilter type="box"/>"#, FilterHint::Box),
        (
            r#"<rfilter type="tent"/>"#,
            FilterHint::Tent { radius: 1.0 },
        ),
        (
            r#"<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>"#,
            FilterHint::Tent { radius: 1.5 },
        ),
        (
            r#"<rfilter type="gaussian"><float name="stddev" value="0.25"/></rfilter>"#,
            FilterHint::Gaussian { stddev: 0.25 },
        ),
        (
            r#"<rfilter type="mitchell"><float name="B" value="0.5"/></rfilter>"#,
            FilterHint::Mitchell {
                b: 0.5,
                c: 1.0 / 3.0,
            },
        ),
        (r#"<rfilter type="catmullrom"/>"#, FilterHint::CatmullRom),
        (
            r#"<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>"#,
            FilterHint::Lanczos { lobes: 2 },
        ),
    ];
    for (i, (film, want)) in cases.into_iter().enumerate() {
        let path = with_film(&dir, &format!("f{i}.xml"), film);
        let l = load(&path, &strict()).unwrap();
        assert_eq!(l.hints.filter, Some(want), "{film}");
        assert!(l.report.is_empty(), "{film}: {}", l.report);
    }
    // No <film> at all: Mitsuba's default film, hence its default filter.
    let path = dir.join("nofilm.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0"><sensor type="perspective"/><shape type="cube"/></scene>"#,
    )
    .unwrap();
    let l = load(&path, &strict()).unwrap();
    assert_eq!(l.hints.filter, Some(FilterHint::MITSUBA_DEFAULT));
}

#[test]
fn an_unknown_filter_is_reported_once_and_falls_back_to_the_default() {
    let dir = candela_testkit::TempDir::new("mitsuba-rfilter-unknown");
    let path = dir.join("two.xml");
    let sensor = r#"<sensor type="perspective"><film type="hdrfilm">
            <rfilter type="bspline"/></film></sensor>"#;
    let body = format!(r#"<scene version="3.0.0">{sensor}{sensor}<shape type="cube"/></scene>"#);
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(l.report.len(), 1, "{}", l.report);
    assert_eq!(l.report.warnings[0].count, 2, "{}", l.report);
    assert!(l.report.mentions("bspline"), "{}", l.report);
    assert_eq!(l.hints.filter, Some(FilterHint::MITSUBA_DEFAULT));
    let err = load(&path, &strict()).unwrap_err();
    assert_eq!(err.kind, candela_scene::ErrorKind::Unsupported, "{err}");
    // A bad parameter is an error at its element.
    let bad = with_film(
        &dir,
        "bad.xml",
        r#"<rfilter type="tent"><float name="radius" value="-1"/></rfilter>"#,
    );
    let err = load(&bad, &LoadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("radius -1 must be > 0"), "{err}");
    assert!(err.to_string().contains("rfilter"), "{err}");
}

#[test]
fn a_spot_fades_from_its_beam_width_to_its_cutoff() {
    // Mitsuba's default beam_width is 3/4 of cutoff_angle: a linear fade in
    // the angle between them (drawn as a hard cone before: +26% on the
    // wall it lit against Mitsuba). A beam as wide as the cutoff is hard.
    let dir = candela_testkit::TempDir::new("mitsuba-spot");
    let path = dir.join("spot.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0">
    <emitter type="spot"><float name="cutoff_angle" value="30"/></emitter>
    <emitter type="spot">
        <float name="cutoff_angle" value="30"/><float name="beam_width" value="30"/>
    </emitter>
</scene>"#,
    )
    .unwrap();
    let l = load(&path, &strict()).expect("a faded spot loads without a warning");
    let edges: Vec<SpotEdge> = l
        .scene
        .lights
        .iter()
        .map(|light| match light.kind {
            LightKind::Spot {
                cone_angle_deg,
                edge,
                ..
            } => {
                assert_eq!(cone_angle_deg, 60.0);
                edge
            }
            ref other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        edges,
        [
            SpotEdge::LinearInAngle {
                beam_angle_deg: 45.0
            },
            SpotEdge::Hard
        ]
    );
}

#[test]
fn normal_bump_and_mask_wrappers_carry_mitsubas_rules() {
    // bumpmap's `scale` multiplies the height; both maps take Mitsuba's
    // shading-frame rules (use_shadowing_function read, true by default);
    // a mask's constant opacity is kept (a colour by its luminance).
    let dir = candela_testkit::TempDir::new("mitsuba-maps");
    std::fs::write(dir.join("h.png"), TINY_PNG).unwrap();
    let path = dir.join("maps.xml");
    let body = r#"<scene version="3.0.0">
    <shape type="rectangle"><bsdf type="bumpmap">
        <texture type="bitmap"><string name="filename" value="h.png"/><boolean name="raw" value="true"/></texture>
        <float name="scale" value="0.25"/><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="normalmap">
        <texture type="bitmap" name="normalmap"><string name="filename" value="h.png"/><boolean name="raw" value="true"/></texture>
        <boolean name="use_shadowing_function" value="false"/><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="mask"><float name="opacity" value="0.3"/><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="mask"><rgb name="opacity" value="0.2, 0.5, 0.9"/><bsdf type="diffuse"/></bsdf></shape>
    <shape type="rectangle"><bsdf type="diffuse"/></shape>
</scene>"#;
    std::fs::write(&path, body).unwrap();
    let l = load(&path, &strict()).unwrap();
    let m = &l.scene.materials;
    let bump = m[0].textures.bump.as_ref().expect("bump slot");
    assert_eq!(bump.scale, 0.25);
    assert_eq!(bump.color_space, ColorSpace::Linear, "raw");
    assert_eq!(m[0].textures.perturbation, PerturbationRules::MITSUBA);
    assert!(m[1].textures.normal.is_some());
    assert_eq!(
        m[1].textures.perturbation,
        PerturbationRules {
            shadow_terminator: false,
            ..PerturbationRules::MITSUBA
        }
    );
    assert_eq!(m[2].textures.opacity_constant, Some(0.3));
    let lum = 0.2126 * 0.2 + 0.7152 * 0.5 + 0.0722 * 0.9;
    let got = m[3].textures.opacity_constant.expect("rgb opacity");
    assert!((got - lum).abs() < 1e-6, "{got} vs {lum}");
    // A plain BSDF keeps the default (glTF's) rules and full opacity.
    assert_eq!(m[4].textures.perturbation, PerturbationRules::default());
    assert_eq!(m[4].textures.opacity_constant, None);
    assert!(l.report.is_empty(), "{}", l.report);
}

/// A 1 × 1 grey PNG.
const TINY_PNG: &[u8] = &[
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
    0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a, 0x7e, 0x9b,
    0x55, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68, 0x00, 0x00, 0x00,
    0x82, 0x00, 0x81, 0x77, 0xcd, 0x72, 0xb6, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae,
    0x42, 0x60, 0x82,
];

#[test]
fn sensors_carry_their_clip_range_and_envmaps_mitsubas_lookup() {
    let dir = candela_testkit::TempDir::new("mitsuba-clip");
    std::fs::write(dir.join("sky.exr"), b"not read by the loader").unwrap();
    let path = dir.join("clip.xml");
    std::fs::write(
        &path,
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <float name="near_clip" value="3.5"/>
        <float name="far_clip" value="40"/>
    </sensor>
    <sensor type="thinlens">
        <float name="aperture_radius" value="0.1"/>
        <float name="focus_distance" value="2"/>
    </sensor>
    <emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>
    <shape type="cube"/>
</scene>"#,
    )
    .unwrap();
    let l = load(&path, &strict()).unwrap();
    let clips: Vec<_> = l.scene.cameras.iter().map(|c| c.clip).collect();
    assert_eq!(
        clips,
        [
            Some(ClipRange {
                near: 3.5,
                far: 40.0
            }),
            // Mitsuba's defaults.
            Some(ClipRange {
                near: 0.01,
                far: 10_000.0
            }),
        ]
    );
    match &l.scene.environment {
        Some(EnvironmentDesc::Map { lookup, .. }) => {
            assert_eq!(*lookup, EnvironmentLookup::BilinearPoleRows)
        }
        other => panic!("{other:?}"),
    }
}

/// The scene of one environment map with `transform` as its `to_world`.
fn envmap_with(name: &str, transform: &str) -> Loaded {
    let dir = candela_testkit::TempDir::new(name);
    std::fs::write(dir.join("sky.exr"), b"not read by the loader").unwrap();
    let path = dir.join("env.xml");
    std::fs::write(
        &path,
        format!(
            r#"<scene version="3.0.0"><emitter type="envmap">
            <string name="filename" value="sky.exr"/>
            <transform name="to_world">{transform}</transform></emitter></scene>"#
        ),
    )
    .unwrap();
    load(&path, &LoadOptions::default()).unwrap()
}

fn env_to_world(l: &Loaded) -> glam::Mat3 {
    match &l.scene.environment {
        Some(EnvironmentDesc::Map { to_world, .. }) => *to_world,
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_envmaps_to_world_turns_it_and_only_its_rotation_is_kept() {
    // A yaw then a tilt, a uniform scale and a translation: the rotation is
    // kept exactly, the rest changes no direction and is dropped silently.
    let l = envmap_with(
        "mitsuba-env-rotate",
        r#"<scale value="3"/><rotate y="1" angle="70"/><rotate x="1" angle="25"/>
           <translate x="5"/>"#,
    );
    let want = glam::Mat3::from_rotation_x(25f32.to_radians())
        * glam::Mat3::from_rotation_y(70f32.to_radians());
    let got = env_to_world(&l);
    assert!(
        (got - want).to_cols_array().iter().all(|e| e.abs() < 1e-5),
        "{got} against {want}"
    );
    assert!(l.report.is_empty(), "{}", l.report);
    // An uneven scale is reported once and its rotation (none here) kept.
    let l = envmap_with("mitsuba-env-squash", r#"<scale x="1" y="2" z="1"/>"#);
    assert!(l.report.mentions("to_world"), "{}", l.report);
    let got = env_to_world(&l);
    assert!(
        (got - glam::Mat3::IDENTITY)
            .to_cols_array()
            .iter()
            .all(|e| e.abs() < 1e-6),
        "{got}"
    );
}
