//! The scene's primitives, kept apart from the acceleration structure: the
//! closest hit is found on compact data, and only then is the full surface
//! description computed for that one hit.
//!
//! [`Geometry`] is the one place that maps a [`PrimRef`] to its data: its
//! material, its surface at a hit, its shape as an emitter. Mesh instances
//! are flattened here: every instance's triangles are transformed to world
//! space once, at build time (see `ARCHITECTURE-scene.md` for the figures
//! behind that choice over a two-level BVH).

use crate::accel::Hit;
use crate::geometry::Ray;
use crate::light::AreaShape;
use crate::shape::{self, PrimKind, PrimRef, SurfaceHit};
use crate::texture::TexturePoint;
use candela_scene::{InstanceDesc, MeshDesc, SceneDesc, Sides, SphereDesc, TangentFrame};
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

/// All triangles of the scene, every instance flattened into global arrays
/// in world space (triangle index = [`PrimRef::index`] of a triangle).
#[derive(Debug, Default)]
pub struct TriangleData {
    /// World-space positions.
    pub positions: Vec<Vec3>,
    /// Position indices per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Unit shading normals.
    pub normals: Vec<Vec3>,
    /// Normal indices per triangle; `u32::MAX` in the first slot means none.
    pub normal_indices: Vec<[u32; 3]>,
    /// Per-vertex tangents (xyz unit, w = ±1 handedness), indexed like
    /// `normals` by `normal_indices`. Shorter than `normals` (or zero at a
    /// vertex) where a mesh has none: the normal map then follows the
    /// triangle's own dp/du.
    pub tangents: Vec<Vec4>,
    /// Texture coordinates.
    pub uvs: Vec<Vec2>,
    /// UV indices per triangle; `u32::MAX` in the first slot means none.
    pub uv_indices: Vec<[u32; 3]>,
    /// Per-vertex colours (linear RGB), indexed like `positions` by
    /// `triangles`. Empty unless some mesh has colours, and shorter than
    /// `positions` past the last mesh that has them: a vertex without one
    /// reads white ([`TexturePoint::NO_VERTEX_COLOR`]), so scenes without
    /// vertex colours store nothing.
    pub colors: Vec<Vec3>,
    /// Material index per triangle.
    pub material: Vec<u32>,
    /// Unit geometric normal per triangle ([`shape::triangle_normal`] of its
    /// corners, the same bits): a closest hit reads it instead of computing
    /// a cross product and a square root (about 30 instructions per hit).
    pub geometric_normals: Vec<Vec3>,
}

/// An analytic sphere with its material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereData {
    /// World-space centre.
    pub center: Vec3,
    /// Radius.
    pub radius: f32,
    /// Material index.
    pub material: u32,
    /// Axes of its (u, v) parameterisation ([`candela_scene::SphereDesc::axes`]).
    pub axes: Mat3,
    /// Normals point inward ([`candela_scene::SphereDesc::inward`]).
    pub inward: bool,
}

/// Every primitive of the scene, by kind.
#[derive(Debug, Default)]
pub struct Geometry {
    /// Triangles (flattened instances).
    pub triangles: TriangleData,
    /// Spheres.
    pub spheres: Vec<SphereData>,
}

const NONE: u32 = u32::MAX;

/// Why the description's geometry cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum GeometryError {
    /// An instance names a mesh that does not exist.
    #[error("instance {instance} names mesh {mesh}, but there are {meshes} meshes")]
    NoSuchMesh {
        /// Offending instance.
        instance: usize,
        /// The mesh it names.
        mesh: usize,
        /// Number of meshes.
        meshes: usize,
    },
    /// An instance's transform is singular or not finite.
    #[error("instance {0} has a singular or non-finite transform")]
    BadTransform(usize),
    /// A mesh's vertex colours are not one per position.
    #[error("mesh {mesh} has {colors} vertex colours for {positions} positions")]
    ColorCount {
        /// The mesh.
        mesh: usize,
        /// How many colours it has.
        colors: usize,
        /// How many positions.
        positions: usize,
    },
    /// More primitives of one kind than a [`PrimRef`] can name.
    #[error("{count} {kind:?} primitives exceed the limit of {max}")]
    TooMany {
        /// The kind.
        kind: PrimKind,
        /// How many there are.
        count: usize,
        /// The limit.
        max: u32,
    },
}

impl Geometry {
    /// Flattens the instances and collects the spheres of `desc`.
    pub fn from_desc(desc: &SceneDesc) -> Result<Self, GeometryError> {
        let mut triangles = TriangleData::default();
        // Tangents generated from the UVs, once per mesh, for meshes drawn
        // with a normal map that came without any.
        let mut generated: Vec<Option<Vec<Vec4>>> = vec![None; desc.meshes.len()];
        for (i, mesh) in desc.meshes.iter().enumerate() {
            if !mesh.colors.is_empty() && mesh.colors.len() != mesh.positions.len() {
                return Err(GeometryError::ColorCount {
                    mesh: i,
                    colors: mesh.colors.len(),
                    positions: mesh.positions.len(),
                });
            }
        }
        for (i, inst) in desc.instances.iter().enumerate() {
            let mesh = desc
                .meshes
                .get(inst.mesh)
                .ok_or(GeometryError::NoSuchMesh {
                    instance: i,
                    mesh: inst.mesh,
                    meshes: desc.meshes.len(),
                })?;
            let material = inst.material.unwrap_or(mesh.material);
            let normal_mapped = desc.materials.get(material).is_some_and(|m| {
                let mapped = |m: &candela_scene::MaterialDesc| {
                    m.textures.normal.is_some()
                        && m.textures.perturbation.tangent_frame == TangentFrame::VertexTangents
                };
                mapped(m) || matches!(&m.sides, Sides::Back(b) if mapped(b))
            });
            let tangents: &[Vec4] = if mesh.tangents.is_empty() && normal_mapped {
                generated[inst.mesh]
                    .get_or_insert_with(|| mesh.generated_tangents().unwrap_or_default())
            } else {
                &mesh.tangents
            };
            triangles.add_instance(mesh, tangents, inst, i)?;
        }
        let spheres: Vec<SphereData> = desc
            .spheres
            .iter()
            .map(|s| SphereData {
                center: s.center,
                radius: s.radius,
                material: s.material as u32,
                axes: s.axes,
                inward: s.inward,
            })
            .collect();
        for (kind, count) in [
            (PrimKind::Triangle, triangles.triangles.len()),
            (PrimKind::Sphere, spheres.len()),
        ] {
            if count > PrimRef::MAX_INDEX as usize {
                return Err(GeometryError::TooMany {
                    kind,
                    count,
                    max: PrimRef::MAX_INDEX,
                });
            }
        }
        Ok(Self { triangles, spheres })
    }

    /// Number of primitives of every kind.
    pub fn len(&self) -> usize {
        self.triangles.triangles.len() + self.spheres.len()
    }

    /// Whether there are no primitives.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every primitive, kind by kind.
    pub fn prims(&self) -> impl Iterator<Item = PrimRef> {
        let n_tri = self.triangles.triangles.len() as u32;
        let n_sphere = self.spheres.len() as u32;
        (0..n_tri)
            .map(PrimRef::triangle)
            .chain((0..n_sphere).map(PrimRef::sphere))
    }

    /// The material index of `prim`.
    pub fn material(&self, prim: PrimRef) -> u32 {
        let i = prim.index() as usize;
        match prim.kind() {
            PrimKind::Triangle => self.triangles.material[i],
            PrimKind::Sphere => self.spheres[i].material,
        }
    }

    /// `prim` as an emitting surface; `None` for one that can neither be
    /// hit nor sampled (a zero-area triangle).
    pub fn emitter_shape(&self, prim: PrimRef) -> Option<AreaShape> {
        let i = prim.index() as usize;
        match prim.kind() {
            PrimKind::Triangle => {
                let v = self.triangles.corners(i);
                let normal = self.triangles.emitting_normal(i, v)?;
                Some(AreaShape::Triangle { v, normal })
            }
            PrimKind::Sphere => {
                let s = &self.spheres[i];
                Some(AreaShape::Sphere {
                    center: s.center,
                    radius: s.radius,
                    inward: s.inward,
                })
            }
        }
    }

    /// Computes the surface description for `hit` of `ray`.
    pub fn surface_hit(&self, ray: &Ray, hit: &Hit) -> SurfaceHit {
        surface_hit(self, ray, hit)
    }
}

impl TriangleData {
    /// Appends the triangles of `mesh` placed by `inst` (instance number
    /// `number`, for messages), with `tangents` for its normals (the mesh's
    /// own or generated; ignored unless one per normal). An identity
    /// placement copies the mesh's values bit for bit.
    fn add_instance(
        &mut self,
        mesh: &MeshDesc,
        tangents: &[Vec4],
        inst: &InstanceDesc,
        number: usize,
    ) -> Result<(), GeometryError> {
        let m = inst.world_from_object;
        let base_p = self.positions.len() as u32;
        let base_n = self.normals.len() as u32;
        let base_uv = self.uvs.len() as u32;
        let with_tangents = !tangents.is_empty() && tangents.len() == mesh.normals.len();
        if !mesh.colors.is_empty() {
            // Colours are a vertex's whatever the placement; the vertices
            // before them (meshes without colours) read white.
            self.colors
                .resize(base_p as usize, TexturePoint::NO_VERTEX_COLOR);
            self.colors.extend_from_slice(&mesh.colors);
        }
        if with_tangents {
            self.tangents.resize(base_n as usize, Vec4::ZERO);
        }
        if m == Mat4::IDENTITY {
            self.positions.extend_from_slice(&mesh.positions);
            self.normals.extend_from_slice(&mesh.normals);
            if with_tangents {
                self.tangents.extend_from_slice(tangents);
            }
        } else {
            let linear = Mat3::from_mat4(m);
            let det = linear.determinant();
            if !m.is_finite() || !det.is_finite() || det == 0.0 {
                return Err(GeometryError::BadTransform(number));
            }
            // Normals transform by the inverse transpose.
            let normal_m = linear.inverse().transpose();
            self.positions
                .extend(mesh.positions.iter().map(|&p| m.transform_point3(p)));
            self.normals
                .extend(mesh.normals.iter().map(|&n| (normal_m * n).normalize_or(n)));
            if with_tangents {
                // A tangent is a direction; a mirroring placement flips the
                // handedness so that w · (N × T) is still the placed
                // bitangent (N × T turns with det, the bitangent does not).
                let sign = det.signum();
                self.tangents.extend(tangents.iter().map(|&t| {
                    match (linear * t.truncate()).try_normalize() {
                        Some(xyz) if t != Vec4::ZERO => xyz.extend(t.w * sign),
                        _ => Vec4::ZERO,
                    }
                }));
            }
        }
        self.uvs.extend_from_slice(&mesh.uvs);
        let material = inst.material.unwrap_or(mesh.material) as u32;
        let offset = |t: [u32; 3], base: u32| t.map(|i| i.saturating_add(base));
        for (i, &tri) in mesh.triangles.iter().enumerate() {
            self.triangles.push(offset(tri, base_p));
            self.normal_indices.push(match mesh.normal_indices.get(i) {
                Some(&n) => offset(n, base_n),
                None => [NONE; 3],
            });
            self.uv_indices.push(match mesh.uv_indices.get(i) {
                Some(&t) => offset(t, base_uv),
                None => [NONE; 3],
            });
            self.material.push(material);
            self.geometric_normals
                .push(self.normal_of(offset(tri, base_p)));
        }
        Ok(())
    }

    /// The [`shape::triangle_normal`] of the triangle of position indices
    /// `tri`; zero if an index is out of range (the accel build reports it).
    fn normal_of(&self, tri: [u32; 3]) -> Vec3 {
        match tri.map(|v| self.positions.get(v as usize)) {
            [Some(&v0), Some(&v1), Some(&v2)] => shape::triangle_normal(&[v0, v1, v2]),
            _ => Vec3::ZERO,
        }
    }

    /// The three corners of triangle `i`.
    pub fn corners(&self, i: usize) -> [Vec3; 3] {
        self.triangles[i].map(|v| self.positions[v as usize])
    }

    /// The tangent interpolated at barycentrics `b` of a triangle of normal
    /// indices `ni`: xyz as interpolated (not normalised: the shading frame
    /// orthogonalises it), w the sign of the interpolated handedness; `None`
    /// when any corner has no tangent.
    fn tangent_at(&self, ni: [u32; 3], b: [f32; 3]) -> Option<Vec4> {
        if ni[0] == NONE || self.tangents.is_empty() {
            return None;
        }
        let mut sum = Vec4::ZERO;
        for (k, w) in ni.into_iter().zip(b) {
            let t = *self.tangents.get(k as usize)?;
            if t == Vec4::ZERO {
                return None;
            }
            sum += t * w;
        }
        let w = if sum.w < 0.0 { -1.0 } else { 1.0 };
        Some(sum.truncate().extend(w))
    }

    /// The vertex colour interpolated at barycentrics `b` of the triangle
    /// of position indices `tri`: Σ bₖ cₖ, white where its vertices have
    /// none.
    #[inline]
    pub fn color_at(&self, tri: [u32; 3], b: [f32; 3]) -> Vec3 {
        if self.colors.is_empty() {
            return TexturePoint::NO_VERTEX_COLOR;
        }
        self.corner_colors(tri)
            .into_iter()
            .zip(b)
            .map(|(c, w)| c * w)
            .sum()
    }

    /// The vertex colours at the corners of the triangle of position
    /// indices `tri` (white where there are none).
    pub fn corner_colors(&self, tri: [u32; 3]) -> [Vec3; 3] {
        tri.map(|k| {
            self.colors
                .get(k as usize)
                .copied()
                .unwrap_or(TexturePoint::NO_VERTEX_COLOR)
        })
    }

    /// The unit normal on the side triangle `i` emits toward: its authored
    /// normals' side when it has them (the files' winding does not always
    /// agree with them), else its winding's.
    fn emitting_normal(&self, i: usize, v: [Vec3; 3]) -> Option<Vec3> {
        let ng = (v[1] - v[0]).cross(v[2] - v[0]).try_normalize()?;
        let ni = self.normal_indices[i];
        if ni[0] == NONE {
            return Some(ng);
        }
        let authored: Vec3 = ni.iter().map(|&k| self.normals[k as usize]).sum();
        Some(if authored.dot(ng) < 0.0 { -ng } else { ng })
    }
}

/// Computes the surface description for `hit` of `ray`.
fn surface_hit(geometry: &Geometry, ray: &Ray, hit: &Hit) -> SurfaceHit {
    let wo = -ray.dir.normalize();
    let i = hit.prim.index() as usize;
    let (p, p_error, ng_raw, ns_raw, uv, tangent, vertex_color, material) = match hit.prim.kind() {
        PrimKind::Triangle => {
            let tris = &geometry.triangles;
            let [v0, v1, v2] = tris.corners(i);
            let b = [1.0 - hit.b1 - hit.b2, hit.b1, hit.b2];
            let sp = shape::triangle_surface_point_with_normal(
                &[v0, v1, v2],
                hit.b1,
                hit.b2,
                tris.geometric_normals[i],
            );
            let (p, p_error, ng) = (sp.p, sp.p_error, sp.n);
            let ni = tris.normal_indices[i];
            let ns = if ni[0] == NONE {
                ng
            } else {
                let n = ni.map(|k| tris.normals[k as usize]);
                (b[0] * n[0] + b[1] * n[1] + b[2] * n[2]).normalize_or(ng)
            };
            let tangent = tris.tangent_at(ni, b);
            let ti = tris.uv_indices[i];
            let uv = if ti[0] == NONE {
                Vec2::new(hit.b1, hit.b2)
            } else {
                let t = ti.map(|k| tris.uvs[k as usize]);
                b[0] * t[0] + b[1] * t[1] + b[2] * t[2]
            };
            let vertex_color = tris.color_at(tris.triangles[i], b);
            (
                p,
                p_error,
                ng,
                ns,
                uv,
                tangent,
                vertex_color,
                tris.material[i],
            )
        }
        PrimKind::Sphere => {
            let s = &geometry.spheres[i];
            let sp = shape::sphere_surface_point(s.center, s.radius, ray, hit.t);
            // The accelerator's (u, v) are in the default axes.
            let uv = if s.axes == SphereDesc::Y_POLE {
                Vec2::new(hit.b1, hit.b2)
            } else {
                Vec2::from(shape::sphere_uv_in(s.axes, s.center, sp.p))
            };
            // An inward sphere's front (shading and emitting side) is inside.
            let n = if s.inward { -sp.n } else { sp.n };
            let white = TexturePoint::NO_VERTEX_COLOR;
            (sp.p, sp.p_error, n, n, uv, None, white, s.material)
        }
    };
    // Emitters emit on the side their authored (shading) normals point to;
    // the files' winding does not always agree with those normals.
    let front_face = ns_raw.dot(wo) > 0.0;
    let ng = if ng_raw.dot(wo) < 0.0 {
        -ng_raw
    } else {
        ng_raw
    };
    SurfaceHit {
        p,
        p_error,
        ng,
        ns: ns_raw,
        uv,
        vertex_color,
        tangent,
        material,
        prim: hit.prim,
        wo,
        front_face,
        t: hit.t,
    }
}
