//! Vertex colours from every format that carries them, each from a small
//! file written here: PLY `red green blue` (floats as given, 8- and 16-bit
//! integers normalised and decoded from sRGB), OBJ `v x y z r g b`, glTF
//! `COLOR_0` (float `VEC3`, normalised 8- and 16-bit `VEC4`, alpha
//! reported) and the product glTF defines with the base colour, Mitsuba's
//! `mesh_attribute`; meshes without colours carry none.

// The shared document helpers; this file needs only the `.gltf` ones.
#[allow(dead_code)]
mod gltf;

use candela_scene::{
    load, LoadOptions, Loaded, MaterialDesc, TextureRef, TextureSlot, TextureSource,
};
use glam::Vec3;
use serde_json::json;

fn load_file(name: &str, bytes: &[u8]) -> Loaded {
    let file = candela_testkit::TempFile::new("vertex-colors", name, bytes);
    load(&file, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The sRGB decoding of a stored value in [0, 1] (IEC 61966-2-1).
fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

fn assert_close(got: &[Vec3], want: &[Vec3], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?}");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (*g - *w).abs().max_element() < 1e-6,
            "{what}, vertex {i}: {g} vs {w}"
        );
    }
}

fn color_texture(m: &MaterialDesc) -> &TextureRef {
    m.textures
        .get(TextureSlot::Color)
        .unwrap_or_else(|| panic!("material {} has no colour texture", m.name))
}

fn ply(types: &str, rows: &[&str]) -> Vec<u8> {
    format!(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nproperty {types} red\nproperty {types} green\nproperty {types} blue\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n{}\n3 0 1 2\n",
        rows.join("\n")
    )
    .into_bytes()
}

#[test]
fn ply_float_colours_are_linear_and_integers_decoded_from_srgb() {
    let float = load_file(
        "float.ply",
        &ply(
            "float",
            &["0 0 0 1 0 0.5", "1 0 0 0 2 0.25", "0 1 0 0.125 0 1"],
        ),
    );
    let mesh = &float.scene.meshes[0];
    assert_close(
        &mesh.colors,
        &[
            Vec3::new(1.0, 0.0, 0.5),
            Vec3::new(0.0, 2.0, 0.25),
            Vec3::new(0.125, 0.0, 1.0),
        ],
        "float",
    );
    // A PLY has no material: its own shows the colours.
    let t = color_texture(&float.scene.materials[mesh.material]);
    assert_eq!(t.source, TextureSource::VertexColor);
    assert!(float.report.warnings.is_empty(), "{}", float.report);

    let bytes = load_file(
        "uchar.ply",
        &ply(
            "uchar",
            &["0 0 0 255 0 128", "1 0 0 10 64 200", "0 1 0 1 2 3"],
        ),
    );
    let decode = |c: [u32; 3], max: f32| Vec3::from(c.map(|v| srgb_to_linear(v as f32 / max)));
    assert_close(
        &bytes.scene.meshes[0].colors,
        &[
            decode([255, 0, 128], 255.0),
            decode([10, 64, 200], 255.0),
            decode([1, 2, 3], 255.0),
        ],
        "uchar",
    );
    let shorts = load_file(
        "ushort.ply",
        &ply(
            "ushort",
            &["0 0 0 65535 0 1000", "1 0 0 30000 7 0", "0 1 0 1 2 3"],
        ),
    );
    assert_close(
        &shorts.scene.meshes[0].colors,
        &[
            decode([65535, 0, 1000], 65535.0),
            decode([30000, 7, 0], 65535.0),
            decode([1, 2, 3], 65535.0),
        ],
        "ushort",
    );
}

#[test]
fn ply_without_colours_carries_none() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nproperty float red\nelement face 1\n\
                property list uchar int vertex_indices\nend_header\n\
                0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n";
    let l = load_file("red-only.ply", text.as_bytes());
    assert!(l.scene.meshes[0].colors.is_empty());
    assert!(l.scene.materials[0].textures.color.is_none());
}

#[test]
fn obj_vertex_colours_are_read_as_given_and_dropped_when_partial() {
    let l = load_file(
        "colors.obj",
        b"v 0 0 0 1 0 0.5\nv 1 0 0 0 1 0.25\nv 0 1 0 0.2 0.3 1\nv 1 1 0 0 0 0\nf 1 2 3\nf 2 4 3\n",
    );
    let mesh = &l.scene.meshes[0];
    let by_vertex = [
        Vec3::new(1.0, 0.0, 0.5),
        Vec3::new(0.0, 1.0, 0.25),
        Vec3::new(0.2, 0.3, 1.0),
        Vec3::ZERO,
    ];
    // The file's vertices, found by position, carry their own colours.
    let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)];
    assert_eq!(mesh.colors.len(), mesh.positions.len());
    for (p, c) in mesh.positions.iter().zip(&mesh.colors) {
        let k = positions
            .iter()
            .position(|q| q == p)
            .expect("a file vertex");
        assert_eq!(*c, by_vertex[k], "vertex at {p}");
    }
    let t = color_texture(&l.scene.materials[mesh.material]);
    assert_eq!(t.source, TextureSource::VertexColor);

    let partial = load_file("partial.obj", b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(partial.scene.meshes[0].colors.is_empty());
    let report = partial.report.to_string();
    assert!(report.contains("1 of 3 vertices have a colour"), "{report}");
}

/// The base document with `COLOR_0` from `bytes` (appended to the base
/// buffer) as an accessor of `component_type`/`ty`, normalised when
/// integer, and the material's base colour factor `factor`.
fn gltf_with_colors(bytes: &[u8], component_type: u32, ty: &str, factor: [f32; 4]) -> Vec<u8> {
    let mut buf = gltf::buffer();
    buf.extend_from_slice(bytes);
    gltf::gltf_text(|d| {
        d["buffers"] = json!([{"uri": gltf::data_uri(&buf), "byteLength": buf.len()}]);
        let views = d["bufferViews"].as_array_mut().unwrap();
        views.push(json!({"buffer": 0, "byteOffset": 44, "byteLength": bytes.len()}));
        let mut acc =
            json!({"bufferView": 2, "componentType": component_type, "count": 3, "type": ty});
        if component_type != 5126 {
            acc["normalized"] = json!(true);
        }
        d["accessors"].as_array_mut().unwrap().push(acc);
        d["meshes"][0]["primitives"][0]["attributes"] = json!({"POSITION": 0, "COLOR_0": 2});
        d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = json!(factor);
    })
}

#[test]
fn gltf_color_0_reads_floats_and_normalised_integers() {
    let floats = [0.25f32, 0.5, 1.0, 0.0, 0.125, 2.0, 0.75, 0.5, 0.25];
    let bytes: Vec<u8> = floats.iter().flat_map(|v| v.to_le_bytes()).collect();
    let l = load_file(
        "float.gltf",
        &gltf_with_colors(&bytes, 5126, "VEC3", [1.0; 4]),
    );
    let want: Vec<Vec3> = floats.chunks(3).map(Vec3::from_slice).collect();
    assert_close(&l.scene.meshes[0].colors, &want, "float VEC3");
    assert!(l.report.warnings.is_empty(), "{}", l.report);

    // Normalised unsigned bytes, RGBA with an alpha below 1: c / 255.
    let rgba: [u8; 12] = [255, 0, 128, 255, 1, 254, 64, 200, 7, 9, 11, 255];
    let l = load_file("u8.gltf", &gltf_with_colors(&rgba, 5121, "VEC4", [1.0; 4]));
    let want: Vec<Vec3> = rgba
        .chunks(4)
        .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / 255.0)
        .collect();
    assert_close(&l.scene.meshes[0].colors, &want, "u8 VEC4");
    let report = l.report.to_string();
    assert!(report.contains("COLOR_0 alpha"), "{report}");

    // Normalised unsigned shorts: c / 65535.
    let shorts: [u16; 12] = [
        65535, 0, 1, 65535, 300, 40000, 65535, 65535, 0, 9, 65534, 65535,
    ];
    let bytes: Vec<u8> = shorts.iter().flat_map(|v| v.to_le_bytes()).collect();
    let l = load_file(
        "u16.gltf",
        &gltf_with_colors(&bytes, 5123, "VEC4", [1.0; 4]),
    );
    let want: Vec<Vec3> = shorts
        .chunks(4)
        .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / 65535.0)
        .collect();
    assert_close(&l.scene.meshes[0].colors, &want, "u16 VEC4");
    assert!(l.report.warnings.is_empty(), "{}", l.report);
}

#[test]
fn gltf_vertex_colours_multiply_the_base_colour() {
    let floats = [0.25f32, 0.5, 1.0, 0.0, 0.125, 1.0, 0.75, 0.5, 0.25];
    let bytes: Vec<u8> = floats.iter().flat_map(|v| v.to_le_bytes()).collect();
    // Without a texture: the vertex colour, tinted by the factor, channel
    // by channel (a coloured factor, kept whole, unreported).
    let l = load_file(
        "factor.gltf",
        &gltf_with_colors(&bytes, 5126, "VEC3", [0.9, 0.6, 0.3, 1.0]),
    );
    assert!(l.report.warnings.is_empty(), "{}", l.report);
    let mesh = &l.scene.meshes[0];
    let t = color_texture(&l.scene.materials[mesh.material]);
    assert_eq!(t.source, TextureSource::VertexColor);
    assert_eq!((t.tint, t.scale), (Vec3::new(0.9, 0.6, 0.3), 1.0));
    assert!(!t.times_vertex_color);

    // With a base colour texture: the texture times the vertex colour,
    // with the factor its tint. A primitive of the same material without
    // COLOR_0 keeps the plain texture (and the tint).
    let mut doc: serde_json::Value = serde_json::from_slice(&gltf_with_colors(
        &bytes,
        5126,
        "VEC3",
        [0.5, 0.25, 1.0, 1.0],
    ))
    .unwrap();
    doc["images"] = json!([{"uri": "base.png"}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
    let prims = doc["meshes"][0]["primitives"].as_array_mut().unwrap();
    prims.push(json!({"attributes": {"POSITION": 0}, "indices": 1, "material": 0}));
    let l = load_file("texture.gltf", &serde_json::to_vec(&doc).unwrap());
    let colored = l
        .scene
        .meshes
        .iter()
        .find(|m| !m.colors.is_empty())
        .unwrap();
    let plain = l.scene.meshes.iter().find(|m| m.colors.is_empty()).unwrap();
    assert_ne!(colored.material, plain.material);
    let t = color_texture(&l.scene.materials[colored.material]);
    assert!(matches!(&t.source, TextureSource::Image(p) if p.ends_with("base.png")));
    assert!(t.times_vertex_color);
    assert_eq!((t.tint, t.scale), (Vec3::new(0.5, 0.25, 1.0), 1.0));
    let t = color_texture(&l.scene.materials[plain.material]);
    assert!(!t.times_vertex_color);
    assert_eq!(t.tint, Vec3::new(0.5, 0.25, 1.0));
}

fn mitsuba_scene(attribute: &str) -> Loaded {
    let dir = candela_testkit::TempDir::new("vertex-colors-mitsuba");
    std::fs::write(
        dir.join("m.ply"),
        ply(
            "float",
            &["0 0 0 1 0 0.5", "1 0 0 0 1 0.25", "0 1 0 0.2 0.3 1"],
        ),
    )
    .unwrap();
    let scene = format!(
        r#"<scene version="3.0.0">
    <shape type="ply">
        <string name="filename" value="m.ply"/>
        <bsdf type="diffuse">
            <texture type="mesh_attribute" name="reflectance">
                <string name="name" value="{attribute}"/>
                <float name="scale" value="0.8"/>
            </texture>
        </bsdf>
    </shape>
</scene>"#
    );
    let path = dir.join("scene.xml");
    std::fs::write(&path, scene).unwrap();
    load(&path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn mitsuba_mesh_attribute_vertex_color_reads_the_ply_colours() {
    let l = mitsuba_scene("vertex_color");
    let mesh = &l.scene.meshes[0];
    assert_close(
        &mesh.colors,
        &[
            Vec3::new(1.0, 0.0, 0.5),
            Vec3::new(0.0, 1.0, 0.25),
            Vec3::new(0.2, 0.3, 1.0),
        ],
        "mitsuba ply",
    );
    let t = color_texture(&l.scene.materials[mesh.material]);
    assert_eq!(t.source, TextureSource::VertexColor);
    assert!((t.scale - 0.8).abs() < 1e-6, "scale {}", t.scale);
    assert!(l.report.warnings.is_empty(), "{}", l.report);

    let other = mitsuba_scene("face_color");
    let report = other.report.to_string();
    assert!(report.contains("\"face_color\""), "{report}");
    let m = &other.scene.materials[other.scene.meshes[0].material];
    assert!(m.textures.color.is_none());
}
