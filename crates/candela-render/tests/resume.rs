//! Continuing a render from the film of a stopped one ends bit for bit where
//! the uninterrupted render ends: for uniform and adaptive sampling, a
//! sample range, another thread count and tiling, stopped after any number
//! of passes.

use candela_render::film::{Adaptive, Film};
use candela_render::integrator::IntegratorSettings;
use candela_render::render::{
    render, render_from, Cancel, Continuation, PassEnd, RenderControl, RenderSettings, StopReason,
};
use candela_render::scene::{Scene, SceneOptions};
use std::sync::Mutex;

fn cornell() -> Scene {
    let opts = SceneOptions {
        width: 24,
        height: 18,
        ..Default::default()
    };
    Scene::build(&candela_scene::demo_scene().scene, &opts).expect("demo scene builds")
}

/// The film after `passes` finished passes of `settings` (the render is
/// cancelled as soon as they are done).
fn stopped_after(scene: &Scene, settings: &RenderSettings, passes: u32) -> Film {
    let cancel = Cancel::new();
    let saved = Mutex::new(None);
    let after_pass = |p: &PassEnd<'_>| {
        if p.stats.passes == passes {
            *saved.lock().unwrap() = Some(p.film());
            cancel.cancel();
        }
    };
    let control = RenderControl {
        cancel: Some(cancel.clone()),
        progress: None,
    };
    let from = Continuation {
        start: None,
        after_pass: Some(&after_pass),
    };
    let out = render_from(scene, settings, &control, &from).expect("renders");
    assert_eq!(out.stop, StopReason::Cancelled, "stopped before the end");
    let film = saved.into_inner().unwrap().expect("the pass was reported");
    assert_eq!(
        out.film, film,
        "the cancelled render returns the saved passes"
    );
    film
}

fn resumed(scene: &Scene, settings: &RenderSettings, film: &Film) -> Film {
    let from = Continuation {
        start: Some(film),
        after_pass: None,
    };
    let out = render_from(scene, settings, &RenderControl::default(), &from).expect("renders");
    assert_eq!(out.stop, StopReason::Complete);
    out.film
}

fn bits(film: &Film) -> String {
    format!("{:?}", film.pixels)
}

#[test]
fn a_resumed_render_equals_the_uninterrupted_one_bit_for_bit() {
    let scene = cornell();
    let uniform = RenderSettings {
        spp: 96,
        seed: 11,
        integrator: IntegratorSettings::default(),
        threads: 2,
        ..Default::default()
    };
    let adaptive = RenderSettings {
        spp: 256,
        adaptive: Some(Adaptive {
            batch: 8,
            tolerance: 0.2,
        }),
        ..uniform.clone()
    };
    let range = RenderSettings {
        sample_range: Some(40..100),
        ..uniform.clone()
    };
    for settings in [uniform, adaptive, range] {
        let whole = render(&scene, &settings, &|_| ()).expect("renders").film;
        for passes in [1, 2] {
            let stopped = stopped_after(&scene, &settings, passes);
            assert!(stopped.pixels.iter().any(|p| p.count > 0));
            assert_ne!(bits(&stopped), bits(&whole));
            // Another thread count and tiling on the way back.
            let other = RenderSettings {
                threads: 1,
                tile: 5,
                ..settings.clone()
            };
            let back = resumed(&scene, &other, &stopped);
            assert!(
                bits(&back) == bits(&whole),
                "{settings:?} stopped after {passes} passes resumes to another film"
            );
        }
    }
}

#[test]
fn adaptive_stops_are_read_back_from_the_sums() {
    // Pixels that converged before the stop must not take more samples
    // after it (they would if the rule were not re-read from the sums).
    let scene = cornell();
    let settings = RenderSettings {
        spp: 4096,
        seed: 3,
        integrator: IntegratorSettings::default(),
        threads: 2,
        adaptive: Some(Adaptive {
            batch: 4,
            tolerance: 0.5,
        }),
        ..Default::default()
    };
    let stopped = stopped_after(&scene, &settings, 3);
    let converged: Vec<usize> = (0..stopped.pixels.len())
        .filter(|&i| {
            let p = &stopped.pixels[i];
            settings
                .adaptive
                .unwrap()
                .should_stop(p.count, p.lum, p.lum_sq)
        })
        .collect();
    assert!(!converged.is_empty(), "some pixels converge early");
    let back = resumed(&scene, &settings, &stopped);
    for i in converged {
        assert_eq!(back.pixels[i], stopped.pixels[i], "pixel {i} sampled again");
    }
}

#[test]
fn a_film_that_cannot_continue_is_refused() {
    let scene = cornell();
    let settings = RenderSettings {
        spp: 4,
        threads: 2,
        ..Default::default()
    };
    let done = render(&scene, &settings, &|_| ()).expect("renders").film;
    let fewer = RenderSettings { spp: 2, ..settings };
    let from = Continuation {
        start: Some(&done),
        after_pass: None,
    };
    let err = render_from(&scene, &fewer, &RenderControl::default(), &from).unwrap_err();
    assert!(err.to_string().contains("up to 4 samples"), "{err}");
    let small = Film::new(3, 3);
    let from = Continuation {
        start: Some(&small),
        after_pass: None,
    };
    let err = render_from(&scene, &fewer, &RenderControl::default(), &from).unwrap_err();
    assert!(err.to_string().contains("3x3"), "{err}");
}
