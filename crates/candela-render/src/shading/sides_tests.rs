//! The sidedness rule where a hit's BSDF is built (`Material::facing`,
//! `Material::bsdf_at`, `shading_frame`): a one-sided material is black
//! from behind its shading normal, a two-sided one turns over, a material
//! with a back BSDF uses that one behind; and an anisotropic BSDF's frame
//! follows dp/du.

use super::shading_frame;
use crate::bsdf::Bsdf;
use crate::geometry::Ray;
use crate::scene::{Scene, SceneOptions};
use crate::shape::SurfaceHit;
use candela_scene::{
    Alpha, BsdfDesc, InstanceDesc, MaterialDesc, MeshDesc, MicrofacetModel, SceneDesc, Sides,
    SourceLoc,
};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A diffuse material of `albedo` with `sides` (shared with the blend's
/// material tests).
pub(super) fn diffuse(albedo: f32, sides: Sides) -> MaterialDesc {
    MaterialDesc {
        bsdf: BsdfDesc::Diffuse {
            albedo: Vec3::splat(albedo),
        },
        sides,
        ..MaterialDesc::default_grey()
    }
}

/// A unit square at z = 0 centred on x = `x`, facing +z (counter-clockwise
/// seen from +z), with u running along +y and v along −x.
pub(super) fn square(x: f32, material: usize) -> MeshDesc {
    let p = |dx: f32, dy: f32| Vec3::new(x + dx, dy, 0.0);
    MeshDesc {
        name: format!("square {material}"),
        positions: vec![p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: vec![
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
        ],
        uv_indices: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..MeshDesc::default()
    }
}

/// Squares at x = 0, 2, 4, 6 with, in order: a one-sided diffuse 0.2, a
/// two-sided diffuse 0.3, a diffuse 0.1 with a diffuse 0.4 on its back,
/// and a one-sided anisotropic rough conductor.
fn scene() -> Scene {
    let materials = vec![
        diffuse(0.2, Sides::Front),
        diffuse(0.3, Sides::Both),
        diffuse(0.1, Sides::Back(Box::new(diffuse(0.4, Sides::Both)))),
        MaterialDesc {
            bsdf: BsdfDesc::Conductor {
                distribution: MicrofacetModel::Ggx,
                masking: candela_scene::Masking::HeightCorrelated,
                alpha: Alpha { u: 0.05, v: 0.4 },
                eta: Vec3::splat(0.2),
                k: Vec3::splat(3.0),
            },
            sides: Sides::Front,
            ..MaterialDesc::default_grey()
        },
    ];
    let meshes: Vec<MeshDesc> = (0..4).map(|i| square(2.0 * i as f32, i)).collect();
    let desc = SceneDesc {
        instances: (0..4)
            .map(|i| InstanceDesc::identity(i, SourceLoc::default()))
            .collect(),
        meshes,
        materials,
        ..SceneDesc::default()
    };
    Scene::build(&desc, &SceneOptions::default()).unwrap()
}

/// The hit on square `i` of a ray from the front (+z) or from behind.
pub(super) fn hit(scene: &Scene, i: usize, front: bool) -> SurfaceHit {
    let z = if front { 1.0 } else { -1.0 };
    let target = Vec3::new(2.0 * i as f32 + 0.1, 0.2, 0.0);
    let origin = target + Vec3::new(0.05, -0.1, z);
    let ray = Ray::new(origin, (target - origin).normalize());
    scene.intersect(&ray, &mut Default::default()).unwrap()
}

/// f at `hit` for a light direction `wi` mirrored from the viewer's about
/// the normal (same side as the viewer), in the hit's shading frame.
fn f_at(scene: &Scene, hit: &SurfaceHit) -> Option<Vec3> {
    let material = scene.material(hit.material);
    let bsdf = material.bsdf_at(hit)?;
    let frame = shading_frame(scene, hit, material);
    let wo = frame.to_local(hit.wo);
    let wi = Vec3::new(-wo.x, -wo.y, wo.z);
    Some(bsdf.f(wo, wi))
}

#[test]
fn one_sided_is_black_behind_two_sided_turns_over_and_a_back_bsdf_is_used_behind() {
    let scene = scene();
    let grey = |a: f32| Some(Vec3::splat(a * FRAC_1_PI));
    let close = |a: Option<Vec3>, b: Option<Vec3>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs().max_element() < 1e-6,
        (a, b) => a == b,
    };
    // (square, from the front?, f for a direction on the viewer's side)
    let expected = [
        (0, true, grey(0.2)),
        (0, false, None),
        (1, true, grey(0.3)),
        (1, false, grey(0.3)),
        (2, true, grey(0.1)),
        (2, false, grey(0.4)),
    ];
    for (i, front, want) in expected {
        let h = hit(&scene, i, front);
        assert_eq!(h.front_face, front, "square {i}");
        let got = f_at(&scene, &h);
        assert!(
            close(got, want),
            "square {i}, front {front}: {got:?} != {want:?}"
        );
    }
    // The one-sided square has no BSDF at all from behind, so neither light
    // samples nor BSDF samples nor their MIS weights can see one there.
    let back = hit(&scene, 0, false);
    assert_eq!(scene.material(back.material).bsdf_at(&back), None);
    assert!(scene.material(back.material).facing(&back).is_none());
}

#[test]
fn an_anisotropic_bsdfs_frame_follows_dp_du() {
    let scene = scene();
    let h = hit(&scene, 3, true);
    let material = scene.material(h.material);
    assert!(material.anisotropic);
    let Some(Bsdf::Microfacet { distribution, .. }) = material.bsdf_at(&h) else {
        panic!("{:?}", material.bsdf_at(&h))
    };
    assert_eq!(distribution.alphas(), (0.05, 0.4));
    let frame = shading_frame(&scene, &h, material);
    // u runs along +y on the square: the frame's x (alpha_u) is +y.
    assert!((frame.x - Vec3::Y).length() < 1e-5, "{frame:?}");
    assert!((frame.z - Vec3::Z).length() < 1e-5, "{frame:?}");
    // An isotropic material keeps the frame built from the normal alone.
    let iso = hit(&scene, 0, true);
    let iso_frame = shading_frame(&scene, &iso, scene.material(iso.material));
    assert_eq!(iso_frame.frame, crate::geometry::Frame::from_normal(iso.ns));
}
