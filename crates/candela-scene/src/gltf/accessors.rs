//! Typed reads of accessors, with every byte range checked against its
//! buffer view and buffer before anything is read or allocated: a count or
//! offset that does not fit is an [`ErrorKind::IndexOutOfRange`] error, so
//! a file claiming ten billion elements allocates nothing. Sparse accessors
//! are applied over their base values (or zeros).

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

/// Reads accessor `acc` element by element with `decode`, after checking its
/// shape is `dims` and its component type one of `types`.
fn read<T: Copy + Default>(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
    dims: Dimensions,
    types: &[DataType],
    decode: impl Fn(&[u8], DataType) -> T,
) -> Result<Vec<T>, LoadError> {
    let at = format!("/accessors/{}", acc.index());
    if acc.dimensions() != dims {
        return Err(ctx.err(
            format!("{at}/type"),
            ErrorKind::BadValue,
            format!("type {:?} where {dims:?} is needed", acc.dimensions()),
        ));
    }
    let ty = acc.data_type();
    if !types.contains(&ty) {
        return Err(ctx.err(
            format!("{at}/componentType"),
            ErrorKind::BadValue,
            format!("component type {ty:?} not allowed here (expected one of {types:?})"),
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
            (0..count).map(|i| decode(s.get(i), ty)).collect()
        }
        None => vec![T::default(); count],
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(ctx, buffers, &sparse, &at, elem, &mut out, |b| {
            decode(b, ty)
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

/// Component `i` of an element as a float: floats as stored, integers as
/// normalised values (the only integer kinds the read attributes allow).
fn component(b: &[u8], ty: DataType, i: usize) -> f32 {
    match ty {
        DataType::F32 => {
            let c = &b[4 * i..4 * i + 4];
            f32::from_le_bytes([c[0], c[1], c[2], c[3]])
        }
        DataType::U8 => b[i] as f32 / 255.0,
        DataType::U16 => u16::from_le_bytes([b[2 * i], b[2 * i + 1]]) as f32 / 65535.0,
        // Signed normalised: max(c / (2^(n-1) - 1), -1) per the glTF spec.
        DataType::I8 => (b[i] as i8 as f32 / 127.0).max(-1.0),
        DataType::I16 => (i16::from_le_bytes([b[2 * i], b[2 * i + 1]]) as f32 / 32767.0).max(-1.0),
        DataType::U32 => {
            u32::from_le_bytes([b[4 * i], b[4 * i + 1], b[4 * i + 2], b[4 * i + 3]]) as f32
        }
    }
}

/// A `VEC3` float attribute (POSITION, NORMAL).
pub(super) fn vec3(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec3>, LoadError> {
    read(
        ctx,
        buffers,
        acc,
        Dimensions::Vec3,
        &[DataType::F32],
        |b, ty| {
            glam::Vec3::new(
                component(b, ty, 0),
                component(b, ty, 1),
                component(b, ty, 2),
            )
        },
    )
}

/// A `VEC4` float attribute (TANGENT).
pub(super) fn vec4(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec4>, LoadError> {
    read(
        ctx,
        buffers,
        acc,
        Dimensions::Vec4,
        &[DataType::F32],
        |b, ty| glam::Vec4::from_array([0, 1, 2, 3].map(|k| component(b, ty, k))),
    )
}

/// A `VEC2` texture-coordinate attribute: float or normalised 8/16-bit.
pub(super) fn vec2(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec2>, LoadError> {
    let types = [DataType::F32, DataType::U8, DataType::U16];
    read(ctx, buffers, acc, Dimensions::Vec2, &types, |b, ty| {
        glam::Vec2::new(component(b, ty, 0), component(b, ty, 1))
    })
}

/// A `COLOR_n` attribute: `VEC3` or `VEC4` (alpha 1 when absent), float
/// or normalised unsigned 8/16-bit, as the spec allows.
pub(super) fn colors(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec4>, LoadError> {
    let types = [DataType::F32, DataType::U8, DataType::U16];
    let dims = match acc.dimensions() {
        Dimensions::Vec3 => Dimensions::Vec3,
        _ => Dimensions::Vec4,
    };
    let n = dims.multiplicity();
    read(ctx, buffers, acc, dims, &types, |b, ty| {
        glam::Vec4::from_array([0, 1, 2, 3].map(|k| if k < n { component(b, ty, k) } else { 1.0 }))
    })
}

/// A `SCALAR` unsigned index accessor.
pub(super) fn indices(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<u32>, LoadError> {
    let types = [DataType::U8, DataType::U16, DataType::U32];
    read(ctx, buffers, acc, Dimensions::Scalar, &types, |b, _| {
        uint(b)
    })
}
