//! The shading-frame rule of `normal_map.rs` under strong, random normal
//! maps: no sampled reflection crosses the geometric surface, no sampled
//! transmission stays on the viewer's side, and the bent frame always sees
//! the viewer on its own side. (Light sampling applies the same
//! `scatter_allowed` before evaluating `f`, in `integrator/direct.rs`.)

use super::normal_map::{keep_viewer_above, mapped_normal};
use super::sample_scatter;
use crate::bsdf::Masking;
use crate::bsdf::{Bsdf, MetallicRoughness, MicrofacetDistribution};
use crate::geometry::Frame;
use crate::sampling::warp::{square_to_uniform_hemisphere, square_to_uniform_sphere};
use crate::sampling::{Sampler, SamplerKind};
use glam::Vec3;

fn models() -> [Bsdf; 4] {
    [
        Bsdf::Diffuse {
            albedo: Vec3::splat(0.8),
        },
        Bsdf::Microfacet {
            distribution: MicrofacetDistribution::ggx(0.3),
            masking: Masking::HeightCorrelated,
            eta: Vec3::splat(0.2),
            k: Vec3::splat(3.0),
        },
        Bsdf::MetallicRoughness(MetallicRoughness::new(Vec3::splat(0.6), 0.5, 0.5, 0.0, 1.5)),
        Bsdf::RoughGlass {
            distribution: MicrofacetDistribution::beckmann(0.2),
            masking: Masking::HeightCorrelated,
            reflectance: Vec3::ONE,
            transmittance: Vec3::ONE,
            ior: 1.5,
        },
    ]
}

#[test]
fn no_sampled_direction_leaks_through_the_geometric_surface() {
    let mut sampler = Sampler::new(SamplerKind::Independent, 41);
    let ng = Vec3::Z;
    let (mut kept, mut rejected) = (0u32, 0u32);
    for i in 0..20_000u32 {
        sampler.start_pixel_sample(0, 0, i);
        // A strongly tilted map texel (up to ~80° off the normal) on an
        // interpolated normal tilted up to 30° from the geometric one.
        let ns = (ng
            + 0.5 * square_to_uniform_sphere(sampler.next_2d()) * Vec3::new(1.0, 1.0, 0.0))
        .normalize();
        let texel_dir = square_to_uniform_hemisphere(sampler.next_2d());
        let texel = (texel_dir.max(Vec3::new(-1.0, -1.0, 0.15)).normalize() + Vec3::ONE) * 0.5;
        let wo = square_to_uniform_hemisphere(sampler.next_2d());
        if wo.dot(ns) <= 0.0 {
            continue; // the viewer is always above the interpolated normal here
        }
        let n = mapped_normal(ns, Vec3::X, Vec3::Y, texel, 1.0);
        let n = keep_viewer_above(n, ns, wo);
        let frame = Frame::from_normal(n);
        assert!(frame.to_local(wo).z > 0.0, "the bent frame sees the viewer");
        for bsdf in models() {
            let (u1, u2) = (sampler.next_1d(), sampler.next_2d());
            let Ok((wi, s)) = sample_scatter(&bsdf, &frame, ng, frame.to_local(wo), u1, u2) else {
                rejected += 1;
                continue;
            };
            kept += 1;
            if s.flags.is_transmission() {
                assert!(
                    wi.dot(ng) < 0.0,
                    "{bsdf:?}: transmission stayed above: {wi}"
                );
            } else {
                assert!(wi.dot(ng) > 0.0, "{bsdf:?}: reflection went below: {wi}");
            }
        }
    }
    let lost = f64::from(rejected) / f64::from(kept + rejected);
    eprintln!(
        "strong random normal maps: {lost:.3} of the samples rejected (lost energy, no leaks)"
    );
    assert!(kept > 30_000, "{kept}");
}
