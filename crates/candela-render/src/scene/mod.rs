//! The render-ready scene: the only module that reads a `SceneDesc`.
//!
//! [`Scene::build`] turns the plain description into an immutable, `Sync`
//! structure: flattened geometry, the acceleration structure, materials,
//! lights and the camera. Integrators only see this.

mod geometry;
mod lights;

pub use geometry::{SphereData, SurfaceHit, TriangleData};

use crate::accel::{Accel, AccelError, AccelInfo};
use crate::camera::framing::{frame_scene, CameraMode, FramingError};
use crate::camera::Camera;
use crate::geometry::Ray;
use crate::light::LightSet;
pub use crate::material::Material;
use candela_bvh::BuildStrategy;
use candela_bvh::TraversalStats;
use candela_scene::SceneDesc;
use std::time::{Duration, Instant};

/// How to build a scene for rendering.
#[derive(Clone, Copy, Debug)]
pub struct SceneOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Camera placement.
    pub camera_mode: CameraMode,
    /// BVH construction strategy.
    pub bvh: BuildStrategy,
}

impl Default for SceneOptions {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            camera_mode: CameraMode::Cs184,
            bvh: BuildStrategy::Sah,
        }
    }
}

/// Why a scene could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The camera could not be placed.
    #[error("camera: {0}")]
    Camera(#[from] FramingError),
    /// The geometry is inconsistent.
    #[error("geometry: {0}")]
    Geometry(#[from] AccelError),
}

/// An immutable scene, shared by all render threads.
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Triangle shading data.
    pub triangles: TriangleData,
    /// Spheres.
    pub spheres: Vec<SphereData>,
    /// Materials, indexed by the primitives' material ids.
    pub materials: Vec<Material>,
    /// Light sources, including emissive primitives.
    pub lights: LightSet,
    /// Things the description asks for that this renderer does not do,
    /// each named once.
    pub unsupported: Vec<String>,
    accel: Accel,
    /// Time spent building the acceleration structure.
    pub build_time: Duration,
}

impl Scene {
    /// Builds the render-ready scene from a description.
    pub fn build(desc: &SceneDesc, opts: &SceneOptions) -> Result<Scene, SceneError> {
        let camera = frame_scene(desc, opts.camera_mode, opts.width, opts.height)?;
        let triangles = TriangleData::from_desc(desc);
        let spheres: Vec<SphereData> = desc
            .spheres
            .iter()
            .map(|s| SphereData {
                center: s.center,
                radius: s.radius,
                material: s.material as u32,
            })
            .collect();
        let mut unsupported: Vec<String> = Vec::new();
        let mut materials: Vec<Material> = desc
            .materials
            .iter()
            .map(|m| {
                let (material, missing) = Material::from_desc(m);
                for u in missing {
                    if !unsupported.contains(&u.0) {
                        unsupported.push(u.0);
                    }
                }
                material
            })
            .collect();
        if materials.is_empty() {
            materials.push(Material::from_desc(&candela_scene::MaterialDesc::default_grey()).0);
        }
        let (lo, hi) = desc
            .bounds()
            .unwrap_or((glam::Vec3::ZERO, glam::Vec3::ZERO));
        let scene_radius = 0.5 * (hi - lo).length();
        let lights = lights::build_lights(desc, &triangles, &spheres, &materials, scene_radius);
        let start = Instant::now();
        let sphere_shapes: Vec<_> = spheres.iter().map(|s| (s.center, s.radius)).collect();
        let accel = Accel::build_indexed(
            &triangles.positions,
            &triangles.triangles,
            &sphere_shapes,
            opts.bvh,
        )?;
        let build_time = start.elapsed();
        Ok(Scene {
            camera,
            triangles,
            spheres,
            materials,
            lights,
            unsupported,
            accel,
            build_time,
        })
    }

    /// The material with index `i`.
    pub fn material(&self, i: u32) -> &Material {
        &self.materials[i as usize]
    }

    /// Number of primitives (triangles and spheres).
    pub fn primitive_count(&self) -> usize {
        self.triangles.triangles.len() + self.spheres.len()
    }

    /// Statistics of the acceleration structure.
    pub fn accel_info(&self) -> AccelInfo {
        self.accel.info()
    }

    /// The closest surface along `ray`, if any.
    pub fn intersect(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        let hit = self.accel.intersect_counted(ray, stats)?;
        Some(geometry::surface_hit(
            &self.triangles,
            &self.spheres,
            ray,
            &hit,
        ))
    }

    /// Whether anything blocks `ray` before its `t_max`.
    pub fn occluded(&self, ray: &Ray, stats: &mut TraversalStats) -> bool {
        self.accel.occluded_counted(ray, stats)
    }
}
