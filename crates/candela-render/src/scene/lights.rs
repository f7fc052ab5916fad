//! Gathers the scene's lights: the description's light sources plus every
//! emissive triangle and sphere.

use super::{Geometry, SceneNames};
use crate::light::{
    AmbientLight, AreaLight, AreaShape, DirectionalLight, EnvironmentLight, EnvironmentMap, Light,
    LightSet, PointLight, SpotLight,
};
use crate::material::Material;
use crate::sampling::warp::Parallelogram;
use candela_scene::{LightKind, SceneDesc};
use glam::Vec3;
use std::sync::Arc;

/// Builds the light set, with `environment` (if any) as one more light at
/// infinity. Emissive primitives come first, in [`Geometry::prims`] order.
/// Each light's name goes to `names.lights`, in light order.
pub fn build_lights(
    desc: &SceneDesc,
    geometry: &Geometry,
    materials: &[Material],
    environment: Option<&Arc<EnvironmentMap>>,
    scene_radius: f32,
    names: &mut SceneNames,
) -> LightSet {
    let mut lights = Vec::new();
    let mut prim_light = Vec::new();
    for prim in geometry.prims() {
        let Some(radiance) = materials[geometry.material(prim) as usize].emission else {
            continue;
        };
        let Some(shape) = geometry.emitter_shape(prim) else {
            continue; // zero area: it can neither be hit nor sampled
        };
        prim_light.push((prim, lights.len() as u32));
        lights.push(Light::Area(AreaLight { shape, radiance }));
        names.lights.push(format!("emitting {}", names.shape(prim)));
    }
    for light in &desc.lights {
        names.lights.push(light.name.clone());
        lights.push(match light.kind {
            LightKind::Point {
                position,
                intensity,
            } => Light::Point(PointLight {
                position,
                intensity,
            }),
            LightKind::Spot {
                position,
                direction,
                intensity,
                cone_angle_deg,
                falloff_exponent,
            } => Light::Spot(SpotLight {
                position,
                direction: direction.normalize_or(-Vec3::Y),
                intensity,
                cos_cutoff: (cone_angle_deg.to_radians() * 0.5).cos(),
                exponent: falloff_exponent,
            }),
            LightKind::Directional {
                direction,
                radiance,
            } => Light::Directional(DirectionalLight {
                direction: direction.normalize_or(-Vec3::Y),
                irradiance: radiance,
            }),
            LightKind::Ambient { radiance } => Light::Ambient(AmbientLight { radiance }),
            LightKind::Area {
                center,
                edge_x,
                edge_y,
                normal,
                radiance,
            } => Light::Area(AreaLight {
                shape: AreaShape::Rect {
                    shape: Parallelogram {
                        origin: center - 0.5 * (edge_x + edge_y),
                        edge0: edge_x,
                        edge1: edge_y,
                    },
                    normal: normal.normalize_or(-Vec3::Y),
                },
                radiance,
            }),
        });
    }
    if let Some(map) = environment {
        lights.push(Light::Environment(EnvironmentLight { map: map.clone() }));
        names.lights.push("environment map".into());
    }
    LightSet::new(lights, &prim_light, scene_radius)
}
