//! Mitsuba's `.serialized` meshes: the binary format its own exporters write
//! and many of its example scenes use.
//!
//! Layout, as Mitsuba's documentation of the `serialized` plugin gives it
//! (little endian): a file holds one or more meshes, each `u16` 0x041C,
//! `u16` version (3 or 4), then a zlib stream of `u32` flags, (version 4)
//! the mesh's name up to a NUL, `u64` vertex and triangle counts, positions,
//! optional normals, uvs and colours (`f32`, or `f64` with flag 0x2000), and
//! `u32` triangle indices. The file ends with each mesh's byte offset
//! (`u64`, version 3: `u32`) and the `u32` number of meshes, which is how
//! `shape_index` finds a mesh other than the first.
//!
//! Nothing in the file is trusted: counts are checked against a size limit
//! before anything is allocated, the decompressed stream may not exceed
//! that limit, and a stream that ends early is an error, never a panic.

use crate::desc::MeshDesc;
use crate::error::{ErrorKind, LoadError};
use crate::text_file::MAX_FILE_BYTES;
use glam::{Vec2, Vec3};
use std::io::Read;
use std::path::Path;

const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_UVS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const FACE_NORMALS: u32 = 0x0010;
const DOUBLE_PRECISION: u32 = 0x2000;

/// A mesh read from a `.serialized` file, and whether the file asks for
/// face normals (flag 0x0010, the same as the shape's `face_normals`).
pub(super) struct SerializedMesh {
    pub mesh: MeshDesc,
    pub face_normals: bool,
}

/// Reads mesh `shape_index` of the `.serialized` file `path`.
pub(super) fn read_serialized(path: &Path, shape_index: u32) -> Result<SerializedMesh, LoadError> {
    let bytes = crate::text_file::read_bytes(path)?;
    let element = format!("mesh {shape_index}");
    let fail = |kind: ErrorKind, message: String| LoadError {
        element: element.clone(),
        ..LoadError::whole_file(path.to_path_buf(), kind, message)
    };
    let (version, start) = header_at(&bytes, 0).map_err(|m| fail(ErrorKind::BadValue, m))?;
    let start = if shape_index == 0 {
        start
    } else {
        let offset =
            mesh_offset(&bytes, version, shape_index).map_err(|m| fail(ErrorKind::BadValue, m))?;
        let (v, s) = header_at(&bytes, offset).map_err(|m| fail(ErrorKind::BadValue, m))?;
        if v != version {
            return Err(fail(
                ErrorKind::BadValue,
                format!("version {v} at byte {offset}, the file's first mesh has {version}"),
            ));
        }
        s
    };
    // The limit bounds the memory a small, highly compressed file can ask for.
    let mut stream = flate2::read::ZlibDecoder::new(&bytes[start..]).take(MAX_FILE_BYTES);
    let mut reader = Reader {
        stream: &mut stream,
        read: 0,
    };
    let short = |e: String| fail(ErrorKind::CountMismatch, e);
    let flags = reader.u32().map_err(short)?;
    let name = if version >= 4 {
        reader.name().map_err(short)?
    } else {
        String::new()
    };
    let vertices = reader.u64().map_err(short)?;
    let triangles = reader.u64().map_err(short)?;
    let real = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let floats_per_vertex = 3
        + 3 * u64::from(flags & HAS_NORMALS != 0)
        + 2 * u64::from(flags & HAS_UVS != 0)
        + 3 * u64::from(flags & HAS_COLORS != 0);
    let needed = vertices
        .checked_mul(floats_per_vertex * real)
        .and_then(|v| triangles.checked_mul(12).and_then(|t| v.checked_add(t)));
    match needed {
        Some(n) if n <= MAX_FILE_BYTES => {}
        _ => {
            return Err(fail(
                ErrorKind::TooLarge,
                format!(
                    "{vertices} vertices and {triangles} triangles exceed the limit of \
                     {MAX_FILE_BYTES} bytes"
                ),
            ))
        }
    }
    let (vertices, triangles) = (vertices as usize, triangles as usize);
    let read_vec3s = |r: &mut Reader, what: &str| -> Result<Vec<Vec3>, LoadError> {
        let v = r
            .reals(3 * vertices, real == 8)
            .map_err(|e| short(format!("{what}: {e}")))?;
        Ok(v.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect())
    };
    let positions = read_vec3s(&mut reader, "positions")?;
    let normals = if flags & HAS_NORMALS != 0 {
        read_vec3s(&mut reader, "normals")?
    } else {
        Vec::new()
    };
    let uvs: Vec<Vec2> = if flags & HAS_UVS != 0 {
        let v = reader
            .reals(2 * vertices, real == 8)
            .map_err(|e| short(format!("uvs: {e}")))?;
        v.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect()
    } else {
        Vec::new()
    };
    // Vertex colours, linear as stored (Mitsuba's `vertex_color`
    // attribute, read by a `mesh_attribute` texture).
    let colors = if flags & HAS_COLORS != 0 {
        read_vec3s(&mut reader, "colours")?
    } else {
        Vec::new()
    };
    let indices = reader
        .u32s(3 * triangles)
        .map_err(|e| short(format!("triangles: {e}")))?;
    let tris: Vec<[u32; 3]> = indices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    if let Some((t, tri)) = tris
        .iter()
        .enumerate()
        .find(|(_, tri)| tri.iter().any(|&i| i as usize >= vertices))
    {
        return Err(fail(
            ErrorKind::IndexOutOfRange,
            format!("triangle {t} {tri:?} indexes past the {vertices} vertices"),
        ));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(fail(
            ErrorKind::NonFinite,
            format!("vertex {i} position {}", positions[i]),
        ));
    }
    let mesh = MeshDesc {
        name,
        normal_indices: if normals.is_empty() {
            Vec::new()
        } else {
            tris.clone()
        },
        uv_indices: if uvs.is_empty() {
            Vec::new()
        } else {
            tris.clone()
        },
        positions,
        normals,
        uvs,
        colors,
        triangles: tris,
        ..MeshDesc::default()
    };
    Ok(SerializedMesh {
        mesh,
        face_normals: flags & FACE_NORMALS != 0,
    })
}

/// The version of the mesh header at `offset` and where its zlib stream starts.
fn header_at(bytes: &[u8], offset: usize) -> Result<(u16, usize), String> {
    let field = |at: usize| -> Option<u16> {
        bytes
            .get(at..at + 2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
    };
    let (Some(magic), Some(version)) = (field(offset), field(offset + 2)) else {
        return Err(format!("no mesh header at byte {offset}: the file ends"));
    };
    if magic != MAGIC {
        return Err(format!(
            "byte {offset}: 0x{magic:04X} is not a serialized mesh (0x{MAGIC:04X})"
        ));
    }
    if !(3..=4).contains(&version) {
        return Err(format!(
            "byte {offset}: version {version} (only 3 and 4 exist)"
        ));
    }
    Ok((version, offset + 4))
}

/// The byte offset of mesh `index`, from the dictionary at the file's end.
fn mesh_offset(bytes: &[u8], version: u16, index: u32) -> Result<usize, String> {
    let n = bytes.len();
    let count = n
        .checked_sub(4)
        .map(|at| u32::from_le_bytes(bytes[at..n].try_into().unwrap()))
        .ok_or("the file is too short for its mesh dictionary")?;
    if index >= count {
        return Err(format!(
            "shape_index {index}, but the file holds {count} meshes"
        ));
    }
    let width = if version >= 4 { 8 } else { 4 };
    let at = (count as usize)
        .checked_sub(index as usize)
        .and_then(|k| k.checked_mul(width))
        .and_then(|k| n.checked_sub(4 + k))
        .ok_or("the mesh dictionary runs past the file's start")?;
    let offset = if width == 8 {
        u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap())
    } else {
        u64::from(u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()))
    };
    usize::try_from(offset)
        .ok()
        .filter(|&o| o < n)
        .ok_or_else(|| format!("mesh {index} starts at byte {offset}, past the file's end"))
}

/// Little-endian values from the decompressed stream; errors say what was
/// short and where.
struct Reader<'a> {
    stream: &'a mut dyn Read,
    read: u64,
}

impl Reader<'_> {
    fn exact(&mut self, buf: &mut [u8]) -> Result<(), String> {
        self.stream.read_exact(buf).map_err(|e| {
            format!(
                "the data ends at byte {} of the decompressed stream ({e})",
                self.read
            )
        })?;
        self.read += buf.len() as u64;
        Ok(())
    }

    fn u32(&mut self) -> Result<u32, String> {
        let mut b = [0; 4];
        self.exact(&mut b)?;
        Ok(u32::from_le_bytes(b))
    }

    fn u64(&mut self) -> Result<u64, String> {
        let mut b = [0; 8];
        self.exact(&mut b)?;
        Ok(u64::from_le_bytes(b))
    }

    /// The NUL-terminated name (at most 4 KiB, lossy UTF-8).
    fn name(&mut self) -> Result<String, String> {
        let mut name = Vec::new();
        loop {
            let mut b = [0; 1];
            self.exact(&mut b)?;
            if b[0] == 0 {
                return Ok(String::from_utf8_lossy(&name).into_owned());
            }
            if name.len() >= 4096 {
                return Err("a mesh name longer than 4 KiB".into());
            }
            name.push(b[0]);
        }
    }

    /// `count` reals (`f64` narrowed to `f32` when `double`).
    fn reals(&mut self, count: usize, double: bool) -> Result<Vec<f32>, String> {
        if double {
            self.values(count, |b: &[u8; 8]| f64::from_le_bytes(*b) as f32)
        } else {
            self.values(count, |b: &[u8; 4]| f32::from_le_bytes(*b))
        }
    }

    fn u32s(&mut self, count: usize) -> Result<Vec<u32>, String> {
        self.values(count, |b: &[u8; 4]| u32::from_le_bytes(*b))
    }

    /// `count` little-endian values of `N` bytes each, read in bounded
    /// chunks so that memory grows only with data actually present.
    fn values<const N: usize, T>(
        &mut self,
        count: usize,
        decode: impl Fn(&[u8; N]) -> T,
    ) -> Result<Vec<T>, String> {
        let mut out = Vec::with_capacity(count.min(1 << 20));
        let mut chunk = vec![0u8; 1 << 16];
        let mut left = count;
        while left > 0 {
            let n = left.min(chunk.len() / N);
            let buf = &mut chunk[..n * N];
            self.exact(buf)?;
            out.extend(buf.chunks_exact(N).map(|b| decode(b.try_into().unwrap())));
            left -= n;
        }
        Ok(out)
    }
}

#[cfg(test)]
#[path = "serialized_tests.rs"]
mod tests;
