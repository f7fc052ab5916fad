//! Gathers the scene's lights: the description's light sources plus every
//! emissive triangle and sphere.

use super::{Material, SphereData, TriangleData};
use crate::light::{
    AmbientLight, AreaLight, AreaShape, DirectionalLight, EnvironmentLight, EnvironmentMap, Light,
    LightSet, PointLight, SpotLight,
};
use crate::sampling::warp::Parallelogram;
use candela_scene::{LightKind, SceneDesc};
use glam::Vec3;
use std::sync::Arc;

/// Builds the light set, with `environment` (if any) as one more light at
/// infinity. Primitive ids are triangles first, then spheres.
pub fn build_lights(
    desc: &SceneDesc,
    tris: &TriangleData,
    spheres: &[SphereData],
    materials: &[Material],
    environment: Option<&Arc<EnvironmentMap>>,
    scene_radius: f32,
) -> LightSet {
    let mut lights = Vec::new();
    let n_prims = tris.triangles.len() + spheres.len();
    let mut prim_light = vec![None; n_prims];
    for (i, &m) in tris.material.iter().enumerate() {
        let Some(radiance) = materials[m as usize].emission else {
            continue;
        };
        let v = tris.corners(i);
        let Some(normal) = emitting_normal(tris, i, v) else {
            continue; // zero area: it can neither be hit nor sampled
        };
        prim_light[i] = Some(lights.len() as u32);
        lights.push(Light::Area(AreaLight {
            shape: AreaShape::Triangle { v, normal },
            radiance,
        }));
    }
    for (i, s) in spheres.iter().enumerate() {
        if let Some(radiance) = materials[s.material as usize].emission {
            prim_light[tris.triangles.len() + i] = Some(lights.len() as u32);
            lights.push(Light::Area(AreaLight {
                shape: AreaShape::Sphere {
                    center: s.center,
                    radius: s.radius,
                },
                radiance,
            }));
        }
    }
    for light in &desc.lights {
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
    }
    LightSet::new(lights, prim_light, scene_radius)
}

/// The unit normal on the side a triangle emits toward: its authored
/// normals' side when it has them (the files' winding does not always agree
/// with them), else its winding's.
fn emitting_normal(tris: &TriangleData, i: usize, v: [Vec3; 3]) -> Option<Vec3> {
    let ng = (v[1] - v[0]).cross(v[2] - v[0]).try_normalize()?;
    let ni = tris.normal_indices[i];
    if ni[0] == u32::MAX {
        return Some(ng);
    }
    let authored: Vec3 = ni.iter().map(|&k| tris.normals[k as usize]).sum();
    Some(if authored.dot(ng) < 0.0 { -ng } else { ng })
}
