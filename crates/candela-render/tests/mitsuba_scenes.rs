//! A Mitsuba file and the COLLADA file it was converted from describe the
//! same scene: `bench/mitsuba/CBspheres_lambertian.xml` is
//! `scenes/cs184/CBspheres_lambertian.dae` with the CS184 program's camera
//! for a 480x360 image written out as a Mitsuba sensor. The COLLADA file is
//! Z-up (Candela turns it Y-up on loading) and the Mitsuba file keeps the
//! Z-up coordinates, so the worlds differ by that turn; seen from their
//! cameras the two must give the same image. Checked twice: the cameras
//! agree exactly (after the turn), and renders of both (the COLLADA one
//! from the CS184 camera for 480x360, at a smaller size with the same
//! fields of view) agree by a per-block z-test over independent batches.

mod common;

use candela_image::metrics::ztest::{z_test, BlockStats};
use candela_image::RgbImage;
use candela_render::camera::framing::{frame_scene, CameraMode};
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, CameraDesc, LoadOptions, Projection, SceneDesc, SourceLoc};
use glam::{Mat4, Vec3};
use std::path::PathBuf;

fn mitsuba_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/bench/mitsuba/CBspheres_lambertian.xml")
}

/// Z-up to Y-up, as the COLLADA loader turns `Z_UP` files.
fn z_up_to_y_up(p: Vec3) -> Vec3 {
    Vec3::new(-p.x, p.z, p.y)
}

/// The COLLADA scene with the CS184 camera for 480x360 as its file camera.
fn collada_with_cs184_camera() -> SceneDesc {
    let mut desc = load(
        &common::cs184("CBspheres_lambertian.dae"),
        &LoadOptions::default(),
    )
    .unwrap()
    .scene;
    let cam = frame_scene(&desc, CameraMode::Cs184, 480, 360).unwrap();
    let right = cam.forward.cross(cam.up).normalize();
    let up = right.cross(cam.forward);
    desc.cameras = vec![CameraDesc {
        name: "cs184".into(),
        world_from_camera: Mat4::from_cols(
            right.extend(0.0),
            up.extend(0.0),
            (-cam.forward).extend(0.0),
            cam.eye.extend(1.0),
        ),
        projection: Projection::Perspective {
            xfov_deg: cam.hfov_deg(),
            yfov_deg: cam.vfov_deg(),
        },
        znear: None,
        zfar: None,
        clip: None,
        loc: SourceLoc::default(),
    }];
    desc
}

#[test]
fn the_mitsuba_camera_is_the_cs184_framing() {
    let xml = load(&mitsuba_file(), &LoadOptions::default())
        .unwrap()
        .scene;
    let dae = collada_with_cs184_camera();
    let (x, d) = (&xml.cameras[0], &dae.cameras[0]);
    let eye_x = z_up_to_y_up(x.world_from_camera.transform_point3(Vec3::ZERO));
    let eye_d = d.world_from_camera.transform_point3(Vec3::ZERO);
    assert!((eye_x - eye_d).length() < 1e-4, "{eye_x} vs {eye_d}");
    // Forward (-z) and right (+x) of both cameras, in the Y-up world; the
    // turn is a reflection (x' = -x swaps handedness), so vectors map
    // through it and the cross product does not.
    for v in [-Vec3::Z, Vec3::X, Vec3::Y] {
        let a = z_up_to_y_up(x.world_from_camera.transform_vector3(v));
        let b = d.world_from_camera.transform_vector3(v);
        assert!((a - b).length() < 1e-4, "{v}: {a} vs {b}");
    }
    let (fx, fd) = (x.fov_deg().unwrap(), d.fov_deg().unwrap());
    assert!(
        (fx.0 - fd.0).abs() < 1e-3 && (fx.1 - fd.1).abs() < 1e-3,
        "{fx:?} {fd:?}"
    );
    // Same light and materials.
    let lamps = |s: &SceneDesc| -> Vec3 { s.materials.iter().filter_map(|m| m.emission).sum() };
    assert!((lamps(&xml) - lamps(&dae)).length() < 1e-5);
}

/// Independent batches per scene, and samples per pixel in each.
const BATCHES: u64 = 8;
const SPP: u32 = 16;

fn batches(desc: &SceneDesc, seed: u64) -> Vec<RgbImage> {
    common::file_camera_batches(desc, (64, 48), SPP, BATCHES, 4, seed)
}

#[test]
fn the_mitsuba_and_collada_files_render_alike() {
    let xml = load(&mitsuba_file(), &LoadOptions::default())
        .unwrap()
        .scene;
    let dae = collada_with_cs184_camera();
    let a = BlockStats::from_batches(&batches(&xml, 1), 8).unwrap();
    let b = BlockStats::from_batches(&batches(&dae, 2), 8).unwrap();
    let summary = z_test(&a, &b, 1e-3).unwrap().summary();
    eprintln!("mitsuba vs collada: {summary:?}");
    assert!(summary.passed(), "{summary:?}");
    // The images are not black (a test of nothing otherwise), and not
    // mirrored: the red wall is on the left in both.
    let mean = |imgs: &[RgbImage], x0: usize, x1: usize| -> Vec3 {
        let mut s = Vec3::ZERO;
        for img in imgs {
            for y in 0..img.height() {
                for x in x0..x1 {
                    s += Vec3::from(img.get(x, y).unwrap());
                }
            }
        }
        s
    };
    let imgs = batches(&xml, 3);
    let (left, right) = (mean(&imgs, 0, 8), mean(&imgs, 56, 64));
    assert!(
        left.x > left.z && right.z > right.x,
        "left {left} right {right}"
    );
}

#[test]
fn a_constant_environment_is_seen_in_every_direction() {
    // Mitsuba's `constant` emitter: the same radiance from the whole sphere
    // (the CS184 ambient light covers only the upper hemisphere).
    let desc = SceneDesc {
        cameras: vec![common::camera_at(Vec3::ZERO)],
        // A speck far away, so that the scene is not empty.
        spheres: vec![candela_scene::SphereDesc {
            axes: candela_scene::SphereDesc::Y_POLE,
            name: "speck".into(),
            center: Vec3::splat(1000.0),
            radius: 1e-3,
            material: 0,
            inward: false,
            loc: SourceLoc::default(),
        }],
        materials: vec![common::material(
            "grey",
            candela_scene::BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            None,
        )],
        environment: Some(candela_scene::EnvironmentDesc::Constant {
            radiance: Vec3::new(0.25, 0.5, 1.0),
        }),
        ..SceneDesc::default()
    };
    for turn in [0.0f32, 90.0, 180.0] {
        let mut desc = desc.clone();
        desc.cameras[0].world_from_camera = Mat4::from_rotation_x(turn.to_radians());
        let opts = SceneOptions {
            width: 8,
            height: 8,
            camera_mode: CameraMode::File,
            ..SceneOptions::default()
        };
        let scene = Scene::build(&desc, &opts).unwrap();
        let settings = RenderSettings {
            spp: 2,
            integrator: IntegratorSettings::default(),
            ..Default::default()
        };
        let image = render(&scene, &settings, &|_| {}).unwrap().film.resolve();
        for p in image.pixels() {
            assert!(
                (Vec3::from(*p) - Vec3::new(0.25, 0.5, 1.0)).length() < 1e-4,
                "{p:?} at {turn}"
            );
        }
    }
}

#[test]
fn the_new_bsdf_descriptions_map_to_the_renderers_bsdfs() {
    use candela_render::bsdf::Bsdf;
    use candela_render::material::Material;
    use candela_render::texture::TextureCache;
    use candela_scene::{BsdfDesc, MicrofacetModel};
    let map = |bsdf: BsdfDesc| {
        let desc = common::material("m", bsdf, None);
        let (m, unsupported) = Material::from_desc(&desc, &mut TextureCache::new());
        (m.bsdf.unwrap(), unsupported.len())
    };
    let ggx = MicrofacetModel::Ggx;
    let one = Vec3::ONE;
    let separable = candela_scene::Masking::Separable;
    let (b, n) = map(BsdfDesc::RoughDielectric {
        distribution: ggx,
        masking: separable,
        alpha: candela_scene::Alpha::isotropic(0.3),
        ior: 1.5,
        reflectance: one,
        transmittance: one,
    });
    assert!(
        matches!(b, Bsdf::RoughGlass { distribution, masking, .. }
            if distribution.alphas() == (0.3, 0.3) && masking == separable)
            && n == 0
    );
    let (b, _) = map(BsdfDesc::ThinDielectric {
        ior: 1.5,
        reflectance: one,
        transmittance: one,
    });
    assert!(matches!(b, Bsdf::ThinGlass { .. }));
    let plastic = |alpha| BsdfDesc::Plastic {
        diffuse: Vec3::splat(0.5),
        specular: one,
        ior: 1.49,
        alpha,
        distribution: MicrofacetModel::Beckmann,
        masking: separable,
        internal_reflectance: candela_scene::InternalReflectance::EvenSampleMean,
        nonlinear: false,
    };
    assert!(matches!(map(plastic(0.0)), (Bsdf::Plastic(_), 0)));
    assert!(matches!(map(plastic(0.2)), (Bsdf::RoughPlastic(_), 0)));
    let conductor = |alpha: f32, eta: Vec3, k: Vec3| BsdfDesc::Conductor {
        distribution: ggx,
        masking: separable,
        alpha: candela_scene::Alpha::isotropic(alpha),
        eta,
        k,
    };
    assert!(matches!(
        map(conductor(0.2, one, one)).0,
        Bsdf::Microfacet { masking, .. } if masking == separable
    ));
    // Smooth: a delta conductor with the complex Fresnel term.
    assert_eq!(
        map(conductor(0.0, Vec3::splat(2.0), one)),
        (
            Bsdf::Conductor {
                eta: Vec3::splat(2.0),
                k: one
            },
            0
        )
    );
}
