//! From `tobj`'s models to [`MeshDesc`]s: `tobj` reads the plain text the
//! checking pass wrote (so its input is known good) and groups faces into
//! one model per object, group and `usemtl` run, fan-triangulating n-gons
//! and keeping separate position, normal and UV indices.

use crate::desc::MeshDesc;
use crate::error::{ErrorKind, LoadError};
use glam::{Vec2, Vec3};
use std::path::Path;

/// A mesh and the index of its material among the file's, if it named one.
pub(crate) struct Model {
    pub mesh: MeshDesc,
    pub material: Option<usize>,
}

/// Assembles the checked OBJ text `clean`; `library` gives the material
/// names an `mtllib` argument defines, in order.
pub(crate) fn assemble(
    clean: &str,
    file: &Path,
    library: impl Fn(&str) -> Vec<String>,
) -> Result<Vec<Model>, LoadError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut clean.as_bytes(), &options, |p| {
        let names = library(&p.to_string_lossy());
        let map = names.iter().enumerate().map(|(i, n)| (n.clone(), i));
        let materials = names
            .iter()
            .map(|n| tobj::Material {
                name: n.clone(),
                ..tobj::Material::default()
            })
            .collect();
        Ok((materials, map.collect()))
    })
    .map_err(|e| {
        // The checking pass rejects everything tobj does; should the two
        // ever disagree, the file is still refused with a message.
        LoadError::whole_file(
            file.to_path_buf(),
            ErrorKind::BadValue,
            format!("OBJ geometry could not be assembled: {e}"),
        )
    })?;
    Ok(models
        .into_iter()
        .filter(|m| !m.mesh.indices.is_empty())
        .map(|m| Model {
            material: m.mesh.material_id,
            mesh: to_mesh(m.name, m.mesh),
        })
        .collect())
}

fn to_mesh(name: String, m: tobj::Mesh) -> MeshDesc {
    let triangles = triples(&m.indices);
    let corners = m.indices.len();
    let (normals, normal_indices) = if m.normal_indices.len() == corners && !m.normals.is_empty() {
        let n = m
            .normals
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]).normalize_or(Vec3::Y))
            .collect();
        (n, triples(&m.normal_indices))
    } else {
        (Vec::new(), Vec::new())
    };
    let (uvs, uv_indices) = if m.texcoord_indices.len() == corners && !m.texcoords.is_empty() {
        let t = m
            .texcoords
            .chunks_exact(2)
            .map(|c| Vec2::new(c[0], c[1]))
            .collect();
        (t, triples(&m.texcoord_indices))
    } else {
        (Vec::new(), Vec::new())
    };
    // tobj copies a vertex's colour beside its position, one per position.
    let colors = if m.vertex_color.len() == m.positions.len() {
        m.vertex_color
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect()
    } else {
        Vec::new()
    };
    MeshDesc {
        name,
        positions: m
            .positions
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect(),
        colors,
        triangles,
        normals,
        normal_indices,
        uvs,
        uv_indices,
        ..MeshDesc::default()
    }
}

fn triples(indices: &[u32]) -> Vec<[u32; 3]> {
    indices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

/// Appends `more` to `mesh`, offsetting its indices. Normals, UVs and
/// colours are kept only if both meshes have them (or `mesh` is still
/// empty).
pub(crate) fn append(mesh: &mut MeshDesc, more: MeshDesc) {
    let first = mesh.triangles.is_empty();
    let offset = |base: usize, t: &[[u32; 3]]| -> Vec<[u32; 3]> {
        let b = base as u32;
        t.iter().map(|c| c.map(|i| i + b)).collect()
    };
    let keep_normals = first || !mesh.normal_indices.is_empty();
    let keep_uvs = first || !mesh.uv_indices.is_empty();
    let keep_colors = first || !mesh.colors.is_empty();
    let tris = offset(mesh.positions.len(), &more.triangles);
    mesh.triangles.extend(tris);
    mesh.positions.extend(more.positions);
    if keep_colors && !more.colors.is_empty() {
        mesh.colors.extend(more.colors);
    } else {
        mesh.colors.clear();
    }
    if keep_normals && !more.normal_indices.is_empty() {
        let t = offset(mesh.normals.len(), &more.normal_indices);
        mesh.normal_indices.extend(t);
        mesh.normals.extend(more.normals);
    } else {
        mesh.normals.clear();
        mesh.normal_indices.clear();
    }
    if keep_uvs && !more.uv_indices.is_empty() {
        let t = offset(mesh.uvs.len(), &more.uv_indices);
        mesh.uv_indices.extend(t);
        mesh.uvs.extend(more.uvs);
    } else {
        mesh.uvs.clear();
        mesh.uv_indices.clear();
    }
}
