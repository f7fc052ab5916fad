//! A blend's material at a hit (`Material::bsdf_at`): each part's BSDF on
//! the side the hit sees (a one-sided part is black from behind), mixed by
//! the weight texture's value at the hit's uv, or by the constant.

use super::sides_tests::{diffuse, hit, square};
use crate::scene::{Scene, SceneOptions};
use crate::shape::SurfaceHit;
use candela_scene::{
    BlendDesc, BsdfDesc, InstanceDesc, MaterialDesc, SceneDesc, Sides, SourceLoc, TextureRef,
    TextureSlot, TextureSource,
};
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;

const CHECKER: (f32, f32) = (0.25, 0.75);

/// Square 0: a one-sided diffuse 0.2 and a two-sided diffuse 0.6 under a
/// checkerboard weight; square 1: the same parts under the constant 0.3.
fn scene() -> Scene {
    let blend = |weight| MaterialDesc {
        bsdf: BsdfDesc::Blend(Box::new(BlendDesc {
            weight,
            parts: [diffuse(0.2, Sides::Front), diffuse(0.6, Sides::Both)],
        })),
        ..MaterialDesc::default_grey()
    };
    let mut textured = blend(0.5);
    textured.textures.set(
        TextureSlot::Weight,
        TextureRef::checkerboard(Vec3::splat(CHECKER.0), Vec3::splat(CHECKER.1)),
    );
    let desc = SceneDesc {
        instances: (0..2)
            .map(|i| InstanceDesc::identity(i, SourceLoc::default()))
            .collect(),
        meshes: (0..2).map(|i| square(2.0 * i as f32, i)).collect(),
        materials: vec![textured, blend(0.3)],
        ..SceneDesc::default()
    };
    Scene::build(&desc, &SceneOptions::default()).unwrap()
}

/// f of the hit's BSDF for a light direction on the viewer's side.
fn f_at(scene: &Scene, hit: &SurfaceHit) -> Option<f32> {
    let bsdf = scene.material(hit.material).bsdf_at(hit)?;
    let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
    Some(bsdf.f(wo, Vec3::new(-wo.x, -wo.y, wo.z)).x)
}

#[test]
fn a_blend_mixes_each_parts_side_by_the_weight_at_the_hit() {
    let scene = scene();
    assert!(scene.unsupported.is_empty(), "{:?}", scene.unsupported);
    for (i, front) in [(0, true), (0, false), (1, true), (1, false)] {
        let h = hit(&scene, i, front);
        let w = if i == 1 {
            0.3
        } else if TextureSource::checker_cell_is_even(h.uv) {
            CHECKER.0
        } else {
            CHECKER.1
        };
        // From behind, the one-sided part is black.
        let first = if front { 0.2 } else { 0.0 };
        let want = ((1.0 - w) * first + w * 0.6) * FRAC_1_PI;
        let got = f_at(&scene, &h).expect("the two-sided part scatters");
        assert!(
            (got - want).abs() < 1e-6,
            "square {i}, front {front}, uv {}: {got} != {want}",
            h.uv
        );
    }
}
