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
//! - A mesh is stored once, in its own (object) space, and drawn by the
//!   [`InstanceDesc`]s that name it, each with a world-from-object transform.
//!   A mesh no instance names is not drawn. Loaders whose format has no
//!   sharing (COLLADA as read here bakes each `<instance_geometry>`) store
//!   world-space meshes with one identity instance each ([`SceneDesc::add_mesh`]).
//! - Materials carry a texture slot per parameter ([`material`]), each an
//!   image or a procedural texture read through its own uv transform
//!   ([`texture`]); cameras carry their own projection ([`camera`]).

mod camera;
mod extent;
mod material;
mod perturbation;
mod smooth_normals;
mod tangents;
mod texture;
mod winding;

pub use camera::{CameraDesc, ClipRange, Projection};
pub use extent::MAX_COORDINATE;
pub use material::{
    Alpha, BlendDesc, BsdfDesc, InternalReflectance, Masking, MaterialDesc, MicrofacetModel,
    PrincipledParameters, Sides, TextureSlot, TextureSlots,
};
pub use perturbation::{AwayFromViewer, PerturbationRules, TangentFrame};
pub use texture::{
    ColorSpace, TextureFilter, TextureRef, TextureSource, TextureWrap, UvTransform, WrapMode,
};

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
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
    /// Triangle meshes, each stored once in its own space.
    pub meshes: Vec<MeshDesc>,
    /// Placements of meshes in the world; a mesh is drawn once per instance.
    pub instances: Vec<InstanceDesc>,
    /// Analytic spheres, already in world space.
    pub spheres: Vec<SphereDesc>,
    /// Materials; meshes, instances and spheres refer to them by index.
    pub materials: Vec<MaterialDesc>,
    /// Light sources that are not emissive geometry.
    pub lights: Vec<LightDesc>,
    /// Light arriving from infinitely far away in every direction, if the
    /// file describes some (a renderer's own environment option replaces it).
    pub environment: Option<EnvironmentDesc>,
    /// Participating media, in file order; [`SceneDesc::medium_interfaces`]
    /// and [`SceneDesc::camera_medium`] refer to them by index.
    pub media: Vec<MediumDesc>,
    /// The media on either side of the surfaces of a material, by material
    /// index. A surface whose material has no entry is no boundary: a ray
    /// crossing it stays in its medium (pbrt-v4 and Mitsuba 3 alike). A
    /// loader whose format attaches media to shapes gives such a shape a
    /// material of its own.
    pub medium_interfaces: Vec<(usize, MediumInterface)>,
    /// The medium the camera sits in (`None`: vacuum).
    pub camera_medium: Option<usize>,
}

/// A homogeneous participating medium: it absorbs and scatters at rates that
/// are the same everywhere inside it.
#[derive(Clone, Debug, PartialEq)]
pub struct MediumDesc {
    /// Name (Mitsuba's `id`).
    pub name: String,
    /// Extinction coefficient per channel, per unit of world length
    /// (Mitsuba's `sigma_t` times its `scale`).
    pub sigma_t: Vec3,
    /// Single-scattering albedo per channel: the scattered fraction of what
    /// is extinguished (`sigma_s = albedo · sigma_t`), in [0, 1].
    pub albedo: Vec3,
    /// Henyey–Greenstein asymmetry of the phase function, in (-1, 1); 0 is
    /// isotropic, positive scatters forward.
    pub phase_g: f32,
    /// Where the medium was described.
    pub loc: SourceLoc,
}

/// The media on the two sides of a surface, by index into
/// [`SceneDesc::media`]; `None` is vacuum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MediumInterface {
    /// The medium on the side opposite the surface's geometric normal
    /// (inside a closed shape with outward normals).
    pub interior: Option<usize>,
    /// The medium on the side the geometric normal points to.
    pub exterior: Option<usize>,
}

/// An environment (light at infinity over the whole sphere of directions).
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentDesc {
    /// An equirectangular image (+Y up), its radiance times `scale`.
    Map {
        /// Path of the image, resolved relative to the scene file.
        path: PathBuf,
        /// Multiplies every pixel's radiance.
        scale: f32,
        /// How radiance between pixel centres is read.
        lookup: EnvironmentLookup,
        /// The map's orientation in the world: a rotation taking the map's
        /// own frame (+Y its zenith) to world directions (Mitsuba's
        /// `to_world`); the identity for formats that have none.
        to_world: Mat3,
    },
    /// The same radiance from every direction.
    Constant {
        /// Radiance per channel.
        radiance: Vec3,
    },
}

/// How an environment image is read between its pixel centres: each
/// format's own renderer decides, and a loader says which it follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvironmentLookup {
    /// Each pixel is constant over its patch of the sphere (pbrt-v4's
    /// image infinite light looks up the nearest texel; the renderer's own
    /// built-in default).
    #[default]
    Nearest,
    /// Bilinear between pixel centres `((i + ½)/W, (j + ½)/H)`, wrapping
    /// across the `u = 0` seam and clamped within half a row of the poles
    /// (CS184's `EnvironmentLight::bilerp`).
    Bilinear,
    /// Bilinear with columns at pixel centres (wrapping) but rows from pole
    /// to pole: row `j` at `θ = π j/(H − 1)`, the first on the zenith and
    /// the last on the nadir (Mitsuba 3's `envmap`).
    BilinearPoleRows,
}

/// A triangle mesh. Attributes have their own index arrays (as COLLADA does),
/// so per-corner normals and UV seams need no vertex duplication.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshDesc {
    /// Name of the geometry (or node) it came from.
    pub name: String,
    /// Vertex positions in the mesh's own space.
    pub positions: Vec<Vec3>,
    /// One entry per triangle: indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Shading normals (unit length) in the mesh's own space, if the file had any.
    pub normals: Vec<Vec3>,
    /// Per-triangle corner indices into `normals`; empty when there are none.
    pub normal_indices: Vec<[u32; 3]>,
    /// Per-vertex tangents for normal maps, as glTF's `TANGENT` defines
    /// them: xyz a unit tangent along +u in the mesh's own space, w = ±1
    /// the handedness (bitangent = w · cross(normal, tangent)). Empty when
    /// the file had none; else one per entry of `normals`, indexed by
    /// `normal_indices` (a tangent belongs to its vertex's normal).
    pub tangents: Vec<Vec4>,
    /// Texture coordinates, if the file had any.
    pub uvs: Vec<Vec2>,
    /// Per-triangle corner indices into `uvs`; empty when there are none.
    pub uv_indices: Vec<[u32; 3]>,
    /// Per-vertex colours (linear RGB), one per entry of `positions` and
    /// indexed by `triangles` (every format that carries them attaches
    /// them to the vertex), or empty when the file had none: a mesh
    /// without colours costs nothing. Read by the vertex-colour texture
    /// ([`TextureSource::VertexColor`]).
    pub colors: Vec<Vec3>,
    /// Index into [`SceneDesc::materials`] (an instance may override it).
    pub material: usize,
    /// Where the mesh was described.
    pub loc: SourceLoc,
}

/// One placement of a mesh: the mesh is stored once and drawn once per
/// instance that names it.
#[derive(Clone, Debug, PartialEq)]
pub struct InstanceDesc {
    /// Index into [`SceneDesc::meshes`].
    pub mesh: usize,
    /// World-from-object transform (must be invertible).
    pub world_from_object: Mat4,
    /// Index into [`SceneDesc::materials`] replacing the mesh's own, if any.
    pub material: Option<usize>,
    /// Where the instance was described.
    pub loc: SourceLoc,
}

impl InstanceDesc {
    /// The mesh `mesh` placed where it is stored (identity transform).
    pub fn identity(mesh: usize, loc: SourceLoc) -> Self {
        Self {
            mesh,
            world_from_object: Mat4::IDENTITY,
            material: None,
            loc,
        }
    }
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
    /// The axes of its (u, v) parameterisation in world space (orthonormal
    /// columns x, y, z): v = θ/π from the pole +z, u = φ/2π around it from
    /// +x toward +y. Texture lookups and the tangent of anisotropic BSDFs
    /// (dp/du) follow them. [`SphereDesc::Y_POLE`] unless the format says
    /// otherwise (Mitsuba: the shape's `to_world` rotation with z reversed,
    /// since its v runs the other way; a reflection is orthonormal too).
    pub axes: Mat3,
    /// Its normals point inward (Mitsuba's `flip_normals`): its front side,
    /// where a one-sided BSDF scatters and its material's emission leaves,
    /// is the inside, and a dielectric's inside is the outside.
    pub inward: bool,
    /// Where the sphere was instanced.
    pub loc: SourceLoc,
}

impl SphereDesc {
    /// Candela's own parameterisation (COLLADA, CS184): the pole along +Y,
    /// φ measured from +X toward +Z.
    pub const Y_POLE: Mat3 = Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::Y);
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

/// How a spot light's intensity fades toward the edge of its cone (the
/// half angle is half of `cone_angle_deg`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpotEdge {
    /// Full intensity up to the edge (COLLADA, Blender).
    Hard,
    /// Mitsuba 3's `spot`: full intensity inside `beam_angle_deg` (a full
    /// angle, like `cone_angle_deg`), then linear in the angle from the
    /// axis down to zero at the cone's edge.
    LinearInAngle {
        /// Full angle of the fully lit beam, in degrees.
        beam_angle_deg: f32,
    },
    /// glTF's `KHR_lights_punctual` spot: `t²` with `t` linear in `cos θ`,
    /// 0 at the outer cone (the edge) and 1 at the inner one.
    SmoothInCosine {
        /// Full angle of the inner cone, in degrees.
        inner_angle_deg: f32,
    },
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
        /// How the intensity fades toward the cone's edge.
        edge: SpotEdge,
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
    /// Adds a mesh stored in world space and one identity instance of it;
    /// returns the mesh's index.
    pub fn add_mesh(&mut self, mesh: MeshDesc) -> usize {
        let loc = mesh.loc;
        self.meshes.push(mesh);
        let i = self.meshes.len() - 1;
        self.instances.push(InstanceDesc::identity(i, loc));
        i
    }

    /// Axis-aligned world bounds of all drawn geometry (every instance's
    /// transformed vertices, and the spheres), or `None` for a scene without
    /// geometry. Instances naming no mesh are skipped.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            let Some(m) = self.meshes.get(inst.mesh) else {
                continue;
            };
            for &p in &m.positions {
                let p = inst.world_from_object.transform_point3(p);
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

    /// Total number of triangles stored over all meshes (each counted once,
    /// however many instances draw it).
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }

    /// Number of triangles drawn: each instance counts its mesh's triangles.
    pub fn instanced_triangle_count(&self) -> usize {
        self.instances
            .iter()
            .filter_map(|i| self.meshes.get(i.mesh))
            .map(|m| m.triangles.len())
            .sum()
    }
}
