//! Lenient loading beyond the malformed corpus: the CGL profile aliases of
//! the CMU 15-462 files, the CS184 lamp whose area light and mesh disagree on
//! radiance, and the CS184 corpus loading identically in both modes.

use candela_scene::{load, load_str, BsdfDesc, ErrorKind, LoadOptions, SourceLoc};
use glam::Vec3;
use std::path::{Path, PathBuf};

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..Default::default()
    }
}

/// 1-based line:col of the first occurrence of `needle` in `text`.
fn loc_of(text: &str, needle: &str) -> SourceLoc {
    let byte = text.find(needle).unwrap();
    let before = &text[..byte];
    let line = before.matches('\n').count() + 1;
    let col = byte - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    SourceLoc {
        line: line as u32,
        col: col as u32,
    }
}

fn valid_base() -> String {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests");
    std::fs::read_to_string(dir.join("valid_base.dae")).unwrap()
}

#[test]
fn cmu462_profile_reads_as_cgl_and_is_reported_once() {
    let text = valid_base()
        .replace("profile=\"CGL\"><sphere>", "profile=\"CMU462\"><sphere>")
        .replace(
            "</profile_COMMON></effect>",
            "</profile_COMMON><extra><technique profile=\"CMU462\"><mirror/></technique></extra></effect>",
        );
    let loaded = load_str(&text, Path::new("cmu.dae"), &LoadOptions::default()).unwrap();
    let s = &loaded.scene;
    assert_eq!(s.spheres.len(), 1, "the sphere is read through the alias");
    let red = s.materials.iter().find(|m| m.name == "red").unwrap();
    assert!(
        matches!(red.bsdf, BsdfDesc::Mirror { .. }),
        "{:?}",
        red.bsdf
    );
    let [w] = loaded.report.warnings.as_slice() else {
        panic!("expected one warning:\n{}", loaded.report)
    };
    assert!(w.message.contains("\"CMU462\""), "{w}");
    assert_eq!(w.element, "<technique>");
    // Reported once, at the first use (the quad's material is read before the sphere).
    assert_eq!(w.count, 2, "{w}");
    assert_eq!(
        w.loc,
        loc_of(&text, "<technique profile=\"CMU462\">"),
        "{w}"
    );

    // Strict mode does not know the alias: as before, the sphere is an
    // unsupported geometry.
    let err = load_str(&text, Path::new("cmu.dae"), &strict()).unwrap_err();
    assert_eq!(err.kind, ErrorKind::Unsupported, "{err}");
    assert_eq!(err.element, "<geometry>", "{err}");
    assert_eq!(
        err.loc,
        Some(loc_of(&text, "<geometry id=\"ball\">")),
        "{err}"
    );
}

/// A CS184-style lamp: an emissive 0.8 x 0.6 quad at height 1.49 facing down
/// (radiance `mesh`) and a CGL area light of the same size 0.004 below it
/// (radiance `light`).
fn lamp_scene(mesh: f32, light: f32) -> String {
    format!(
        r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_lights>
    <light id="area"><extra><technique profile="CGL"><area><color>{light} {light} {light}</color></area></technique></extra></light>
  </library_lights>
  <library_effects>
    <effect id="glow"><extra><technique profile="CGL"><emission><radiance>{mesh} {mesh} {mesh}</radiance></emission></technique></extra></effect>
  </library_effects>
  <library_materials><material id="lamp"><instance_effect url="#glow"/></material></library_materials>
  <library_geometries>
    <geometry id="quad" name="lamp_mesh"><mesh>
      <source id="pos">
        <float_array id="pos-a" count="12">0.4 1.49 -0.3 0.4 1.49 0.3 -0.4 1.49 0.3 -0.4 1.49 -0.3</float_array>
        <technique_common><accessor source="#pos-a" count="4" stride="3"/></technique_common>
      </source>
      <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
      <triangles material="m" count="2"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2 0 2 3</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="s">
      <node id="lightnode"><translate>0 1.486 0</translate><rotate>1 0 0 -90</rotate><scale>0.8 0.6 1</scale><instance_light url="#area"/></node>
      <node id="quadnode"><instance_geometry url="#quad"><bind_material><technique_common><instance_material symbol="m" target="#lamp"/></technique_common></bind_material></instance_geometry></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##
    )
}

/// The emission of the lamp mesh's one instance.
fn lamp_emission(s: &candela_scene::SceneDesc) -> Option<Vec3> {
    let [inst] = s.instances.as_slice() else {
        panic!("{:?}", s.instances)
    };
    s.materials[inst.material.unwrap_or(s.meshes[inst.mesh].material)].emission
}

#[test]
fn an_area_light_on_a_brighter_lamp_mesh_sets_its_radiance_once() {
    for opts in [LoadOptions::default(), strict()] {
        let text = lamp_scene(10.0, 5.0);
        let loaded = load_str(&text, Path::new("lamp.dae"), &opts).unwrap();
        assert!(loaded.report.is_empty(), "{}", loaded.report);
        assert!(loaded.scene.lights.is_empty(), "the lamp is counted once");
        assert_eq!(lamp_emission(&loaded.scene), Some(Vec3::splat(5.0)));
        let [note] = loaded.report.notes.as_slice() else {
            panic!("{:?}", loaded.report.notes)
        };
        assert!(note.message.contains("(5, 5, 5)"), "{note}");
        assert!(note.message.contains("(10, 10, 10)"), "{note}");
        assert_eq!(note.loc, loc_of(&text, "<instance_light"), "{note}");
    }
    // Agreeing radiances: the mesh keeps its own (the CS184 Cornell boxes).
    let loaded = load_str(&lamp_scene(10.0, 10.0), Path::new("lamp.dae"), &strict()).unwrap();
    assert!(loaded.scene.lights.is_empty());
    assert_eq!(lamp_emission(&loaded.scene), Some(Vec3::splat(10.0)));
    assert!(loaded.report.notes[0].message.contains("counted once"));
    // Asked to keep duplicates: both stay, at their own radiances.
    let opts = LoadOptions {
        keep_duplicate_lamps: true,
        ..Default::default()
    };
    let loaded = load_str(&lamp_scene(10.0, 5.0), Path::new("lamp.dae"), &opts).unwrap();
    assert_eq!(loaded.scene.lights.len(), 1);
    assert_eq!(lamp_emission(&loaded.scene), Some(Vec3::splat(10.0)));
}

#[test]
fn every_cs184_scene_loads_the_same_in_both_modes() {
    let dir = candela_testkit::shared_dir().join("scenes/cs184");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "dae") {
            continue;
        }
        let strict = load(&path, &strict()).unwrap_or_else(|e| panic!("{e}"));
        let lenient = load(&path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        assert!(lenient.report.is_empty(), "{}", lenient.report);
        assert_eq!(strict.report.notes, lenient.report.notes);
        assert_eq!(
            format!("{:?}", strict.scene),
            format!("{:?}", lenient.scene),
            "{}",
            path.display()
        );
        n += 1;
    }
    assert!(n >= 17, "only {n} CS184 scenes in {}", dir.display());
}
