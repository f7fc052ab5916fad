//! The render-ready scene: the only module that reads a `SceneDesc`.
//!
//! [`Scene::build`] turns the plain description into an immutable, `Sync`
//! structure: the geometry (instances flattened, every primitive named by a
//! [`crate::shape::PrimRef`]), the acceleration structure, materials,
//! lights and the camera. Integrators only see this.

mod geometry;
#[cfg(test)]
mod geometry_tests;
mod lights;
mod names;
mod visibility;

pub use geometry::{Geometry, GeometryError, SphereData, TriangleData};
pub use names::SceneNames;
pub use visibility::{continue_past, MAX_CUTOUTS};

use crate::accel::{Accel, AccelError, AccelInfo};
use crate::camera::framing::{frame_scene, CameraMode, FramingError};
use crate::camera::{Camera, CameraView, FilmFilter, PixelFilter};
use crate::geometry::Ray;
use crate::light::{EnvironmentMap, EnvironmentOptions, LightSet, SceneSphere};
use crate::material::Material;
use crate::medium::Media;
use crate::shape::SurfaceHit;
use crate::texture::TextureCache;
use candela_bvh::BuildStrategy;
use candela_bvh::TraversalStats;
use candela_image::RgbImage;
use candela_scene::{EnvironmentDesc, SceneDesc};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How to build a scene for rendering.
#[derive(Clone, Debug)]
pub struct SceneOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Camera placement.
    pub camera_mode: CameraMode,
    /// BVH construction strategy.
    pub bvh: BuildStrategy,
    /// Thin-lens aperture radius in world units (CS184 `-b`); 0 keeps the
    /// file camera's lens (a pinhole unless the file describes a thin
    /// lens). Applied after framing, so it works with either camera mode.
    pub lens_radius: f32,
    /// Distance from the eye to the plane in focus, along the view
    /// direction (CS184 `-d`); `None` keeps the framing's (the file's thin
    /// lens focus distance, else the distance to the camera's target).
    pub focal_distance: Option<f32>,
    /// An environment map lighting the scene from infinity, in addition to
    /// the file's own lights (CS184 `-e`).
    pub environment: Option<Arc<EnvironmentMap>>,
    /// An explicit placement replacing the framing's (`--eye`, `--look-at`,
    /// `--up`, `--fov`; the viewer's camera); the lens options still apply.
    pub view: Option<CameraView>,
    /// The pixel reconstruction filter the camera samples from.
    pub filter: PixelFilter,
}

impl Default for SceneOptions {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            camera_mode: CameraMode::Cs184,
            bvh: BuildStrategy::Sah,
            lens_radius: 0.0,
            focal_distance: None,
            environment: None,
            view: None,
            filter: PixelFilter::default(),
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
    /// An instance cannot be placed.
    #[error("instances: {0}")]
    Instances(#[from] GeometryError),
    /// A lens setting is negative or not finite.
    #[error("lens: {0}")]
    Lens(String),
    /// The description's environment map cannot be read.
    #[error("environment: {0}")]
    Environment(String),
}

/// An immutable scene, shared by all render threads.
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Every primitive's data, by kind.
    pub geometry: Geometry,
    /// Materials, indexed by the primitives' material ids.
    pub materials: Vec<Material>,
    /// Light sources, including emissive primitives.
    pub lights: LightSet,
    /// The description's names of materials, lights and shapes.
    pub names: SceneNames,
    /// Things the description asks for that this renderer does not do,
    /// each named once.
    pub unsupported: Vec<String>,
    /// Problems met while building (e.g. a texture file that cannot be
    /// read and was replaced by the flat colour), each named once.
    pub warnings: Vec<String>,
    /// Whether any material has an opacity texture (rays then continue
    /// through cut-outs: `visibility.rs`).
    pub has_cutouts: bool,
    /// Participating media, the surfaces that bound them and the camera's.
    pub media: Media,
    accel: Accel,
    /// The sphere around the description's bounding box.
    scene_sphere: SceneSphere,
    /// Time spent building the acceleration structure.
    pub build_time: Duration,
}

impl Scene {
    /// Builds the render-ready scene from a description.
    pub fn build(desc: &SceneDesc, opts: &SceneOptions) -> Result<Scene, SceneError> {
        let camera = Scene::camera_for(desc, opts)?;
        let geometry = Geometry::from_desc(desc)?;
        let mut names = SceneNames::from_desc(desc);
        let mut unsupported: Vec<String> = Vec::new();
        let mut textures = TextureCache::new();
        let mut materials: Vec<Material> = desc
            .materials
            .iter()
            .map(|m| {
                let (material, missing) = Material::from_desc(m, &mut textures);
                for u in missing {
                    if !unsupported.contains(&u.0) {
                        unsupported.push(u.0);
                    }
                }
                material
            })
            .collect();
        for (m, d) in materials.iter().zip(&desc.materials) {
            if m.invisible && m.emission.is_some() {
                unsupported.push(format!(
                    "material '{}': the emission of an invisible (null) surface is seen by the path tracer only (the bidirectional integrators pass it)",
                    d.name
                ));
            }
        }
        if materials.is_empty() {
            let grey = candela_scene::MaterialDesc::default_grey();
            materials.push(Material::from_desc(&grey, &mut textures).0);
            names.materials.push(grey.name);
        }
        let mut warnings = textures.into_problems();
        warnings.extend(unplaced_meshes(desc));
        let (lo, hi) = desc
            .bounds()
            .unwrap_or((glam::Vec3::ZERO, glam::Vec3::ZERO));
        let scene_radius = 0.5 * (hi - lo).length();
        let scene_sphere = SceneSphere {
            center: 0.5 * (lo + hi),
            radius: scene_radius,
        };
        // The caller's environment (the CLI's `-e`) replaces the file's.
        let environment = match &opts.environment {
            Some(map) => Some(map.clone()),
            None => desc_environment(desc)?,
        };
        let lights = lights::build_lights(
            desc,
            &geometry,
            &materials,
            environment.as_ref(),
            scene_radius,
            &mut names,
        );
        let start = Instant::now();
        let sphere_shapes: Vec<_> = geometry
            .spheres
            .iter()
            .map(|s| (s.center, s.radius))
            .collect();
        let accel = Accel::build_indexed(
            &geometry.triangles.positions,
            &geometry.triangles.triangles,
            &sphere_shapes,
            opts.bvh,
        )?;
        let build_time = start.elapsed();
        let media = Media::from_desc(desc, materials.len());
        let has_cutouts = materials
            .iter()
            .any(|m| m.textures.has_opacity() || m.invisible);
        Ok(Scene {
            camera,
            geometry,
            materials,
            lights,
            names,
            unsupported,
            warnings,
            has_cutouts,
            media,
            accel,
            scene_sphere,
            build_time,
        })
    }

    /// The camera of `opts` for `desc`: framed ([`frame_scene`]), moved to
    /// the explicit view if any ([`Camera::with_view`]), then the lens
    /// options. Cheap: a viewer calls it to move the camera of a built
    /// scene without rebuilding it.
    pub fn camera_for(desc: &SceneDesc, opts: &SceneOptions) -> Result<Camera, SceneError> {
        let mut camera = frame_scene(desc, opts.camera_mode, opts.width, opts.height)?;
        if let Some(view) = &opts.view {
            camera = camera.with_view(view)?;
        }
        apply_lens(&mut camera, opts)?;
        camera.filter = FilmFilter::new(opts.filter);
        Ok(camera)
    }

    /// The sphere around the scene's bounding box: where lights at infinity
    /// emit from ([`crate::light::Light::sample_le`]), and the radius their
    /// power is measured with.
    pub fn scene_sphere(&self) -> SceneSphere {
        self.scene_sphere
    }

    /// The material with index `i`.
    pub fn material(&self, i: u32) -> &Material {
        &self.materials[i as usize]
    }

    /// Number of primitives (of every kind).
    pub fn primitive_count(&self) -> usize {
        self.geometry.len()
    }

    /// Statistics of the acceleration structure.
    pub fn accel_info(&self) -> AccelInfo {
        self.accel.info()
    }

    /// The closest surface along `ray`, if any.
    pub fn intersect(&self, ray: &Ray, stats: &mut TraversalStats) -> Option<SurfaceHit> {
        let hit = self.accel.intersect_counted(ray, stats)?;
        Some(self.geometry.surface_hit(ray, &hit))
    }

    /// Whether anything blocks `ray` before its `t_max`.
    pub fn occluded(&self, ray: &Ray, stats: &mut TraversalStats) -> bool {
        self.accel.occluded_counted(ray, stats)
    }
}

/// The environment the description asks for: an image, or a constant
/// radiance (a one-pixel map, uniform over the sphere).
fn desc_environment(desc: &SceneDesc) -> Result<Option<Arc<EnvironmentMap>>, SceneError> {
    let bad = |e: &dyn std::fmt::Display| SceneError::Environment(e.to_string());
    let map = match &desc.environment {
        None => return Ok(None),
        Some(EnvironmentDesc::Map {
            path,
            scale,
            lookup,
            to_world,
        }) => {
            let options = EnvironmentOptions {
                scale: *scale,
                lookup: *lookup,
                to_world: *to_world,
                ..EnvironmentOptions::default()
            };
            EnvironmentMap::load(path, &options)
                .map_err(|e| bad(&format!("{}: {e}", path.display())))?
        }
        Some(EnvironmentDesc::Constant { radiance }) => {
            let image =
                RgbImage::from_pixels(1, 1, vec![radiance.to_array()]).map_err(|e| bad(&e))?;
            EnvironmentMap::from_image(&image, &EnvironmentOptions::default())
                .map_err(|e| bad(&e))?
        }
    };
    Ok(Some(Arc::new(map)))
}

/// One warning per mesh that no instance places (stored but not drawn).
fn unplaced_meshes(desc: &SceneDesc) -> Vec<String> {
    let mut placed = vec![false; desc.meshes.len()];
    for inst in &desc.instances {
        if let Some(p) = placed.get_mut(inst.mesh) {
            *p = true;
        }
    }
    desc.meshes
        .iter()
        .zip(placed)
        .filter(|(_, placed)| !placed)
        .map(|(m, _)| format!("mesh '{}' is placed by no instance: not drawn", m.name))
        .collect()
}

/// Sets the thin lens of `opts` on the framed camera.
fn apply_lens(camera: &mut Camera, opts: &SceneOptions) -> Result<(), SceneError> {
    if !(opts.lens_radius.is_finite() && opts.lens_radius >= 0.0) {
        return Err(SceneError::Lens(format!(
            "aperture radius {} must be finite and not negative",
            opts.lens_radius
        )));
    }
    if opts.lens_radius > 0.0 {
        if camera.is_orthographic() {
            return Err(SceneError::Lens(
                "an orthographic camera has no lens (aperture must be 0)".into(),
            ));
        }
        camera.lens_radius = opts.lens_radius;
    }
    if let Some(d) = opts.focal_distance {
        if !(d.is_finite() && d > 0.0) {
            return Err(SceneError::Lens(format!(
                "focal distance {d} must be finite and positive"
            )));
        }
        camera.focal_distance = d;
    }
    Ok(())
}
