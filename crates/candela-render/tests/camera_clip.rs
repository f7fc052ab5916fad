//! A camera's clip range (Mitsuba's `near_clip` / `far_clip`) on real
//! geometry: a sphere nearer than the near plane is passed through, the
//! room behind it is seen; a far plane nearer than the room leaves every
//! camera ray empty. The camera looks down −Z from the centre of a closed
//! room of radius 5 with a ball of radius 0.5 at depth 1.5 in front of it.

mod common;

use candela_bvh::TraversalStats;
use candela_render::camera::framing::CameraMode;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{BsdfDesc, ClipRange, MeshDesc, SceneDesc, SourceLoc, SphereDesc};
use glam::{Vec2, Vec3};

const ROOM_RADIUS: f32 = 5.0;

fn room_and_ball(clip: Option<ClipRange>) -> SceneDesc {
    let (positions, triangles) = common::inward_icosphere(2, ROOM_RADIUS);
    let mut camera = common::camera_at(Vec3::ZERO);
    camera.clip = clip;
    SceneDesc {
        source: "clip".into(),
        cameras: vec![camera],
        meshes: vec![MeshDesc {
            name: "room".into(),
            positions,
            triangles,
            material: 0,
            ..Default::default()
        }],
        instances: vec![candela_scene::InstanceDesc::identity(0, Default::default())],
        spheres: vec![SphereDesc {
            axes: SphereDesc::Y_POLE,
            name: "ball".into(),
            center: Vec3::new(0.0, 0.0, -1.5),
            radius: 0.5,
            material: 0,
            inward: false,
            loc: SourceLoc::default(),
        }],
        materials: vec![common::material(
            "grey",
            BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            None,
        )],
        ..Default::default()
    }
}

/// The first hit's distance from the eye for a grid of film points
/// (`None` where the camera ray hits nothing).
fn hit_distances(desc: &SceneDesc) -> Vec<Option<f32>> {
    let opts = SceneOptions {
        width: 16,
        height: 16,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(desc, &opts).expect("test scene builds");
    let mut out = Vec::new();
    for y in 0..16 {
        for x in 0..16 {
            let ray = scene
                .camera
                .generate_ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), Vec2::ZERO);
            let hit = scene.intersect(&ray, &mut TraversalStats::default());
            out.push(hit.map(|h| h.p.length()));
        }
    }
    out
}

#[test]
fn a_ball_nearer_than_the_near_plane_is_passed_through() {
    // Unclipped, the centre rays stop on the ball (distance 1 to 1.5).
    let unclipped = hit_distances(&room_and_ball(None));
    let on_ball = unclipped
        .iter()
        .filter(|d| d.is_some_and(|d| d < 2.0))
        .count();
    assert!(on_ball > 4, "the ball must be in view ({on_ball} rays)");
    // The icosphere's facets lie between its inradius and its radius.
    let on_room = |d: &Option<f32>| d.is_some_and(|d| d > 0.9 * ROOM_RADIUS && d <= ROOM_RADIUS);
    let clipped = hit_distances(&room_and_ball(Some(ClipRange {
        near: 2.5,
        far: 100.0,
    })));
    for (i, d) in clipped.iter().enumerate() {
        assert!(on_room(d), "ray {i}: {d:?} (the room expected)");
    }
}

#[test]
fn a_far_plane_before_the_room_leaves_rays_empty() {
    let clipped = hit_distances(&room_and_ball(Some(ClipRange {
        near: 0.01,
        far: 3.0,
    })));
    for (i, d) in clipped.iter().enumerate() {
        // Only the ball (within depth 3) may be hit.
        assert!(d.is_none_or(|d| d < 2.0), "ray {i}: {d:?}");
    }
    assert!(
        clipped.iter().any(Option::is_some),
        "the ball stays in view"
    );
}
