//! glTF loading: the Khronos sample files, instancing, cameras, light units,
//! materials, `.glb` against `.gltf`.

#[allow(dead_code)]
mod gltf;

use candela_scene::{
    load, BsdfDesc, LightKind, LoadOptions, Loaded, Projection, TextureFilter, TextureSlot,
    TextureWrap, WrapMode,
};
use glam::{Mat4, Vec3};
use gltf::{glb, gltf_text, write};
use serde_json::json;
use std::path::PathBuf;

fn shared(name: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/scenes/formats/gltf")
        .join(name)
        .join(format!("{name}.gltf"));
    assert!(path.exists(), "shared sample {} is missing", path.display());
    path
}

fn load_ok(path: &std::path::Path) -> Loaded {
    load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

#[test]
fn khronos_box_loads_with_its_counts_and_bounds() {
    let l = load_ok(&shared("Box"));
    let s = &l.scene;
    // Box.gltf: 24 vertices, 36 indices, one red diffuse material, no camera.
    assert_eq!((s.meshes.len(), s.instances.len()), (1, 1));
    assert_eq!(s.meshes[0].positions.len(), 24);
    assert_eq!(s.triangle_count(), 12);
    assert_eq!(s.meshes[0].normals.len(), 24);
    let (lo, hi) = s.bounds().expect("bounds");
    assert!(
        close(lo, Vec3::splat(-0.5)) && close(hi, Vec3::splat(0.5)),
        "{lo} {hi}"
    );
    assert!(
        matches!(s.materials[0].bsdf, BsdfDesc::MetallicRoughness { base_color, .. } if close(base_color, Vec3::new(0.8, 0.0, 0.0)))
    );
    assert!(s.cameras.is_empty() && !l.hints.file_camera);
}

#[test]
fn khronos_box_textured_embeds_its_png_where_the_renderer_reads_it() {
    let l = load_ok(&shared("BoxTextured"));
    let s = &l.scene;
    assert_eq!(s.triangle_count(), 12);
    assert_eq!(s.meshes[0].uvs.len(), 24);
    assert_eq!(s.meshes[0].uv_indices, s.meshes[0].triangles);
    let tex = s.materials[0]
        .textures
        .get(TextureSlot::Color)
        .expect("colour texture");
    let path = tex.image_path().expect("an image");
    let bytes = std::fs::read(path).expect("cached image");
    assert!(bytes.starts_with(b"\x89PNG"), "{}", path.display());
    assert_eq!(path.extension().and_then(|e| e.to_str()), Some("png"));
}

#[test]
fn khronos_simple_meshes_is_one_mesh_drawn_twice() {
    let s = load_ok(&shared("SimpleMeshes")).scene;
    assert_eq!((s.meshes.len(), s.instances.len()), (1, 2));
    assert_eq!((s.triangle_count(), s.instanced_triangle_count()), (1, 2));
    assert_eq!(
        s.instances[1].world_from_object,
        Mat4::from_translation(Vec3::X)
    );
    let (lo, hi) = s.bounds().expect("bounds");
    assert!(
        close(lo, Vec3::ZERO) && close(hi, Vec3::new(2.0, 1.0, 0.0)),
        "{lo} {hi}"
    );
}

#[test]
fn glb_and_gltf_of_one_document_load_the_same() {
    let a = load_ok(&write("same.gltf", &gltf_text(|_| {}))).scene;
    let b = load_ok(&write("same.glb", &glb())).scene;
    assert_eq!(a.meshes, b.meshes);
    assert_eq!(a.instances, b.instances);
    assert_eq!(a.cameras.len(), b.cameras.len());
    assert_eq!(a.lights, b.lights);
}

#[test]
fn a_perspective_camera_is_the_file_camera_with_its_fields_of_view() {
    let l = load_ok(&write("camera.gltf", &gltf_text(|_| {})));
    assert!(l.hints.file_camera);
    let cam = &l.scene.cameras[0];
    let Projection::Perspective { xfov_deg, yfov_deg } = cam.projection else {
        panic!("{:?}", cam.projection)
    };
    assert!((yfov_deg - 0.8f32.to_degrees()).abs() < 1e-4);
    // tan(x/2) = aspect * tan(y/2).
    let expect_x = 2.0 * (1.5 * (0.4f32).tan()).atan().to_degrees();
    assert!(
        (xfov_deg - expect_x).abs() < 1e-3,
        "{xfov_deg} vs {expect_x}"
    );
    assert_eq!(
        cam.world_from_camera,
        Mat4::from_translation(Vec3::new(0.0, 0.0, 5.0))
    );
}

#[test]
fn cameras_are_kept_in_node_order_and_orthographic_keeps_its_width() {
    let text = gltf_text(|d| {
        d["cameras"].as_array_mut().unwrap().push(json!(
            {"type": "orthographic", "orthographic": {"xmag": 3.0, "ymag": 2.0, "znear": 0.1, "zfar": 50.0}}
        ));
        // Node 4 (the orthographic camera) is listed first in the scene.
        d["nodes"]
            .as_array_mut()
            .unwrap()
            .push(json!({"camera": 1}));
        d["scenes"][0]["nodes"] = json!([4, 0, 1, 2, 3]);
    });
    let s = load_ok(&write("ortho.gltf", &text)).scene;
    assert_eq!(s.cameras.len(), 2);
    assert!(matches!(
        s.cameras[0].projection,
        Projection::Perspective { .. }
    ));
    assert_eq!(
        s.cameras[1].projection,
        Projection::Orthographic { width: 6.0 }
    );
}

#[test]
fn punctual_lights_are_divided_by_683_lumens_per_watt() {
    let text = gltf_text(|d| {
        let lights = d["extensions"]["KHR_lights_punctual"]["lights"]
            .as_array_mut()
            .unwrap();
        lights.push(json!({"type": "directional", "intensity": 1366.0}));
        lights.push(json!({"type": "spot", "intensity": 68.3, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}));
        let nodes = d["nodes"].as_array_mut().unwrap();
        nodes.push(json!({"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-std::f32::consts::FRAC_1_SQRT_2, 0.0, 0.0, std::f32::consts::FRAC_1_SQRT_2]}));
        nodes.push(json!({"extensions": {"KHR_lights_punctual": {"light": 2}}, "translation": [1.0, 2.0, 3.0]}));
        d["scenes"][0]["nodes"] = json!([0, 1, 2, 3, 4, 5]);
    });
    let l = load_ok(&write("lights.gltf", &text));
    let lights = &l.scene.lights;
    assert_eq!(lights.len(), 3);
    // 683 cd of colour (1, 0.5, 0.25) = (1, 0.5, 0.25) W/sr.
    assert!(
        matches!(lights[0].kind, LightKind::Point { position, intensity }
        if close(position, Vec3::new(0.0, 3.0, 0.0)) && close(intensity, Vec3::new(1.0, 0.5, 0.25)))
    );
    // 1366 lux = 2 W/m², travelling down local -Z turned by -90° about X: straight down.
    assert!(
        matches!(lights[1].kind, LightKind::Directional { direction, radiance }
        if close(direction, Vec3::NEG_Y) && close(radiance, Vec3::splat(2.0))),
        "{:?}",
        lights[1]
    );
    let LightKind::Spot {
        position,
        direction,
        intensity,
        cone_angle_deg,
        edge,
        ..
    } = lights[2].kind
    else {
        panic!("{:?}", lights[2])
    };
    assert!(close(position, Vec3::new(1.0, 2.0, 3.0)) && close(direction, Vec3::NEG_Z));
    assert!(close(intensity, Vec3::splat(0.1)));
    assert!((cone_angle_deg - 2.0 * 0.5f32.to_degrees()).abs() < 1e-4);
    // The smooth fade from the inner cone (0.1 rad) to the outer one.
    match edge {
        candela_scene::SpotEdge::SmoothInCosine { inner_angle_deg } => {
            assert!((inner_angle_deg - 2.0 * 0.1f32.to_degrees()).abs() < 1e-4)
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn metallic_roughness_materials_map_onto_the_bsdfs() {
    let text = gltf_text(|d| {
        d["materials"] = json!([
            {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.5}},
        ]);
    });
    let s = load_ok(&write("metal.gltf", &text)).scene;
    assert_eq!(
        s.materials[0].bsdf,
        BsdfDesc::MetallicRoughness {
            base_color: Vec3::new(0.9, 0.6, 0.3),
            metallic: 1.0,
            roughness: 0.5,
            transmission: 0.0,
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            sheen_color: Vec3::ZERO,
            sheen_roughness: 0.0,
        }
    );
}

#[test]
fn khr_materials_specular_sets_the_layers_strength_and_tint() {
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!(["KHR_materials_specular"]);
        d["materials"] = json!([
            {"pbrMetallicRoughness": {"metallicFactor": 0.0},
             "extensions": {"KHR_materials_specular":
                 {"specularFactor": 0.0, "specularColorFactor": [0.5, 1.0, 2.0]}}},
        ]);
    });
    let l = load_ok(&write("specular.gltf", &text));
    assert!(
        matches!(l.scene.materials[0].bsdf, BsdfDesc::MetallicRoughness { specular, specular_color, .. }
            if specular == 0.0 && specular_color == Vec3::new(0.5, 1.0, 2.0)),
        "{:?}",
        l.scene.materials[0].bsdf
    );
    assert!(!l.report.mentions("KHR_materials_specular"), "{}", l.report);
}

#[test]
fn emission_transmission_and_texture_slots() {
    let png = gltf::data_uri(b"\x89PNG not really");
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!([
            "KHR_lights_punctual",
            "KHR_materials_emissive_strength",
            "KHR_materials_transmission",
            "KHR_materials_ior"
        ]);
        d["images"] = json!([{"uri": png.replace("application/octet-stream", "image/png")}, {"uri": "rough metal.png"}]);
        d["textures"] = json!([{"source": 0}, {"source": 1}]);
        d["materials"] = json!([
            {"emissiveFactor": [1.0, 1.0, 1.0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5.0}},
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
                                      "metallicFactor": 0.0, "roughnessFactor": 0.7},
             "normalTexture": {"index": 1, "scale": 0.5}, "alphaMode": "MASK"},
            {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.33}},
             "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.0}}
        ]);
        let mut second = d["meshes"][0]["primitives"][0].clone();
        second["material"] = json!(1);
        d["meshes"][0]["primitives"]
            .as_array_mut()
            .unwrap()
            .push(second);
    });
    let path = write("slots.gltf", &text);
    let l = load_ok(&path);
    let s = &l.scene;
    // One glTF mesh of two primitives used by two nodes: two meshes, four instances.
    assert_eq!((s.meshes.len(), s.instances.len()), (2, 4));
    let m = &s.materials[0];
    assert_eq!(m.emission, Some(Vec3::splat(5.0)));
    let t = &m.textures;
    let rough = t.get(TextureSlot::Roughness).expect("roughness");
    let metal = t.get(TextureSlot::Metalness).expect("metalness");
    assert_eq!((rough.channel, metal.channel), (Some(1), Some(2)));
    assert_eq!(
        rough.image_path(),
        Some(path.parent().unwrap().join("rough metal.png").as_path())
    );
    assert!((rough.scale - 0.7).abs() < 1e-6 && metal.scale == 0.0);
    assert_eq!(t.get(TextureSlot::Normal).map(|n| n.scale), Some(0.5));
    assert_eq!(t.get(TextureSlot::Opacity).and_then(|o| o.channel), Some(3));
    assert!(t.get(TextureSlot::Color).is_some());
    assert_eq!(t.opacity_cutoff, Some(0.5), "MASK with the default cutoff");
    assert_eq!(
        s.materials[1].bsdf,
        BsdfDesc::MetallicRoughness {
            base_color: Vec3::ONE,
            metallic: 0.0,
            roughness: 0.0,
            transmission: 1.0,
            ior: 1.33,
            specular: 1.0,
            specular_color: Vec3::ONE,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            sheen_color: Vec3::ZERO,
            sheen_roughness: 0.0,
        }
    );
}

#[test]
fn colour_factors_tint_their_textures_per_channel() {
    // glTF: base colour = baseColorFactor × texel, emission = emissiveFactor
    // × emissive_strength × texel, per channel; neither is reported.
    let text = gltf::with_materials(
        &["KHR_materials_emissive_strength"],
        json!([{
            "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1.0],
                                     "baseColorTexture": {"index": 0}},
            "emissiveFactor": [1.0, 0.5, 0.0], "emissiveTexture": {"index": 1},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}}]),
    );
    let l = load_ok(&write("tinted.gltf", &text));
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    let t = &l.scene.materials[0].textures;
    let color = t.get(TextureSlot::Color).expect("baseColorTexture");
    assert_eq!(color.tint, Vec3::new(0.9, 0.6, 0.3));
    assert_eq!((color.scale, color.channel), (1.0, None));
    let emission = t.get(TextureSlot::Emission).expect("emissiveTexture");
    assert_eq!(emission.tint, Vec3::new(1.0, 0.5, 0.0));
    assert_eq!((emission.scale, emission.channel), (4.0, None));
    // The constant emission stays the factor times the strength.
    assert_eq!(
        l.scene.materials[0].emission,
        Some(Vec3::new(4.0, 2.0, 0.0))
    );
}

#[test]
fn unsupported_features_are_reported_once_by_name() {
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!([
            "KHR_lights_punctual",
            "KHR_draco_mesh_compression",
            "KHR_texture_basisu"
        ]);
        let mut lines = d["meshes"][0]["primitives"][0].clone();
        lines["mode"] = json!(1);
        d["meshes"] = json!([{"primitives": [lines.clone(), lines]}]);
        d["animations"] = json!([]);
    });
    let l = load_ok(&write("unsupported.gltf", &text));
    let r = &l.report;
    assert!(
        r.mentions("KHR_draco_mesh_compression") && r.mentions("KHR_texture_basisu"),
        "{r}"
    );
    let mode: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.element.contains("mode"))
        .collect();
    assert_eq!(mode.len(), 1, "{r}");
    assert_eq!(mode[0].count, 2);
    assert!(l.scene.meshes.is_empty());
    let strict = load(
        &write("unsupported-strict.gltf", &text),
        &LoadOptions {
            strict: true,
            ..Default::default()
        },
    );
    assert_eq!(
        strict.expect_err("strict").kind,
        candela_scene::ErrorKind::Unsupported
    );
}

#[test]
fn sparse_accessors_overwrite_their_base() {
    // Move vertex 2 to (0, 2, 0) with a sparse entry stored after the indices.
    let mut buf = gltf::buffer();
    buf.extend_from_slice(&2u16.to_le_bytes());
    buf.extend_from_slice(&[0, 0]);
    for v in [0.0f32, 2.0, 0.0] {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    let text = gltf_text(|d| {
        d["buffers"] = json!([{"uri": gltf::data_uri(&buf), "byteLength": buf.len()}]);
        d["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(json!({"buffer": 0, "byteOffset": 44, "byteLength": 2}));
        d["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(json!({"buffer": 0, "byteOffset": 48, "byteLength": 12}));
        d["accessors"][0]["sparse"] = json!({"count": 1,
            "indices": {"bufferView": 2, "componentType": 5123}, "values": {"bufferView": 3}});
    });
    let s = load_ok(&write("sparse.gltf", &text)).scene;
    assert_eq!(s.meshes[0].positions[2], Vec3::new(0.0, 2.0, 0.0));
}

#[test]
fn the_projects_textured_scene_loads_with_flipped_uvs_and_every_slot() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/gltf/textured.gltf");
    let l = load_ok(&path);
    let s = &l.scene;
    assert_eq!(s.cameras.len(), 2, "front and side");
    // glTF's (u, v) = (0, 0) is the image's top-left: Candela's (0, 1).
    let bricks = &s.meshes[0];
    assert_eq!(bricks.uvs[0], glam::Vec2::new(0.0, 1.0));
    let t = &s.materials[0].textures;
    assert!(t.get(TextureSlot::Color).is_some() && t.get(TextureSlot::Normal).is_some());
    assert_eq!(t.get(TextureSlot::Opacity).and_then(|o| o.channel), Some(3));
    assert_eq!(t.opacity_cutoff, Some(0.5));
    assert!(
        matches!(s.materials[1].bsdf, BsdfDesc::MetallicRoughness { metallic, .. } if metallic == 1.0)
    );
    assert!(l.report.warnings.is_empty(), "{}", l.report);
}

#[test]
fn khr_texture_transform_places_every_texture_as_the_extension_says() {
    // The extension reads a texture at T(offset) R(rotation) S(scale) uv in
    // glTF's uv (v down): u' = c sx u + s sy v + ox, v' = -s sx u + c sy v
    // + oy. Candela's uv has v up, so its transform must map the flipped
    // point to the flipped result.
    let png = gltf::data_uri(b"\x89PNG not really");
    let (offset, rotation, scale) = ([0.25f32, 0.5f32], 0.3f32, [2.0f32, 3.0f32]);
    let transform = json!({"offset": offset, "rotation": rotation, "scale": scale});
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!(["KHR_texture_transform"]);
        d["images"] = json!([{"uri": png.replace("application/octet-stream", "image/png")}]);
        d["textures"] = json!([{"source": 0}]);
        d["materials"] = json!([{
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": transform}},
                "metallicRoughnessTexture": {"index": 0}},
            "normalTexture": {"index": 0, "extensions": {"KHR_texture_transform": transform}}
        }, {
            "normalTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"rotation": "a lot"}}}
        }]);
        let mut second = d["meshes"][0]["primitives"][0].clone();
        second["material"] = json!(1);
        d["meshes"][0]["primitives"]
            .as_array_mut()
            .unwrap()
            .push(second);
    });
    let l = load_ok(&write("texture-transform.gltf", &text));
    // Only the second material's malformed transform is reported.
    assert_eq!(l.report.len(), 1, "{}", l.report);
    assert!(l.report.mentions("KHR_texture_transform"), "{}", l.report);
    assert!(l.scene.materials[1]
        .textures
        .get(TextureSlot::Normal)
        .expect("normal")
        .uv
        .is_identity());
    let t = &l.scene.materials[0].textures;
    let (s, c) = rotation.sin_cos();
    let gltf_map = |u: f32, v: f32| {
        (
            c * scale[0] * u + s * scale[1] * v + offset[0],
            -s * scale[0] * u + c * scale[1] * v + offset[1],
        )
    };
    for slot in [TextureSlot::Color, TextureSlot::Normal] {
        let uv = t.get(slot).expect("textured").uv;
        for (u, v) in [(0.0, 0.0), (1.0, 0.0), (0.3, 0.7), (-0.4, 1.2)] {
            let (tu, tv) = gltf_map(u, v);
            let got = uv.apply(glam::Vec2::new(u, 1.0 - v));
            let want = glam::Vec2::new(tu, 1.0 - tv);
            assert!(
                (got - want).length() < 1e-5,
                "{slot:?} at ({u}, {v}): {got} against {want}"
            );
        }
    }
    // A reference without the extension reads at the surface's own uv.
    let plain = t.get(TextureSlot::Roughness).expect("roughness").uv;
    assert!(plain.is_identity());
}

/// A material whose base colour, metallic-roughness and normal textures
/// read one image through samplers 0, 1 and none, loaded.
fn three_slots_with_samplers(name: &str, samplers: serde_json::Value) -> Loaded {
    let png = gltf::data_uri(b"\x89PNG not really");
    let text = gltf_text(|d| {
        d["images"] = json!([{"uri": png.replace("application/octet-stream", "image/png")}]);
        d["samplers"] = samplers;
        d["textures"] = json!([
            {"source": 0, "sampler": 0},
            {"source": 0, "sampler": 1},
            {"source": 0}
        ]);
        d["materials"] = json!([{
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0},
                "metallicRoughnessTexture": {"index": 1}},
            "normalTexture": {"index": 2}
        }]);
    });
    load_ok(&write(name, &text))
}

#[test]
fn sampler_wrap_modes_are_kept_per_axis() {
    // 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 REPEAT (the
    // default when a sampler or its field is absent).
    let l = three_slots_with_samplers(
        "samplers.gltf",
        json!([{"wrapS": 33071, "wrapT": 33648}, {"wrapT": 33071}]),
    );
    assert!(l.report.is_empty(), "{}", l.report);
    let t = &l.scene.materials[0].textures;
    let wrap = |slot| t.get(slot).expect("textured").wrap;
    let clamp_mirror = TextureWrap {
        u: WrapMode::Clamp,
        v: WrapMode::Mirror,
    };
    let repeat_clamp = TextureWrap {
        u: WrapMode::Repeat,
        v: WrapMode::Clamp,
    };
    assert_eq!(wrap(TextureSlot::Color), clamp_mirror);
    assert_eq!(wrap(TextureSlot::Roughness), repeat_clamp);
    assert_eq!(wrap(TextureSlot::Normal), TextureWrap::REPEAT);
}

#[test]
fn sampler_mag_filter_nearest_keeps_texels_sharp() {
    // 9728 NEAREST, 9729 LINEAR; the default (no sampler, or no magFilter)
    // is the renderer's bilinear filter.
    let l = three_slots_with_samplers(
        "mag_filter.gltf",
        json!([{"magFilter": 9728, "minFilter": 9729}, {"magFilter": 9729}]),
    );
    assert!(l.report.is_empty(), "{}", l.report);
    let t = &l.scene.materials[0].textures;
    let filter = |slot| t.get(slot).expect("textured").filter;
    assert_eq!(filter(TextureSlot::Color), TextureFilter::Nearest);
    assert_eq!(filter(TextureSlot::Roughness), TextureFilter::Bilinear);
    assert_eq!(filter(TextureSlot::Normal), TextureFilter::Bilinear);
}

#[test]
fn ext_texture_webp_reads_the_webp_image() {
    // Texture 0 has a PNG fallback and a WebP source; texture 1 only the
    // WebP source, as a file that requires the extension may have. Both
    // read the WebP image (embedded: cached under a .webp name, so the
    // renderer picks its reader by the extension).
    let png = gltf::data_uri(b"\x89PNG fallback").replace("application/octet-stream", "image/png");
    let webp =
        gltf::data_uri(b"RIFF....WEBPVP8L").replace("application/octet-stream", "image/webp");
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!(["EXT_texture_webp"]);
        d["extensionsRequired"] = json!(["EXT_texture_webp"]);
        d["images"] = json!([{"uri": png}, {"uri": webp}]);
        let ext = json!({"EXT_texture_webp": {"source": 1}});
        d["textures"] = json!([{"source": 0, "extensions": ext}, {"extensions": ext}]);
        d["materials"] = json!([{
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0},
                "metallicRoughnessTexture": {"index": 1}}
        }]);
    });
    let l = load_ok(&write("webp.gltf", &text));
    assert!(l.report.is_empty(), "{}", l.report);
    let t = &l.scene.materials[0].textures;
    for slot in [TextureSlot::Color, TextureSlot::Roughness] {
        let path = t.get(slot).and_then(|t| t.image_path()).expect("an image");
        assert_eq!(
            path.extension().and_then(|e| e.to_str()),
            Some("webp"),
            "{slot:?}"
        );
        let bytes = std::fs::read(path).expect("the cached image");
        assert_eq!(bytes, b"RIFF....WEBPVP8L", "{slot:?}");
    }
}

#[test]
fn loads_of_one_new_embedded_image_on_many_threads_all_succeed() {
    // Bytes no earlier run has cached (the process id and the clock), so
    // every thread finds the cache file missing and writes it: each write
    // must use its own temporary file, or one thread's rename takes the
    // file from under another's.
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    // A megabyte, so the writes take long enough to overlap.
    let mut fresh = format!("\u{89}PNG fresh {} {nanos}", std::process::id()).into_bytes();
    fresh.resize(1 << 20, 7);
    let png = gltf::data_uri(&fresh);
    let text = gltf_text(|d| {
        d["images"] = json!([{"uri": png.replace("application/octet-stream", "image/png")}]);
        d["textures"] = json!([{"source": 0}]);
        d["materials"] = json!([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]);
    });
    let path = write("fresh_image.gltf", &text);
    let cached: Vec<PathBuf> = std::thread::scope(|s| {
        let loads: Vec<_> = (0..16).map(|_| s.spawn(|| load_ok(&path))).collect();
        loads
            .into_iter()
            .map(|l| {
                let l = l.join().expect("a load panicked");
                let image = l.scene.materials[0].textures.get(TextureSlot::Color);
                image
                    .and_then(|t| t.image_path())
                    .expect("an image")
                    .to_path_buf()
            })
            .collect()
    });
    assert!(cached.iter().all(|p| p == &cached[0]), "{cached:?}");
    let bytes = std::fs::read(&cached[0]).expect("the cached image");
    assert!(bytes == fresh, "the cached image holds other bytes");
    std::fs::remove_file(&cached[0]).expect("the cached image removed");
}

#[test]
fn khr_materials_volume_fills_thick_meshes_with_an_absorbing_medium() {
    // Material 0: thick, white turns (0.5, 0.25, 1) after 2 units; material
    // 1: the same colour but thin-walled (thicknessFactor 0, the default);
    // material 2: thick with no attenuation distance (infinite: clear).
    let text = gltf_text(|d| {
        d["extensionsUsed"] = json!([
            "KHR_lights_punctual",
            "KHR_materials_transmission",
            "KHR_materials_volume"
        ]);
        let volume = |v: serde_json::Value| {
            json!({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                  "KHR_materials_volume": v}})
        };
        d["materials"] = json!([
            volume(json!({"thicknessFactor": 0.1, "attenuationDistance": 2.0,
                          "attenuationColor": [0.5, 0.25, 1.0]})),
            volume(json!({"attenuationDistance": 2.0, "attenuationColor": [0.5, 0.25, 1.0]})),
            volume(json!({"thicknessFactor": 1.0, "attenuationColor": [0.5, 0.25, 1.0]})),
        ]);
        let primitive = d["meshes"][0]["primitives"][0].clone();
        let with = |i: usize| {
            let mut p = primitive.clone();
            p["material"] = json!(i);
            p
        };
        d["meshes"][0]["primitives"] = json!([with(0), with(1), with(2)]);
    });
    let l = load_ok(&write("volume.gltf", &text));
    let s = &l.scene;
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    assert_eq!(s.media.len(), 1, "only the thick, attenuating material");
    let m = &s.media[0];
    let expected = Vec3::new(0.5f32.ln(), 0.25f32.ln(), 0.0) / -2.0;
    assert!(close(m.sigma_t, expected), "{:?}", m.sigma_t);
    assert_eq!((m.albedo, m.phase_g), (Vec3::ZERO, 0.0));
    // The interface belongs to the material of the first primitive: the
    // medium is inside (behind the outward normals), vacuum outside.
    let first = s
        .meshes
        .iter()
        .find(|mesh| !mesh.triangles.is_empty())
        .unwrap()
        .material;
    assert_eq!(
        s.medium_interfaces,
        vec![(
            first,
            candela_scene::MediumInterface {
                interior: Some(0),
                exterior: None
            }
        )]
    );
    // White through 2 units of it turns the attenuation colour.
    let through = (-m.sigma_t * 2.0).to_array().map(f32::exp);
    assert!(close(Vec3::from(through), Vec3::new(0.5, 0.25, 1.0)));
}

#[test]
fn mirrored_nodes_wind_their_triangles_the_other_way() {
    // The one-triangle mesh faces +z. Node 1 mirrors x (determinant -1),
    // node 4 mirrors x and y (determinant +1), node 5 mirrors z: the glTF
    // specification turns the front face of nodes 1 and 5 round, so every
    // placed triangle's face normal keeps pointing out of the same side
    // as the plain node's, mirrored.
    let text = gltf_text(|d| {
        d["nodes"][1]["scale"] = json!([-1.0, 1.0, 1.0]);
        let nodes = d["nodes"].as_array_mut().unwrap();
        nodes.push(json!({"mesh": 0, "scale": [-1.0, -1.0, 1.0]}));
        nodes.push(json!({"mesh": 0, "scale": [1.0, 1.0, -1.0]}));
        d["scenes"][0]["nodes"] = json!([0, 1, 2, 3, 4, 5]);
    });
    let l = load_ok(&write("mirrored.gltf", &text));
    let s = &l.scene;
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    assert_eq!(s.instances.len(), 4);
    let face_normal = |i: usize| {
        let inst = &s.instances[i];
        let mesh = &s.meshes[inst.mesh];
        let [a, b, c] = mesh.triangles[0].map(|k| {
            inst.world_from_object
                .transform_point3(mesh.positions[k as usize])
        });
        (b - a).cross(c - a).normalize()
    };
    // Where the plain triangle's +z normal goes under each placement
    // (normals transform by the inverse transpose).
    let expected = [Vec3::Z, Vec3::Z, Vec3::Z, -Vec3::Z];
    for (i, want) in expected.into_iter().enumerate() {
        assert!(
            close(face_normal(i), want),
            "instance {i}: {:?}",
            face_normal(i)
        );
    }
    // One wound-the-other-way copy serves both mirroring nodes; the
    // determinant +1 node uses the mesh as read.
    let mesh_of = |i: usize| s.instances[i].mesh;
    assert_eq!(mesh_of(0), mesh_of(2));
    assert_eq!(mesh_of(1), mesh_of(3));
    assert_ne!(mesh_of(0), mesh_of(1));
    assert_eq!(s.meshes.len(), 2);
    assert_eq!(s.meshes[mesh_of(1)].material, s.meshes[mesh_of(0)].material);
}
