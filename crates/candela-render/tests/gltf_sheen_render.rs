//! `KHR_materials_sheen` from a glTF file to pixels: a large grey cloth
//! under a white sky, seen straight down and at 80° from its normal, with
//! and without a white sheen. The sheen is a back-scattering rim: it
//! brightens the grazing view by far more than the straight one (where the
//! base, dimmed by the sheen's albedo scaling, may even lose a little).
//!
//! Under a constant sky of radiance 1 the plane's radiance is its
//! directional albedo, so each render's mean is that albedo; bounds are 5
//! standard errors of the difference (fixed seeds).

mod common;

use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_scene::{load, CameraDesc, EnvironmentDesc, LoadOptions, Projection, SceneDesc};
use common::{estimate, Estimate};
use glam::{Mat4, Vec3};
use serde_json::{json, Value};

/// Half the plane's side: it fills both views to their edges.
const HALF: f32 = 50.0;

/// The plane (y = 0, normal +Y) as a glTF file in `dir`, its material a
/// grey rough dielectric with `extensions`, loaded strictly (nothing
/// reported, the sheen extension included).
fn cloth(dir: &candela_testkit::TempDir, name: &str, extensions: Value) -> SceneDesc {
    let mut bin = Vec::new();
    for [x, z] in [[-HALF, -HALF], [HALF, -HALF], [HALF, HALF], [-HALF, HALF]] {
        for v in [x, 0.0, z] {
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    for i in [0u16, 2, 1, 0, 3, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.join(format!("{name}.bin")), &bin).unwrap();
    let doc = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_sheen"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{
            "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.7},
            "extensions": extensions
        }],
        "buffers": [{"uri": format!("{name}.bin"), "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 12}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-HALF, 0.0, -HALF], "max": [HALF, 0.0, HALF]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ]
    });
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    let options = LoadOptions {
        strict: true,
        ..LoadOptions::default()
    };
    let loaded = load(&path, &options).unwrap_or_else(|e| panic!("{e}"));
    let mut desc = loaded.scene;
    desc.environment = Some(EnvironmentDesc::Constant {
        radiance: Vec3::ONE,
    });
    desc
}

/// A narrow camera (4°) one unit above the plane's centre, looking at it
/// `degrees` from its normal.
fn camera(degrees: f32) -> CameraDesc {
    let (s, c) = degrees.to_radians().sin_cos();
    // The camera looks down its −Z: columns right, up, back, eye.
    let (forward, up) = (Vec3::new(0.0, -c, -s), Vec3::new(0.0, s, -c));
    let eye = Vec3::new(0.0, 1.0, 0.0);
    CameraDesc {
        name: format!("{degrees}°"),
        world_from_camera: Mat4::from_cols(
            forward.cross(up).extend(0.0),
            up.extend(0.0),
            (-forward).extend(0.0),
            eye.extend(1.0),
        ),
        projection: Projection::Perspective {
            xfov_deg: 4.0,
            yfov_deg: 4.0,
        },
        znear: None,
        zfar: None,
        clip: None,
        loc: Default::default(),
    }
}

/// The mean radiance of `desc` seen from `camera`.
fn albedo_seen(desc: &SceneDesc, camera: CameraDesc, seed: u64) -> Estimate {
    let mut desc = desc.clone();
    desc.cameras = vec![camera];
    let e = estimate(
        &desc,
        IntegratorSettings::path(4, LightingMode::Mis),
        8,
        64,
        seed,
    );
    assert_eq!(e.invalid, 0);
    e
}

#[test]
fn a_gltf_sheen_brightens_grazing_views_most() {
    let dir = candela_testkit::TempDir::new("gltf-sheen-render");
    let plain = cloth(&dir, "plain", json!({}));
    let sheen = cloth(
        &dir,
        "sheen",
        json!({"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5}}),
    );
    let gain = |degrees: f32, seed: u64| {
        let a = albedo_seen(&sheen, camera(degrees), seed);
        let b = albedo_seen(&plain, camera(degrees), seed + 1);
        let error = (a.std_error.powi(2) + b.std_error.powi(2)).sqrt();
        eprintln!(
            "{degrees}°: sheen {:.4} ± {:.4}, plain {:.4} ± {:.4}",
            a.mean, a.std_error, b.mean, b.std_error
        );
        (a.mean - b.mean, error)
    };
    let (straight, straight_error) = gain(0.0, 1);
    let (grazing, grazing_error) = gain(80.0, 3);
    assert!(
        grazing > 5.0 * grazing_error,
        "grazing gain {grazing} ± {grazing_error}"
    );
    let error = (straight_error.powi(2) + grazing_error.powi(2)).sqrt();
    assert!(
        grazing - straight > 5.0 * error,
        "grazing gain {grazing} vs straight {straight} (± {error})"
    );
}
