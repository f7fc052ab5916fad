//! Shading data of the scene's triangles and spheres, kept apart from the
//! acceleration structure: the closest hit is found on compact data, and only
//! then is the full surface description computed for that one hit.

use crate::accel::Hit;
use crate::geometry::Ray;
use crate::shape;
use candela_scene::SceneDesc;
use glam::{Vec2, Vec3};

/// All triangles of the scene, flattened into global arrays (primitive id =
/// index into `triangles`).
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
    /// Texture coordinates.
    pub uvs: Vec<Vec2>,
    /// UV indices per triangle; `u32::MAX` in the first slot means none.
    pub uv_indices: Vec<[u32; 3]>,
    /// Material index per triangle.
    pub material: Vec<u32>,
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
}

const NONE: u32 = u32::MAX;

impl TriangleData {
    /// Flattens the meshes of `desc`.
    pub fn from_desc(desc: &SceneDesc) -> Self {
        let mut data = TriangleData::default();
        for mesh in &desc.meshes {
            let base_p = data.positions.len() as u32;
            let base_n = data.normals.len() as u32;
            let base_uv = data.uvs.len() as u32;
            data.positions.extend_from_slice(&mesh.positions);
            data.normals.extend_from_slice(&mesh.normals);
            data.uvs.extend_from_slice(&mesh.uvs);
            let offset = |t: [u32; 3], base: u32| t.map(|i| i + base);
            for (i, &tri) in mesh.triangles.iter().enumerate() {
                data.triangles.push(offset(tri, base_p));
                data.normal_indices.push(match mesh.normal_indices.get(i) {
                    Some(&n) => offset(n, base_n),
                    None => [NONE; 3],
                });
                data.uv_indices.push(match mesh.uv_indices.get(i) {
                    Some(&t) => offset(t, base_uv),
                    None => [NONE; 3],
                });
                data.material.push(mesh.material as u32);
            }
        }
        data
    }

    /// The three corners of triangle `i`.
    pub fn corners(&self, i: usize) -> [Vec3; 3] {
        self.triangles[i].map(|v| self.positions[v as usize])
    }
}

/// Everything the integrators need to know about a hit point.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// World position.
    pub p: Vec3,
    /// Bound on the absolute error of `p` per axis.
    pub p_error: Vec3,
    /// Unit geometric normal, flipped to the side the ray came from.
    pub ng: Vec3,
    /// Unit shading normal as the surface defines it (not flipped toward
    /// the ray): BSDF frames are built on it, so dielectrics can tell
    /// entering from leaving.
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Material index.
    pub material: u32,
    /// Primitive id (triangles first, then spheres).
    pub prim: u32,
    /// Unit direction back toward the ray origin.
    pub wo: Vec3,
    /// Whether the ray arrived on the side the surface's own normal points
    /// to (the side an emitter emits on).
    pub front_face: bool,
    /// Ray parameter of the hit.
    pub t: f32,
}

impl SurfaceHit {
    /// The shading normal flipped to the side the ray came from.
    pub fn ns_facing(&self) -> Vec3 {
        if self.front_face {
            self.ns
        } else {
            -self.ns
        }
    }

    /// Origin for a ray leaving this point in direction `w`, offset past the
    /// error bound so that it cannot re-hit this surface.
    pub fn spawn_origin(&self, w: Vec3) -> Vec3 {
        shape::offset_ray_origin(self.p, self.p_error, self.ng, w)
    }
}

/// Computes the surface description for `hit` of `ray`.
pub fn surface_hit(
    tris: &TriangleData,
    spheres: &[SphereData],
    ray: &Ray,
    hit: &Hit,
) -> SurfaceHit {
    let wo = -ray.dir.normalize();
    let n_tri = tris.triangles.len() as u32;
    let (p, p_error, ng_raw, ns_raw, uv, material) = if hit.prim < n_tri {
        let i = hit.prim as usize;
        let [v0, v1, v2] = tris.corners(i);
        let b = [1.0 - hit.b1 - hit.b2, hit.b1, hit.b2];
        let sp = shape::triangle_surface_point(&[v0, v1, v2], hit.b1, hit.b2);
        let (p, p_error, ng) = (sp.p, sp.p_error, sp.n);
        let ni = tris.normal_indices[i];
        let ns = if ni[0] == NONE {
            ng
        } else {
            let n = ni.map(|k| tris.normals[k as usize]);
            (b[0] * n[0] + b[1] * n[1] + b[2] * n[2]).normalize_or(ng)
        };
        let ti = tris.uv_indices[i];
        let uv = if ti[0] == NONE {
            Vec2::new(hit.b1, hit.b2)
        } else {
            let t = ti.map(|k| tris.uvs[k as usize]);
            b[0] * t[0] + b[1] * t[1] + b[2] * t[2]
        };
        (p, p_error, ng, ns, uv, tris.material[i])
    } else {
        let s = &spheres[(hit.prim - n_tri) as usize];
        let sp = shape::sphere_surface_point(s.center, s.radius, ray, hit.t);
        let uv = Vec2::new(hit.b1, hit.b2);
        (sp.p, sp.p_error, sp.n, sp.n, uv, s.material)
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
        material,
        prim: hit.prim,
        wo,
        front_face,
        t: hit.t,
    }
}
