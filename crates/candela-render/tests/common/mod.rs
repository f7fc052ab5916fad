//! Scenes built in code for the estimator tests, and a helper that renders
//! them and returns the image mean with its standard error.
#![allow(dead_code)]

pub mod agreement;
pub mod agreement_scenes;

use candela_render::camera::framing::CameraMode;
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{
    BsdfDesc, CameraDesc, LightDesc, LightKind, MaterialDesc, MeshDesc, Projection, SceneDesc,
    SourceLoc, SphereDesc,
};
use glam::{Mat4, Vec3};

/// A unit icosphere subdivided `levels` times, its triangles wound so that
/// the geometric normals point **inward**: a closed room whose walls face
/// its centre.
pub fn inward_icosphere(levels: u32, radius: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (v, f) = candela_render::shape::icosphere(levels, Vec3::ZERO, radius);
    (v, f.into_iter().map(|[a, b, c]| [a, c, b]).collect())
}

/// A material description.
pub fn material(name: &str, bsdf: BsdfDesc, emission: Option<Vec3>) -> MaterialDesc {
    MaterialDesc {
        sides: candela_scene::Sides::Both,
        name: name.into(),
        bsdf,
        emission,
        textures: Default::default(),
        loc: SourceLoc::default(),
    }
}

/// A square of half-size `s` in the plane z = 0, facing +Z, of
/// `material` (drawn through an instance, as a loader would place it).
pub fn square_z0(name: &str, s: f32, material: usize) -> MeshDesc {
    MeshDesc {
        name: name.into(),
        positions: vec![
            Vec3::new(-s, -s, 0.0),
            Vec3::new(s, -s, 0.0),
            Vec3::new(s, s, 0.0),
            Vec3::new(-s, s, 0.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..Default::default()
    }
}

/// A camera at `eye` looking down -Z with a 60° field of view.
pub fn camera_at(eye: Vec3) -> CameraDesc {
    CameraDesc {
        name: "test".into(),
        world_from_camera: Mat4::from_translation(eye),
        projection: Projection::Perspective {
            xfov_deg: 60.0,
            yfov_deg: 60.0,
        },
        znear: None,
        zfar: None,
        clip: None,
        loc: SourceLoc::default(),
    }
}

/// The white furnace: a closed room of albedo `albedo` whose walls all emit
/// `le`, seen from its centre.
pub fn furnace(albedo: f32, le: f32) -> SceneDesc {
    // Flat facets, no shading normals: with bent normals a diffuse wall no
    // longer conserves energy exactly, and the closed-form answer is lost.
    let (positions, triangles) = inward_icosphere(2, 1.0);
    let mesh = MeshDesc {
        name: "room".into(),
        positions,
        triangles,
        material: 0,
        ..Default::default()
    };
    SceneDesc {
        source: "furnace".into(),
        cameras: vec![camera_at(Vec3::ZERO)],
        meshes: vec![mesh],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        materials: vec![material(
            "wall",
            BsdfDesc::Diffuse {
                albedo: Vec3::splat(albedo),
            },
            Some(Vec3::splat(le)),
        )],
        ..Default::default()
    }
}

/// The white furnace with a lossless glass ball (reflectance and
/// transmittance 1, IOR 1.5) filling the camera's view: a path through it
/// carries weight 1 (each `1/η²` on entering is undone on leaving), so the
/// radiance stays `le / (1 - albedo)`.
pub fn furnace_with_glass_ball(albedo: f32, le: f32) -> SceneDesc {
    let mut desc = furnace(albedo, le);
    desc.materials.push(material(
        "glass",
        BsdfDesc::Glass {
            reflectance: Vec3::ONE,
            transmittance: Vec3::ONE,
            roughness: 0.0,
            ior: 1.5,
        },
        None,
    ));
    desc.spheres.push(SphereDesc {
        axes: candela_scene::SphereDesc::Y_POLE,
        name: "ball".into(),
        center: Vec3::new(0.0, 0.0, -0.55),
        radius: 0.35,
        material: desc.materials.len() - 1,
        inward: false,
        loc: SourceLoc::default(),
    });
    desc
}

/// pbrt's analytic scene: inside a unit sphere of albedo 0.5 with a point
/// light of intensity π at its centre, the radiance is exactly 1 everywhere.
pub fn analytic_sphere() -> SceneDesc {
    SceneDesc {
        source: "analytic".into(),
        cameras: vec![camera_at(Vec3::new(0.0, 0.0, 0.3))],
        spheres: vec![SphereDesc {
            axes: candela_scene::SphereDesc::Y_POLE,
            name: "room".into(),
            center: Vec3::ZERO,
            radius: 1.0,
            material: 0,
            inward: false,
            loc: SourceLoc::default(),
        }],
        materials: vec![material(
            "wall",
            BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            None,
        )],
        lights: vec![LightDesc {
            name: "bulb".into(),
            kind: LightKind::Point {
                position: Vec3::ZERO,
                intensity: Vec3::splat(std::f32::consts::PI),
            },
            loc: SourceLoc::default(),
        }],
        ..Default::default()
    }
}

/// Mean luminance over all samples of a render, and its standard error
/// (from the film's sums of squares: every sample is an independent
/// estimate of the same constant when the scene is uniform).
pub struct Estimate {
    /// Sample mean.
    pub mean: f64,
    /// Standard error of the mean.
    pub std_error: f64,
    /// Samples that were NaN or infinite.
    pub invalid: u64,
}

/// Renders `desc` from its file camera and pools every sample.
pub fn estimate(
    desc: &SceneDesc,
    integrator: IntegratorSettings,
    size: u32,
    spp: u32,
    seed: u64,
) -> Estimate {
    let opts = SceneOptions {
        width: size,
        height: size,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(desc, &opts).expect("test scene builds");
    let settings = RenderSettings {
        spp,
        seed,
        integrator,
        threads: 2,
        ..Default::default()
    };
    let out = render(&scene, &settings, &|_| {}).expect("render runs");
    let (mut n, mut sum, mut sum_sq) = (0u64, 0.0f64, 0.0f64);
    for p in &out.film.pixels {
        n += p.count as u64;
        sum += p.lum;
        sum_sq += p.lum_sq;
    }
    let mean = sum / n as f64;
    let var = (sum_sq / n as f64 - mean * mean).max(0.0) * n as f64 / (n as f64 - 1.0);
    Estimate {
        mean,
        std_error: (var / n as f64).sqrt(),
        invalid: out.stats.invalid_samples,
    }
}

/// Asserts `e.mean` is within `z` standard errors of `expected`, plus the
/// f32 rounding of the sums (which matters only for zero-variance cases).
pub fn assert_converges(label: &str, e: &Estimate, expected: f64, z: f64) {
    eprintln!(
        "{label}: {:.5} ± {:.5} (expected {expected:.5})",
        e.mean, e.std_error
    );
    assert_eq!(e.invalid, 0, "{label}: NaN or infinite samples");
    let rounding = 1e-5 * expected.abs();
    let dev = ((e.mean - expected).abs() - rounding).max(0.0) / e.std_error.max(1e-12);
    assert!(
        dev <= z,
        "{label}: mean {:.5} ± {:.5} vs expected {expected:.5} ({dev:.2} standard errors)",
        e.mean,
        e.std_error
    );
}

/// A CS184 scene file from the shared corpus beside the repository, or
/// `None` (with a note) when the corpus is absent.
pub fn cs184(name: &str) -> std::path::PathBuf {
    candela_testkit::cs184_scene(name)
}

/// `batches` independent renders (seeds `seed + 1000 b`) of `desc` from its
/// own camera at `size`, path traced to `max_depth` with `spp` samples: the
/// input of a block z-test between two descriptions of one scene.
pub fn file_camera_batches(
    desc: &SceneDesc,
    size: (u32, u32),
    spp: u32,
    batches: u64,
    max_depth: u32,
    seed: u64,
) -> Vec<candela_image::RgbImage> {
    let opts = SceneOptions {
        width: size.0,
        height: size.1,
        camera_mode: CameraMode::File,
        ..SceneOptions::default()
    };
    let scene = Scene::build(desc, &opts).expect("scene builds");
    (0..batches)
        .map(|b| {
            let settings = RenderSettings {
                spp,
                seed: seed + 1000 * b,
                integrator: IntegratorSettings {
                    max_depth,
                    ..Default::default()
                },
                ..Default::default()
            };
            let out = render(&scene, &settings, &|_| {}).expect("render");
            assert_eq!(out.stats.invalid_samples, 0, "NaN or infinite samples");
            out.film.resolve()
        })
        .collect()
}

/// A small open room for the bounce-view and path-inspector tests, with
/// every kind of light path the integrator handles: a diffuse floor and back
/// wall, a glass ball (specular reflection and refraction), a diffuse ball,
/// an emitting quad overhead (area light found by both MIS strategies), a
/// point light (delta) and a dim sky (a light at infinity, seen by rays that
/// escape over the wall). The camera looks down -Z from the origin.
pub fn glass_room() -> SceneDesc {
    let mut desc = SceneDesc {
        source: "glass room".into(),
        cameras: vec![camera_at(Vec3::new(0.0, 0.0, 0.5))],
        materials: vec![
            material(
                "floor",
                BsdfDesc::Diffuse {
                    albedo: Vec3::new(0.7, 0.6, 0.5),
                },
                None,
            ),
            material(
                "glass",
                BsdfDesc::Glass {
                    reflectance: Vec3::ONE,
                    transmittance: Vec3::ONE,
                    roughness: 0.0,
                    ior: 1.5,
                },
                None,
            ),
            material(
                "lamp",
                BsdfDesc::Diffuse { albedo: Vec3::ZERO },
                Some(Vec3::splat(6.0)),
            ),
            material(
                "clay",
                BsdfDesc::Diffuse {
                    albedo: Vec3::new(0.3, 0.5, 0.8),
                },
                None,
            ),
        ],
        spheres: vec![
            SphereDesc {
                axes: candela_scene::SphereDesc::Y_POLE,
                name: "glass ball".into(),
                center: Vec3::new(0.45, -0.55, -2.3),
                radius: 0.45,
                material: 1,
                inward: false,
                loc: SourceLoc::default(),
            },
            SphereDesc {
                axes: candela_scene::SphereDesc::Y_POLE,
                name: "clay ball".into(),
                center: Vec3::new(-0.6, -0.65, -2.8),
                radius: 0.35,
                material: 3,
                inward: false,
                loc: SourceLoc::default(),
            },
        ],
        lights: vec![
            LightDesc {
                name: "bulb".into(),
                kind: LightKind::Point {
                    position: Vec3::new(-1.0, 0.8, -1.5),
                    intensity: Vec3::splat(1.5),
                },
                loc: SourceLoc::default(),
            },
            LightDesc {
                name: "sky".into(),
                kind: LightKind::Ambient {
                    radiance: Vec3::new(0.2, 0.25, 0.35),
                },
                loc: SourceLoc::default(),
            },
        ],
        ..Default::default()
    };
    // Floor (y = -1, facing up) and back wall (z = -4, facing +z, up to
    // y = 0.3 so that rays over it escape to the sky).
    let quad = |name: &str, corners: [Vec3; 4], material: usize| MeshDesc {
        name: name.into(),
        positions: corners.to_vec(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..Default::default()
    };
    let (x0, x1) = (-2.0, 2.0);
    desc.add_mesh(quad(
        "floor",
        [
            Vec3::new(x0, -1.0, 0.5),
            Vec3::new(x1, -1.0, 0.5),
            Vec3::new(x1, -1.0, -4.0),
            Vec3::new(x0, -1.0, -4.0),
        ],
        0,
    ));
    desc.add_mesh(quad(
        "wall",
        [
            Vec3::new(x0, -1.0, -4.0),
            Vec3::new(x1, -1.0, -4.0),
            Vec3::new(x1, 0.3, -4.0),
            Vec3::new(x0, 0.3, -4.0),
        ],
        0,
    ));
    // The lamp faces down (-y).
    desc.add_mesh(quad(
        "lamp",
        [
            Vec3::new(-0.4, 1.2, -2.8),
            Vec3::new(0.4, 1.2, -2.8),
            Vec3::new(0.4, 1.2, -2.0),
            Vec3::new(-0.4, 1.2, -2.0),
        ],
        2,
    ));
    desc
}

/// A quad `corner + s·u + t·v`, uv = (s, t), facing `u × v`: the textured
/// test scenes' one shape.
pub fn textured_quad(corner: Vec3, u: Vec3, v: Vec3, material: usize) -> MeshDesc {
    MeshDesc {
        name: format!("quad {material}"),
        positions: vec![corner, corner + u, corner + u + v, corner + v],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        normals: vec![u.cross(v).normalize()],
        normal_indices: vec![[0; 3]; 2],
        uvs: vec![
            glam::Vec2::ZERO,
            glam::Vec2::X,
            glam::Vec2::ONE,
            glam::Vec2::Y,
        ],
        uv_indices: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..Default::default()
    }
}

/// Writes a grey EXR texture of `w × h` values, row 0 at the top.
pub fn grey_exr(path: &std::path::Path, w: usize, h: usize, values: &[f32]) {
    let image =
        candela_image::RgbImage::from_pixels(w, h, values.iter().map(|&v| [v; 3]).collect())
            .expect("texture size");
    candela_image::write_exr(path, &candela_image::ExrLayers::beauty(image))
        .expect("write texture");
}
