//! Primitives to meshes: each glTF primitive (its own material) becomes one
//! [`MeshDesc`] in the mesh's own space, read once however many nodes use
//! it. glTF vertices carry all their attributes, so the per-attribute index
//! arrays of [`MeshDesc`] are the triangle indices again. `COLOR_0`
//! becomes the mesh's vertex colours (a primitive that has them draws a
//! vertex-coloured copy of its material, `nodes.rs`).

use super::accessors::{self, Buffers};
use super::Ctx;
use crate::desc::MeshDesc;
use crate::error::{ErrorKind, LoadError};
use gltf::mesh::{Mode, Semantic};

/// Reads primitive `prim` of mesh `mesh`; `None` (after a warning) for a
/// primitive that draws no triangles. Its material is left for the caller
/// to set: which copy it gets depends on the vertex colours read here.
pub(super) fn read_primitive(
    ctx: &Ctx,
    buffers: &Buffers,
    mesh: &gltf::Mesh,
    prim: &gltf::Primitive,
) -> Result<Option<MeshDesc>, LoadError> {
    let at = format!("/meshes/{}/primitives/{}", mesh.index(), prim.index());
    if prim.mode() != Mode::Triangles {
        ctx.warn(
            &format!("primitive mode {:?}", prim.mode()),
            "only TRIANGLES primitives are drawn; ignored",
        )?;
        return Ok(None);
    }
    if prim.morph_targets().next().is_some() {
        ctx.warn("morph targets", "not supported; the base shape is drawn")?;
    }
    let Some(pos_acc) = prim.get(&Semantic::Positions) else {
        return Err(ctx.err(
            format!("{at}/attributes"),
            ErrorKind::MissingElement,
            "primitive has no POSITION attribute".into(),
        ));
    };
    let positions = accessors::vec3(ctx, buffers, &pos_acc, &accessors::POSITION)?;
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(ctx.err(
            format!("/accessors/{}", pos_acc.index()),
            ErrorKind::NonFinite,
            format!("position {i} is {}", positions[i]),
        ));
    }
    let n = positions.len();
    let triangles = match prim.indices() {
        Some(acc) => {
            let idx = accessors::indices(ctx, buffers, &acc)?;
            if let Some(&bad) = idx.iter().find(|&&i| i as usize >= n) {
                return Err(ctx.err(
                    format!("/accessors/{}", acc.index()),
                    ErrorKind::IndexOutOfRange,
                    format!("index {bad} is past the {n} vertices of POSITION"),
                ));
            }
            triangles_of(ctx, &at, &idx)?
        }
        None => {
            let all: Vec<u32> = (0..n as u32).collect();
            triangles_of(ctx, &at, &all)?
        }
    };
    let attribute = |sem: &Semantic| -> Result<Option<gltf::Accessor>, LoadError> {
        let Some(acc) = prim.get(sem) else {
            return Ok(None);
        };
        if acc.count() != n {
            return Err(ctx.err(
                format!("/accessors/{}/count", acc.index()),
                ErrorKind::CountMismatch,
                format!("{sem:?} has {} elements, POSITION has {n}", acc.count()),
            ));
        }
        Ok(Some(acc))
    };
    let mut desc = MeshDesc {
        name: mesh.name().unwrap_or("mesh").to_string(),
        ..MeshDesc::default()
    };
    if let Some(acc) = attribute(&Semantic::Normals)? {
        let normals = accessors::vec3(ctx, buffers, &acc, &accessors::NORMAL)?;
        // Unit length per the spec; exporters round, quantised normals
        // (`KHR_mesh_quantization`) must be renormalised, and a zero normal
        // falls back to the face's own.
        desc.normals = normals
            .into_iter()
            .map(|v| v.try_normalize().unwrap_or(glam::Vec3::ZERO))
            .collect();
        desc.normal_indices = triangles.clone();
    }
    if let Some(acc) = attribute(&Semantic::TexCoords(0))? {
        // glTF's UV origin is the image's top-left corner (v runs down);
        // Candela's v runs bottom to top (OpenGL's, COLLADA's, OBJ's).
        desc.uvs = accessors::vec2(ctx, buffers, &acc, &accessors::TEXCOORD)?
            .into_iter()
            .map(|uv| glam::Vec2::new(uv.x, 1.0 - uv.y))
            .collect();
        desc.uv_indices = triangles.clone();
    }
    if let Some(acc) = attribute(&Semantic::Tangents)? {
        if desc.normals.is_empty() {
            ctx.warn(
                "TANGENT",
                "tangents without NORMAL are ignored (the spec requires both)",
            )?;
        } else {
            desc.tangents = tangents(ctx, buffers, &acc)?;
        }
    }
    if let Some(acc) = attribute(&Semantic::Colors(0))? {
        desc.colors = vertex_colors(ctx, buffers, &acc)?;
    }
    for (sem, _) in prim.attributes() {
        if matches!(sem, Semantic::Joints(_) | Semantic::Weights(_)) {
            ctx.warn(
                "skinning attributes",
                "skins are not supported; the bind pose is drawn",
            )?;
        } else if matches!(sem, Semantic::TexCoords(k) if k > 0) {
            ctx.warn("TEXCOORD_1+", "only TEXCOORD_0 is read")?;
        } else if matches!(sem, Semantic::Colors(k) if k > 0) {
            ctx.warn("COLOR_1+", "only COLOR_0 is read")?;
        }
    }
    desc.positions = positions;
    desc.triangles = triangles;
    Ok(Some(desc))
}

/// Groups an index list into triangles (a count not divisible by three is a
/// [`ErrorKind::CountMismatch`]).
fn triangles_of(ctx: &Ctx, at: &str, idx: &[u32]) -> Result<Vec<[u32; 3]>, LoadError> {
    if !idx.len().is_multiple_of(3) {
        return Err(ctx.err(
            at.to_string(),
            ErrorKind::CountMismatch,
            format!("{} indices do not make whole triangles", idx.len()),
        ));
    }
    Ok(idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
}

/// A `COLOR_0` accessor's linear RGB (glTF vertex colours are linear; the
/// material multiplies its base colour by them, `materials.rs`). Alpha is
/// not read: an alpha other than 1 is reported once.
fn vertex_colors(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec3>, LoadError> {
    let rgba = accessors::colors(ctx, buffers, acc)?;
    if let Some(i) = rgba.iter().position(|c| !c.is_finite()) {
        return Err(ctx.err(
            format!("/accessors/{}", acc.index()),
            ErrorKind::NonFinite,
            format!("colour {i} is {}", rgba[i]),
        ));
    }
    if rgba.iter().any(|c| c.w != 1.0) {
        ctx.warn(
            "COLOR_0 alpha",
            "vertex colour alpha is not read (opaque); the colour is",
        )?;
    }
    Ok(rgba.into_iter().map(glam::Vec4::truncate).collect())
}

/// A `TANGENT` accessor: xyz normalised (exporters round; quantised
/// tangents must be renormalised), w the
/// handedness sign. A zero or non-finite tangent becomes zero, which the
/// renderer reads as "no tangent here" (it falls back to the UVs' frame).
fn tangents(
    ctx: &Ctx,
    buffers: &Buffers,
    acc: &gltf::Accessor,
) -> Result<Vec<glam::Vec4>, LoadError> {
    Ok(accessors::vec4(ctx, buffers, acc, &accessors::TANGENT)?
        .into_iter()
        .map(|t| match t.truncate().try_normalize() {
            Some(xyz) if t.w.is_finite() => xyz.extend(if t.w < 0.0 { -1.0 } else { 1.0 }),
            _ => glam::Vec4::ZERO,
        })
        .collect())
}
