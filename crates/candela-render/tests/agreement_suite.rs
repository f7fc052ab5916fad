//! One agreement suite for every estimator: each row of the table below is
//! a scene, and every estimator of `common::agreement::Method` (uniform
//! hemisphere sampling, light sampling, the MIS path tracer; light tracing
//! and BDPT join there) must converge on it to the image of a common
//! reference, the MIS path tracer at more samples, by a block z-test whose
//! threshold comes from the variance of both and is Bonferroni-corrected
//! over every block and every comparison (see `common/agreement.rs`).
//!
//! The scenes cover what each estimator handles differently: area lights
//! large and small (CS184 boxes), a point light (`CBempty`, the glass room),
//! glass and mirror (`CBspheres`: specular chains, which light sampling
//! cannot connect through), rough glass and rough gold, rough plastic and
//! conductors (the Mitsuba boxes), smooth shading normals on a dense mesh
//! (`CBbunny`), an environment map (the ball under the sky), lights at
//! infinity together with delta lights (the glass room), a thin lens,
//! textured emission behind stochastic cut-outs (the textured lamp), and
//! Mitsuba's normal and bump maps, whose bump shadowing is not reciprocal
//! (tex-maps: light and camera subpaths must attenuate the same side; its
//! normals are bent rather than mirrored there, see `tex_maps_bent`), and
//! Mitsuba's `blendbsdf`, a mixture whose parts may be delta (bsdf-blend),
//! and glTF clear coats, which dim the base by the view alone (not
//! reciprocal: light subpaths evaluate the adjoint).
//!
//! `cargo test --test agreement_suite` runs the CI table (about a minute on
//! two cores); `cargo test --test agreement_suite -- --ignored` runs the
//! long table too: the same estimators at more bounces and on heavier
//! scenes.

mod common;

use common::agreement::{assert_all_agree, comparisons, Case, Method, Setup, SUITE_FALSE_ALARM};
use common::agreement_scenes::*;

/// Why uniform hemisphere rays cannot reach a light: they find emitters by
/// hitting them, and a point light has no area.
const HEMISPHERE_POINT_LIGHT: &str =
    "uniform hemisphere rays never hit a point light (no area): its light is missing";

/// Why light sampling alone does not converge at test budgets on a nearly
/// specular lobe. It is unbiased, but the light the glossy silver sphere
/// (Beckmann α = 0.025) reflects onto the walls is found only when a light
/// sample falls into the narrow lobe: rarely, and then hugely. Below the
/// samples needed for those events to average out, block means are far
/// from normal and most batches miss the rare mass: measured, 21 of 90
/// block-channels darker than the reference at 8 spp per batch, 3 at 32
/// spp, while the image means agree (global |z| 0.3 and 1.1). The missing
/// mass shrinking with samples is a heavy tail, not a bias (which would
/// fail more blocks with more samples); MIS, which finds that light by BSDF
/// sampling, passes on the same scene.
const BDPT_SEES_THE_CAUSTIC: &str = "the point light seen through the glass pane \
    lights the room by a caustic that BDPT's light subpaths find and the reference (a \
    unidirectional path tracer, which can never connect to a delta light through a \
    specular surface) cannot: the two converge to different images here (measured: \
    max block |z| 11.6, global 2.9 at 48x40, 8 spp x 16 batches)";
const LIGHT_TRACER_SPECULAR: &str = "surfaces the camera sees only through a mirror, a \
    smooth conductor or glass (a specular chain ending at the pinhole) are out of the light \
    tracer's reach: a light path cannot be connected to the camera through a delta BSDF \
    (measured: |z| 29 on cornell-materials' smooth glass sphere, 88 on cornell-coated's \
    smooth copper sphere)";
const LIGHT_TRACER_SKY: &str = "the sky the camera sees directly is a light at infinity, \
    which light subpaths cannot hit the pinhole from (measured: |z| 5e5 on the background)";
const LIGHT_SAMPLING_NEAR_SPECULAR: &str = "light sampling alone on a Beckmann alpha = 0.025 \
     lobe is heavy-tailed: block means are far from normal at test budgets";

/// The table CI runs.
fn ci_cases() -> Vec<Case> {
    vec![
        Case {
            name: "CBspheres_lambertian",
            scene: || cs184_box("CBspheres_lambertian.dae"),
            max_depth: 4,
            spp: 8,
            excluded: &[],
            seed: 1,
        },
        Case {
            name: "CBspheres (glass and mirror)",
            scene: || cs184_box("CBspheres.dae"),
            max_depth: 5,
            spp: 8,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 2,
        },
        Case {
            name: "CBempty (point light)",
            scene: || cs184_box("CBempty.dae"),
            max_depth: 3,
            spp: 4,
            excluded: &[(Method::Hemisphere, HEMISPHERE_POINT_LIGHT)],
            seed: 3,
        },
        Case {
            name: "cornell-materials (rough glass, rough gold)",
            scene: || mitsuba_box("cornell-materials.xml"),
            max_depth: 4,
            spp: 8,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 4,
        },
        Case {
            name: "cornell-coated (rough plastic, conductors)",
            scene: || mitsuba_box("cornell-coated.xml"),
            max_depth: 3,
            spp: 8,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 5,
        },
        Case {
            name: "CBspheres_lambertian under glTF clear coats (a non-reciprocal BSDF)",
            scene: || cs184_box_coated("CBspheres_lambertian.dae"),
            max_depth: 3,
            // Light subpaths that evaluated the coat without swapping its
            // directions drift by about 2% here: BDPT's global |z| was 5.6
            // at 8 spp (threshold 5.3), 7.0 at this budget.
            spp: 16,
            excluded: &[],
            seed: 16,
        },
        Case {
            name: "ball under the sky (environment map)",
            scene: ball_under_the_sky,
            max_depth: 2,
            spp: 8,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SKY)],
            seed: 6,
        },
        Case {
            name: "CBspheres_lambertian through a thin lens",
            scene: || cs184_box_thin_lens("CBspheres_lambertian.dae", 0.2, 4.5),
            max_depth: 3,
            spp: 8,
            excluded: &[],
            seed: 7,
        },
        Case {
            name: "glass room (area, point and sky lights, glass)",
            scene: glass_room,
            max_depth: 4,
            spp: 8,
            excluded: &[
                (Method::Hemisphere, HEMISPHERE_POINT_LIGHT),
                (Method::Bdpt, BDPT_SEES_THE_CAUSTIC),
                (Method::LightTracer, LIGHT_TRACER_SPECULAR),
            ],
            seed: 8,
        },
        Case {
            name: "CBspheres_lambertian, gaussian pixel filter",
            scene: || cs184_box_filtered("CBspheres_lambertian.dae", "gaussian"),
            max_depth: 3,
            spp: 8,
            excluded: &[],
            seed: 12,
        },
        Case {
            name: "CBspheres_lambertian, catmull-rom pixel filter (negative lobes)",
            scene: || cs184_box_filtered("CBspheres_lambertian.dae", "catmull-rom"),
            max_depth: 2,
            spp: 8,
            excluded: &[],
            seed: 13,
        },
        Case {
            name: "textured lamp through a cut-out screen",
            scene: textured_lamp_through_a_cut_out_screen,
            max_depth: 2,
            spp: 8,
            excluded: &[],
            seed: 9,
        },
        Case {
            name: "tex-maps, normals bent (Mitsuba normal and bump maps, bump shadowing, masks)",
            scene: tex_maps_bent,
            max_depth: 3,
            spp: 8,
            excluded: &[],
            seed: 14,
        },
        Case {
            name: "bsdf-blend (blendbsdf: textured weight, delta beside smooth parts, nested)",
            scene: bsdf_blend,
            max_depth: 3,
            spp: 8,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 15,
        },
    ]
}

/// The long table: heavier scenes and deeper paths.
fn long_cases() -> Vec<Case> {
    vec![
        Case {
            name: "CBbunny (smooth normals on a dense mesh)",
            scene: || cs184_box("CBbunny.dae"),
            max_depth: 4,
            spp: 8,
            excluded: &[],
            seed: 101,
        },
        Case {
            name: "CBspheres_microfacet_al_ag (CS184 microfacet metals)",
            scene: || cs184_box("CBspheres_microfacet_al_ag.dae"),
            max_depth: 4,
            spp: 8,
            excluded: &[(Method::LightSampling, LIGHT_SAMPLING_NEAR_SPECULAR)],
            seed: 102,
        },
        Case {
            name: "CBspheres (glass and mirror), deep",
            scene: || cs184_box("CBspheres.dae"),
            max_depth: 12,
            spp: 16,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 103,
        },
        Case {
            name: "cornell-materials, deep",
            scene: || mitsuba_box("cornell-materials.xml"),
            max_depth: 8,
            spp: 16,
            excluded: &[(Method::LightTracer, LIGHT_TRACER_SPECULAR)],
            seed: 104,
        },
    ]
}

/// Comparisons of both tables: the Bonferroni factor of each.
fn all_comparisons() -> usize {
    comparisons(&ci_cases()) + comparisons(&long_cases())
}

#[test]
fn every_estimator_converges_to_the_reference_on_every_scene() {
    assert_all_agree(&ci_cases(), all_comparisons());
}

#[test]
#[ignore = "long: run with `cargo test --test agreement_suite -- --ignored`"]
fn every_estimator_converges_to_the_reference_on_the_long_table() {
    assert_all_agree(&long_cases(), all_comparisons());
}

#[test]
fn the_suite_sees_a_missing_light_and_a_missing_bounce() {
    // The suite's test must be able to fail, and see small biases: on
    // CBempty, uniform hemisphere rays miss the point light (the reason for
    // their exclusion), and the MIS path tracer stopped at 4 bounces misses
    // the light of the fifth, 0.9% of the image (measured with
    // `--bounce-layers`); both must fail against a reference of 5 bounces.
    let case = Case {
        name: "CBempty (point light), 5 bounces",
        scene: || cs184_box("CBempty.dae"),
        max_depth: 5,
        spp: 4,
        excluded: &[],
        seed: 10,
    };
    let rate = SUITE_FALSE_ALARM / all_comparisons() as f64;
    let setup = Setup::new(&case);
    let missing_light = setup.compare(Method::Hemisphere, Method::Hemisphere.integrator(5), rate);
    assert!(!missing_light.summary().passed());
    let short = setup.compare(Method::Mis, Method::Mis.integrator(4), rate);
    let summary = short.summary();
    assert!(!summary.passed(), "{summary:?}");
}
