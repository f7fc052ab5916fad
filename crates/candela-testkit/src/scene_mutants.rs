//! The repository's own small scenes, each with a fixed, seeded set of
//! mutants of one of its files: the input of the bad-input sweeps (the
//! loaders' in `candela-scene`, the render-side build's in
//! `candela-render`), defined once so both sweep the same mutants.
//!
//! Every format is covered: COLLADA, OBJ + MTL, glTF (text with its `.bin`,
//! and a `.glb` made here from the same data), PLY (ASCII, binary big- and
//! little-endian) and Mitsuba 3 XML (which draws the PLY files).

use crate::mutate::{self, Mutant, EXTREME_NUMBERS, HUGE_COUNTS};
use std::path::{Path, PathBuf};

/// A scene folder to lay out, the file to load, and one mutant of one of
/// its files.
pub struct SceneMutant {
    /// The files of the scene: name in the folder, and contents.
    pub files: std::rc::Rc<Vec<(String, Vec<u8>)>>,
    /// The file to load (a name in the folder).
    pub load: String,
    /// The file this mutant replaces (a name in the folder).
    pub mutated: String,
    /// The mutation.
    pub mutant: Mutant,
}

impl SceneMutant {
    /// A label for messages: `cornell.gltf <- cornell.bin: flip@12^0x40`.
    pub fn label(&self) -> String {
        format!("{} <- {}: {}", self.load, self.mutated, self.mutant.name)
    }

    /// Writes the scene into `dir` with the mutant in place, and returns
    /// the path to load.
    ///
    /// # Panics
    /// If a file cannot be written (a test environment problem).
    pub fn stage(&self, dir: &Path) -> PathBuf {
        for (name, bytes) in self.files.iter() {
            let bytes = if *name == self.mutated {
                &self.mutant.bytes
            } else {
                bytes
            };
            std::fs::write(dir.join(name), bytes).expect("write sweep file");
        }
        dir.join(&self.load)
    }
}

/// How a file is mutated.
#[derive(Clone, Copy)]
enum Plan {
    /// Text: every byte-level mutation, numbers, and the format's keys.
    Text(&'static [Key]),
    /// Binary data (a `.bin` buffer): truncations and flips.
    Binary,
    /// A binary PLY: its text header's keys, and the body's bytes.
    BinaryPly,
    /// A `.glb`: bytes and the header's length words.
    Glb,
}

/// A key whose value is replaced, and the values it gets.
type Key = (&'static str, &'static [&'static str]);

const MISSING: &[&str] = &["missing"];
const BAD_INDEX: &[&str] = &["4294967295", "99"];

const COLLADA: &[Key] = &[
    ("count=\"", &HUGE_COUNTS),
    ("stride=\"", &HUGE_COUNTS),
    ("offset=\"", &HUGE_COUNTS),
    ("url=\"#", MISSING),
    ("source=\"#", MISSING),
    ("target=\"#", MISSING),
    ("material=\"", MISSING),
    ("symbol=\"", MISSING),
    ("id=\"", MISSING),
];

const GLTF: &[Key] = &[
    ("\"count\": ", &HUGE_COUNTS),
    ("\"byteLength\": ", &HUGE_COUNTS),
    ("\"byteOffset\": ", &HUGE_COUNTS),
    ("\"componentType\": ", &["5130", "0"]),
    ("\"type\": \"", &["MAT4", "SCALAR"]),
    (
        "\"uri\": \"",
        &["missing.bin", "data:application/octet-stream;base64,@@"],
    ),
    ("\"buffer\": ", BAD_INDEX),
    ("\"bufferView\": ", BAD_INDEX),
    ("\"indices\": ", BAD_INDEX),
    ("\"POSITION\": ", BAD_INDEX),
    ("\"NORMAL\": ", BAD_INDEX),
    ("\"material\": ", BAD_INDEX),
    ("\"mesh\": ", BAD_INDEX),
    ("\"camera\": ", BAD_INDEX),
    ("\"scene\": ", BAD_INDEX),
    ("\"index\": ", BAD_INDEX),
    ("\"source\": ", BAD_INDEX),
    ("\"sampler\": ", BAD_INDEX),
];

const OBJ: &[Key] = &[
    ("mtllib ", &["missing.mtl"]),
    ("usemtl ", MISSING),
    ("f ", &["0", "-99", "4294967295"]),
];

const MTL: &[Key] = &[("newmtl ", MISSING), ("illum ", &["99", "-1"])];

const PLY: &[Key] = &[
    ("element vertex ", &HUGE_COUNTS),
    ("element face ", &HUGE_COUNTS),
    ("property list ", &["uint", "float", "double"]),
    (
        "format ",
        &["binary_little_endian", "binary_big_endian", "ascii"],
    ),
];

const MITSUBA: &[Key] = &[
    (
        "name=\"filename\" value=\"",
        &["missing.ply", "cornell.xml"],
    ),
    ("type=\"", &["bogus"]),
    ("id=\"", &["lamp"]),
    ("name=\"width\" value=\"", &HUGE_COUNTS),
    ("version=\"", &["9.9.9"]),
];

/// The scenes of the repository's `scenes/` folder used by the sweeps.
fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn read(rel: &str) -> Vec<u8> {
    let path = scenes_dir().join(rel);
    std::fs::read(&path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()))
}

/// A `.glb` of `scenes/cornell/cornell.gltf`, its buffer moved into the
/// BIN chunk.
fn cornell_glb() -> Vec<u8> {
    let text = String::from_utf8(read("cornell/cornell.gltf")).expect("UTF-8 glTF");
    let uri = "\"uri\": \"cornell.bin\",";
    assert!(
        text.contains(uri),
        "cornell.gltf names its buffer differently"
    );
    crate::glb::glb_of(
        text.replace(uri, "").as_bytes(),
        &read("cornell/cornell.bin"),
    )
}

fn mutants_of(bytes: &[u8], plan: Plan, seed: u64) -> Vec<Mutant> {
    let mut out = mutate::truncations(bytes);
    out.extend(mutate::flips(bytes, seed, 8));
    match plan {
        Plan::Text(keys) => {
            out.extend(mutate::deletions(bytes, seed + 1, 4));
            out.extend(mutate::numbers(bytes, &EXTREME_NUMBERS, 2, seed + 2));
            for (i, (key, values)) in keys.iter().enumerate() {
                out.extend(mutate::after_key(
                    bytes,
                    key,
                    values,
                    1,
                    seed + 3 + i as u64,
                ));
            }
        }
        Plan::Binary => {}
        Plan::BinaryPly => {
            out.extend(mutate::deletions(bytes, seed + 1, 2));
            for (i, (key, values)) in PLY.iter().enumerate() {
                out.extend(mutate::after_key(
                    bytes,
                    key,
                    values,
                    0,
                    seed + 3 + i as u64,
                ));
            }
        }
        Plan::Glb => {
            let json_len = u32::from_le_bytes(bytes[12..16].try_into().expect("4 bytes")) as usize;
            let words = [8, 12, 20 + json_len];
            out.extend(mutate::u32_words(
                bytes,
                &words,
                &[0, 7, 0x7fff_ffff, u32::MAX],
            ));
        }
    }
    out
}

/// One scene: its files (`(name in the folder, path under scenes/)`), the
/// file to load, and the files to mutate with their plans.
struct Scene {
    files: Vec<(String, Vec<u8>)>,
    load: &'static str,
    mutate: Vec<(&'static str, Plan)>,
}

fn scene(files: &[(&str, &str)], load: &'static str, mutate: Vec<(&'static str, Plan)>) -> Scene {
    Scene {
        files: files
            .iter()
            .map(|(name, rel)| (name.to_string(), read(rel)))
            .collect(),
        load,
        mutate,
    }
}

fn scenes() -> Vec<Scene> {
    let plys = ["white", "red", "green", "lamp", "matte", "mirror"]
        .map(|n| (format!("{n}.ply"), format!("cornell/{n}.ply")));
    let mut mitsuba: Vec<(&str, &str)> = vec![("cornell.xml", "cornell/cornell.xml")];
    mitsuba.extend(plys.iter().map(|(a, b)| (a.as_str(), b.as_str())));
    vec![
        scene(
            &[("cornell.dae", "cornell/cornell.dae")],
            "cornell.dae",
            vec![("cornell.dae", Plan::Text(COLLADA))],
        ),
        scene(
            &[("demo.dae", "demo.dae")],
            "demo.dae",
            vec![("demo.dae", Plan::Text(COLLADA))],
        ),
        scene(
            &[
                ("cornell.obj", "cornell/cornell.obj"),
                ("cornell.mtl", "cornell/cornell.mtl"),
            ],
            "cornell.obj",
            vec![
                ("cornell.obj", Plan::Text(OBJ)),
                ("cornell.mtl", Plan::Text(MTL)),
            ],
        ),
        scene(
            &[
                ("cornell.gltf", "cornell/cornell.gltf"),
                ("cornell.bin", "cornell/cornell.bin"),
            ],
            "cornell.gltf",
            vec![
                ("cornell.gltf", Plan::Text(GLTF)),
                ("cornell.bin", Plan::Binary),
            ],
        ),
        scene(
            &[
                ("textured.gltf", "gltf/textured.gltf"),
                ("textured.bin", "gltf/textured.bin"),
                ("albedo.png", "gltf/albedo.png"),
                ("normal.png", "gltf/normal.png"),
            ],
            "textured.gltf",
            vec![
                ("textured.gltf", Plan::Text(GLTF)),
                ("albedo.png", Plan::Binary),
            ],
        ),
        Scene {
            files: vec![("cornell.glb".into(), cornell_glb())],
            load: "cornell.glb",
            mutate: vec![("cornell.glb", Plan::Glb)],
        },
        scene(
            &[("lamp.ply", "cornell/lamp.ply")],
            "lamp.ply",
            vec![("lamp.ply", Plan::Text(PLY))],
        ),
        scene(
            &[("green.ply", "cornell/green.ply")],
            "green.ply",
            vec![("green.ply", Plan::BinaryPly)],
        ),
        scene(
            &[("red.ply", "cornell/red.ply")],
            "red.ply",
            vec![("red.ply", Plan::BinaryPly)],
        ),
        scene(
            &mitsuba,
            "cornell.xml",
            vec![
                ("cornell.xml", Plan::Text(MITSUBA)),
                ("matte.ply", Plan::BinaryPly),
            ],
        ),
    ]
}

/// Every mutant of every scene, in a fixed order, from fixed seeds.
pub fn scene_mutants() -> Vec<SceneMutant> {
    let mut out = Vec::new();
    for (s, scene) in scenes().into_iter().enumerate() {
        let files = std::rc::Rc::new(scene.files);
        for (f, (name, plan)) in scene.mutate.into_iter().enumerate() {
            let bytes = &files
                .iter()
                .find(|(n, _)| n == name)
                .expect("mutated file is in the scene")
                .1;
            let seed = 0x5eed_0000 + 100 * s as u64 + 10 * f as u64;
            for mutant in mutants_of(bytes, plan, seed) {
                out.push(SceneMutant {
                    files: files.clone(),
                    load: scene.load.to_string(),
                    mutated: name.to_string(),
                    mutant,
                });
            }
        }
    }
    out
}
