//! Per-vertex tangents (glTF `TANGENT`) in the renderer:
//!
//! - flattening places them like directions: an identity placement copies
//!   them bit for bit, a rotation turns xyz, a mirror flips the handedness w
//!   (so that w · N × T is still the placed bitangent);
//! - a tangent-space normal map on a smooth tessellated sphere whose
//!   supplied tangents run along the meridians (not along dp/du, so the
//!   triangles' own frames would give another normal) and are left-handed
//!   gives, at random hits, the mapped normal computed analytically from
//!   the sphere's own frame at the hit, for a plain and a mirrored placement;
//! - without supplied tangents, the generated ones give the analytic
//!   normal of the UVs' own frame (east, north) as smoothly.

mod common;

use candela_bvh::TraversalStats;
use candela_image::{write_exr, ExrLayers, RgbImage};
use candela_render::camera::framing::CameraMode;
use candela_render::geometry::Ray;
use candela_render::sampling::warp::square_to_uniform_sphere;
use candela_render::sampling::{Sampler, SamplerKind};
use candela_render::scene::Geometry;
use candela_render::scene::{Scene, SceneOptions};
use candela_render::shading::shading_frame;
use candela_scene::{
    BsdfDesc, ColorSpace, InstanceDesc, MaterialDesc, MeshDesc, SceneDesc, TextureRef,
};
use glam::{Mat3, Mat4, Vec2, Vec3};

const ROWS: u32 = 32;
const COLUMNS: u32 = 64;
/// The supplied tangents' handedness.
const W: f32 = -1.0;

/// The unit sphere's point, normal and meridian tangent ∂p/∂θ at (θ, φ).
fn sphere_frame(theta: f32, phi: f32) -> (Vec3, Vec3) {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    (
        Vec3::new(st * cp, ct, st * sp),
        Vec3::new(ct * cp, -st, ct * sp),
    )
}

/// A UV sphere of unit radius, normals = positions, tangents along the
/// meridians with handedness [`W`]; every attribute indexed by the
/// triangles, as glTF stores them.
fn smooth_sphere() -> MeshDesc {
    let mut mesh = MeshDesc {
        name: "sphere".into(),
        ..Default::default()
    };
    for i in 0..=ROWS {
        for j in 0..=COLUMNS {
            let theta = std::f32::consts::PI * i as f32 / ROWS as f32;
            let phi = std::f32::consts::TAU * j as f32 / COLUMNS as f32;
            let (p, t) = sphere_frame(theta, phi);
            mesh.positions.push(p);
            mesh.normals.push(p);
            mesh.tangents.push(t.extend(W));
            mesh.uvs.push(Vec2::new(
                j as f32 / COLUMNS as f32,
                1.0 - i as f32 / ROWS as f32,
            ));
        }
    }
    let at = |i: u32, j: u32| i * (COLUMNS + 1) + j;
    for i in 0..ROWS {
        for j in 0..COLUMNS {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            mesh.triangles.push([a, b, c]);
            mesh.triangles.push([a, c, d]);
        }
    }
    mesh.normal_indices = mesh.triangles.clone();
    mesh.uv_indices = mesh.triangles.clone();
    mesh
}

fn scene_of(mesh: MeshDesc, world_from_object: Mat4, material: MaterialDesc) -> SceneDesc {
    let mut instance = InstanceDesc::identity(0, Default::default());
    instance.world_from_object = world_from_object;
    SceneDesc {
        source: "vertex tangents".into(),
        cameras: vec![common::camera_at(Vec3::new(0.0, 0.0, 5.0))],
        meshes: vec![mesh],
        instances: vec![instance],
        materials: vec![material],
        ..Default::default()
    }
}

#[test]
fn placements_turn_tangents_like_directions_and_mirrors_flip_their_handedness() {
    let mesh = smooth_sphere();
    let plain = common::material("grey", BsdfDesc::Diffuse { albedo: Vec3::ONE }, None);
    let flatten = |m: Mat4| {
        Geometry::from_desc(&scene_of(mesh.clone(), m, plain.clone()))
            .expect("geometry")
            .triangles
            .tangents
    };
    assert_eq!(
        flatten(Mat4::IDENTITY),
        mesh.tangents,
        "identity: bit for bit"
    );
    let turn = Mat4::from_rotation_y(0.7) * Mat4::from_scale(Vec3::splat(2.0));
    let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)) * turn;
    for (m, w) in [(turn, W), (mirror, -W)] {
        let placed = flatten(m);
        assert_eq!(placed.len(), mesh.tangents.len());
        let linear = Mat3::from_mat4(m);
        for (t, p) in mesh.tangents.iter().zip(&placed) {
            let expected = (linear * t.truncate()).normalize();
            assert!(
                (p.truncate() - expected).length() < 1e-6,
                "{p} vs {expected}"
            );
            assert_eq!(p.w, w);
        }
    }
}

/// One tangent-space normal everywhere, tilted about 23° off N.
fn tilt() -> Vec3 {
    Vec3::new(0.35, -0.25, 1.0).normalize()
}

/// The largest distance, over random hits away from the poles, between the
/// shading normal of the sphere `mesh` placed by `m` under a constant normal
/// map of [`tilt`] and the mapped normal of the analytic frame
/// `frame(θ, φ) = (N, T, B)` (object space) at the hit, and the same over
/// the hits within a column of the UV seam (φ = 0).
fn worst_error(mesh: MeshDesc, m: Mat4, frame: impl Fn(f32, f32) -> [Vec3; 3]) -> (f32, f32) {
    let dir = candela_testkit::TempDir::new("vertex-tangents");
    let d = tilt();
    let texel = (d + Vec3::ONE) * 0.5;
    let map = dir.join("tilt.exr");
    let image = RgbImage::from_fn(2, 2, |_, _| texel.to_array()).unwrap();
    write_exr(&map, &ExrLayers::beauty(image)).unwrap();
    let mut material = common::material("grey", BsdfDesc::Diffuse { albedo: Vec3::ONE }, None);
    material.textures.normal = Some(TextureRef::new(&map, ColorSpace::Linear));
    let desc = scene_of(mesh, m, material);
    let opts = SceneOptions {
        width: 8,
        height: 8,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(&desc, &opts).expect("scene builds");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let (linear, object_from_world) = (Mat3::from_mat4(m), m.inverse());
    let mut sampler = Sampler::new(SamplerKind::Independent, 73);
    let (mut checked, mut worst, mut worst_seam) = (0, 0.0f32, 0.0f32);
    for k in 0..2000u32 {
        sampler.start_pixel_sample(0, 0, k);
        let from = square_to_uniform_sphere(sampler.next_2d());
        let aim = 0.3 * square_to_uniform_sphere(sampler.next_2d());
        let ray = Ray::new(3.0 * from, (aim - 3.0 * from).normalize());
        let Some(hit) = scene.intersect(&ray, &mut TraversalStats::default()) else {
            continue;
        };
        // The analytic frame at the hit's own direction from the centre.
        let q = object_from_world.transform_point3(hit.p).normalize();
        if q.y.abs() > 0.95 {
            continue; // the frames are singular at the poles
        }
        let phi = q.z.atan2(q.x);
        let [n, t, b] = frame(q.y.acos(), phi);
        let expected = (linear * (d.x * t + d.y * b + d.z * n)).normalize();
        let got = shading_frame(&scene, &hit, scene.material(hit.material)).z;
        let error = (got - expected).length();
        if phi.abs() < std::f32::consts::TAU / COLUMNS as f32 {
            worst_seam = worst_seam.max(error);
        } else {
            worst = worst.max(error);
        }
        checked += 1;
    }
    assert!(checked > 500, "{checked} hits");
    (worst, worst_seam)
}

#[test]
fn a_normal_map_on_a_smooth_sphere_follows_the_supplied_tangents() {
    // The supplied frame: T along the meridian, B = W · N × T.
    let supplied = |theta: f32, phi: f32| {
        let (n, t) = sphere_frame(theta, phi);
        [n, t, W * n.cross(t)]
    };
    let turn = Mat4::from_rotation_z(0.4);
    let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)) * turn;
    for (label, m) in [("plain", turn), ("mirrored", mirror)] {
        let (off_seam, seam) = worst_error(smooth_sphere(), m, supplied);
        let worst = off_seam.max(seam);
        eprintln!("{label}: worst error {worst:.5}");
        // Interpolating a smooth unit field linearly over a triangle of
        // edge h ≈ π/32 errs by about h²/8 times its curvature (≤ 1/sin θ ≈
        // 3.2 off the poles): ≈ 0.004, so 0.01 is 2.5 times that.
        assert!(worst < 0.01, "{label}: worst error {worst}");
    }
}

#[test]
fn generated_tangents_follow_the_uvs_smoothly() {
    // Without TANGENT: T along dp/du (east, ∂p/∂φ), B along dp/dv (north,
    // −∂p/∂θ, as v = 1 − θ/π), generated per vertex.
    let mut mesh = smooth_sphere();
    mesh.tangents.clear();
    let from_uvs = |theta: f32, phi: f32| {
        let (n, meridian) = sphere_frame(theta, phi);
        [n, Vec3::new(-phi.sin(), 0.0, phi.cos()), -meridian]
    };
    let (worst, seam) = worst_error(mesh, Mat4::IDENTITY, from_uvs);
    eprintln!("generated: worst error {worst:.5}, {seam:.5} by the seam");
    // Off the seam a vertex averages the chords either side, symmetric
    // about it, so its tangent is the analytic one up to second order: the
    // supplied tangents' bound holds.
    assert!(worst < 0.01, "worst error {worst}");
    // The seam's vertices are split (u = 0 and u = 1) and see one side's
    // chord only, half a column (Δφ/2 ≈ 0.049) off; the map's tilt (its xy
    // is 0.41 long) turns that into ≤ 0.02 of the mapped normal. MikkTSpace
    // splits those vertices too.
    assert!(seam < 0.025, "by the seam: {seam}");
}
