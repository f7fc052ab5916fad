//! A small valid glTF document for the glTF tests to start from and
//! mutate: two instances of a one-triangle mesh, a camera and a point light,
//! written as `.gltf` (base64 buffer) or `.glb` (BIN chunk).

use base64::Engine;
use serde_json::{json, Value};

/// Three positions (0,0,0), (1,0,0), (0,1,0), then u16 indices 0 1 2 and
/// two bytes of padding.
pub fn buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// The document, its buffer given by `uri` (none for a `.glb`).
pub fn document(uri: Option<String>) -> Value {
    let mut buffer = json!({"byteLength": 44});
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 0, "translation": [2.0, 0.0, 0.0]},
            {"camera": 0, "translation": [0.0, 0.0, 5.0]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.0, 3.0, 0.0]}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1.0], "metallicFactor": 0.0}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": 1.5}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 683.0, "color": [1.0, 0.5, 0.25]}]}},
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ]
    })
}

/// A `data:` URI of `bytes`.
pub fn data_uri(bytes: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// The `.gltf` text of the document with an embedded buffer.
pub fn gltf_text(patch: impl FnOnce(&mut Value)) -> Vec<u8> {
    let mut doc = document(Some(data_uri(&buffer())));
    patch(&mut doc);
    serde_json::to_vec_pretty(&doc).expect("json")
}

/// The `.gltf` text of the document with `extensions` used, one material
/// per entry of `materials`, each on its own primitive of the mesh, and two
/// textures of (unreadable) PNG images: texture 0 embedded, texture 1
/// `second texture.png` beside the file.
pub fn with_materials(extensions: &[&str], materials: Value) -> Vec<u8> {
    let png = data_uri(b"\x89PNG not really");
    let n = materials.as_array().map_or(0, Vec::len);
    gltf_text(|d| {
        d["extensionsUsed"] = json!(extensions);
        d["images"] = json!([
            {"uri": png.replace("application/octet-stream", "image/png")},
            {"uri": "second texture.png"}
        ]);
        d["textures"] = json!([{"source": 0}, {"source": 1}]);
        d["materials"] = materials;
        let first = d["meshes"][0]["primitives"][0].clone();
        let primitives: Vec<Value> = (0..n)
            .map(|i| {
                let mut p = first.clone();
                p["material"] = json!(i);
                p
            })
            .collect();
        d["meshes"][0]["primitives"] = json!(primitives);
    })
}

/// A `.glb` of `doc` with `bin` as its BIN chunk.
pub fn glb_of(doc: &Value, bin: &[u8]) -> Vec<u8> {
    candela_testkit::glb::glb_of(&serde_json::to_vec(doc).expect("json"), bin)
}

/// The valid `.glb`.
pub fn glb() -> Vec<u8> {
    glb_of(&document(None), &buffer())
}

/// Writes `bytes` to a fresh file `name` in a temporary folder of its own,
/// removed when the returned guard is dropped.
pub fn write(name: &str, bytes: &[u8]) -> candela_testkit::TempFile {
    candela_testkit::TempFile::new("gltf-tests", name, bytes)
}

/// Appends `bytes` to `buf` (first padded to 4 bytes, as vertex attributes
/// must be aligned), as a new buffer view with `stride` bytes between
/// elements, and `accessor` reading it (its `bufferView` filled in);
/// returns the accessor's index. [`set_buffer`] then embeds `buf`.
pub fn push_accessor(
    d: &mut Value,
    buf: &mut Vec<u8>,
    bytes: &[u8],
    stride: Option<usize>,
    mut accessor: Value,
) -> usize {
    buf.resize(buf.len().next_multiple_of(4), 0);
    let views = d["bufferViews"].as_array_mut().expect("bufferViews");
    let mut view = json!({"buffer": 0, "byteOffset": buf.len(), "byteLength": bytes.len()});
    if let Some(stride) = stride {
        view["byteStride"] = json!(stride);
    }
    accessor["bufferView"] = json!(views.len());
    views.push(view);
    buf.extend_from_slice(bytes);
    let accessors = d["accessors"].as_array_mut().expect("accessors");
    accessors.push(accessor);
    accessors.len() - 1
}

/// Makes `buf` the document's one buffer, embedded as a `data:` URI.
pub fn set_buffer(d: &mut Value, buf: &[u8]) {
    d["buffers"] = json!([{"uri": data_uri(buf), "byteLength": buf.len()}]);
}
