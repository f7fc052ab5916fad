//! The `.serialized` reader against files written here from the format's
//! description: both versions, single and double precision, several meshes,
//! and every way a file can be wrong.

use super::*;
use std::io::Write;

/// One mesh as the format stores it.
struct Written {
    flags: u32,
    name: &'static str,
    positions: Vec<[f64; 3]>,
    normals: Vec<[f64; 3]>,
    uvs: Vec<[f64; 2]>,
    colors: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
}

fn quad(flags: u32, name: &'static str) -> Written {
    Written {
        flags,
        name,
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.25]],
        colors: vec![[0.5, 0.25, 0.125]; 4],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// The zlib-compressed body of `m`, with `vertices` and `triangles` as the
/// stored counts (tests pass wrong ones).
fn body(m: &Written, version: u16, vertices: u64, triangles: u64) -> Vec<u8> {
    let mut raw = Vec::new();
    raw.extend(m.flags.to_le_bytes());
    if version >= 4 {
        raw.extend(m.name.as_bytes());
        raw.push(0);
    }
    raw.extend(vertices.to_le_bytes());
    raw.extend(triangles.to_le_bytes());
    let double = m.flags & DOUBLE_PRECISION != 0;
    let mut reals = |values: &[f64]| {
        for &v in values {
            if double {
                raw.extend(v.to_le_bytes());
            } else {
                raw.extend((v as f32).to_le_bytes());
            }
        }
    };
    reals(m.positions.concat().as_slice());
    if m.flags & HAS_NORMALS != 0 {
        reals(m.normals.concat().as_slice());
    }
    if m.flags & HAS_UVS != 0 {
        reals(m.uvs.concat().as_slice());
    }
    if m.flags & HAS_COLORS != 0 {
        reals(m.colors.concat().as_slice());
    }
    for t in &m.triangles {
        for i in t {
            raw.extend(i.to_le_bytes());
        }
    }
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(&raw).unwrap();
    z.finish().unwrap()
}

/// A whole file of `meshes` with their true counts and the dictionary.
fn file(meshes: &[Written], version: u16) -> Vec<u8> {
    let mut out = Vec::new();
    let mut offsets = Vec::new();
    for m in meshes {
        offsets.push(out.len() as u64);
        out.extend(MAGIC.to_le_bytes());
        out.extend(version.to_le_bytes());
        out.extend(body(
            m,
            version,
            m.positions.len() as u64,
            m.triangles.len() as u64,
        ));
    }
    for o in offsets {
        if version >= 4 {
            out.extend(o.to_le_bytes());
        } else {
            out.extend((o as u32).to_le_bytes());
        }
    }
    out.extend((meshes.len() as u32).to_le_bytes());
    out
}

fn read(bytes: &[u8], index: u32) -> Result<SerializedMesh, LoadError> {
    let dir = candela_testkit::TempDir::new("serialized");
    let path = dir.join("m.serialized");
    std::fs::write(&path, bytes).unwrap();
    read_serialized(&path, index)
}

#[test]
fn every_mesh_of_a_file_reads_back_in_either_version_and_precision() {
    for version in [3, 4] {
        // Colours sit between the uvs and the indices: a reader that does
        // not read them whole reads wrong indices.
        let meshes = [
            quad(HAS_NORMALS | HAS_UVS, "first"),
            quad(DOUBLE_PRECISION | HAS_UVS | FACE_NORMALS, "second"),
            quad(HAS_UVS | HAS_COLORS, "third"),
            quad(DOUBLE_PRECISION | HAS_COLORS, "fourth"),
        ];
        let bytes = file(&meshes, version);
        for (index, m) in meshes.iter().enumerate() {
            let got = read(&bytes, index as u32).unwrap_or_else(|e| panic!("{e}"));
            let mesh = &got.mesh;
            let want_name = if version >= 4 { m.name } else { "" };
            assert_eq!(mesh.name, want_name);
            assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
            assert_eq!(mesh.triangles, m.triangles);
            assert_eq!(mesh.normals.is_empty(), m.flags & HAS_NORMALS == 0);
            assert_eq!(mesh.uvs.is_empty(), m.flags & HAS_UVS == 0);
            if !mesh.uvs.is_empty() {
                assert_eq!(mesh.uvs[3], Vec2::new(0.0, 0.25));
                assert_eq!(mesh.uv_indices, m.triangles);
            }
            assert_eq!(got.face_normals, m.flags & FACE_NORMALS != 0);
            // Colours are read, one per vertex, as stored.
            let want_colors: Vec<Vec3> = if m.flags & HAS_COLORS != 0 {
                m.colors
                    .iter()
                    .map(|c| c.map(|x| x as f32).into())
                    .collect()
            } else {
                Vec::new()
            };
            assert_eq!(mesh.colors, want_colors);
        }
    }
}

#[test]
fn a_bad_file_is_a_clear_error_never_a_panic() {
    let good = file(&[quad(HAS_NORMALS, "a")], 4);
    let kind_of =
        |bytes: &[u8], index: u32| read(bytes, index).err().map(|e| (e.kind, e.to_string()));

    let (kind, msg) = kind_of(&good, 1).unwrap();
    assert_eq!(kind, ErrorKind::BadValue, "{msg}");
    assert!(msg.contains("holds 1 meshes"), "{msg}");

    let mut bad_magic = good.clone();
    bad_magic[0] ^= 0xFF;
    let (kind, msg) = kind_of(&bad_magic, 0).unwrap();
    assert_eq!(kind, ErrorKind::BadValue, "{msg}");
    assert!(
        msg.contains("mesh 0") && msg.contains("not a serialized mesh"),
        "{msg}"
    );

    let mut bad_version = good.clone();
    bad_version[2] = 9;
    assert_eq!(kind_of(&bad_version, 0).unwrap().0, ErrorKind::BadValue);

    // Counts larger than the data: the stream ends early.
    let m = quad(HAS_NORMALS, "a");
    let mut short = Vec::new();
    short.extend(MAGIC.to_le_bytes());
    short.extend(4u16.to_le_bytes());
    short.extend(body(&m, 4, 40, 2));
    let (kind, msg) = kind_of(&short, 0).unwrap();
    assert_eq!(kind, ErrorKind::CountMismatch, "{msg}");
    assert!(
        msg.contains("positions") || msg.contains("normals"),
        "{msg}"
    );

    // Counts no memory could hold: refused before anything is allocated.
    let mut huge = Vec::new();
    huge.extend(MAGIC.to_le_bytes());
    huge.extend(4u16.to_le_bytes());
    huge.extend(body(&m, 4, 1 << 40, 1 << 40));
    assert_eq!(kind_of(&huge, 0).unwrap().0, ErrorKind::TooLarge);

    let mut out_of_range = quad(0, "a");
    out_of_range.triangles[1] = [0, 2, 4];
    let bytes = file(&[out_of_range], 4);
    assert_eq!(kind_of(&bytes, 0).unwrap().0, ErrorKind::IndexOutOfRange);

    for cut in [0, 1, 3, 4, 10, good.len() / 2] {
        assert!(kind_of(&good[..cut], 0).is_some(), "cut at {cut}");
    }
}
