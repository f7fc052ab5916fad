//! File cameras with their own projections: an orthographic camera sends a
//! known pixel to a known point, and a thin lens described in the file
//! focuses where the file says (and the command line still overrides it).

mod common;

use candela_render::camera::framing::CameraMode;
use candela_render::scene::{Scene, SceneError, SceneOptions};
use candela_scene::{BsdfDesc, Projection, SceneDesc};
use glam::{Mat4, Quat, Vec2, Vec3};

/// A large quad in the plane z = 0, seen by `projection` placed at `eye`
/// looking down -Z (rotated by `turn` about Y).
fn quad_seen_by(projection: Projection, eye: Vec3, turn: f32) -> SceneDesc {
    let mesh = common::square_z0("wall", 50.0, 0);
    let mut camera = common::camera_at(eye);
    camera.world_from_camera = Mat4::from_rotation_translation(Quat::from_rotation_y(turn), eye);
    camera.projection = projection;
    let mut desc = SceneDesc {
        cameras: vec![camera],
        materials: vec![common::material(
            "grey",
            BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            None,
        )],
        ..Default::default()
    };
    desc.add_mesh(mesh);
    desc
}

fn options(width: u32, height: u32, mode: CameraMode) -> SceneOptions {
    SceneOptions {
        width,
        height,
        camera_mode: mode,
        ..Default::default()
    }
}

#[test]
fn an_orthographic_pixel_hits_its_point_on_the_wall() {
    // 40 x 20 pixels over a 4-unit-wide view: 0.1 unit per pixel, 2 high.
    let desc = quad_seen_by(
        Projection::Orthographic { width: 4.0 },
        Vec3::new(0.3, -0.2, 5.0),
        0.0,
    );
    let scene = Scene::build(&desc, &options(40, 20, CameraMode::File)).expect("builds");
    let mut stats = Default::default();
    for (px, py) in [(10.5, 5.5), (0.0, 0.0), (40.0, 20.0), (20.0, 10.0)] {
        let ray = scene
            .camera
            .generate_ray(Vec2::new(px, py), Vec2::new(0.3, 0.8));
        assert!(
            (ray.dir - Vec3::NEG_Z).length() < 1e-6,
            "parallel rays: {ray:?}"
        );
        let hit = scene.intersect(&ray, &mut stats).expect("the wall is hit");
        // x grows to the right, y down the image; the centre is the eye.
        let want = Vec3::new(0.3 + (px - 20.0) * 0.1, -0.2 + (10.0 - py) * 0.1, 0.0);
        assert!(
            (hit.p - want).length() < 1e-5,
            "pixel ({px}, {py}): {} vs {want}",
            hit.p
        );
        assert!((hit.t - 5.0).abs() < 1e-5);
    }
}

#[test]
fn an_orthographic_camera_under_the_cs184_framing_keeps_its_width() {
    let desc = quad_seen_by(
        Projection::Orthographic { width: 3.0 },
        Vec3::new(0.0, 0.0, 5.0),
        0.0,
    );
    let scene = Scene::build(&desc, &options(30, 30, CameraMode::Cs184)).expect("builds");
    assert_eq!(scene.camera.orthographic, Some(Vec2::new(1.5, 1.5)));
    let a = scene.camera.generate_ray(Vec2::new(0.0, 15.0), Vec2::ZERO);
    let b = scene.camera.generate_ray(Vec2::new(30.0, 15.0), Vec2::ZERO);
    assert!((a.dir - b.dir).length() < 1e-6);
    assert!(((b.origin - a.origin).length() - 3.0).abs() < 1e-5);
    // A lens on an orthographic camera is refused, not ignored.
    let lens = SceneOptions {
        lens_radius: 0.1,
        ..options(30, 30, CameraMode::File)
    };
    assert!(matches!(
        Scene::build(&desc, &lens),
        Err(SceneError::Lens(_))
    ));
}

#[test]
fn a_thin_lens_from_the_file_focuses_on_its_plane() {
    let projection = Projection::ThinLens {
        xfov_deg: 50.0,
        yfov_deg: 40.0,
        aperture_radius: 0.25,
        focus_distance: 3.0,
    };
    // Turned, so the focal plane is not the wall's plane by construction.
    let desc = quad_seen_by(projection, Vec3::new(0.0, 0.0, 6.0), 0.3);
    let scene = Scene::build(&desc, &options(32, 24, CameraMode::File)).expect("builds");
    let c = &scene.camera;
    assert_eq!((c.lens_radius, c.focal_distance), (0.25, 3.0));
    assert!((c.vfov_deg() - 40.0).abs() < 1e-3);
    let film = Vec2::new(7.0, 19.0);
    let mut pinhole = c.clone();
    pinhole.lens_radius = 0.0;
    let centre = pinhole.generate_ray(film, Vec2::ZERO);
    let focus = centre.at(3.0 / centre.dir.dot(c.forward));
    let mut spread = 0.0f32;
    for u in [
        Vec2::new(0.1, 0.9),
        Vec2::new(0.8, 0.3),
        Vec2::new(0.5, 0.05),
    ] {
        let r = c.generate_ray(film, u);
        spread = spread.max((r.origin - c.eye).length());
        let t = (focus - r.origin).dot(c.forward) / r.dir.dot(c.forward);
        assert!((r.at(t) - focus).length() < 1e-4, "lens sample {u}");
    }
    assert!(spread > 0.05, "rays start across the lens, not at the eye");
    // The command line's aperture and focus replace the file's.
    let opts = SceneOptions {
        lens_radius: 0.1,
        focal_distance: Some(2.0),
        ..options(32, 24, CameraMode::File)
    };
    let c = Scene::build(&desc, &opts).expect("builds").camera;
    assert_eq!((c.lens_radius, c.focal_distance), (0.1, 2.0));
}
