//! A stable content hash of a loaded scene, so that a checkpoint is never
//! continued with another scene.
//!
//! The hash covers what the render reads: every mesh's arrays (as raw
//! bytes), instances, spheres, materials, lights, cameras and the
//! environment (through their `Debug` form, which prints every field and
//! every float exactly), plus the bytes of every image file they reference
//! (textures, environment maps), so an edited texture changes it too. The
//! source path does not enter: the same scene moved elsewhere is the same
//! scene. Structs whose fields are hashed one by one are destructured
//! without `..`, so a new field cannot be forgotten silently.
//!
//! The hasher is a small two-lane multiply-rotate hash over 64-bit words
//! with 128 bits of output: not cryptographic (nobody forges checkpoints),
//! stable across runs, machines and Rust versions (unlike `std`'s
//! `DefaultHasher`), and fast enough for meshes of millions of triangles.

use candela_scene::{EnvironmentDesc, MeshDesc, SceneDesc};
use std::fmt::{self, Write as _};
use std::io::Read;
use std::path::Path;

/// A 128-bit content hash.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ContentHash(pub [u64; 2]);

impl fmt::Display for ContentHash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:016x}{:016x}", self.0[0], self.0[1])
    }
}

impl ContentHash {
    /// Parses the 32 hex digits of [`Display`](fmt::Display).
    pub fn parse(text: &str) -> Option<Self> {
        if text.len() != 32 || !text.is_ascii() {
            return None;
        }
        let a = u64::from_str_radix(&text[..16], 16).ok()?;
        let b = u64::from_str_radix(&text[16..], 16).ok()?;
        Some(Self([a, b]))
    }
}

/// A streaming hasher: every [`write`](ContentHasher::write) is prefixed
/// with its length, so concatenations cannot collide.
#[derive(Clone, Debug)]
pub struct ContentHasher {
    lanes: [u64; 2],
}

impl Default for ContentHasher {
    fn default() -> Self {
        Self {
            lanes: [0x243F_6A88_85A3_08D3, 0x1319_8A2E_0370_7344],
        }
    }
}

impl ContentHasher {
    /// A hasher with nothing written.
    pub fn new() -> Self {
        Self::default()
    }

    fn word(&mut self, w: u64) {
        let [a, b] = &mut self.lanes;
        *a = (*a ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(31);
        *b = (*b ^ w.rotate_left(23))
            .wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
            .rotate_left(29);
    }

    /// Adds `bytes`.
    pub fn write(&mut self, bytes: &[u8]) {
        self.word(bytes.len() as u64);
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            self.word(u64::from_le_bytes(w.try_into().expect("8 bytes")));
        }
        let tail = words.remainder();
        if !tail.is_empty() {
            let mut last = [0u8; 8];
            last[..tail.len()].copy_from_slice(tail);
            self.word(u64::from_le_bytes(last));
        }
    }

    /// Adds a value through its `Debug` form.
    pub fn debug(&mut self, value: &impl fmt::Debug) {
        // Writing to the hasher cannot fail.
        let _ = write!(self, "{value:?}");
    }

    /// Adds the contents of the file at `path` (or a marker if it cannot be
    /// read: a missing texture is part of what was rendered too).
    pub fn file(&mut self, path: &Path) {
        let Ok(mut file) = std::fs::File::open(path) else {
            self.write(b"<unreadable>");
            return;
        };
        let mut buf = vec![0u8; 1 << 20];
        loop {
            match file.read(&mut buf) {
                Ok(0) => break,
                Ok(n) => self.write(&buf[..n]),
                Err(_) => {
                    self.write(b"<read error>");
                    break;
                }
            }
        }
    }

    /// The hash of everything written.
    pub fn finish(&self) -> ContentHash {
        let mix = |mut z: u64| {
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        };
        let [a, b] = self.lanes;
        ContentHash([mix(a ^ b.rotate_left(17)), mix(b ^ a.rotate_left(41))])
    }
}

impl fmt::Write for ContentHasher {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.write(s.as_bytes());
        Ok(())
    }
}

/// Raw bytes of a slice of plain numbers (f32 vectors, index triples).
fn bytes_of<T: AsBytes>(v: &[T]) -> Vec<u8> {
    let mut out = Vec::with_capacity(std::mem::size_of_val(v));
    for x in v {
        x.append(&mut out);
    }
    out
}

/// Plain numeric values of the mesh arrays, as little-endian bytes.
trait AsBytes {
    fn append(&self, out: &mut Vec<u8>);
}

macro_rules! as_bytes_f32 {
    ($($t:ty),*) => {$(
        impl AsBytes for $t {
            fn append(&self, out: &mut Vec<u8>) {
                for c in self.to_array() {
                    out.extend_from_slice(&c.to_bits().to_le_bytes());
                }
            }
        }
    )*};
}
as_bytes_f32!(glam::Vec2, glam::Vec3, glam::Vec4);

impl AsBytes for [u32; 3] {
    fn append(&self, out: &mut Vec<u8>) {
        for c in self {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
}

fn hash_mesh(h: &mut ContentHasher, mesh: &MeshDesc) {
    let MeshDesc {
        name,
        positions,
        triangles,
        normals,
        normal_indices,
        tangents,
        uvs,
        uv_indices,
        colors,
        material,
        loc: _,
    } = mesh;
    h.write(name.as_bytes());
    h.write(&bytes_of(positions));
    h.write(&bytes_of(triangles));
    h.write(&bytes_of(normals));
    h.write(&bytes_of(normal_indices));
    h.write(&bytes_of(tangents));
    h.write(&bytes_of(uvs));
    h.write(&bytes_of(uv_indices));
    // Only when present: a scene without vertex colours keeps the hash it
    // had before meshes could carry them, so its checkpoints still resume.
    if !colors.is_empty() {
        h.write(&bytes_of(colors));
    }
    h.write(&(*material as u64).to_le_bytes());
}

/// The content hash of a loaded scene and of the files it references, plus
/// the environment map file `env_map` a render adds (the `-e` setting), if
/// any.
pub fn scene_hash(desc: &SceneDesc, env_map: Option<&Path>) -> ContentHash {
    let SceneDesc {
        source: _,
        cameras,
        meshes,
        instances,
        spheres,
        materials,
        lights,
        environment,
        media,
        medium_interfaces,
        camera_medium,
    } = desc;
    let mut h = ContentHasher::new();
    h.write(b"candela scene v1");
    h.write(&(meshes.len() as u64).to_le_bytes());
    for mesh in meshes {
        hash_mesh(&mut h, mesh);
    }
    // Source locations are part of these Debug forms; they change only with
    // the file, which is then another scene anyway.
    h.debug(cameras);
    h.debug(instances);
    h.debug(spheres);
    h.debug(materials);
    h.debug(lights);
    h.debug(environment);
    // Only when present, as vertex colours above: scenes without media keep
    // their hash.
    if !media.is_empty() {
        h.debug(media);
        h.debug(medium_interfaces);
        h.debug(camera_medium);
    }
    for material in materials {
        for path in material.textures.iter().filter_map(|(_, t)| t.image_path()) {
            h.file(path);
        }
    }
    if let Some(EnvironmentDesc::Map { path, .. }) = environment {
        h.file(path);
    }
    if let Some(path) = env_map {
        h.debug(&path);
        h.file(path);
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_is_stable_and_sees_every_byte() {
        let hash = |b: &[&[u8]]| {
            let mut h = ContentHasher::new();
            b.iter().for_each(|b| h.write(b));
            h.finish()
        };
        // A fixed value (computed independently from the algorithm): the
        // hash must not change between versions, or old checkpoints would
        // be refused.
        assert_eq!(
            hash(&[b"candela"]).to_string(),
            "9168bd15162ac39e6da6ff3b91c1afe2"
        );
        assert_ne!(hash(&[b"ab", b"c"]), hash(&[b"a", b"bc"]));
        assert_ne!(hash(&[b"abcdefgh1"]), hash(&[b"abcdefgh2"]));
        assert_ne!(hash(&[b"\0"]), hash(&[b""]));
        let h = hash(&[b"x"]);
        assert_eq!(ContentHash::parse(&h.to_string()), Some(h));
        assert_eq!(ContentHash::parse("xyz"), None);
    }

    #[test]
    fn a_moved_vertex_changes_the_scene_hash() {
        let mut desc = candela_scene::demo_scene().scene;
        let before = scene_hash(&desc, None);
        assert_eq!(before, scene_hash(&desc, None));
        desc.source = "elsewhere.dae".into();
        assert_eq!(before, scene_hash(&desc, None), "the path is not content");
        let mesh = desc.meshes.iter_mut().find(|m| !m.positions.is_empty());
        let mesh = mesh.expect("the demo has a mesh");
        mesh.positions[0].x += 1e-6;
        let moved = scene_hash(&desc, None);
        assert_ne!(before, moved);
        // Vertex colours are content too; a changed one changes the hash.
        let mesh = desc.meshes.iter_mut().find(|m| !m.positions.is_empty());
        let mesh = mesh.expect("the demo has a mesh");
        mesh.colors = vec![glam::Vec3::splat(0.5); mesh.positions.len()];
        let colored = scene_hash(&desc, None);
        assert_ne!(moved, colored);
        desc.meshes
            .iter_mut()
            .find(|m| !m.colors.is_empty())
            .unwrap()
            .colors[0]
            .y = 0.25;
        assert_ne!(colored, scene_hash(&desc, None));
    }
}
