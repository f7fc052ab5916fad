//! The primitive seam and instances, end to end through `Scene::build`:
//! a scene mixing instanced meshes and spheres intersects exactly as brute
//! force over every (transformed) primitive does, and two instances of one
//! mesh render bit for bit like the mesh duplicated by hand.

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::geometry::Ray;
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_render::shape::{intersect_sphere, intersect_triangle, PrimKind, PrimRef, TriangleRay};
use candela_scene::{BsdfDesc, InstanceDesc, MeshDesc, SceneDesc, SourceLoc, SphereDesc};
use glam::{Mat4, Quat, Vec3};

/// A tiny deterministic generator (splitmix64).
struct Rng(u64);
impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32()) * (hi - lo) + Vec3::splat(lo)
    }
}

fn diffuse(name: &str, albedo: f32) -> candela_scene::MaterialDesc {
    common::material(
        name,
        BsdfDesc::Diffuse {
            albedo: Vec3::splat(albedo),
        },
        None,
    )
}

/// One mesh of random triangles placed by three instances (the last with
/// its own material), plus two spheres; materials tell the instances apart.
fn mixed_scene(rng: &mut Rng) -> SceneDesc {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..40u32 {
        let c = rng.vec(-2.0, 2.0);
        for _ in 0..3 {
            positions.push(c + rng.vec(-0.6, 0.6));
        }
        triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
    }
    let mesh = MeshDesc {
        name: "shards".into(),
        positions,
        triangles,
        material: 0,
        ..Default::default()
    };
    let place = |m: Mat4, material: Option<usize>| InstanceDesc {
        mesh: 0,
        world_from_object: m,
        material,
        loc: SourceLoc::default(),
    };
    let sphere = |center: Vec3, radius: f32| SphereDesc {
        axes: candela_scene::SphereDesc::Y_POLE,
        name: "ball".into(),
        center,
        radius,
        material: 1,
        inward: false,
        loc: SourceLoc::default(),
    };
    SceneDesc {
        cameras: vec![common::camera_at(Vec3::new(0.0, 0.0, 12.0))],
        meshes: vec![mesh],
        instances: vec![
            place(Mat4::IDENTITY, None),
            place(Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0)), None),
            place(
                Mat4::from_scale_rotation_translation(
                    Vec3::new(1.5, 0.5, 1.0),
                    Quat::from_rotation_y(0.7),
                    Vec3::new(-4.0, 1.0, -1.0),
                ),
                Some(2),
            ),
        ],
        spheres: vec![
            sphere(Vec3::new(0.0, 4.0, 0.0), 1.0),
            sphere(Vec3::new(2.0, -3.0, 1.0), 0.7),
        ],
        materials: vec![diffuse("a", 0.5), diffuse("b", 0.3), diffuse("c", 0.7)],
        ..Default::default()
    }
}

/// The closest primitive by testing every triangle of every instance
/// (transformed as the description says) and every sphere: (t, primitive,
/// material). Triangles are numbered instance by instance, as documented
/// on `scene::Geometry`.
fn brute(desc: &SceneDesc, ray: &Ray) -> Option<(f32, PrimRef, usize)> {
    let tr = TriangleRay::new(ray.origin, ray.dir);
    let mut best = None;
    let mut t_max = ray.t_max;
    let mut index = 0u32;
    for inst in &desc.instances {
        let mesh = &desc.meshes[inst.mesh];
        for tri in &mesh.triangles {
            let v = tri.map(|k| {
                inst.world_from_object
                    .transform_point3(mesh.positions[k as usize])
            });
            if let Some(h) = intersect_triangle(&tr, &v, t_max) {
                t_max = h.t;
                best = Some((
                    h.t,
                    PrimRef::triangle(index),
                    inst.material.unwrap_or(mesh.material),
                ));
            }
            index += 1;
        }
    }
    for (j, s) in desc.spheres.iter().enumerate() {
        if let Some(t) = intersect_sphere(ray.origin, ray.dir, s.center, s.radius, t_max) {
            t_max = t;
            best = Some((t, PrimRef::sphere(j as u32), s.material));
        }
    }
    best
}

#[test]
fn triangles_spheres_and_instances_intersect_as_brute_force_does() {
    let mut rng = Rng(7);
    let desc = mixed_scene(&mut rng);
    let scene = Scene::build(&desc, &SceneOptions::default()).expect("scene builds");
    assert_eq!(scene.primitive_count(), 3 * 40 + 2);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // A stored mesh that nothing places is not drawn, and the scene says so.
    let mut unplaced = desc.clone();
    unplaced.meshes.push(MeshDesc {
        name: "spare".into(),
        ..unplaced.meshes[0].clone()
    });
    let spare = Scene::build(&unplaced, &SceneOptions::default()).expect("builds");
    assert_eq!(spare.primitive_count(), scene.primitive_count());
    assert!(
        spare.warnings.iter().any(|w| w.contains("'spare'")),
        "{:?}",
        spare.warnings
    );
    let (mut kinds, mut stats) = ([0u32; PrimKind::COUNT], Default::default());
    for k in 0..3000 {
        let o = rng.vec(-9.0, 9.0);
        let target = rng.vec(-5.0, 5.0);
        let ray = Ray::new(o, (target - o).normalize());
        let want = brute(&desc, &ray);
        let got = scene.intersect(&ray, &mut stats);
        assert_eq!(got.map(|h| h.t), want.map(|w| w.0), "ray {k}: {ray:?}");
        assert_eq!(
            scene.occluded(&ray, &mut stats),
            want.is_some(),
            "ray {k} occluded"
        );
        if let (Some(g), Some((_, prim, material))) = (got, want) {
            // Distinct random primitives never tie exactly at these sizes.
            assert_eq!((g.prim, g.material as usize), (prim, material), "ray {k}");
            kinds[prim.kind() as usize] += 1;
        }
    }
    // The test means something only if every kind (and instance) was hit.
    assert!(kinds.iter().all(|&n| n > 50), "hits per kind {kinds:?}");
}

/// The shards lit by an emissive sphere, with a second copy of the mesh
/// shifted along x: placed by a second instance of the one mesh when
/// `instanced`, otherwise stored as a second mesh written out by hand.
fn two_copies(instanced: bool) -> SceneDesc {
    let mut desc = mixed_scene(&mut Rng(11));
    desc.spheres.truncate(1);
    desc.spheres[0].center = Vec3::new(0.0, 6.0, 4.0);
    desc.materials[1].emission = Some(Vec3::splat(2.0));
    // A shift by a power of two is exact in f32, so the hand-made copy has
    // the very positions the instance transform makes.
    let shift = Vec3::new(4.0, 0.0, 0.0);
    desc.instances.truncate(1);
    if instanced {
        desc.instances.push(InstanceDesc {
            world_from_object: Mat4::from_translation(shift),
            ..InstanceDesc::identity(0, SourceLoc::default())
        });
    } else {
        let mesh = desc.meshes[0].clone();
        desc.add_mesh(MeshDesc {
            positions: mesh.positions.iter().map(|&p| p + shift).collect(),
            ..mesh
        });
    }
    // A wall behind both copies, so most pixels see lit geometry.
    let s = 20.0;
    desc.add_mesh(MeshDesc {
        name: "backdrop".into(),
        positions: vec![
            Vec3::new(-s, -s, -4.0),
            Vec3::new(s, -s, -4.0),
            Vec3::new(s, s, -4.0),
            Vec3::new(-s, s, -4.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        material: 0,
        ..Default::default()
    });
    desc.cameras = vec![common::camera_at(Vec3::new(2.0, 0.0, 8.0))];
    desc
}

#[test]
fn two_instances_render_like_the_mesh_duplicated_by_hand() {
    let opts = SceneOptions {
        width: 24,
        height: 24,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let settings = RenderSettings {
        spp: 4,
        seed: 3,
        integrator: IntegratorSettings {
            roulette: false,
            ..IntegratorSettings::path(3, LightingMode::Mis)
        },
        threads: 2,
        ..Default::default()
    };
    let films: Vec<_> = [true, false]
        .map(|instanced| {
            let desc = two_copies(instanced);
            assert_eq!(desc.meshes.len(), if instanced { 2 } else { 3 });
            let scene = Scene::build(&desc, &opts).expect("scene builds");
            assert_eq!(scene.primitive_count(), 2 * 40 + 2 + 1);
            render(&scene, &settings, &|_| {}).expect("render").film
        })
        .into_iter()
        .collect();
    let lit = films[0]
        .pixels
        .iter()
        .filter(|p| p.radiance.max_element() > 0.0)
        .count();
    assert!(
        lit > 24 * 24 / 4,
        "only {lit} lit pixels: the test would prove little"
    );
    for (i, (a, b)) in films[0].pixels.iter().zip(&films[1].pixels).enumerate() {
        assert!(
            a.radiance == b.radiance && a.radiance_sq == b.radiance_sq && a.count == b.count,
            "pixel {i}: {a:?} vs {b:?}"
        );
    }
}
