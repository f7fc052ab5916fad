//! Golden tests over the CS184 scenes. Expected numbers were derived by an
//! independent reading of the files (a short Python script walking the XML:
//! node matrices, the Z_UP change x' = -x, y' = z, z' = y, vcount sums), not
//! by printing what this loader produces.

// The expected numbers are the files' values rounded to 5 places, some of
// which happen to be close to 1/sqrt(2); they are data, not that constant.
#![allow(clippy::approx_constant)]

use candela_scene::{load, BsdfDesc, LightKind, LoadOptions, SceneDesc};
use glam::Vec3;
use std::path::PathBuf;

/// The shared CS184 corpus; a test that needs it fails without it.
fn cs184_dir() -> Option<PathBuf> {
    Some(candela_testkit::shared_dir().join("scenes/cs184"))
}

fn load_strict(name: &str) -> Option<SceneDesc> {
    let path = cs184_dir()?.join(name);
    let opts = LoadOptions {
        strict: true,
        keep_duplicate_lamps: true,
        ..LoadOptions::default()
    };
    let loaded = load(&path, &opts).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.report.is_empty(), "{}", loaded.report);
    Some(loaded.scene)
}

fn near(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

fn v(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z)
}

/// (file, triangles, bounds min, bounds max, xfov, yfov, camera position)
type Basic = (&'static str, usize, Vec3, Vec3, f32, f32, Vec3);

fn basics() -> Vec<Basic> {
    let cb_lo = v(-1.0, 0.0, -1.0);
    let cb_hi = v(1.0, 1.5, 1.0);
    vec![
        (
            "CBbunny.dae",
            28588,
            cb_lo,
            cb_hi,
            49.13434,
            28.8415,
            v(0.0, 0.0, -3.0),
        ),
        (
            "CBbunny_microfacet_cu.dae",
            28588,
            cb_lo,
            cb_hi,
            49.13434,
            28.8415,
            v(0.0, 0.0, -3.0),
        ),
        (
            "CBempty.dae",
            12,
            cb_lo,
            cb_hi,
            49.13434,
            28.8415,
            v(0.0, 0.0, 3.0),
        ),
        (
            "CBspheres.dae",
            12,
            cb_lo,
            cb_hi,
            49.13434,
            37.8493,
            v(0.0, 0.0, 3.0),
        ),
        (
            "CBspheres_lambertian.dae",
            12,
            cb_lo,
            cb_hi,
            49.13434,
            37.8493,
            v(0.0, 0.0, 3.0),
        ),
        (
            "CBspheres_microfacet_al_ag.dae",
            12,
            cb_lo,
            cb_hi,
            49.13434,
            37.8493,
            v(0.0, 0.0, 3.0),
        ),
        (
            "CBspheres_tex.dae",
            12,
            cb_lo,
            cb_hi,
            49.13434,
            37.8493,
            v(0.0, 0.0, 3.0),
        ),
        (
            "banana.dae",
            2458,
            cb_lo,
            v(1.0, 0.58148, 1.0),
            49.13434,
            28.8415,
            v(2.5, 1.0, 2.5),
        ),
        (
            "building.dae",
            39506,
            v(-1.0, -0.00239, -1.0),
            v(1.0, 0.38259, 1.0),
            54.4322,
            32.2688,
            v(0.00218, 0.0952, -0.63941),
        ),
        (
            "bunny.dae",
            33696,
            v(-0.75, -0.09969, -0.75),
            v(0.75, 0.86456, 0.75),
            49.13434,
            37.8493,
            v(0.0, 0.5, 2.5),
        ),
        (
            "bunny_microfacet_cu.dae",
            33696,
            v(-0.75, -0.09969, -0.75),
            v(0.75, 0.86456, 0.75),
            49.13434,
            37.8493,
            v(0.0, 0.5, 2.5),
        ),
        (
            "bunny_unlit.dae",
            33696,
            v(-0.75, -0.09969, -0.75),
            v(0.75, 0.86456, 0.75),
            49.13434,
            37.8493,
            v(0.0, 0.5, 2.5),
        ),
        (
            "cow.dae",
            5856,
            v(-0.40649, -0.76804, -0.83337),
            v(0.40649, 0.68915, 0.64751),
            39.5978,
            22.8952,
            v(0.0, 0.0, 5.0),
        ),
        (
            "cube.dae",
            12,
            v(-0.34435, -0.19291, -2.78598),
            v(0.08475, 0.23619, -2.35688),
            49.13434,
            28.8415,
            v(0.0, 0.0, 3.0),
        ),
        (
            "maxplanck.dae",
            50801,
            v(-0.5135, -0.86813, -0.65192),
            v(0.5135, 0.86813, 0.65192),
            39.5978,
            22.8952,
            v(0.0, 0.0, 5.0),
        ),
        (
            "plane.dae",
            2,
            v(-1.0, -0.5, -0.99568),
            v(1.0, 1.0, -0.99568),
            49.13434,
            28.8415,
            v(0.0, 0.0, 3.0),
        ),
        (
            "teapot.dae",
            2464,
            v(-0.79263, -0.38832, -0.49311),
            v(0.79263, 0.38832, 0.49311),
            39.5978,
            22.8952,
            v(0.0, 0.0, 3.0),
        ),
    ]
}

#[test]
fn every_cs184_scene_loads_strictly_with_the_right_geometry_and_camera() {
    if cs184_dir().is_none() {
        return;
    }
    for (file, tris, lo, hi, xfov, yfov, eye) in basics() {
        let s = load_strict(file).unwrap();
        assert_eq!(s.triangle_count(), tris, "{file}");
        let (blo, bhi) = s.bounds().unwrap();
        assert!(
            near(blo, lo, 2e-5) && near(bhi, hi, 2e-5),
            "{file}: {blo} {bhi}"
        );
        assert_eq!(s.cameras.len(), 1, "{file}");
        let c = &s.cameras[0];
        let (c_xfov, c_yfov) = c.fov_deg().expect("a perspective camera");
        assert!(
            (c_xfov - xfov).abs() < 1e-4 && (c_yfov - yfov).abs() < 1e-3,
            "{file}: {c:?}"
        );
        assert!(
            near(c.world_from_camera.w_axis.truncate(), eye, 2e-5),
            "{file}: {c:?}"
        );
        // Every mesh has per-corner normals of unit length.
        for m in &s.meshes {
            assert_eq!(m.normal_indices.len(), m.triangles.len(), "{file}");
            assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
        }
    }
}

#[test]
fn cornell_box_camera_transform_lights_spheres_and_materials() {
    let Some(s) = load_strict("CBspheres.dae") else {
        return;
    };
    // Camera: world_from_camera rows (1 0 0 0 / 0 1 0 0 / 0 0 1 3).
    let m = s.cameras[0].world_from_camera;
    let expected = glam::Mat4::from_cols_array(&[
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 3., 1.,
    ]);
    assert!(m.abs_diff_eq(expected, 1e-5), "{m}");
    // The CGL area light wins over the common point light.
    assert_eq!(s.lights.len(), 1);
    match &s.lights[0].kind {
        LightKind::Area {
            center,
            edge_x,
            edge_y,
            normal,
            radiance,
        } => {
            assert!(near(*center, v(0.0, 1.49, 0.0), 1e-6));
            assert!(near(*edge_x, v(-0.6, 0.0, 0.0), 1e-6));
            assert!(near(*edge_y, v(0.0, 0.0, 0.8), 1e-6));
            assert!(near(*normal, v(0.0, -1.0, 0.0), 1e-6));
            assert_eq!(*radiance, Vec3::splat(10.0));
        }
        k => panic!("expected an area light, got {k:?}"),
    }
    // Loaded for rendering, the area light merges into the lamp mesh it
    // duplicates, and the report says so.
    let path = cs184_dir().unwrap().join("CBspheres.dae");
    let merged = load(&path, &LoadOptions::default()).unwrap();
    assert!(merged.scene.lights.is_empty());
    assert_eq!(merged.report.notes.len(), 1);
    assert!(merged.report.notes[0].message.contains("counted once"));
    assert!(merged.report.is_empty(), "a merge is a note, not a warning");
    let mut spheres: Vec<_> = s
        .spheres
        .iter()
        .map(|sp| (sp.center, sp.radius, &s.materials[sp.material].bsdf))
        .collect();
    spheres.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    assert!(near(spheres[0].0, v(-0.4, 0.3, -0.3), 1e-6) && (spheres[0].1 - 0.3).abs() < 1e-6);
    assert!(near(spheres[1].0, v(0.4, 0.3, 0.3), 1e-6) && (spheres[1].1 - 0.3).abs() < 1e-6);
    assert_eq!(
        *spheres[0].2,
        BsdfDesc::Mirror {
            reflectance: Vec3::ONE
        }
    );
    assert_eq!(
        *spheres[1].2,
        BsdfDesc::Glass {
            reflectance: Vec3::ONE,
            transmittance: Vec3::ONE,
            roughness: 0.0,
            ior: 1.45
        }
    );
    let by_name = |n: &str| {
        s.meshes
            .iter()
            .find(|m| m.name == n)
            .map(|m| &s.materials[m.material])
            .unwrap()
    };
    let lamp = by_name("light");
    assert_eq!(
        (lamp.bsdf.clone(), lamp.emission),
        (BsdfDesc::Black, Some(Vec3::splat(10.0)))
    );
    assert_eq!(
        by_name("leftWall").bsdf,
        BsdfDesc::Diffuse {
            albedo: v(0.6, 0.2, 0.2)
        }
    );
    assert_eq!(
        by_name("rightWall").bsdf,
        BsdfDesc::Diffuse {
            albedo: v(0.2, 0.2, 0.6)
        }
    );
    assert_eq!(
        by_name("floor").bsdf,
        BsdfDesc::Diffuse {
            albedo: Vec3::splat(0.6)
        }
    );
}

#[test]
fn microfacet_parameters() {
    let Some(s) = load_strict("CBspheres_microfacet_al_ag.dae") else {
        return;
    };
    let want = [
        BsdfDesc::Microfacet {
            alpha: 0.025,
            eta: v(1.3352, 1.0109, 0.68955),
            k: v(7.3398, 6.6157, 5.6471),
        },
        BsdfDesc::Microfacet {
            alpha: 0.25,
            eta: v(0.059193, 0.059881, 0.047366),
            k: v(4.1283, 3.5892, 2.8132),
        },
    ];
    for w in &want {
        assert!(
            s.spheres
                .iter()
                .any(|sp| s.materials[sp.material].bsdf == *w),
            "{w:?}"
        );
    }
    let s = load_strict("CBbunny_microfacet_cu.dae").unwrap();
    let bunny = s.meshes.iter().max_by_key(|m| m.triangles.len()).unwrap();
    assert_eq!(
        s.materials[bunny.material].bsdf,
        BsdfDesc::Microfacet {
            alpha: 0.05,
            eta: v(0.33228, 1.0162, 1.2474),
            k: v(3.1646, 2.5785, 2.4603)
        }
    );
}

#[test]
fn point_ambient_and_directional_lights() {
    let Some(s) = load_strict("CBempty.dae") else {
        return;
    };
    assert_eq!(s.lights.len(), 1);
    assert!(
        matches!(s.lights[0].kind, LightKind::Point { position, intensity }
        if near(position, v(0.0, 1.49, 0.00432), 1e-5) && intensity == Vec3::splat(5.0))
    );

    let s = load_strict("banana.dae").unwrap();
    assert_eq!(s.lights.len(), 2);
    assert!(matches!(s.lights[0].kind, LightKind::Ambient { radiance } if radiance == Vec3::ONE));
    assert!(
        matches!(s.lights[1].kind, LightKind::Directional { direction, radiance }
        if near(direction, v(0.5, -0.70711, 0.5), 1e-5) && radiance == Vec3::ONE)
    );

    let s = load_strict("bunny_unlit.dae").unwrap();
    assert!(matches!(s.lights[0].kind, LightKind::Ambient { radiance } if radiance == Vec3::ZERO));

    let s = load_strict("teapot.dae").unwrap();
    assert!(
        matches!(s.lights[0].kind, LightKind::Directional { direction, .. }
        if near(direction, v(0.5, -0.70711, -0.5), 1e-5))
    );
    let s = load_strict("cube.dae").unwrap();
    assert!(
        matches!(s.lights[0].kind, LightKind::Point { position, intensity }
        if near(position, v(0.0, 1.49, 0.0), 1e-6) && intensity == Vec3::ONE)
    );
    // cube.dae binds no material: the default grey.
    assert_eq!(
        s.materials[s.meshes[0].material].bsdf,
        BsdfDesc::Diffuse {
            albedo: Vec3::splat(0.5)
        }
    );
}

#[test]
fn banana_camera_full_transform() {
    let Some(s) = load_strict("banana.dae") else {
        return;
    };
    let rows = [
        [0.70711, -0.18301, 0.68301, 2.5],
        [0.0, 0.96593, 0.25882, 1.0],
        [-0.70711, -0.18301, 0.68301, 2.5],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let m = s.cameras[0].world_from_camera;
    for (i, row) in rows.iter().enumerate() {
        assert!(
            near(m.row(i).truncate(), v(row[0], row[1], row[2]), 1e-5),
            "{m}"
        );
        assert!((m.row(i).w - row[3]).abs() < 1e-5);
    }
}
