//! Malformed glTF: each case is refused with its [`ErrorKind`] and a
//! one-line message naming the file and where; random mutations of a valid
//! `.glb` and `.gltf` never panic.

#[allow(dead_code)]
mod gltf;

use candela_scene::{load, ErrorKind, LoadError, LoadOptions};
use gltf::{buffer, data_uri, document, glb, glb_of, gltf_text, write};
use proptest::prelude::*;
use serde_json::json;

fn refused(name: &str, bytes: &[u8]) -> LoadError {
    let path = write(name, bytes);
    let e = match load(&path, &LoadOptions::default()) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => e,
    };
    let line = e.to_string();
    assert!(!line.contains('\n'), "{line}");
    assert!(line.starts_with(&path.display().to_string()), "{line}");
    e
}

fn case(name: &str, kind: ErrorKind, at: &str, patch: impl FnOnce(&mut serde_json::Value)) {
    let e = refused(name, &gltf_text(patch));
    assert_eq!(e.kind, kind, "{e}");
    assert!(e.element.starts_with(at), "{name}: expected at {at}: {e}");
}

#[test]
fn truncated_glb() {
    let e = refused("truncated.glb", &glb()[..30]);
    assert_eq!(e.kind, ErrorKind::CountMismatch, "{e}");
}

#[test]
fn glb_shorter_than_its_header() {
    assert_eq!(
        refused("short.glb", b"glTF\x02\0").kind,
        ErrorKind::CountMismatch
    );
}

#[test]
fn glb_with_wrong_magic() {
    let mut b = glb();
    b[..4].copy_from_slice(b"gLTF");
    assert_eq!(refused("magic.glb", &b).kind, ErrorKind::BadValue);
}

#[test]
fn glb_version_1() {
    let mut b = glb();
    b[4] = 1;
    assert_eq!(refused("version.glb", &b).kind, ErrorKind::Unsupported);
}

#[test]
fn glb_chunk_length_beyond_the_file() {
    let mut b = glb();
    b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    let e = refused("chunk.glb", &b);
    assert_eq!(e.kind, ErrorKind::CountMismatch, "{e}");
    assert!(e.message.contains("past the end"), "{e}");
}

#[test]
fn glb_header_length_beyond_the_file() {
    let mut b = glb();
    let claimed = b.len() as u32 + 4;
    b[8..12].copy_from_slice(&claimed.to_le_bytes());
    assert_eq!(refused("length.glb", &b).kind, ErrorKind::CountMismatch);
}

#[test]
fn glb_buffer_without_bin_chunk() {
    let b = glb();
    let json_len = u32::from_le_bytes([b[12], b[13], b[14], b[15]]) as usize;
    let mut cut = b[..20 + json_len].to_vec();
    let n = cut.len() as u32;
    cut[8..12].copy_from_slice(&n.to_le_bytes());
    assert_eq!(refused("nobin.glb", &cut).kind, ErrorKind::MissingReference);
}

#[test]
fn not_json() {
    let e = refused(
        "garbage.gltf",
        b"{\"asset\": {\"version\": \"2.0\"},\n  oops",
    );
    assert_eq!(e.kind, ErrorKind::BadValue);
    assert_eq!(e.loc.map(|l| l.line), Some(2), "{e}");
}

#[test]
fn accessor_out_of_buffer_bounds() {
    case(
        "accessor-bounds.gltf",
        ErrorKind::IndexOutOfRange,
        "/accessors/0",
        |d| {
            d["accessors"][0]["count"] = json!(1000);
        },
    );
}

#[test]
fn buffer_view_past_its_buffer() {
    case(
        "view-bounds.gltf",
        ErrorKind::IndexOutOfRange,
        "/bufferViews/1",
        |d| {
            d["bufferViews"][1]["byteOffset"] = json!(40);
        },
    );
}

#[test]
fn ten_gigabyte_count_claim() {
    case(
        "count.gltf",
        ErrorKind::TooLarge,
        "/accessors/0/count",
        |d| {
            d["accessors"][0]["count"] = json!(10_000_000_000u64);
        },
    );
}

#[test]
fn index_out_of_range() {
    let mut b = buffer();
    b[38..40].copy_from_slice(&7u16.to_le_bytes());
    case(
        "index.gltf",
        ErrorKind::IndexOutOfRange,
        "/accessors/1",
        |d| {
            d["buffers"][0]["uri"] = json!(data_uri(&b));
        },
    );
}

#[test]
fn index_count_not_whole_triangles() {
    case(
        "whole.gltf",
        ErrorKind::CountMismatch,
        "/meshes/0/primitives/0",
        |d| {
            d["accessors"][1]["count"] = json!(2);
        },
    );
}

#[test]
fn nan_position() {
    let mut b = buffer();
    b[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
    case("nan.gltf", ErrorKind::NonFinite, "/accessors/0", |d| {
        d["buffers"][0]["uri"] = json!(data_uri(&b));
    });
}

#[test]
fn infinite_node_matrix() {
    // JSON has no NaN; 1e39 overflows f32 to infinity.
    case("matrix.gltf", ErrorKind::NonFinite, "/nodes/1", |d| {
        d["nodes"][1] =
            json!({"mesh": 0, "matrix": [1e39, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]});
    });
}

#[test]
fn node_cycle() {
    case("cycle.gltf", ErrorKind::TooDeep, "/nodes/", |d| {
        d["nodes"][0]["children"] = json!([1]);
        d["nodes"][1]["children"] = json!([0]);
        d["scenes"][0]["nodes"] = json!([0]);
    });
}

#[test]
fn dangling_mesh_index() {
    case(
        "dangling.gltf",
        ErrorKind::IndexOutOfRange,
        "/nodes/0/mesh",
        |d| {
            d["nodes"][0]["mesh"] = json!(9);
        },
    );
}

#[test]
fn missing_external_bin() {
    case("missing-bin.gltf", ErrorKind::Io, "/buffers/0/uri", |d| {
        d["buffers"][0]["uri"] = json!("no such buffer.bin");
    });
}

#[test]
fn bad_base64() {
    case("base64.gltf", ErrorKind::BadValue, "/buffers/0/uri", |d| {
        d["buffers"][0]["uri"] = json!("data:application/octet-stream;base64,AAA*AAAA");
    });
}

#[test]
fn byte_length_beyond_the_data() {
    case(
        "bytelength.gltf",
        ErrorKind::CountMismatch,
        "/buffers/0",
        |d| {
            d["buffers"][0]["byteLength"] = json!(4000);
        },
    );
}

#[test]
fn required_unsupported_extension() {
    case(
        "required.gltf",
        ErrorKind::Unsupported,
        "/extensionsRequired/0",
        |d| {
            d["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
            d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
        },
    );
}

#[test]
fn zero_field_of_view() {
    case("fov.gltf", ErrorKind::DegenerateCamera, "/cameras/0", |d| {
        d["cameras"][0]["perspective"]["yfov"] = json!(4.0);
    });
}

#[test]
fn missing_position() {
    let e = refused(
        "position.gltf",
        &gltf_text(|d| d["meshes"][0]["primitives"][0]["attributes"] = json!({})),
    );
    assert_eq!(e.kind, ErrorKind::MissingElement, "{e}");
}

#[test]
fn positions_of_the_wrong_type() {
    case("type.gltf", ErrorKind::BadValue, "/accessors/0", |d| {
        d["accessors"][0]["type"] = json!("VEC2");
    });
}

/// The document with its material's base colour read from image 0, as
/// `image` describes it (found by mutating the shipped scene: the `gltf`
/// crate panicked on an image without a `uri`).
fn textured(d: &mut serde_json::Value, image: serde_json::Value) {
    d["images"] = json!([image]);
    d["textures"] = json!([{"source": 0}]);
    d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
}

#[test]
fn image_without_a_source() {
    case("no-uri.gltf", ErrorKind::MissingElement, "/images/0", |d| {
        textured(d, json!({"name": "albedo"}));
    });
}

#[test]
fn image_in_a_buffer_view_without_a_mime_type() {
    case(
        "no-mime.gltf",
        ErrorKind::MissingElement,
        "/images/0",
        |d| {
            textured(d, json!({"bufferView": 0}));
        },
    );
}

#[test]
fn webp_source_past_the_images() {
    case(
        "webp-index.gltf",
        ErrorKind::IndexOutOfRange,
        "/textures/0/extensions/EXT_texture_webp/source",
        |d| {
            textured(d, json!({"uri": "albedo.png"}));
            d["textures"][0]["extensions"] = json!({"EXT_texture_webp": {"source": 3}});
        },
    );
}

#[test]
fn webp_extension_without_a_source() {
    case(
        "webp-none.gltf",
        ErrorKind::MissingElement,
        "/textures/0/extensions/EXT_texture_webp/source",
        |d| {
            textured(d, json!({"uri": "albedo.png"}));
            d["textures"][0]["extensions"] = json!({"EXT_texture_webp": {}});
        },
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Byte flips and truncation of a valid `.glb` load or fail; never panic.
    #[test]
    fn mutated_glb_never_panics(flips in proptest::collection::vec((any::<usize>(), any::<u8>()), 0..8),
                                cut in any::<usize>(), truncate in any::<bool>()) {
        let mut b = glb();
        for (at, v) in flips {
            let i = at % b.len();
            b[i] = v;
        }
        if truncate {
            b.truncate(cut % (b.len() + 1));
        }
        let _ = load(&write("fuzz.glb", &b), &LoadOptions::default());
    }

    /// The same for `.gltf` text, whose flips mostly hit the JSON.
    #[test]
    fn mutated_gltf_never_panics(flips in proptest::collection::vec((any::<usize>(), 0x20u8..0x7f), 0..4)) {
        let mut b = gltf_text(|_| {});
        for (at, v) in flips {
            let i = at % b.len();
            b[i] = v;
        }
        let _ = load(&write("fuzz.gltf", &b), &LoadOptions::default());
    }
}

#[test]
fn the_valid_base_documents_load() {
    // The cases above fail because of their one change, not the base.
    for (name, bytes) in [
        ("base.gltf", gltf_text(|_| {})),
        ("base.glb", glb_of(&document(None), &buffer())),
    ] {
        load(&write(name, &bytes), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    }
}
