//! Turning a checked primitive into a world-space [`MeshDesc`]: index range
//! checks, fan triangulation, compaction of the attributes it uses, and the
//! transform of positions (full matrix) and normals (inverse transpose).

use super::primitives::{fan, Primitive, Stream};
use super::sources::{Source, SourceCache};
use super::xml::Ctx;
use crate::desc::MeshDesc;
use crate::error::LoadError;
use glam::{Mat3, Mat4};

/// Maps a source's indices to a compact, first-use-ordered list.
struct Compactor {
    slot: Vec<u32>,
    used: Vec<u32>,
}

impl Compactor {
    fn new(n: usize) -> Self {
        Self {
            slot: vec![u32::MAX; n],
            used: Vec::new(),
        }
    }

    fn map(&mut self, i: u32) -> u32 {
        let s = &mut self.slot[i as usize];
        if *s == u32::MAX {
            *s = self.used.len() as u32;
            self.used.push(i);
        }
        *s
    }
}

/// Builds the triangles of one attribute stream, checking each index.
fn stream_triangles(
    ctx: &Ctx,
    prim: &Primitive,
    stream: Stream,
    source: &Source,
    what: &str,
) -> Result<(Vec<[u32; 3]>, Compactor), LoadError> {
    let mut tris = Vec::with_capacity(prim.p.len() / prim.stride.max(1));
    let mut compact = Compactor::new(source.count);
    let mut base = 0usize;
    for &n in &prim.vcounts {
        let n = n as usize;
        for corners in fan(n) {
            let mut tri = [0u32; 3];
            for (t, c) in tri.iter_mut().zip(corners) {
                let k = base + c * prim.stride + stream.offset;
                let i = prim.p[k];
                if i as usize >= source.count {
                    let msg = format!(
                        "{what} index {i} out of range (source has {} elements)",
                        source.count
                    );
                    return Err(prim.index_error(ctx, k, msg));
                }
                *t = compact.map(i);
            }
            tris.push(tri);
        }
        base += n * prim.stride;
    }
    Ok((tris, compact))
}

/// Builds the mesh of one primitive under the world-from-node transform `m`.
pub(crate) fn build(
    ctx: &Ctx,
    sources: &mut SourceCache,
    prim: &Primitive,
    m: Mat4,
    name: String,
    material: usize,
) -> Result<MeshDesc, LoadError> {
    let mut mesh = MeshDesc {
        name,
        material,
        loc: ctx.loc(prim.node),
        ..MeshDesc::default()
    };
    let src = sources.get(ctx, prim.pos.source, 3)?;
    let (tris, used) = stream_triangles(ctx, prim, prim.pos, src, "POSITION")?;
    mesh.triangles = tris;
    mesh.positions = used
        .used
        .iter()
        .map(|&i| m.transform_point3(src.vec3(i)))
        .collect();

    if let Some(stream) = prim.normal {
        let src = sources.get(ctx, stream.source, 3)?;
        let (tris, used) = stream_triangles(ctx, prim, stream, src, "NORMAL")?;
        let linear = Mat3::from_mat4(m);
        let normal_matrix = linear.inverse().transpose();
        let normals: Option<Vec<_>> =
            if linear.determinant().abs() > 1e-20 && normal_matrix.is_finite() {
                used.used
                    .iter()
                    .map(|&i| (normal_matrix * src.vec3(i)).try_normalize())
                    .collect()
            } else {
                None
            };
        match normals {
            Some(n) => {
                mesh.normals = n;
                mesh.normal_indices = tris;
            }
            None => ctx.warn(
                stream.source,
                "zero-length normal or singular transform; normals dropped",
            )?,
        }
    }
    if let Some(stream) = prim.uv {
        let src = sources.get(ctx, stream.source, 2)?;
        let (tris, used) = stream_triangles(ctx, prim, stream, src, "TEXCOORD")?;
        mesh.uvs = used.used.iter().map(|&i| src.vec2(i)).collect();
        mesh.uv_indices = tris;
    }
    Ok(mesh)
}
