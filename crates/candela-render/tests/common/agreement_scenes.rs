//! The scenes of the estimator-agreement suite, built at its resolution:
//! the CS184 Cornell boxes (from the shared corpus), the project's Mitsuba
//! boxes of rough and coated materials, a ball under an environment map,
//! a thin-lens view, the glass room of `common::glass_room`, and a lamp
//! with an emission texture seen through a stochastic cut-out screen, and
//! Mitsuba's `blendbsdf` (the conformance scene `bsdf-blend`).

use candela_render::camera::framing::CameraMode;
use candela_render::light::{EnvironmentMap, EnvironmentOptions, ProceduralSky};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{
    load, AwayFromViewer, BsdfDesc, ColorSpace, InstanceDesc, LoadOptions, MeshDesc, SceneDesc,
    SourceLoc, SphereDesc, TextureRef,
};
use glam::{Mat4, Vec3};
use std::path::PathBuf;
use std::sync::Arc;

/// The suite's image size: small, so that the whole table runs in CI, and
/// whole 8×8 blocks (a partial block would pool fewer samples, and its
/// mean would be further from normal).
pub const SIZE: (u32, u32) = (48, 40);

/// Options at the suite's size with this camera placement.
pub fn options(camera_mode: CameraMode) -> SceneOptions {
    SceneOptions {
        width: SIZE.0,
        height: SIZE.1,
        camera_mode,
        ..Default::default()
    }
}

fn build(desc: &SceneDesc, opts: &SceneOptions) -> Scene {
    Scene::build(desc, opts).expect("scene builds")
}

fn load_file(path: PathBuf) -> SceneDesc {
    load(&path, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .scene
}

/// A CS184 Cornell box from the shared corpus, framed as the course does.
pub fn cs184_box(file: &str) -> Scene {
    build(&load_file(super::cs184(file)), &options(CameraMode::Cs184))
}

/// A CS184 box seen through a thin lens (CS184 `-b`, `-d`): radius
/// `lens_radius`, focused `focal_distance` from the eye.
pub fn cs184_box_thin_lens(file: &str, lens_radius: f32, focal_distance: f32) -> Scene {
    let opts = SceneOptions {
        lens_radius,
        focal_distance: Some(focal_distance),
        ..options(CameraMode::Cs184)
    };
    let scene = build(&load_file(super::cs184(file)), &opts);
    assert_eq!(scene.camera.lens_radius, lens_radius, "a thin lens");
    scene
}

/// A CS184 box whose pixels are reconstructed with `filter` (camera
/// samples drawn from it, light paths splatted over its support).
pub fn cs184_box_filtered(file: &str, filter: &str) -> Scene {
    let opts = SceneOptions {
        filter: filter.parse().expect("a filter"),
        ..options(CameraMode::Cs184)
    };
    let scene = build(&load_file(super::cs184(file)), &opts);
    assert!(
        !scene.camera.filter.is_pixel_box(),
        "a filter wider than the pixel"
    );
    scene
}

/// A CS184 box with every diffuse material made a glTF one of the same
/// colour under a rough clear coat (`KHR_materials_clearcoat`): a rough
/// dielectric base, a coat of roughness 0.1. The coat dims the layers
/// beneath by its albedo at the view alone (not reciprocal), so light
/// subpaths must evaluate its adjoint (the directions swapped) to converge
/// to the camera paths' image. Rough lobes only: every estimator, the
/// light tracer too, reaches every surface.
pub fn cs184_box_coated(file: &str) -> Scene {
    let mut desc = load_file(super::cs184(file));
    let mut coated = 0;
    for m in &mut desc.materials {
        if let BsdfDesc::Diffuse { albedo } = m.bsdf {
            m.bsdf = BsdfDesc::MetallicRoughness {
                base_color: albedo,
                metallic: 0.0,
                roughness: 0.5,
                transmission: 0.0,
                ior: 1.5,
                specular: 1.0,
                specular_color: Vec3::ONE,
                clearcoat: 1.0,
                clearcoat_roughness: 0.1,
                sheen_color: Vec3::ZERO,
                sheen_roughness: 0.0,
            };
            coated += 1;
        }
    }
    assert!(coated >= 3, "only {coated} materials coated");
    build(&desc, &options(CameraMode::Cs184))
}

/// One of the project's Mitsuba scenes (`scenes/mitsuba/`) through its
/// own camera.
pub fn mitsuba_box(file: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/mitsuba")
        .join(file);
    build(&load_file(path), &options(CameraMode::File))
}

/// The Mitsuba conformance scene `benches/mitsuba_conformance/tex-maps.xml`
/// (Mitsuba normal and bump maps with their bump shadowing, masks of a
/// bitmap and of a constant opacity) through its own camera, with normals
/// that face away from the viewer bent toward it instead of mirrored.
/// Mitsuba's mirror is not reciprocal: a light subpath mirrors such a
/// normal toward the light, a camera path toward the camera, so the light
/// tracer converges to another image (measured: max block |z| 15, global
/// 17 at this budget). The bending (its grazing floor leaves such points
/// nearly black from either side) and the bump shadowing (every estimator
/// attenuates the light's side) pass.
pub fn tex_maps_bent() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../benches/mitsuba_conformance/tex-maps.xml");
    let mut desc = load_file(path);
    for m in &mut desc.materials {
        m.textures.perturbation.away_from_viewer = AwayFromViewer::BendTowardViewer;
    }
    build(&desc, &options(CameraMode::File))
}

/// The Mitsuba conformance scene `benches/mitsuba_conformance/bsdf-blend.xml`
/// through its own camera: `blendbsdf` with a constant weight over diffuse
/// and rough gold, a checkerboard weight over diffuse and rough plastic,
/// a smooth dielectric beside a diffuse part (a delta lobe and a smooth
/// one in one BSDF), and a blend nested in a blend around a smooth
/// conductor. Each estimator meets the blend its own way: light samples
/// see only its smooth parts, BSDF samples pick a part, BDPT's reverse
/// densities mix both.
pub fn bsdf_blend() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../benches/mitsuba_conformance/bsdf-blend.xml");
    build(&load_file(path), &options(CameraMode::File))
}

/// A unit ball (orange, diffuse) resting on a 20 × 20 grey plane, seen
/// from the front and a little above, lit only by a procedural sky whose
/// sun is wide enough (10°) for uniform hemisphere rays to find it often
/// enough for normal statistics at a few dozen samples per pixel.
pub fn ball_under_the_sky() -> Scene {
    let s = 10.0;
    let plane = MeshDesc {
        name: "ground".into(),
        positions: vec![
            Vec3::new(-s, 0.0, -s),
            Vec3::new(s, 0.0, -s),
            Vec3::new(s, 0.0, s),
            Vec3::new(-s, 0.0, s),
        ],
        triangles: vec![[0, 2, 1], [0, 3, 2]],
        material: 0,
        ..Default::default()
    };
    let mut camera = super::camera_at(Vec3::ZERO);
    // From (0, 2, 5), pitched down toward the ball's middle.
    let pitch = -(1.3f32 / 5.0).atan();
    camera.world_from_camera =
        Mat4::from_translation(Vec3::new(0.0, 2.0, 5.0)) * Mat4::from_rotation_x(pitch);
    let diffuse =
        |name: &str, albedo: Vec3| super::material(name, BsdfDesc::Diffuse { albedo }, None);
    let desc = SceneDesc {
        source: "ball under the sky".into(),
        cameras: vec![camera],
        meshes: vec![plane],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        spheres: vec![SphereDesc {
            axes: candela_scene::SphereDesc::Y_POLE,
            name: "ball".into(),
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 1.0,
            material: 1,
            inward: false,
            loc: SourceLoc::default(),
        }],
        materials: vec![
            diffuse("ground", Vec3::splat(0.5)),
            diffuse("ball", Vec3::new(0.8, 0.4, 0.2)),
        ],
        ..Default::default()
    };
    let sky = ProceduralSky {
        sun_radius_deg: 10.0,
        sun: Vec3::new(12.0, 11.0, 9.0),
        ..Default::default()
    };
    let image = sky.image(128, 64).expect("sky image");
    let map = EnvironmentMap::from_image(&image, &EnvironmentOptions::default()).expect("map");
    let opts = SceneOptions {
        environment: Some(Arc::new(map)),
        ..options(CameraMode::File)
    };
    let scene = build(&desc, &opts);
    assert_eq!(scene.lights.lights().len(), 1, "the sky is the only light");
    scene
}

/// `common::glass_room`: an area lamp, a point light, a dim sky, a glass
/// ball and a diffuse one in an open room.
pub fn glass_room() -> Scene {
    build(&super::glass_room(), &options(CameraMode::File))
}

/// A diffuse floor facing the camera, lit by a lamp above the view whose
/// emission is a 4 × 4 texture, through a diffuse screen with a 3 × 2
/// stochastic-opacity texture (partly in view): light sampling must
/// evaluate the texture at its sampled points, and shadow rays must pass
/// the cut-outs exactly as bounce rays do.
pub fn textured_lamp_through_a_cut_out_screen() -> Scene {
    let dir = candela_testkit::TempDir::new("agreement-textured-lamp");
    let glow = dir.join("glow.exr");
    let glow_values: Vec<f32> = (0..16)
        .map(|k| 0.2 + 3.0 * ((k * 5) % 16) as f32 / 15.0)
        .collect();
    super::grey_exr(&glow, 4, 4, &glow_values);
    let holes = dir.join("holes.exr");
    super::grey_exr(&holes, 3, 2, &[0.0, 1.0, 0.4, 0.8, 0.1, 1.0]);
    let diffuse = |name: &str, albedo: f32| {
        let albedo = Vec3::splat(albedo);
        super::material(name, BsdfDesc::Diffuse { albedo }, None)
    };
    let mut lamp = super::material("lamp", BsdfDesc::Black, Some(Vec3::ONE));
    lamp.textures.emission = Some(TextureRef::new(&glow, ColorSpace::Linear));
    let mut screen = diffuse("screen", 0.5);
    screen.textures.opacity = Some(TextureRef::new(&holes, ColorSpace::Linear));
    let meshes = vec![
        super::textured_quad(Vec3::new(-1.5, -1.5, -2.5), Vec3::X * 3.0, Vec3::Y * 3.0, 0),
        super::textured_quad(Vec3::new(-0.8, 1.6, -2.4), Vec3::X * 1.6, Vec3::Z * 1.4, 1),
        super::textured_quad(Vec3::new(-1.2, 0.9, -2.4), Vec3::X * 2.4, Vec3::Z * 1.8, 2),
    ];
    let desc = SceneDesc {
        source: "textured lamp".into(),
        cameras: vec![super::camera_at(Vec3::ZERO)],
        instances: (0..meshes.len())
            .map(|i| InstanceDesc::identity(i, Default::default()))
            .collect(),
        meshes,
        materials: vec![diffuse("floor", 0.8), lamp, screen],
        ..Default::default()
    };
    // The textures are read while the scene builds; the folder may go after.
    let scene = build(&desc, &options(CameraMode::File));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.lights.lights().len(), 2, "two emissive triangles");
    scene
}

/// The many-lights hall (`scenes/manylights/`, 10,240 emitting triangles)
/// through its own camera.
pub fn many_lights_hall() -> Scene {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/manylights/manylights.xml");
    build(&load_file(path), &options(CameraMode::File))
}
