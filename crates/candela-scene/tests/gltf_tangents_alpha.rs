//! glTF `TANGENT` attributes and constant alpha: tangents load per vertex
//! (normalised xyz, w the handedness sign) without a report; a `BLEND` or
//! `MASK` material with only a base colour factor's alpha gets a constant
//! opacity (with `MASK`'s cutoff).

// The shared document helpers; this file needs only the `.gltf` ones.
#[allow(dead_code)]
mod gltf;

use candela_scene::{load, LoadOptions, Loaded};
use glam::{Vec3, Vec4};
use serde_json::json;

fn load_ok(bytes: &[u8], name: &str) -> Loaded {
    load(&gltf::write(name, bytes), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn tangents_load_per_vertex_with_their_handedness() {
    // After the base buffer (44 bytes): three normals, then three tangents,
    // one unnormalised (an exporter's rounding) and one left-handed.
    let mut buf = gltf::buffer();
    let normals = [Vec3::Z; 3];
    let tangents = [
        Vec4::new(1.0, 0.0, 0.0, 1.0),
        Vec4::new(0.0, 2.0, 0.0, -1.0),
        Vec4::new(0.6, 0.8, 0.0, 1.0),
    ];
    for v in normals.iter().flat_map(|n| n.to_array()) {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    for v in tangents.iter().flat_map(|t| t.to_array()) {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    let text = gltf::gltf_text(|d| {
        d["buffers"] = json!([{"uri": gltf::data_uri(&buf), "byteLength": buf.len()}]);
        let views = d["bufferViews"].as_array_mut().unwrap();
        views.push(json!({"buffer": 0, "byteOffset": 44, "byteLength": 36}));
        views.push(json!({"buffer": 0, "byteOffset": 80, "byteLength": 48}));
        let accessors = d["accessors"].as_array_mut().unwrap();
        accessors.push(json!({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"}));
        accessors.push(json!({"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}));
        d["meshes"][0]["primitives"][0]["attributes"] =
            json!({"POSITION": 0, "NORMAL": 2, "TANGENT": 3});
    });
    let l = load_ok(&text, "tangents.gltf");
    let mesh = &l.scene.meshes[0];
    assert_eq!(
        mesh.tangents,
        vec![
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, -1.0),
            Vec4::new(0.6, 0.8, 0.0, 1.0)
                .truncate()
                .normalize()
                .extend(1.0),
        ]
    );
    assert_eq!(mesh.tangents.len(), mesh.normals.len());
    assert_eq!(mesh.normal_indices, mesh.triangles);
    let report = l.report.to_string();
    assert!(!report.contains("TANGENT"), "{report}");
}

/// The base document with material 0 given `alphaMode` and `extra`.
fn with_alpha(mode: &str, alpha: f32, extra: serde_json::Value) -> Vec<u8> {
    gltf::gltf_text(|d| {
        let m = &mut d["materials"][0];
        m["pbrMetallicRoughness"]["baseColorFactor"] = json!([0.8, 0.2, 0.2, alpha]);
        m["alphaMode"] = json!(mode);
        if let Some(cutoff) = extra.get("alphaCutoff") {
            m["alphaCutoff"] = cutoff.clone();
        }
    })
}

#[test]
fn a_constant_alpha_becomes_a_constant_opacity() {
    let blend = load_ok(&with_alpha("BLEND", 0.25, json!({})), "blend.gltf");
    let t = &blend.scene.materials[0].textures;
    assert_eq!((t.opacity_constant, t.opacity_cutoff), (Some(0.25), None));
    assert!(t.opacity.is_none());
    assert!(blend.report.warnings.is_empty(), "{}", blend.report);
    let mask = load_ok(
        &with_alpha("MASK", 0.3, json!({"alphaCutoff": 0.4})),
        "mask.gltf",
    );
    let t = &mask.scene.materials[0].textures;
    assert_eq!(
        (t.opacity_constant, t.opacity_cutoff),
        (Some(0.3), Some(0.4))
    );
    // Opaque alpha, and OPAQUE whatever the alpha: no opacity at all.
    for (mode, alpha) in [("BLEND", 1.0), ("OPAQUE", 0.25)] {
        let l = load_ok(&with_alpha(mode, alpha, json!({})), "opaque.gltf");
        assert_eq!(l.scene.materials[0].textures.opacity_constant, None);
    }
}
