//! Typed reads of accessors, with every byte range checked against its
//! buffer view and buffer before anything is read or allocated: a count or
//! offset that does not fit is an [`ErrorKind::IndexOutOfRange`] error, so
//! a file claiming ten billion elements allocates nothing. Sparse accessors
//! are applied over their base values (or zeros).
//!
//! Each attribute names the component types it may be stored as
//! ([`Storage`]): the core spec's, widened by `KHR_mesh_quantization` to
//! 8- and 16-bit integers for positions, normals, tangents and texture
//! coordinates. Every element is decoded by [`component`], the one place
//! that knows the component types and the normalised flag.

use super::Ctx;
use crate::error::{ErrorKind, LoadError};
use gltf::accessor::{DataType, Dimensions};
use std::borrow::Cow;

/// Most elements an accessor may have (the positions of a 256M-vertex mesh
/// would not fit the file size limit anyway).
const MAX_COUNT: usize = 1 << 28;

/// The loaded buffers, indexed like the document's.
pub(super) type Buffers<'a> = [Cow<'a, [u8]>];

/// Where an accessor's (or a sparse part's) elements lie.
struct Strided<'b> {
    data: &'b [u8],
    stride: usize,
    elem: usize,
}

impl Strided<'_> {
    fn get(&self, i: usize) -> &[u8] {
        let start = i * self.stride;
        &self.data[start..start + self.elem]
    }
}

/// Element bytes of `count` elements of `elem` bytes at `offset` into
/// `view`, `stride` apart; bounds-checked.
fn strided<'b>(
    ctx: &Ctx,
    buffers: &'b Buffers,
    view: &gltf::buffer::View,
    offset: usize,
    count: usize,
    elem: usize,
    at: &str,
) -> Result<Strided<'b>, LoadError> {
    let vat = format!("/bufferViews/{}", view.index());
    let buffer = &buffers[view.buffer().index()];
    let view_bytes = view
        .offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or_else(|| {
            ctx.err(
                vat.clone(),
                ErrorKind::IndexOutOfRange,
                format!(
                    "bytes {}..+{} run past the end of buffer {} ({} bytes)",
                    view.offset(),
                    view.length(),
                    view.buffer().index(),
                    buffer.len()
                ),
            )
        })?;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(ctx.err(
            format!("{vat}/byteStride"),
            ErrorKind::BadValue,
            format!("stride {stride} is smaller than the {elem}-byte element"),
        ));
    }
    let needed = match count {
        0 => Some(0),
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|b| b.checked_add(elem))
            .and_then(|b| b.checked_add(offset)),
    };
    match needed {
        Some(n) if n <= view_bytes.len() => Ok(Strided {
            data: &view_bytes[offset.min(view_bytes.len())..],
            stride,
            elem,
        }),
        _ => Err(ctx.err(
            at.to_string(),
            ErrorKind::IndexOutOfRange,
            format!(
                "{count} elements of {elem} bytes (stride {stride}) at offset {offset} do not fit in buffer view {} ({} bytes)",
                view.index(),
                view_bytes.len()
            ),
        )),
    }
}

/// The component types an attribute may be stored as: `plain` as stored
/// (floats, and integers read as their value), `normalized` as integers
/// with the accessor's `normalized` flag set.
pub(super) struct Storage {
    /// The attribute's name in messages (`NORMAL`).
    name: &'static str,
    /// Types read as stored.
    plain: &'static [DataType],
    /// Integer types read normalised.
    normalized: &'static [DataType],
}

const FLOAT: &[DataType] = &[DataType::F32];
const SMALL_INTS: &[DataType] = &[DataType::I8, DataType::U8, DataType::I16, DataType::U16];
const FLOAT_AND_SMALL_INTS: &[DataType] = &[
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];

/// `KHR_mesh_quantization`: float, or any 8/16-bit integer, normalised or not
/// (the node transform carries the dequantisation).
pub(super) const POSITION: Storage = Storage {
    name: "POSITION",
    plain: FLOAT_AND_SMALL_INTS,
    normalized: SMALL_INTS,
};

/// `KHR_mesh_quantization`: float or normalised signed 8/16-bit.
pub(super) const NORMAL: Storage = Storage {
    name: "NORMAL",
    plain: FLOAT,
    normalized: &[DataType::I8, DataType::I16],
};

/// As [`NORMAL`].
pub(super) const TANGENT: Storage = Storage {
    name: "TANGENT",
    ..NORMAL
};

/// `KHR_mesh_quantization`: float, or any 8/16-bit integer, normalised or not
/// (`KHR_texture_transform` usually carries the dequantisation).
pub(super) const TEXCOORD: Storage = Storage {
    name: "TEXCOORD_0",
    ..POSITION
};

/// The core spec: float or normalised unsigned 8/16-bit.
pub(super) const COLOR: Storage = Storage {
    name: "COLOR_0",
    plain: FLOAT,
    normalized: &[DataType::U8, DataType::U16],
};

/// Unsigned integers read as stored.
const INDICES: Storage = Storage {
    name: "indices",
    plain: &[DataType::U8, DataType::U16, DataType::U32],
    normalized: &[],
};

/// The glTF name of a component type, for messages.
fn type_name(ty: DataType) -> &'static str {
    match ty {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    }
}

impl Storage {
    /// Whether `ty` (normalised or not) is allowed. The flag means nothing
    /// for floats, so it is not held against them.
    fn allows(&self, ty: DataType, normalized: bool) -> bool {
        match normalized && ty != DataType::F32 {
            true => self.normalized.contains(&ty),
            false => self.plain.contains(&ty),
        }
    }

    /// The allowed types, as in a message: `FLOAT, normalized BYTE`.
    fn allowed(&self) -> String {
        let plain = self.plain.iter().map(|&t| type_name(t).to_string());
        let normalized = self
            .normalized
            .iter()
            .map(|&t| format!("normalized {}", type_name(t)));
        plain.chain(normalized).collect::<Vec<_>>().join(", ")
    }
}

/// Reads accessor `acc` element by element with `decode` (given the element
/// bytes, component type and normalised flag), after checking its shape is
/// `dims` and its storage one that `storage` allows.
fn read<T: Copy + Default>(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
    dims: Dimensions,
    storage: &Storage,
    decode: impl Fn(&[u8], DataType, bool) -> T,
) -> Result<Vec<T>, LoadError> {
    let at = format!("/accessors/{}", acc.index());
    if acc.dimensions() != dims {
        return Err(ctx.err(
            format!("{at}/type"),
            ErrorKind::BadValue,
            format!("type {:?} where {dims:?} is needed", acc.dimensions()),
        ));
    }
    let (ty, normalized) = (acc.data_type(), acc.normalized());
    if !storage.allows(ty, normalized) {
        let stored = match normalized {
            true => format!("normalized {}", type_name(ty)),
            false => type_name(ty).to_string(),
        };
        return Err(ctx.err(
            format!("{at}/componentType"),
            ErrorKind::BadValue,
            format!(
                "{} cannot be {stored} (allowed: {})",
                storage.name,
                storage.allowed()
            ),
        ));
    }
    let count = acc.count();
    if count > MAX_COUNT {
        return Err(ctx.err(
            format!("{at}/count"),
            ErrorKind::TooLarge,
            format!("count {count} exceeds the limit of {MAX_COUNT}"),
        ));
    }
    let elem = ty.size() * dims.multiplicity();
    let mut out = match acc.view() {
        Some(view) => {
            let s = strided(ctx, buffers, &view, acc.offset(), count, elem, &at)?;
            (0..count)
                .map(|i| decode(s.get(i), ty, normalized))
                .collect()
        }
        None => vec![T::default(); count],
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(ctx, buffers, &sparse, &at, elem, &mut out, |b| {
            decode(b, ty, normalized)
        })?;
    }
    Ok(out)
}

/// Overwrites the elements a sparse accessor names.
fn apply_sparse<T>(
    ctx: &Ctx,
    buffers: &Buffers,
    sparse: &gltf::accessor::sparse::Sparse,
    at: &str,
    elem: usize,
    out: &mut [T],
    decode: impl Fn(&[u8]) -> T,
) -> Result<(), LoadError> {
    let n = sparse.count();
    let at = format!("{at}/sparse");
    if n > out.len() {
        return Err(ctx.err(
            format!("{at}/count"),
            ErrorKind::CountMismatch,
            format!("{n} sparse elements in an accessor of {}", out.len()),
        ));
    }
    let idx = sparse.indices();
    let isize = match idx.index_type() {
        gltf::accessor::sparse::IndexType::U8 => 1,
        gltf::accessor::sparse::IndexType::U16 => 2,
        gltf::accessor::sparse::IndexType::U32 => 4,
    };
    let indices = strided(ctx, buffers, &idx.view(), idx.offset(), n, isize, &at)?;
    let vals = sparse.values();
    let values = strided(ctx, buffers, &vals.view(), vals.offset(), n, elem, &at)?;
    for k in 0..n {
        let i = uint(indices.get(k)) as usize;
        let slot = out.get_mut(i).ok_or_else(|| {
            ctx.err(
                format!("{at}/indices"),
                ErrorKind::IndexOutOfRange,
                format!("sparse index {i} is past the accessor's {} elements", n),
            )
        })?;
        *slot = decode(values.get(k));
    }
    Ok(())
}

/// A little-endian unsigned integer of 1, 2 or 4 bytes.
fn uint(b: &[u8]) -> u32 {
    match b.len() {
        1 => b[0] as u32,
        2 => u16::from_le_bytes([b[0], b[1]]) as u32,
        _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    }
}

/// Component `i` of an element as a float: floats as stored, integers
/// normalised as the glTF spec says (unsigned `c / (2^n - 1)`, signed
/// `max(c / (2^(n-1) - 1), -1)`) or, without the flag, as their value.
fn component(b: &[u8], ty: DataType, normalized: bool, i: usize) -> f32 {
    let bytes = |n: usize| &b[n * i..n * i + n];
    let two = |c: &[u8]| [c[0], c[1]];
    let four = |c: &[u8]| [c[0], c[1], c[2], c[3]];
    let (value, max) = match ty {
        DataType::F32 => return f32::from_le_bytes(four(bytes(4))),
        DataType::U8 => (bytes(1)[0] as f32, u8::MAX as f32),
        DataType::I8 => (bytes(1)[0] as i8 as f32, i8::MAX as f32),
        DataType::U16 => (u16::from_le_bytes(two(bytes(2))) as f32, u16::MAX as f32),
        DataType::I16 => (i16::from_le_bytes(two(bytes(2))) as f32, i16::MAX as f32),
        DataType::U32 => (u32::from_le_bytes(four(bytes(4))) as f32, u32::MAX as f32),
    };
    match normalized {
        true => (value / max).max(-1.0),
        false => value,
    }
}

/// The first `N` components of an element as floats.
fn floats<const N: usize>(b: &[u8], ty: DataType, normalized: bool) -> [f32; N] {
    std::array::from_fn(|k| component(b, ty, normalized, k))
}

/// A `VEC3` attribute (POSITION, NORMAL) stored as `storage` allows.
pub(super) fn vec3(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
    storage: &Storage,
) -> Result<Vec<glam::Vec3>, LoadError> {
    read(ctx, buffers, acc, Dimensions::Vec3, storage, |b, ty, n| {
        glam::Vec3::from_array(floats(b, ty, n))
    })
}

/// A `VEC4` attribute (TANGENT) stored as `storage` allows.
pub(super) fn vec4(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
    storage: &Storage,
) -> Result<Vec<glam::Vec4>, LoadError> {
    read(ctx, buffers, acc, Dimensions::Vec4, storage, |b, ty, n| {
        glam::Vec4::from_array(floats(b, ty, n))
    })
}

/// A `VEC2` attribute (TEXCOORD_0) stored as `storage` allows.
pub(super) fn vec2(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
    storage: &Storage,
) -> Result<Vec<glam::Vec2>, LoadError> {
    read(ctx, buffers, acc, Dimensions::Vec2, storage, |b, ty, n| {
        glam::Vec2::from_array(floats(b, ty, n))
    })
}

/// A `COLOR_n` attribute: `VEC3` or `VEC4` (alpha 1 when absent), float
/// or normalised unsigned 8/16-bit, as the spec allows.
pub(super) fn colors(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec4>, LoadError> {
    let dims = match acc.dimensions() {
        Dimensions::Vec3 => Dimensions::Vec3,
        _ => Dimensions::Vec4,
    };
    let n = dims.multiplicity();
    read(ctx, buffers, acc, dims, &COLOR, |b, ty, norm| {
        glam::Vec4::from_array([0, 1, 2, 3].map(|k| match k < n {
            true => component(b, ty, norm, k),
            false => 1.0,
        }))
    })
}

/// A `SCALAR` unsigned index accessor.
pub(super) fn indices(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<u32>, LoadError> {
    read(
        ctx,
        buffers,
        acc,
        Dimensions::Scalar,
        &INDICES,
        |b, _, _| uint(b),
    )
}
