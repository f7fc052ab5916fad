//! The OBJ/MTL and PLY loaders on whole files: the project's Cornell box in
//! both formats (checked against the built-in demo it was generated from),
//! the shared corpus files, missing references in default and strict mode,
//! and mutated files that must never panic.

use candela_scene::{demo_scene, load, BsdfDesc, ErrorKind, LoadOptions, SceneDesc};
use candela_testkit::TempDir;
use glam::Vec3;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn strict() -> LoadOptions {
    LoadOptions {
        strict: true,
        ..Default::default()
    }
}

/// Sphere tessellation of scenes/cornell/make.py: 32 segments, 16 rings.
const SPHERE_TRIANGLES: usize = 2 * 32 + 2 * 32 * 14;

#[test]
fn the_obj_cornell_box_has_the_demos_triangles_materials_and_lamp() {
    let l = load(&repo().join("scenes/cornell/cornell.obj"), &strict()).unwrap();
    let s = &l.scene;
    assert!(l.report.is_empty(), "{}", l.report);
    assert_eq!(s.meshes.len(), 8);
    assert_eq!(s.triangle_count(), 6 * 2 + 2 * SPHERE_TRIANGLES);
    let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["white", "red", "green", "lamp", "matte", "mirror"]);
    let emitters: Vec<_> = s
        .instances
        .iter()
        .filter_map(|i| s.materials[s.meshes[i.mesh].material].emission)
        .collect();
    assert_eq!(emitters, [Vec3::splat(10.0)]);
    assert!(matches!(
        s.materials[5].bsdf,
        BsdfDesc::Mirror { reflectance } if reflectance == Vec3::splat(0.95)
    ));
    // The walls and lamp are the demo's, to float precision.
    let demo = demo_scene().scene;
    for name in [
        "floor",
        "ceiling",
        "backWall",
        "redWall",
        "greenWall",
        "lamp",
    ] {
        let ours = corners(s, name);
        let theirs = corners(&demo, name);
        assert_eq!(ours.len(), theirs.len(), "{name}");
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((*a - *b).abs().max_element() < 1e-6, "{name}: {a} vs {b}");
        }
        let albedo = |s: &SceneDesc| {
            let m = &s.materials[mesh(s, name).material];
            (format!("{:?}", m.bsdf), m.emission)
        };
        if name != "lamp" {
            assert_eq!(albedo(s), albedo(&demo), "{name}");
        }
    }
    // The spheres' vertices lie on the demo's spheres.
    for (name, demo_sphere) in [("matteSphere", 0), ("mirrorSphere", 1)] {
        let sp = &demo.spheres[demo_sphere];
        for p in &mesh(s, name).positions {
            assert!(
                ((*p - sp.center).length() - sp.radius).abs() < 1e-5,
                "{name}"
            );
        }
    }
}

fn mesh<'a>(s: &'a SceneDesc, name: &str) -> &'a candela_scene::MeshDesc {
    s.meshes
        .iter()
        .find(|m| m.name == name || m.name.starts_with(&format!("{name}-")))
        .unwrap_or_else(|| panic!("no mesh {name}"))
}

/// A mesh's triangle corners, sorted (loaders may start a quad's fan at
/// different corners).
fn corners(s: &SceneDesc, name: &str) -> Vec<Vec3> {
    let m = mesh(s, name);
    let mut c: Vec<Vec3> = m
        .triangles
        .iter()
        .flatten()
        .map(|&i| m.positions[i as usize])
        .collect();
    c.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    c.dedup();
    c
}

#[test]
fn the_ply_cornell_box_loads_in_every_encoding() {
    let mut total = 0;
    for (file, triangles) in [
        ("white", 6),
        ("red", 2),
        ("green", 2),
        ("lamp", 2),
        ("matte", SPHERE_TRIANGLES),
        ("mirror", SPHERE_TRIANGLES),
    ] {
        let path = repo().join(format!("scenes/cornell/{file}.ply"));
        let l = load(&path, &strict()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(l.scene.triangle_count(), triangles, "{file}");
        let m = &l.scene.meshes[0];
        assert_eq!(m.normal_indices.len(), m.triangles.len(), "{file}");
        total += triangles;
    }
    assert_eq!(total, 6 * 2 + 2 * SPHERE_TRIANGLES);
    // Same vertices as the OBJ's lamp.
    let ply = load(&repo().join("scenes/cornell/lamp.ply"), &strict()).unwrap();
    let obj = load(&repo().join("scenes/cornell/cornell.obj"), &strict()).unwrap();
    assert_eq!(
        ply.scene.meshes[0].positions,
        mesh(&obj.scene, "lamp").positions
    );
}

#[test]
fn the_shared_corpus_files_load() {
    let shared = repo().join("../shared/scenes/formats");
    let obj = shared.join("obj/CornellBox-Original/CornellBox-Original.obj");
    let l = load(&obj, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        l.scene.triangle_count() > 30,
        "{}",
        l.scene.triangle_count()
    );
    assert!(l.scene.materials.iter().any(|m| m.emission.is_some()));
    let ply = shared.join("ply/bunny_lowres/bunny_lowres.ply");
    let l = load(&ply, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(l.scene.meshes[0].positions.len(), 453);
    assert!(l.scene.triangle_count() >= 948);
    // confidence and intensity are named once each.
    assert!(l.report.mentions("confidence"), "{}", l.report);
}

/// Writes `text` to `name` in the test's folder `dir`.
fn temp(dir: &TempDir, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn missing_references_warn_or_fail_in_strict_mode() {
    let dir = TempDir::new("meshes");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let cases = [
        (
            "no-mtl.obj",
            format!("mtllib absent.mtl\n{tri}f 1 2 3\n"),
            "absent.mtl",
        ),
        (
            "no-mat.obj",
            format!("{tri}usemtl nowhere\nf 1 2 3\n"),
            "nowhere",
        ),
        (
            "no-tex.obj",
            format!("mtllib no-tex.mtl\n{tri}usemtl t\nf 1 2 3\n"),
            "absent.png",
        ),
    ];
    temp(
        &dir,
        "no-tex.mtl",
        "newmtl t\nKd 1 1 1\nmap_Kd absent.png\n",
    );
    for (name, text, needle) in cases {
        let path = temp(&dir, name, &text);
        let l = load(&path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        assert!(l.report.mentions(needle), "{name}: {}", l.report);
        assert_eq!(l.scene.triangle_count(), 1);
        let e = load(&path, &strict()).unwrap_err();
        assert_eq!(e.kind, ErrorKind::MissingReference, "{e}");
        assert!(e.loc.is_some() && !e.to_string().contains('\n'), "{e}");
    }
}

#[test]
fn obj_statements_polygons_and_negative_indices() {
    let dir = TempDir::new("meshes");
    let path = temp(
        &dir,
        "ngon.obj",
        "# a pentagon, CRLF\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0.5 2 0\r\nv 0 1 0\r\nvt 0 0\r\n\
         g pent\r\nf -5/1 -4/1 -3/1 -2/1 -1/1\r\ncurv 0 1 1 2\r\ncurv 0 1 2 3\r\n",
    );
    let l = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(l.scene.triangle_count(), 3);
    assert!(l.scene.meshes[0].normals.is_empty(), "flat shading");
    assert_eq!(l.scene.meshes[0].uv_indices.len(), 3);
    assert_eq!(l.report.len(), 1, "{}", l.report);
    assert_eq!(l.report.warnings[0].count, 2);
    assert_eq!(
        load(&path, &strict()).unwrap_err().kind,
        ErrorKind::Unsupported
    );
}

const VALID_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n\
o a\nf 1/1/1 2/2/1 3/1/1 4/2/1\ng b\nf -1 -2 -3\n";

fn ply_bytes(encoding: &str) -> Vec<u8> {
    let mut b = format!(
        "ply\nformat {encoding} 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nproperty float u\nproperty float v\nelement face 2\n\
         property list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    let verts = [
        [0., 0., 0., 0., 0.],
        [1., 0., 0., 1., 0.],
        [1., 1., 0., 1., 1.],
        [0., 1., 0., 0., 1.],
    ];
    if encoding == "ascii" {
        for v in verts {
            b.extend(format!("{} {} {} {} {}\n", v[0], v[1], v[2], v[3], v[4]).bytes());
        }
        b.extend(b"4 0 1 2 3\n3 0 2 3\n");
    } else {
        for v in verts {
            for x in v {
                b.extend((x as f32).to_le_bytes());
            }
        }
        for face in [&[0i32, 1, 2, 3][..], &[0, 2, 3]] {
            b.push(face.len() as u8);
            for i in face {
                b.extend(i.to_le_bytes());
            }
        }
    }
    b
}

#[test]
fn the_fuzz_bases_load() {
    let dir = TempDir::new("meshes");
    let obj = temp(&dir, "base.obj", VALID_OBJ);
    assert_eq!(load(&obj, &strict()).unwrap().scene.triangle_count(), 3);
    for enc in ["ascii", "binary_little_endian"] {
        let p = temp(&dir, &format!("base-{enc}.ply"), "");
        std::fs::write(&p, ply_bytes(enc)).unwrap();
        let l = load(&p, &strict()).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(l.scene.triangle_count(), 3);
        assert_eq!(l.scene.meshes[0].uv_indices.len(), 3);
    }
}

/// A mutation of a file: flip a byte, cut the file, or insert bytes.
#[derive(Clone, Debug)]
enum Mutation {
    Flip(usize, u8),
    Truncate(usize),
    Insert(usize, Vec<u8>),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Flip(i, b)),
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
    ]
}

fn mutate(mut bytes: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let n = bytes.len().max(1);
        match m {
            Mutation::Flip(i, b) => {
                if let Some(x) = bytes.get_mut(i % n) {
                    *x ^= b | 1;
                }
            }
            Mutation::Truncate(i) => bytes.truncate(i % n),
            Mutation::Insert(i, b) => {
                let at = (i % n).min(bytes.len());
                bytes.splice(at..at, b.iter().copied());
            }
        }
    }
    bytes
}

fn loads_or_fails(path: &Path, bytes: &[u8]) {
    std::fs::write(path, bytes).unwrap();
    // Ok or Err, never a panic; an error is one located line.
    if let Err(e) = load(path, &LoadOptions::default()) {
        assert!(!e.to_string().contains('\n'), "{e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_files_never_panic(ms in proptest::collection::vec(mutation(), 1..4)) {
        let dir = TempDir::new("meshes-fuzz");
        loads_or_fails(&dir.join("fuzz.obj"), &mutate(VALID_OBJ.as_bytes().to_vec(), &ms));
        loads_or_fails(&dir.join("fuzz-ascii.ply"), &mutate(ply_bytes("ascii"), &ms));
        loads_or_fails(&dir.join("fuzz-le.ply"), &mutate(ply_bytes("binary_little_endian"), &ms));
    }
}

#[test]
fn an_mtl_error_names_the_library_and_its_line() {
    let dir = TempDir::new("meshes");
    let mtl = temp(&dir, "bad.mtl", "newmtl a\nKd 0.5 x 0.5\n");
    let obj = temp(&dir, "bad-mtl.obj", "mtllib bad.mtl\nv 0 0 0\n");
    let e = load(&obj, &LoadOptions::default()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::BadNumber);
    assert_eq!(
        e.to_string(),
        format!("{}:2:8: Kd: \"x\" is not a number", mtl.display())
    );
}
