//! The Mitsuba loader's participating media: homogeneous media named by a
//! shape's sides (by reference or inline) and by the sensor, their
//! parameters and Mitsuba's defaults, the material a shape with media gets,
//! what Candela lacks (reported, or refused in strict mode), bad values
//! (located errors), and the integrator that decides whether media are
//! traced at all.
//!
//! Mitsuba's figures below were measured with Mitsuba 3.9 (`scalar_rgb`):
//! its `homogeneous` defaults (sigma_t 1, albedo 0.75, isotropic), `hg`'s
//! default g 0.8, and its readings of spectra.

use candela_scene::{
    load, BsdfDesc, ErrorKind, LoadError, LoadOptions, Loaded, MediumDesc, MediumInterface,
};
use glam::Vec3;

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..LoadOptions::default()
    }
}

/// Loads `body` inside a scene whose integrator is `integrator` (none when
/// empty).
fn try_load_with(
    name: &str,
    integrator: &str,
    body: &str,
    options: &LoadOptions,
) -> Result<Loaded, LoadError> {
    let dir = candela_testkit::TempDir::new(name);
    let path = dir.join("scene.xml");
    let scene = format!("<scene version=\"3.0.0\">\n{integrator}\n{body}\n</scene>");
    std::fs::write(&path, scene).unwrap();
    load(&path, options)
}

const VOLPATH: &str = r#"<integrator type="volpath"/>"#;

/// Loads `body` under `volpath`, strictly: nothing may be reported.
fn load_volpath(name: &str, body: &str) -> Loaded {
    let l = try_load_with(name, VOLPATH, body, &strict()).unwrap();
    assert!(l.report.notes.is_empty(), "{:?}", l.report.notes);
    l
}

/// The interface recorded for material `material`.
fn interface_of(l: &Loaded, material: usize) -> MediumInterface {
    let found: Vec<_> = l
        .scene
        .medium_interfaces
        .iter()
        .filter(|(m, _)| *m == material)
        .collect();
    assert_eq!(found.len(), 1, "{:?}", l.scene.medium_interfaces);
    found[0].1
}

/// The medium on `side`, which must be one.
fn medium(l: &Loaded, side: Option<usize>) -> &MediumDesc {
    &l.scene.media[side.expect("a medium on that side")]
}

const FOG: &str = r#"<medium type="homogeneous" id="fog">
    <rgb name="sigma_t" value="0.5, 1, 2"/><rgb name="albedo" value="0.9, 0.5, 0.1"/>
    <phase type="hg"><float name="g" value="0.3"/></phase></medium>"#;

#[test]
fn a_referenced_medium_is_the_interior_of_a_sphere_and_of_a_rectangle() {
    let l = load_volpath(
        "media-ref",
        &format!(
            r#"{FOG}
    <shape type="sphere"><bsdf type="null"/><ref id="fog" name="interior"/></shape>
    <shape type="rectangle"><ref name="exterior" id="fog"/><ref name="interior" id="fog"/></shape>
    <shape type="sphere"/>"#
        ),
    );
    let s = &l.scene;
    assert_eq!(s.media.len(), 1, "one definition, one medium");
    let fog = &s.media[0];
    assert_eq!(fog.name, "fog");
    assert_eq!(fog.sigma_t, Vec3::new(0.5, 1.0, 2.0));
    assert_eq!(fog.albedo, Vec3::new(0.9, 0.5, 0.1));
    assert_eq!(fog.phase_g, 0.3);
    assert_eq!(fog.loc.line, 3, "where it is defined");

    let sphere = s.spheres[0].material;
    assert_eq!(s.materials[sphere].bsdf, BsdfDesc::Null);
    let inside = interface_of(&l, sphere);
    assert_eq!((inside.interior, inside.exterior), (Some(0), None));

    // The reference is no BSDF: the rectangle keeps Mitsuba's grey diffuse.
    let rect = s.meshes[0].material;
    assert_eq!(
        s.materials[rect].bsdf,
        BsdfDesc::Diffuse {
            albedo: Vec3::splat(0.5)
        }
    );
    let both = interface_of(&l, rect);
    assert_eq!((both.interior, both.exterior), (Some(0), Some(0)));

    // The plain sphere has the shared default material and no interface,
    // which the rectangle's copy is not.
    let plain = s.spheres[1].material;
    assert_ne!(plain, rect);
    assert!(s.medium_interfaces.iter().all(|(m, _)| *m != plain));
    assert_eq!(s.medium_interfaces.len(), 2);
    assert_eq!(s.camera_medium, None);
}

#[test]
fn an_inline_medium_takes_mitsubas_defaults() {
    let l = load_volpath(
        "media-inline",
        r#"<shape type="sphere"><bsdf type="null"/>
        <medium type="homogeneous" name="interior"/>
        <medium type="homogeneous" name="exterior"><float name="sigma_t" value="3"/>
            <float name="albedo" value="0.2"/><phase type="hg"/></medium></shape>"#,
    );
    let sides = interface_of(&l, l.scene.spheres[0].material);
    let inside = medium(&l, sides.interior);
    // Mitsuba 3.9: sigma_t 1, albedo 0.75, isotropic.
    assert_eq!(
        (inside.sigma_t, inside.albedo, inside.phase_g),
        (Vec3::ONE, Vec3::splat(0.75), 0.0)
    );
    let outside = medium(&l, sides.exterior);
    // hg's default g is 0.8 in Mitsuba 3.9.
    assert_eq!(
        (outside.sigma_t, outside.albedo, outside.phase_g),
        (Vec3::splat(3.0), Vec3::splat(0.2), 0.8)
    );
    assert_eq!(l.scene.media.len(), 2);
}

#[test]
fn the_sensors_medium_is_referenced_or_inline() {
    let sensor = |inner: &str| {
        format!(
            r#"{FOG}<sensor type="perspective">{inner}</sensor>
            <sensor type="perspective"/><shape type="sphere"/>"#
        )
    };
    for (inner, expected_sigma_t) in [
        (r#"<ref id="fog"/>"#, Vec3::new(0.5, 1.0, 2.0)),
        (r#"<ref id="fog" name="medium"/>"#, Vec3::new(0.5, 1.0, 2.0)),
        (
            r#"<medium type="homogeneous"><float name="sigma_t" value="4"/></medium>"#,
            Vec3::splat(4.0),
        ),
    ] {
        // The second sensor has no medium: that is a difference from the
        // first, reported.
        let l = try_load_with(
            "media-sensor",
            VOLPATH,
            &sensor(inner),
            &LoadOptions::default(),
        )
        .unwrap();
        assert_eq!(
            medium(&l, l.scene.camera_medium).sigma_t,
            expected_sigma_t,
            "{inner}"
        );
        assert!(l.report.mentions("first sensor's"), "{}", l.report);
        assert!(l.scene.medium_interfaces.is_empty());
    }
    let one = load_volpath(
        "media-sensor-one",
        &format!(r#"{FOG}<sensor type="perspective"><ref id="fog"/></sensor>"#),
    );
    assert_eq!(one.scene.camera_medium, Some(0));
}

#[test]
fn scale_multiplies_sigma_t_and_rgb_may_exceed_one() {
    let l = load_volpath(
        "media-scale",
        r#"<medium type="homogeneous" id="a"><rgb name="sigma_t" value="0.5, 0.25, 1"/>
            <float name="scale" value="4"/></medium>
        <medium type="homogeneous" id="b"><rgb name="sigma_t" value="2, 3, 40"/></medium>
        <medium type="homogeneous" id="c"><float name="scale" value="0.5"/></medium>
        <medium type="homogeneous" id="d">
            <volume type="constvolume" name="sigma_t"><rgb name="value" value="3, 2, 1"/></volume>
            <volume type="constvolume" name="albedo"><float name="value" value="0.4"/></volume>
            <float name="scale" value="2"/></medium>"#,
    );
    let sigma: Vec<Vec3> = l.scene.media.iter().map(|m| m.sigma_t).collect();
    assert_eq!(
        sigma,
        [
            Vec3::new(0.5, 0.25, 1.0) * 4.0,
            Vec3::new(2.0, 3.0, 40.0),
            Vec3::splat(0.5),
            Vec3::new(3.0, 2.0, 1.0) * 2.0
        ]
    );
    assert_eq!(l.scene.media[3].albedo, Vec3::splat(0.4));
}

#[test]
fn a_top_level_volume_and_phase_are_referenced_by_id() {
    let l = load_volpath(
        "media-named-parts",
        r#"<volume type="constvolume" id="dense"><rgb name="value" value="5, 6, 7"/></volume>
        <phase type="hg" id="forward"><float name="g" value="0.6"/></phase>
        <medium type="homogeneous" id="m"><ref name="sigma_t" id="dense"/><ref id="forward"/></medium>
        <shape type="sphere"><ref name="interior" id="m"/></shape>"#,
    );
    let m = &l.scene.media[0];
    assert_eq!((m.sigma_t, m.phase_g), (Vec3::new(5.0, 6.0, 7.0), 0.6));
}

#[test]
fn phase_functions_are_hg_with_their_g_or_isotropic() {
    let l = load_volpath(
        "media-phase",
        r#"<medium type="homogeneous" id="back"><phase type="hg"><float name="g" value="-0.45"/></phase></medium>
        <medium type="homogeneous" id="iso"><phase type="isotropic"/></medium>"#,
    );
    let g: Vec<f32> = l.scene.media.iter().map(|m| m.phase_g).collect();
    assert_eq!(g, [-0.45, 0.0]);
    // Two phase functions are an error, as in Mitsuba.
    let two =
        r#"<medium type="homogeneous" id="m"><phase type="hg"/><phase type="isotropic"/></medium>"#;
    let err = try_load_with("media-two-phases", VOLPATH, two, &strict()).unwrap_err();
    let second = two.find(r#"<phase type="isotropic""#).unwrap() as u32 + 1;
    assert_eq!(
        (
            err.kind,
            err.element.as_str(),
            err.loc.map(|l| (l.line, l.col))
        ),
        (
            ErrorKind::BadValue,
            r#"<phase type="isotropic">"#,
            Some((3, second))
        ),
        "{err}"
    );
}

#[test]
fn a_spectrum_sigma_t_is_read_as_mitsuba_reads_it() {
    let l = try_load_with(
        "media-spectrum",
        VOLPATH,
        r#"<medium type="homogeneous" id="low"><spectrum name="sigma_t" value="400:0.2, 500:0.5, 700:0.9"/></medium>
        <medium type="homogeneous" id="high"><spectrum name="sigma_t" value="400:2, 700:5"/></medium>
        <medium type="homogeneous" id="kept"><volume type="constvolume" name="sigma_t">
            <spectrum name="value" value="400:2, 700:5"/></volume>
            <spectrum name="albedo" value="400:0.2, 700:0.9"/></medium>
        <medium type="homogeneous" id="flat"><spectrum name="sigma_t" value="3"/></medium>"#,
        &strict(),
    )
    .unwrap();
    // Mitsuba 3.9's readings (its printed 6 digits).
    let close = |got: Vec3, want: [f32; 3]| {
        let want = Vec3::from(want);
        assert!(
            ((got - want).abs() / want).max_element() < 2e-5,
            "{got} vs Mitsuba {want}"
        );
    };
    let m = &l.scene.media;
    close(m[0].sigma_t, [0.778248, 0.589654, 0.328566]);
    // Outside a volume Mitsuba clamps a spectrum to [0, 1] (and warns); so
    // does Candela, with a note, which strict mode does not refuse.
    close(m[1].sigma_t, [1.0, 1.0, 1.0]);
    close(m[2].sigma_t, [4.40313, 3.42888, 2.39794]);
    close(m[2].albedo, [0.761972, 0.53347, 0.294211]);
    assert_eq!(m[3].sigma_t, Vec3::splat(3.0));
    let [note] = l.report.notes.as_slice() else {
        panic!("{:?}", l.report.notes)
    };
    assert!(
        note.message.contains("clamped") && note.loc.line == 4,
        "{note}"
    );
}

#[test]
fn only_a_volumetric_integrator_keeps_the_media() {
    let body = format!(
        r#"{FOG}<sensor type="perspective"><ref id="fog"/></sensor>
        <shape type="sphere"><ref id="fog" name="interior"/></shape>"#
    );
    for integrator in [
        r#"<integrator type="path"/>"#,
        "",
        r#"<integrator type="direct"/>"#,
    ] {
        // Not a warning: Mitsuba renders these scenes without media too, so
        // strict mode loads them.
        let l = try_load_with("media-path", integrator, &body, &strict()).unwrap();
        let s = &l.scene;
        assert!(
            s.media.is_empty() && s.medium_interfaces.is_empty() && s.camera_medium.is_none(),
            "{integrator}: {s:?}"
        );
        let [note] = l.report.notes.as_slice() else {
            panic!("{integrator}: {:?}", l.report.notes)
        };
        assert!(
            note.message.contains("participating media are ignored"),
            "{note}"
        );
        let kind = if integrator.is_empty() {
            "\"path\""
        } else {
            integrator.split('"').nth(1).unwrap()
        };
        assert!(note.message.contains(kind), "{note}");
    }
    for integrator in ["volpath", "volpathmis"] {
        let l = try_load_with(
            "media-volpath",
            &format!(r#"<integrator type="{integrator}"/>"#),
            &body,
            &strict(),
        )
        .unwrap();
        assert_eq!(l.scene.media.len(), 1, "{integrator}");
        assert_eq!(l.scene.camera_medium, Some(0));
        assert!(l.report.notes.is_empty());
    }
}

#[test]
fn unsupported_media_are_reported_by_name_and_leave_vacuum() {
    let body = r#"<medium type="heterogeneous" id="smoke"/>
    <medium type="homogeneous" id="sky"><phase type="rayleigh"/></medium>
    <medium type="homogeneous" id="grid"><volume type="gridvolume" name="sigma_t"/></medium>
    <medium type="homogeneous" id="fog"/>
    <shape type="sphere"><ref id="smoke" name="interior"/><ref id="fog" name="exterior"/></shape>
    <shape type="sphere"><ref id="sky" name="interior"/></shape>
    <shape type="sphere"><ref id="grid" name="interior"/></shape>
    <shape type="sphere"><ref id="smoke" name="interior"/></shape>"#;
    let l = try_load_with("media-unsupported", VOLPATH, body, &LoadOptions::default()).unwrap();
    for name in ["heterogeneous", "rayleigh", "gridvolume"] {
        assert!(l.report.mentions(name), "{name}: {}", l.report);
    }
    assert_eq!(l.report.len(), 3, "each once: {}", l.report);
    assert_eq!(l.scene.media.len(), 1, "only fog");
    let s = &l.scene;
    let first = interface_of(&l, s.spheres[0].material);
    assert_eq!((first.interior, first.exterior), (None, Some(0)));
    // The others name only dropped media: vacuum on both sides.
    for sphere in &s.spheres[1..] {
        assert!(s
            .medium_interfaces
            .iter()
            .all(|(m, i)| *m != sphere.material || *i == MediumInterface::default()));
    }
    let err = try_load_with("media-unsupported-strict", VOLPATH, body, &strict()).unwrap_err();
    assert_eq!(err.kind, ErrorKind::Unsupported, "{err}");
    assert!(err.to_string().contains("heterogeneous"), "{err}");
}

#[test]
fn a_medium_named_neither_interior_nor_exterior_is_reported() {
    let l = try_load_with(
        "media-unnamed",
        VOLPATH,
        &format!(r#"{FOG}<shape type="sphere"><ref id="fog"/></shape>"#),
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(l.report.mentions("interior"), "{}", l.report);
    assert!(l.scene.medium_interfaces.is_empty());
}

#[test]
fn bad_values_are_located_errors() {
    // (what wraps it, the property, what the message names, the element)
    let cases = [
        (
            "",
            r#"<rgb name="albedo" value="1.5"/>"#,
            "albedo",
            r#"<rgb name="albedo">"#,
        ),
        (
            "",
            r#"<float name="albedo" value="-0.1"/>"#,
            "albedo",
            r#"<float name="albedo">"#,
        ),
        (
            "",
            r#"<float name="sigma_t" value="-1"/>"#,
            "sigma_t",
            r#"<float name="sigma_t">"#,
        ),
        (
            "",
            r#"<float name="scale" value="-2"/>"#,
            "scale",
            r#"<float name="scale">"#,
        ),
        (
            "phase type=\"hg\"",
            r#"<float name="g" value="1"/>"#,
            "g 1",
            r#"<float name="g">"#,
        ),
    ];
    for (wrapper, property, what, element) in cases {
        let (open, close) = match wrapper {
            "" => (String::new(), String::new()),
            w => (format!("<{w}>"), "</phase>".to_string()),
        };
        let body = format!(
            "<medium type=\"homogeneous\" id=\"bad\">{open}\n    {property}{close}</medium>"
        );
        let err = try_load_with("media-bad", VOLPATH, &body, &LoadOptions::default()).unwrap_err();
        assert_eq!(err.kind, ErrorKind::BadValue, "{err}");
        // The scene's line 1 is <scene>, 2 the integrator, 3 the medium.
        let loc = err.loc.expect("located");
        assert_eq!((loc.line, loc.col), (4, 5), "{err}");
        assert_eq!(err.element, element);
        let line = err.to_string();
        assert!(
            line.contains(":4:5: ") && line.contains(what) && !line.contains('\n'),
            "{line}"
        );
    }
    let missing = try_load_with(
        "media-missing",
        VOLPATH,
        r#"<shape type="sphere"><ref id="nowhere" name="interior"/></shape>"#,
        &LoadOptions::default(),
    )
    .unwrap_err();
    assert_eq!(missing.kind, ErrorKind::MissingReference, "{missing}");
    assert!(missing.message.contains("no <medium>"), "{missing}");
}

#[test]
fn a_shared_bsdf_is_copied_for_the_shape_with_a_medium_only() {
    let l = load_volpath(
        "media-shared-bsdf",
        &format!(
            r#"{FOG}<bsdf type="dielectric" id="glass"/>
        <shape type="sphere"><ref id="glass"/></shape>
        <shape type="sphere"><ref id="glass"/><ref id="fog" name="interior"/></shape>
        <shape type="sphere"><ref id="glass"/></shape>"#
        ),
    );
    let s = &l.scene;
    let [a, b, c] = [0, 1, 2].map(|i| s.spheres[i].material);
    assert_eq!(a, c, "shapes without media share the BSDF's material");
    assert_ne!(a, b);
    assert_eq!(s.materials.len(), 2);
    assert_eq!(
        s.materials[a], s.materials[b],
        "the copy is the same surface"
    );
    assert_eq!(s.medium_interfaces, [(b, interface_of(&l, b))]);
    assert_eq!(interface_of(&l, b).interior, Some(0));
}

#[test]
fn shapes_in_a_group_carry_their_media_to_every_instance() {
    let l = load_volpath(
        "media-group",
        &format!(
            r#"{FOG}<shape type="shapegroup" id="g">
            <shape type="cube"><ref id="fog" name="interior"/></shape></shape>
        <shape type="instance"><ref id="g"/></shape>
        <shape type="instance"><ref id="g"/><transform name="to_world"><translate x="3"/></transform></shape>"#
        ),
    );
    let s = &l.scene;
    assert_eq!((s.meshes.len(), s.instances.len()), (1, 2));
    let sides = interface_of(&l, s.meshes[0].material);
    assert_eq!(sides.interior, Some(0));
}
