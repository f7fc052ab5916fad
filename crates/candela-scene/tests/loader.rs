//! Loader behaviour on small hand-written scenes: transform order, nesting,
//! up axes, normals, triangulation, textures, camera fields of view, and the
//! built-in demo scene. Expected values are worked out by hand in comments.

use candela_scene::{demo_scene, load_str, BsdfDesc, LoadOptions, SceneDesc};
use glam::{Vec3, Vec4Swizzles};
use std::path::Path;

/// A scene with one triangle (0,0,0) (1,0,0) (0,1,0) with normal (1,1,0),
/// instanced under `transforms` inside `outer` (a node wrapper or empty).
fn triangle_scene(up: &str, transforms: &str, outer: (&str, &str)) -> SceneDesc {
    let text = format!(
        r##"<COLLADA><asset><up_axis>{up}</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3"/></technique_common></source>
    <source id="n"><float_array id="na" count="3">1 1 0</float_array>
      <technique_common><accessor source="#na" count="1" stride="3"/></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/>
      <input semantic="NORMAL" source="#n" offset="1"/><p>0 0 1 0 2 0</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">{}<node>{transforms}<instance_geometry url="#g"/></node>{}</visual_scene></library_visual_scenes>
</COLLADA>"##,
        outer.0, outer.1
    );
    load_str(
        &text,
        Path::new("t.dae"),
        &LoadOptions {
            strict: true,
            ..Default::default()
        },
    )
    .unwrap()
    .scene
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

fn point(s: &SceneDesc, i: usize) -> Vec3 {
    s.meshes[0].positions[s.meshes[0].triangles[0][i] as usize]
}

#[test]
fn transforms_compose_in_document_order() {
    // translate(1,0,0) * scale(2): (1,0,0) -> scale -> (2,0,0) -> translate -> (3,0,0).
    let s = triangle_scene(
        "Y_UP",
        "<translate>1 0 0</translate><scale>2 2 2</scale>",
        ("", ""),
    );
    assert!(close(point(&s, 1), Vec3::new(3., 0., 0.)));
    // scale(2) * translate(1,0,0): (1,0,0) -> (2,0,0) -> (4,0,0).
    let s = triangle_scene(
        "Y_UP",
        "<scale>2 2 2</scale><translate>1 0 0</translate>",
        ("", ""),
    );
    assert!(close(point(&s, 1), Vec3::new(4., 0., 0.)));
    // rotate(z, 90) * translate(1,0,0): origin -> (1,0,0) -> (0,1,0).
    let s = triangle_scene(
        "Y_UP",
        "<rotate>0 0 1 90</rotate><translate>1 0 0</translate>",
        ("", ""),
    );
    assert!(close(point(&s, 0), Vec3::new(0., 1., 0.)));
}

#[test]
fn nested_nodes_and_row_major_matrices() {
    let s = triangle_scene(
        "Y_UP",
        "<matrix>1 0 0 1 0 1 0 2 0 0 1 3 0 0 0 1</matrix>",
        (
            "<node id=\"n1\"><translate>0 0 5</translate>",
            "</node><node><translate>10 0 0</translate><instance_node url=\"#n1\"/></node>",
        ),
    );
    assert!(close(point(&s, 0), Vec3::new(1., 2., 8.)));
    // instance_node reuses the subtree under the instancing node's transform.
    let second = s.meshes[1].positions[s.meshes[1].triangles[0][0] as usize];
    assert!(close(second, Vec3::new(11., 2., 8.)));
}

#[test]
fn up_axes_become_y_up() {
    // Z_UP: x' = -x, y' = z, z' = y; the translate (1,2,3) goes to (-1,3,2).
    let s = triangle_scene("Z_UP", "<translate>1 2 3</translate>", ("", ""));
    assert!(close(point(&s, 0), Vec3::new(-1., 3., 2.)));
    // X_UP: x' = y, y' = x, z' = -z.
    let s = triangle_scene("X_UP", "<translate>1 2 3</translate>", ("", ""));
    assert!(close(point(&s, 0), Vec3::new(2., 1., -3.)));
}

#[test]
fn normals_use_the_inverse_transpose() {
    // Normal (1,1,0) under scale (2,1,1): inverse transpose diag(1/2,1,1)
    // gives (0.5,1,0), normalised.
    let s = triangle_scene("Y_UP", "<scale>2 1 1</scale>", ("", ""));
    let n = s.meshes[0].normals[s.meshes[0].normal_indices[0][0] as usize];
    assert!(close(n, Vec3::new(0.5, 1.0, 0.0).normalize()), "{n}");
}

#[test]
fn polygons_are_fan_triangulated_with_per_corner_attributes() {
    let text = r##"<COLLADA><library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="15">0 0 0 1 0 0 2 1 0 1 2 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="5" stride="3"/></technique_common></source>
    <source id="t"><float_array id="ta" count="4">0 0 1 1</float_array>
      <technique_common><accessor source="#ta" count="2" stride="2"/></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><input semantic="TEXCOORD" source="#t" offset="1"/>
      <vcount>5</vcount><p>4 0 3 1 2 0 1 1 0 0</p></polylist>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
</COLLADA>"##;
    let s = load_str(text, Path::new("fan.dae"), &LoadOptions::default())
        .unwrap()
        .scene;
    let m = &s.meshes[0];
    // Pentagon corners (file indices) 4 3 2 1 0 -> triangles (4,3,2) (4,2,1) (4,1,0).
    let file_tris: Vec<[Vec3; 3]> = m
        .triangles
        .iter()
        .map(|t| t.map(|i| m.positions[i as usize]))
        .collect();
    let p = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    assert_eq!(
        file_tris,
        vec![
            [p(0., 1.), p(1., 2.), p(2., 1.)],
            [p(0., 1.), p(2., 1.), p(1., 0.)],
            [p(0., 1.), p(1., 0.), p(0., 0.)]
        ]
    );
    // Corner uvs alternate 0,1,0,1,0 around the polygon.
    let uv = |t: usize, c: usize| m.uvs[m.uv_indices[t][c] as usize].x;
    assert_eq!([uv(0, 0), uv(0, 1), uv(0, 2), uv(2, 2)], [0., 1., 0., 0.]);
    assert_eq!(m.positions.len(), 5);
}

#[test]
fn diffuse_texture_resolves_through_newparams_relative_to_the_file() {
    let text = r##"<COLLADA><library_images><image id="img"><init_from>tex/wood.png</init_from></image></library_images>
  <library_effects><effect id="e"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><lambert><diffuse><texture texture="samp" texcoord="UV"/></diffuse></lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="m"><instance_effect url="#e"/></material></library_materials>
  <library_geometries><geometry id="g"><extra><technique profile="CGL"><sphere><radius>1</radius></sphere></technique></extra></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"><bind_material><technique_common>
    <instance_material symbol="x" target="#m"/></technique_common></bind_material></instance_geometry></node></visual_scene></library_visual_scenes>
</COLLADA>"##;
    let s = load_str(
        text,
        Path::new("/data/scenes/a.dae"),
        &LoadOptions::default(),
    )
    .unwrap()
    .scene;
    let tex = s.materials[s.spheres[0].material]
        .textures
        .color
        .clone()
        .unwrap();
    assert_eq!(
        tex.image_path(),
        Some(Path::new("/data/scenes/tex/wood.png"))
    );
}

#[test]
fn one_fov_and_aspect_gives_the_other() {
    let scene = |persp: &str| {
        let text = format!(
            r##"<COLLADA><library_cameras><camera id="c"><optics><technique_common><perspective>{persp}</perspective></technique_common></optics></camera></library_cameras>
  <library_visual_scenes><visual_scene id="s"><node><instance_camera url="#c"/></node></visual_scene></library_visual_scenes></COLLADA>"##
        );
        load_str(&text, Path::new("c.dae"), &LoadOptions::default())
            .unwrap()
            .scene
    };
    // tan(45°) = 1, aspect 2: yfov = 2 atan(1/2) = 53.1301°.
    let s = scene("<xfov>90</xfov><aspect_ratio>2</aspect_ratio>");
    assert!((s.cameras[0].fov_deg().unwrap().1 - 53.130_1).abs() < 1e-3);
    // And back: yfov 53.1301, aspect 2 -> xfov 90.
    let s = scene("<yfov>53.130102</yfov><aspect_ratio>2</aspect_ratio>");
    assert!((s.cameras[0].fov_deg().unwrap().0 - 90.0).abs() < 1e-3);
}

#[test]
fn demo_scene_is_a_lit_cornell_box() {
    let l = demo_scene();
    assert!(l.report.is_empty(), "{}", l.report);
    let s = l.scene;
    assert_eq!(
        (s.meshes.len(), s.triangle_count(), s.spheres.len()),
        (6, 12, 2)
    );
    let (lo, hi) = s.bounds().unwrap();
    assert!(close(lo, Vec3::new(-1., 0., -1.)) && close(hi, Vec3::new(1., 1.5, 1.)));
    // The lamp: radiance 10, geometric normal (winding) facing down, just under the ceiling.
    let lamp = s
        .meshes
        .iter()
        .find(|m| s.materials[m.material].emission.is_some())
        .unwrap();
    assert_eq!(s.materials[lamp.material].emission, Some(Vec3::splat(10.0)));
    for t in &lamp.triangles {
        let [a, b, c] = t.map(|i| lamp.positions[i as usize]);
        assert!((b - a).cross(c - a).normalize().dot(Vec3::NEG_Y) > 0.999);
        assert!((a.y - 1.49).abs() < 1e-6);
    }
    // Red wall on the camera's left (world -x), green on its right.
    let wall_x = |is_wall: fn(Vec3) -> bool| {
        let wall = s
            .meshes
            .iter()
            .find(|m| match s.materials[m.material].bsdf {
                BsdfDesc::Diffuse { albedo } => is_wall(albedo),
                _ => false,
            });
        wall.map(|m| m.positions[0].x).unwrap()
    };
    let red: fn(Vec3) -> bool = |a| a.x > 2.0 * a.y;
    let green: fn(Vec3) -> bool = |a| a.y > 2.0 * a.x;
    assert!((wall_x(red) + 1.0).abs() < 1e-6 && (wall_x(green) - 1.0).abs() < 1e-6);
    // Its own camera at half the box's height, 2.2 in front of the open
    // side, looking down -z, +y up (the demo renders from it).
    let c = &s.cameras[0];
    let m = c.world_from_camera;
    assert!(close(m.w_axis.xyz(), Vec3::new(0., 0.75, 3.2)));
    assert!(close(m.transform_vector3(Vec3::NEG_Z), Vec3::NEG_Z));
    assert!(close(m.transform_vector3(Vec3::Y), Vec3::Y));
    let kinds: Vec<_> = s
        .spheres
        .iter()
        .map(|sp| s.materials[sp.material].bsdf.clone())
        .collect();
    assert!(kinds.contains(&BsdfDesc::Mirror {
        reflectance: Vec3::splat(0.95)
    }));
    assert!(s
        .spheres
        .iter()
        .all(|sp| (sp.radius - 0.3).abs() < 1e-6 && (sp.center.y - 0.3).abs() < 1e-6));
    // It suggests its camera, a sample count and a firefly clamp.
    assert!(l.hints.file_camera);
    assert_eq!(l.hints.spp, Some(candela_scene::DEMO_SPP));
    assert_eq!(l.hints.clamp, Some(candela_scene::DEMO_CLAMP));
}

#[test]
fn load_picks_the_loader_by_extension_and_names_unknown_ones() {
    let dir = std::env::temp_dir().join(format!("candela-ext-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // An upper-case extension is still COLLADA.
    let upper = dir.join("tiny.DAE");
    std::fs::write(
        &upper,
        r##"<COLLADA><library_visual_scenes><visual_scene id="s"/></library_visual_scenes></COLLADA>"##,
    )
    .unwrap();
    assert!(candela_scene::load(&upper, &LoadOptions::default()).is_ok());
    for (name, shown) in [("scene.xyz", "\".xyz\""), ("scene", "no extension")] {
        let path = dir.join(name);
        std::fs::write(&path, "anything").unwrap();
        let err = candela_scene::load(&path, &LoadOptions::default()).unwrap_err();
        assert_eq!(err.kind, candela_scene::ErrorKind::UnknownFormat, "{err}");
        let line = err.to_string();
        assert!(line.contains(shown), "{line}");
        assert!(line.contains(".dae (COLLADA)"), "{line}");
        assert!(line.starts_with(&path.display().to_string()), "{line}");
        assert!(!line.contains('\n'));
    }
    std::fs::remove_dir_all(&dir).ok();
}
