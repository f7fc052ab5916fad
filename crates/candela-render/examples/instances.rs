//! Instancing cost: one mesh placed N times on a grid, flattened at build
//! time. Reports build time, memory and closest-hit throughput for N = 1
//! and N = 100 (the figures behind the choice in ARCHITECTURE-scene.md).
//!
//! ```text
//! cargo run --release -p candela-render --example instances -- SCENE.dae [N [RAYS]]
//! ```
//!
//! The largest mesh of SCENE is the instanced one. Rays are the primary
//! rays of the one-instance scene's camera (CS184 framing of one mesh),
//! cycled over the image, and the same rays are traced in every scene: they
//! see the first instance (at the origin) and whatever lies behind it.

use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{InstanceDesc, SceneDesc, SourceLoc};
use glam::{Mat4, Vec2, Vec3};
use std::error::Error;
use std::time::Instant;

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .ok_or("usage: instances SCENE.dae [N [RAYS]]")?;
    let n: usize = args.get(1).map_or(Ok(100), |s| s.parse())?;
    let rays: u32 = args.get(2).map_or(Ok(400_000), |s| s.parse())?;
    let loaded = candela_scene::load(std::path::Path::new(path), &Default::default())?;
    let mesh = loaded
        .scene
        .meshes
        .iter()
        .max_by_key(|m| m.triangles.len())
        .ok_or("the scene has no mesh")?
        .clone();
    let mut camera = None;
    for count in [1, n] {
        let mut desc = SceneDesc {
            cameras: loaded.scene.cameras.clone(),
            materials: loaded.scene.materials.clone(),
            meshes: vec![mesh.clone()],
            ..Default::default()
        };
        let (lo, hi) = desc_bounds(&mesh.positions);
        let step = (hi - lo).max_element() * 1.2;
        let side = (count as f32).sqrt().ceil() as usize;
        for k in 0..count {
            let offset = Vec3::new((k % side) as f32 * step, 0.0, (k / side) as f32 * step);
            desc.instances.push(InstanceDesc {
                world_from_object: Mat4::from_translation(offset),
                ..InstanceDesc::identity(0, SourceLoc::default())
            });
        }
        let opts = SceneOptions {
            width: 400,
            height: 300,
            ..Default::default()
        };
        let start = Instant::now();
        let scene = Scene::build(&desc, &opts)?;
        let build = start.elapsed().as_secs_f64();
        let info = scene.accel_info();
        let tris = &scene.geometry.triangles;
        let shading_bytes = tris.positions.len() * 12
            + tris.triangles.len() * (12 * 3 + 4)
            + tris.normals.len() * 12
            + tris.uvs.len() * 8;
        let camera = camera.get_or_insert_with(|| scene.camera.clone());
        let mut stats = Default::default();
        let (mut hits, start) = (0u32, Instant::now());
        for i in 0..rays {
            let (x, y) = (i % 400, (i / 400) % 300);
            let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let ray = camera.generate_ray(film, Vec2::ZERO);
            hits += scene.intersect(&ray, &mut stats).is_some() as u32;
        }
        let secs = start.elapsed().as_secs_f64();
        println!(
            "{count:>4} instances, {:>9} triangles: build {build:.3} s (BVH {:.3} s), \
             BVH+leaves {:.1} MB, shading data {:.1} MB, {:.2} Mrays/s (1 thread, {hits} hits)",
            tris.triangles.len(),
            info.build_seconds,
            info.total_bytes as f64 / 1e6,
            shading_bytes as f64 / 1e6,
            rays as f64 / secs / 1e6,
        );
    }
    Ok(())
}

fn desc_bounds(p: &[Vec3]) -> (Vec3, Vec3) {
    p.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &q| (lo.min(q), hi.max(q)),
    )
}
