//! Gathers the scene's lights: the description's light sources plus every
//! emissive triangle and sphere.

use super::{Geometry, SceneNames};
use crate::light::TexturedEmission;
use crate::light::{
    AmbientLight, AreaLight, AreaShape, DirectionalLight, EnvironmentLight, EnvironmentMap, Light,
    LightSet, PointLight, SpotFade, SpotLight,
};
use crate::material::Material;
use crate::sampling::warp::Parallelogram;
use crate::shading::MaterialTextures;
use crate::shape::{PrimKind, PrimRef};
use crate::texture::TexturePoint;
use candela_scene::{LightKind, SceneDesc, SphereDesc, SpotEdge};
use glam::{Vec2, Vec3};
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
    // Each textured material's textures, shared by all its emitters.
    let shared: Vec<Option<Arc<MaterialTextures>>> = materials
        .iter()
        .map(|m| {
            let t = &m.textures;
            (m.emission.is_some() && (t.emission.is_some() || t.has_opacity()))
                .then(|| Arc::new(t.clone()))
        })
        .collect();
    for prim in geometry.prims() {
        let material = geometry.material(prim) as usize;
        let Some(radiance) = materials[material].emission else {
            continue;
        };
        let Some(shape) = geometry.emitter_shape(prim) else {
            continue; // zero area: it can neither be hit nor sampled
        };
        let textured = shared[material].as_ref().map(|textures| TexturedEmission {
            textures: textures.clone(),
            uvs: corner_uvs(geometry, prim),
            colors: match prim.kind() {
                PrimKind::Triangle => {
                    let tris = &geometry.triangles;
                    tris.corner_colors(tris.triangles[prim.index() as usize])
                }
                PrimKind::Sphere => [TexturePoint::NO_VERTEX_COLOR; 3],
            },
            sphere_axes: match prim.kind() {
                PrimKind::Sphere => geometry.spheres[prim.index() as usize].axes,
                PrimKind::Triangle => SphereDesc::Y_POLE,
            },
            radiance,
        });
        prim_light.push((prim, lights.len() as u32));
        lights.push(Light::Area(AreaLight {
            shape,
            radiance,
            textured,
        }));
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
                edge,
            } => {
                let cutoff = cone_angle_deg.to_radians() * 0.5;
                Light::Spot(SpotLight {
                    position,
                    direction: direction.normalize_or(-Vec3::Y),
                    intensity,
                    cos_cutoff: cutoff.cos(),
                    exponent: falloff_exponent,
                    edge: match edge {
                        SpotEdge::Hard => SpotFade::Hard,
                        SpotEdge::LinearInAngle { beam_angle_deg } => {
                            SpotFade::linear_in_angle(beam_angle_deg.to_radians() * 0.5, cutoff)
                        }
                        SpotEdge::SmoothInCosine { inner_angle_deg } => {
                            SpotFade::smooth_in_cosine(inner_angle_deg.to_radians() * 0.5, cutoff)
                        }
                    },
                })
            }
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
                textured: None,
            }),
        });
    }
    if let Some(map) = environment {
        lights.push(Light::Environment(EnvironmentLight { map: map.clone() }));
        names.lights.push("environment map".into());
    }
    LightSet::new(lights, &prim_light, scene_radius)
}

/// A triangle's UVs at its corners, as `surface_hit` interpolates them (the
/// barycentric parametrisation when it has none); unused for spheres.
fn corner_uvs(geometry: &Geometry, prim: PrimRef) -> [Vec2; 3] {
    let barycentric = [Vec2::ZERO, Vec2::X, Vec2::Y];
    if prim.kind() != PrimKind::Triangle {
        return barycentric;
    }
    let tris = &geometry.triangles;
    let ti = tris.uv_indices[prim.index() as usize];
    if ti[0] == u32::MAX {
        return barycentric;
    }
    ti.map(|k| tris.uvs[k as usize])
}
