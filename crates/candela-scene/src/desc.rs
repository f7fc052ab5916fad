//! The format-neutral scene description: plain data, produced by a loader,
//! consumed once by the renderer's scene builder.
//!
//! Conventions fixed here, for every loader:
//! - World space is right-handed and **Y-up**. Loaders convert their file's up
//!   axis (COLLADA `Z_UP`: x' = -x, y' = z, z' = y) before anything else, so all
//!   positions, directions and transforms below are already in world space.
//! - Colours are linear RGB triples (`Vec3`).
//! - Every item keeps the [`SourceLoc`] it came from, so later stages can report
//!   problems against the file.

use glam::{Mat4, Vec2, Vec3};
use std::path::PathBuf;

/// A position in a source file (1-based line and column).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SourceLoc {
    /// 1-based line number.
    pub line: u32,
    /// 1-based column number.
    pub col: u32,
}

impl std::fmt::Display for SourceLoc {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// A whole scene, ready to be handed to a renderer.
#[derive(Clone, Debug, Default)]
pub struct SceneDesc {
    /// File the scene was loaded from (or a label such as `<built-in demo>`).
    pub source: PathBuf,
    /// Cameras in document order. The first one is the scene's camera.
    pub cameras: Vec<CameraDesc>,
    /// Triangle meshes, already in world space.
    pub meshes: Vec<MeshDesc>,
    /// Analytic spheres, already in world space.
    pub spheres: Vec<SphereDesc>,
    /// Materials; meshes and spheres refer to them by index.
    pub materials: Vec<MaterialDesc>,
    /// Light sources that are not emissive geometry.
    pub lights: Vec<LightDesc>,
}

/// A perspective camera as the file describes it.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDesc {
    /// Name of the node or camera element.
    pub name: String,
    /// Full world-from-camera transform (including the up-axis change). The
    /// camera sits at the local origin, looks down local -Z, local +Y is up.
    pub world_from_camera: Mat4,
    /// Horizontal field of view in degrees.
    pub xfov_deg: f32,
    /// Vertical field of view in degrees.
    pub yfov_deg: f32,
    /// Near clip distance, if given.
    pub znear: Option<f32>,
    /// Far clip distance, if given.
    pub zfar: Option<f32>,
    /// Where the camera was described.
    pub loc: SourceLoc,
}

/// A triangle mesh. Attributes have their own index arrays (as COLLADA does),
/// so per-corner normals and UV seams need no vertex duplication.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshDesc {
    /// Name of the geometry (or node) it came from.
    pub name: String,
    /// World-space vertex positions.
    pub positions: Vec<Vec3>,
    /// One entry per triangle: indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// World-space shading normals (unit length), if the file had any.
    pub normals: Vec<Vec3>,
    /// Per-triangle corner indices into `normals`; empty when there are none.
    pub normal_indices: Vec<[u32; 3]>,
    /// Texture coordinates, if the file had any.
    pub uvs: Vec<Vec2>,
    /// Per-triangle corner indices into `uvs`; empty when there are none.
    pub uv_indices: Vec<[u32; 3]>,
    /// Index into [`SceneDesc::materials`].
    pub material: usize,
    /// Where the mesh was instanced.
    pub loc: SourceLoc,
}

/// An analytic sphere.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereDesc {
    /// Name of the geometry (or node) it came from.
    pub name: String,
    /// World-space centre.
    pub center: Vec3,
    /// World-space radius (> 0).
    pub radius: f32,
    /// Index into [`SceneDesc::materials`].
    pub material: usize,
    /// Where the sphere was instanced.
    pub loc: SourceLoc,
}

/// A material: one BSDF, optionally emissive, optionally textured.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialDesc {
    /// Material id/name from the file.
    pub name: String,
    /// The scattering model.
    pub bsdf: BsdfDesc,
    /// Emitted radiance (one-sided, on the side of the geometric normal), if any.
    pub emission: Option<Vec3>,
    /// Image texture for the diffuse colour, if any.
    pub diffuse_texture: Option<TextureDesc>,
    /// Where the material was described.
    pub loc: SourceLoc,
}

impl MaterialDesc {
    /// The loader's default when a file names no material: diffuse 0.5 grey.
    pub fn default_grey() -> Self {
        Self {
            name: "default".into(),
            bsdf: BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            emission: None,
            diffuse_texture: None,
            loc: SourceLoc::default(),
        }
    }
}

/// An image texture reference.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureDesc {
    /// Path of the image, resolved relative to the scene file.
    pub path: PathBuf,
}

/// Scattering models, as parameters. The renderer turns these into BSDFs.
#[derive(Clone, Debug, PartialEq)]
pub enum BsdfDesc {
    /// Lambertian reflection.
    Diffuse {
        /// Reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
    /// Perfect specular reflection.
    Mirror {
        /// Reflectance per channel.
        reflectance: Vec3,
    },
    /// Dielectric interface with reflection and refraction.
    Glass {
        /// Reflectance scale per channel.
        reflectance: Vec3,
        /// Transmittance scale per channel.
        transmittance: Vec3,
        /// Roughness (0 = smooth).
        roughness: f32,
        /// Index of refraction of the inside.
        ior: f32,
    },
    /// Dielectric interface that only refracts.
    Refraction {
        /// Transmittance scale per channel.
        transmittance: Vec3,
        /// Roughness (0 = smooth).
        roughness: f32,
        /// Index of refraction of the inside.
        ior: f32,
    },
    /// Rough conductor with a Beckmann microfacet distribution.
    Microfacet {
        /// Beckmann roughness alpha.
        alpha: f32,
        /// Real part of the complex index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
    },
    /// Black: absorbs everything (the BSDF of a pure emitter).
    Black,
}

/// A light source that is not emissive geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct LightDesc {
    /// Name of the light element.
    pub name: String,
    /// Which light and its parameters.
    pub kind: LightKind,
    /// Where the light was instanced.
    pub loc: SourceLoc,
}

/// Light types and their world-space parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// Isotropic point light: radiant intensity (W/sr per channel), 1/r² falloff.
    Point {
        /// World position.
        position: Vec3,
        /// Radiant intensity.
        intensity: Vec3,
    },
    /// Directional light: radiance arriving from one direction.
    Directional {
        /// Unit direction the light travels in (node's local -Z).
        direction: Vec3,
        /// Irradiance on a surface facing the light.
        radiance: Vec3,
    },
    /// Spot light: a point light restricted to a cone.
    Spot {
        /// World position.
        position: Vec3,
        /// Unit direction of the cone axis.
        direction: Vec3,
        /// Radiant intensity on the axis.
        intensity: Vec3,
        /// Full cone angle in degrees (COLLADA `falloff_angle`).
        cone_angle_deg: f32,
        /// COLLADA `falloff_exponent`.
        falloff_exponent: f32,
    },
    /// Uniform radiance from the upper hemisphere (an infinite light).
    Ambient {
        /// Radiance of the sky.
        radiance: Vec3,
    },
    /// One-sided emitting rectangle (CGL area light).
    Area {
        /// Centre of the rectangle.
        center: Vec3,
        /// Full edge vector along the node's local X (length = side).
        edge_x: Vec3,
        /// Full edge vector along the node's local Y (length = side).
        edge_y: Vec3,
        /// Unit normal of the emitting side (node's local -Z).
        normal: Vec3,
        /// Emitted radiance.
        radiance: Vec3,
    },
}

impl SceneDesc {
    /// Axis-aligned bounds of all geometry (mesh vertices and spheres), or
    /// `None` for a scene without geometry.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for m in &self.meshes {
            for &p in &m.positions {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        for s in &self.spheres {
            lo = lo.min(s.center - Vec3::splat(s.radius));
            hi = hi.max(s.center + Vec3::splat(s.radius));
        }
        (lo.x <= hi.x).then_some((lo, hi))
    }

    /// Total number of triangles over all meshes.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }
}
