//! The depth and cost AOVs: depth is the distance along the camera ray to
//! the first hit (+inf where nothing is hit), cost the traversal work of
//! every ray of a sample, attributed to the pixel without losing a count.

mod common;

use candela_image::{read_exr_layers, LayerData};
use candela_render::camera::framing::CameraMode;
use candela_render::film::{write_film, CostMeasure, OutputOptions};
use candela_render::integrator::{IntegratorSettings, LightingMode};
use candela_render::render::{render, RenderOutput, RenderSettings};
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{BsdfDesc, SceneDesc, SourceLoc, SphereDesc};
use common::{camera_at, glass_room, material};
use glam::Vec3;

fn render_desc(desc: &SceneDesc, size: (u32, u32), spp: u32) -> RenderOutput {
    let opts = SceneOptions {
        width: size.0,
        height: size.1,
        camera_mode: CameraMode::File,
        ..Default::default()
    };
    let scene = Scene::build(desc, &opts).expect("test scene builds");
    let settings = RenderSettings {
        spp,
        seed: 3,
        integrator: IntegratorSettings::path(3, LightingMode::Mis),
        threads: 2,
        ..Default::default()
    };
    render(&scene, &settings, &|_| {}).expect("render runs")
}

#[test]
fn depth_inside_a_sphere_is_its_radius() {
    // A pinhole at the centre of a sphere of radius 2: every camera ray
    // travels exactly 2 (up to the intersection's rounding).
    let desc = SceneDesc {
        cameras: vec![camera_at(Vec3::ZERO)],
        spheres: vec![SphereDesc {
            axes: candela_scene::SphereDesc::Y_POLE,
            name: "room".into(),
            center: Vec3::ZERO,
            radius: 2.0,
            material: 0,
            inward: false,
            loc: SourceLoc::default(),
        }],
        materials: vec![material(
            "wall",
            BsdfDesc::Diffuse {
                albedo: Vec3::splat(0.5),
            },
            Some(Vec3::ONE),
        )],
        ..Default::default()
    };
    let out = render_desc(&desc, (8, 6), 4);
    let depth = out.film.depth();
    for &d in depth.values() {
        assert!((d - 2.0).abs() < 1e-5, "depth {d}");
    }
    assert!(out.film.pixels.iter().all(|p| p.depth_count == 4));
}

#[test]
fn depth_is_infinite_where_nothing_is_hit_and_grows_up_the_floor() {
    let out = render_desc(&glass_room(), (16, 12), 4);
    let depth = out.film.depth();
    let at = |x, y| depth.get(x, y).unwrap();
    // The top corners look over the wall into the sky (the lamp hangs
    // over the middle columns).
    for x in [0, 1, 14, 15] {
        assert_eq!(at(x, 0), f32::INFINITY, "top row, x = {x}");
    }
    // The bottom corners see the floor: a finite distance, larger one row up.
    for x in [0, 15] {
        let (near, far) = (at(x, 11), at(x, 10));
        assert!(
            near.is_finite() && near > 0.0 && far > near,
            "x = {x}: {near} {far}"
        );
    }
}

#[test]
fn cost_per_pixel_adds_up_to_the_render_statistics() {
    let out = render_desc(&glass_room(), (16, 12), 4);
    let nodes: u64 = out.film.pixels.iter().map(|p| p.nodes).sum();
    let prims: u64 = out.film.pixels.iter().map(|p| p.prim_tests).sum();
    let stats = out.stats.rays.traversal;
    assert!(stats.nodes_visited > 0 && stats.prims_tested > 0);
    assert_eq!((nodes, prims), (stats.nodes_visited, stats.prims_tested));
    // The images are the per-sample means of the same counts.
    let image = out.film.cost(CostMeasure::Total);
    let total: f64 = image.values().iter().map(|&c| c as f64 * 4.0).sum();
    let expected = (nodes + prims) as f64;
    assert!(
        (total - expected).abs() <= 1e-6 * expected,
        "{total} vs {expected}"
    );
}

#[test]
fn exr_layers_carry_depth_and_cost() {
    let out = render_desc(&glass_room(), (16, 12), 2);
    let dir = candela_testkit::TempDir::new("aov-exr");
    let path = dir.join("aovs.exr");
    let opts = OutputOptions {
        depth: true,
        cost: true,
        ..Default::default()
    };
    write_film(&path, &out.film, &opts).expect("EXR written");
    let layers = read_exr_layers(&path).expect("EXR reads back");
    let gray = |name: &str| match layers.extra.iter().find(|(n, _)| n == name) {
        Some((_, LayerData::Gray(image))) => image.clone(),
        _ => panic!("no scalar layer {name}"),
    };
    assert_eq!(gray("depth"), out.film.depth());
    assert_eq!(gray("cost.nodes"), out.film.cost(CostMeasure::Nodes));
    assert_eq!(gray("cost.prims"), out.film.cost(CostMeasure::PrimTests));
    // Without the options, no such layers.
    write_film(&path, &out.film, &OutputOptions::default()).expect("EXR written");
    assert!(read_exr_layers(&path).unwrap().extra.is_empty());
}
