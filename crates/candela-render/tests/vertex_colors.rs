//! Vertex colours at hits: the colour a hit carries is the barycentric
//! interpolation Σ bₖ cₖ of its triangle's corner colours (the point is
//! chosen by its barycentrics, the ray aimed at it, and the hit's colour
//! compared with the formula), through instancing (a moved and a mirrored
//! placement), white on a mesh without colours; a vertex-colour texture
//! gives scale × colour, a texture multiplied by the vertex colour gives
//! texture × colour; a mesh whose colours are not one per position is
//! refused.

use candela_render::bsdf::Bsdf;
use candela_render::geometry::Ray;
use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{
    BsdfDesc, InstanceDesc, MaterialDesc, MeshDesc, SceneDesc, SourceLoc, TextureRef, TextureSource,
};
use candela_testkit::SplitMix64;
use glam::{Mat4, Quat, Vec2, Vec3};

const CORNERS: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::Y];
const COLORS: [Vec3; 3] = [
    Vec3::new(1.0, 0.0, 0.5),
    Vec3::new(0.0, 1.0, 0.25),
    Vec3::new(0.2, 0.3, 1.0),
];
const SCALE: f32 = 0.5;

fn triangle(colors: Vec<Vec3>, material: usize) -> MeshDesc {
    MeshDesc {
        positions: CORNERS.to_vec(),
        triangles: vec![[0, 1, 2]],
        colors,
        material,
        ..MeshDesc::default()
    }
}

fn diffuse(name: &str, texture: TextureRef) -> MaterialDesc {
    let mut m = MaterialDesc {
        name: name.into(),
        bsdf: BsdfDesc::Diffuse {
            albedo: Vec3::splat(0.8),
        },
        ..MaterialDesc::default_grey()
    };
    m.textures.color = Some(texture);
    m
}

/// The checkerboard of material 1, multiplied by the vertex colour.
fn checker_times_colors() -> TextureRef {
    let mut t = TextureRef::checkerboard(Vec3::splat(0.5), Vec3::splat(0.25));
    t.times_vertex_color = true;
    t
}

/// Placements: (mesh, world_from_object). Mesh 0 has no colours, 1 and 2
/// have [`COLORS`]; 1 is drawn as stored elsewhere, moved, and mirrored.
fn placements() -> Vec<(usize, Mat4)> {
    let mirrored = Mat4::from_translation(Vec3::new(8.0, 0.0, 0.0))
        * Mat4::from_quat(Quat::from_rotation_y(0.5))
        * Mat4::from_scale(Vec3::new(-1.5, 1.0, 2.0));
    vec![
        (0, Mat4::IDENTITY),
        (1, Mat4::from_translation(Vec3::new(2.0, 0.0, 0.0))),
        (1, mirrored),
        (2, Mat4::from_translation(Vec3::new(4.0, 0.0, 0.0))),
    ]
}

fn scene() -> Scene {
    let mut vertex_color = TextureRef::vertex_color();
    vertex_color.scale = SCALE;
    let desc = SceneDesc {
        meshes: vec![
            triangle(Vec::new(), 0),
            triangle(COLORS.to_vec(), 0),
            triangle(COLORS.to_vec(), 1),
        ],
        instances: placements()
            .into_iter()
            .map(|(mesh, m)| InstanceDesc {
                world_from_object: m,
                ..InstanceDesc::identity(mesh, SourceLoc::default())
            })
            .collect(),
        materials: vec![
            diffuse("vertex colour", vertex_color),
            diffuse("checker × vertex colour", checker_times_colors()),
        ],
        ..SceneDesc::default()
    };
    Scene::build(&desc, &SceneOptions::default()).expect("a valid scene")
}

/// Corner weights uniform over the triangle, kept away from its edges and
/// from the checkerboard's cell edges (u = b₁, v = b₂ without UVs).
fn interior_barycentrics(rng: &mut SplitMix64) -> [f32; 3] {
    loop {
        let (b1, b2) = (rng.f32(), rng.f32());
        let b0 = 1.0 - b1 - b2;
        let near_cell_edge = |x: f32| ((2.0 * x) - (2.0 * x).round()).abs() < 1e-3;
        if b0 > 1e-3 && b1 > 1e-3 && b2 > 1e-3 && !near_cell_edge(b1) && !near_cell_edge(b2) {
            return [b0, b1, b2];
        }
    }
}

#[test]
fn a_hit_carries_the_barycentric_interpolation_of_its_corner_colours() {
    let scene = scene();
    let mut rng = SplitMix64::new(0x5eed_c010);
    for (placement, (mesh, m)) in placements().into_iter().enumerate() {
        let world = CORNERS.map(|p| m.transform_point3(p));
        let normal = (world[1] - world[0]).cross(world[2] - world[0]).normalize();
        for _ in 0..200 {
            let b = interior_barycentrics(&mut rng);
            let target = b[0] * world[0] + b[1] * world[1] + b[2] * world[2];
            let origin = target + 0.7 * normal + 0.1 * (world[1] - world[0]);
            let ray = Ray::new(origin, (target - origin).normalize());
            let hit = scene
                .intersect(&ray, &mut Default::default())
                .unwrap_or_else(|| panic!("placement {placement}: no hit at {target}"));
            let formula = if mesh == 0 {
                Vec3::ONE
            } else {
                b[0] * COLORS[0] + b[1] * COLORS[1] + b[2] * COLORS[2]
            };
            let err = (hit.vertex_color - formula).abs().max_element();
            assert!(
                err < 1e-5,
                "placement {placement} at {b:?}: {} vs Σ bₖ cₖ = {formula}",
                hit.vertex_color
            );
            let Some(Bsdf::Diffuse { albedo }) = scene.material(hit.material).bsdf_at(&hit) else {
                panic!("placement {placement}: not a diffuse BSDF");
            };
            let texture = if mesh == 2 {
                let uv = Vec2::new(b[1], b[2]);
                if TextureSource::checker_cell_is_even(uv) {
                    0.5
                } else {
                    0.25
                }
            } else {
                SCALE
            };
            let want = texture * formula;
            let err = (albedo - want).abs().max_element();
            assert!(
                err < 1e-5,
                "placement {placement} at {b:?}: albedo {albedo}, want {want}"
            );
        }
    }
}

#[test]
fn colours_not_one_per_position_are_refused() {
    let mut mesh = triangle(COLORS[..2].to_vec(), 0);
    mesh.name = "short".into();
    let mut desc = SceneDesc {
        materials: vec![MaterialDesc::default_grey()],
        ..SceneDesc::default()
    };
    desc.add_mesh(mesh);
    let message = match Scene::build(&desc, &SceneOptions::default()) {
        Ok(_) => panic!("a mesh with 2 colours for 3 positions was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        message.contains("2 vertex colours for 3 positions"),
        "{message}"
    );
}
