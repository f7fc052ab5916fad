use super::*;
use crate::film::{Adaptive, PixelRect};
use serde_json::json;

fn changes(v: Value) -> Map<String, Value> {
    match v {
        Value::Object(m) => m,
        _ => panic!("not an object"),
    }
}

fn refused(v: Value) -> String {
    match Settings::from_json(&changes(v.clone())) {
        Ok(s) => panic!("{v} was accepted as {s:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn defaults_round_trip_through_json() {
    let d = Settings::default();
    assert_eq!(Settings::from_json(&d.to_json()).unwrap(), d);
    assert_eq!(Settings::from_json(&Map::new()).unwrap(), d);
    assert_eq!(d.sampling.spp(), DEFAULT_SPP);
    assert_eq!((d.image.width, d.image.height), (800, 600));
}

#[test]
fn every_group_is_flat_in_json() {
    let s = Settings::from_json(&changes(json!({
        "spp": 64, "max_depth": 3, "width": 320, "height": 240, "exposure": -1.5,
        "threads": 2, "integrator": "direct", "lighting": "hemisphere",
        "camera": "file", "bvh": "median", "tone": "filmic", "sampler": "independent",
        "exr_compression": "piz",
        "cell": [10, 20, 30, 40], "adaptive": [32, 0.1]
    })))
    .unwrap();
    assert_eq!(s.sampling.spp, Some(64));
    assert_eq!(s.integrator.bounces(), 0..=1);
    assert_eq!(
        s.integrator.lighting,
        crate::integrator::LightingMode::Hemisphere
    );
    assert_eq!(s.image.cell, Some(PixelRect::new(10, 20, 30, 40)));
    assert_eq!(
        s.sampling.adaptive,
        Some(Adaptive {
            batch: 32,
            tolerance: 0.1
        })
    );
    assert_eq!(
        (s.run.threads, s.run.bvh, s.output.tone),
        (2, Bvh::Median, ToneCurve::Filmic)
    );
    assert_eq!(s.output.exr_compression, candela_image::ExrCompression::Piz);
    // The JSON of the settings reads back as the same settings.
    assert_eq!(Settings::from_json(&s.to_json()).unwrap(), s);
}

#[test]
fn adaptive_takes_every_documented_form() {
    let get = |v: Value| {
        Settings::from_json(&changes(json!({ "adaptive": v })))
            .unwrap()
            .sampling
            .adaptive
    };
    assert_eq!(get(json!(true)), Some(Adaptive::default()));
    assert_eq!(get(json!(false)), None);
    assert_eq!(get(Value::Null), None);
    assert_eq!(get(json!(0.2)).unwrap().tolerance, 0.2);
    assert_eq!(
        get(json!({"batch": 8, "tolerance": 0.01})),
        Some(Adaptive {
            batch: 8,
            tolerance: 0.01
        })
    );
    assert!(refused(json!({"adaptive": [0.5, 0.05]})).starts_with("adaptive (-a)"));
    assert!(refused(json!({"adaptive": [64, -1]})).contains("TOL a number >= 0"));
}

#[test]
fn unknown_keys_and_wrong_types_are_named() {
    let e = refused(json!({"spp": 4, "sppp": 4}));
    assert!(e.starts_with("unknown setting `sppp`"), "{e}");
    assert!(e.contains("max_depth"), "{e}");
    let e = refused(json!({"max_depth": "deep"}));
    assert!(e.starts_with("setting `max_depth` = \"deep\""), "{e}");
    let e = refused(json!({"integrator": "photons"}));
    assert!(e.starts_with("setting `integrator`"), "{e}");
}

#[test]
fn impossible_values_are_refused_with_the_flag() {
    for (v, start) in [
        (json!({"spp": 0}), "spp (-s) 0"),
        (json!({"width": 0}), "width, height (-r) 0 600"),
        (json!({"focal_distance": 0.0}), "focal_distance (-d) 0"),
        (json!({"aperture": -0.1}), "aperture (-b) -0.1"),
        (json!({"light_samples": 0}), "light_samples (-l) 0"),
        (json!({"time": 0.0}), "time (--time) 0"),
        (json!({"cell": [790, 0, 20, 10]}), "cell (-p) 790 0 20 10"),
        (json!({"tile": 0}), "tile (--tile) 0"),
    ] {
        let e = refused(v);
        assert!(e.starts_with(start), "{e} should start with {start}");
    }
}

#[test]
fn non_finite_numbers_are_refused() {
    // JSON has no NaN; front ends that do (the CLI, Python) fill the struct.
    let mut s = Settings::default();
    s.output.exposure = f32::NAN;
    assert!(s
        .validate()
        .unwrap_err()
        .to_string()
        .starts_with("exposure (--exposure) NaN"));
    let mut s = Settings::default();
    s.image.env_scale = f32::INFINITY;
    assert!(s.validate().is_err());
    let mut s = Settings::default();
    s.sampling.time = Some(f64::NAN);
    assert!(s.validate().is_err());
}

#[test]
fn a_film_that_would_not_fit_is_refused_unless_the_limit_is_raised() {
    let huge = json!({"width": 100_000, "height": 100_000});
    let e = refused(huge.clone());
    assert!(
        e.starts_with("width, height (-r) 100000 100000: the film would need"),
        "{e}"
    );
    assert!(e.contains("--memory-limit"), "{e}");
    // The estimate is what the limit compares: 1e10 pixels need far more
    // than 16 GiB, and a limit above the estimate lets the render through.
    let need = film_bytes(100_000, 100_000, 0) as f64 / (1u64 << 30) as f64;
    assert!(need > 1000.0);
    let mut raised = changes(huge);
    raised.insert("memory_limit".into(), json!(need * 1.01));
    assert!(Settings::from_json(&raised).is_ok());
    // An ordinary HD render is far below the default limit.
    assert!(film_bytes(1920, 1080, 0) < (1 << 30));
    // Each extra layer adds its sums (twice) and its image.
    assert_eq!(
        film_bytes(10, 10, 3) - film_bytes(10, 10, 0),
        100 * 3 * (2 * 24 + 12)
    );
}

#[test]
fn cs184_views_map_to_bounce_ranges() {
    let i = |v: Value| Settings::from_json(&changes(v)).unwrap().integrator;
    assert_eq!(i(json!({"max_depth": 4})).bounces(), 0..=4);
    assert_eq!(
        i(json!({"max_depth": 4, "accumulate": false})).bounces(),
        4..=4
    );
    assert_eq!(
        i(json!({"max_depth": 4, "integrator": "indirect"})).bounces(),
        2..=4
    );
    assert_eq!(
        i(json!({"max_depth": 0, "integrator": "direct"})).bounces(),
        0..=0
    );
    assert_eq!(i(json!({"max_depth": 4, "bounce": 2})).bounces(), 2..=2);
    assert_eq!(i(json!({"bounce": 0})).bounces(), 0..=0);
    assert!(i(json!({"integrator": "normals"}))
        .path_settings()
        .is_none());
    let p = i(json!({"roulette": false})).path_settings().unwrap();
    assert_eq!(p.roulette_from, None);
}

#[test]
fn with_threads_bounds_the_pool() {
    let mut s = Settings::default();
    s.run.threads = 1;
    assert_eq!(s.with_threads(rayon::current_num_threads).unwrap(), 1);
    s.run.threads = 3;
    assert_eq!(s.with_threads(rayon::current_num_threads).unwrap(), 3);
}

#[test]
fn explicit_settings_beat_scene_hints_which_beat_defaults() {
    let hints = RenderHints {
        spp: Some(64),
        max_depth: Some(9),
        resolution: Some((320, 200)),
        file_camera: true,
        clamp: Some(3.0),
        filter: Some(candela_scene::FilterHint::Tent { radius: 1.5 }),
        hide_emitters: true,
    };
    let s = Settings::resolve(&hints, &changes(json!({"spp": 4, "camera": "cs184"}))).unwrap();
    assert_eq!(
        s.image.filter,
        crate::camera::PixelFilter::Tent { radius: 1.5 }
    );
    let explicit = Settings::resolve(&hints, &changes(json!({"filter": "box"}))).unwrap();
    assert_eq!(explicit.image.filter, crate::camera::PixelFilter::default());
    assert_eq!(s.sampling.spp, Some(4));
    assert_eq!(s.image.camera, crate::camera::framing::CameraMode::Cs184);
    assert_eq!(s.integrator.max_depth, 9);
    assert_eq!(s.integrator.clamp, Some(3.0));
    assert!(s.integrator.hide_emitters);
    assert_eq!(s.integrator.bounces(), 1..=9);
    let shown = Settings::resolve(&hints, &changes(json!({"hide_emitters": false}))).unwrap();
    assert_eq!(shown.integrator.bounces(), 0..=9);
    assert_eq!((s.image.width, s.image.height), (320, 200));
    assert_eq!(s.output, OutputSettings::default());
    assert_eq!(
        Settings::resolve(&RenderHints::default(), &Map::new()).unwrap(),
        Settings::default()
    );
}

#[test]
fn a_time_budget_is_not_capped_by_a_suggested_sample_count() {
    let hints = RenderHints {
        spp: Some(64),
        ..RenderHints::default()
    };
    let timed = Settings::resolve(&hints, &changes(json!({"time": 1.0}))).unwrap();
    assert_eq!(timed.sampling.spp(), u32::MAX);
    let both = Settings::resolve(&hints, &changes(json!({"time": 1.0, "spp": 8}))).unwrap();
    assert_eq!(both.sampling.spp(), 8);
    assert_eq!(
        Settings::resolve(&hints, &Map::new())
            .unwrap()
            .sampling
            .spp(),
        64
    );
}

#[test]
fn a_bounce_beyond_the_depth_or_with_a_cs184_view_is_refused() {
    assert_eq!(
        refused(json!({"max_depth": 3, "bounce": 4})),
        "bounce (--bounce) 4: at most the maximum depth (-m 3)"
    );
    for (view, name) in [
        (json!({"integrator": "direct"}), "--integrator direct"),
        (json!({"integrator": "indirect"}), "--integrator indirect"),
        (json!({"integrator": "normals"}), "--integrator normals"),
        (json!({"accumulate": false}), "-o 0"),
    ] {
        let mut v = changes(view);
        v.insert("bounce".into(), json!(1));
        assert_eq!(
            refused(Value::Object(v)),
            format!("bounce (--bounce) 1: only with the path integrator adding every bounce, not {name}")
        );
    }
    assert_eq!(
        refused(json!({"bounce": -1})).split(':').next(),
        Some("setting `bounce` = -1")
    );
}

#[test]
fn hidden_emitters_start_the_image_at_bounce_one_in_the_path_tracer_only() {
    let s = Settings::from_json(&changes(json!({"hide_emitters": true}))).unwrap();
    assert_eq!(s.integrator.bounces(), 1..=5);
    assert!(s.integrator.path_settings().unwrap().hide_emitters);
    assert_eq!(
        refused(json!({"hide_emitters": true, "bounce": 0})),
        "bounce (--bounce) 0: at least 1 with --hide-emitters (bounce 0 is the emitters it hides)"
    );
    for estimator in ["bdpt", "light"] {
        assert_eq!(
            refused(json!({"hide_emitters": true, "integrator": estimator})),
            "hide_emitters (--hide-emitters) true: only with the path tracer (a scene may ask for it: --hide-emitters=false)"
        );
    }
}

#[test]
fn bounce_layers_name_one_layer_per_bounce_count_up_to_the_depth() {
    let i = |v: Value| Settings::from_json(&changes(v)).unwrap().integrator;
    let names = crate::integrator::layer_names;
    assert!(names(&i(json!({}))).is_empty());
    assert_eq!(
        names(&i(json!({"max_depth": 3, "bounce_layers": 2}))),
        ["bounce_0", "bounce_1", "bounce_2"]
    );
    // The layers do not narrow what the image shows.
    assert_eq!(
        i(json!({"max_depth": 3, "bounce_layers": 2})).bounces(),
        0..=3
    );
    assert_eq!(
        refused(json!({"max_depth": 3, "bounce_layers": 4})),
        "bounce_layers (--bounce-layers) 4: at most the maximum depth (-m 3)"
    );
    assert_eq!(
        refused(json!({"integrator": "direct", "bounce_layers": 1})),
        "bounce_layers (--bounce-layers) 1: only with the path integrator adding every bounce, \
         not --integrator direct"
    );
    assert_eq!(
        refused(json!({"bounce": 1, "bounce_layers": 2})),
        "bounce_layers (--bounce-layers) 2: not with --bounce 1, which keeps one bounce count only"
    );
}

#[test]
fn the_camera_is_a_name_or_a_file_camera_number() {
    use crate::camera::framing::CameraMode;
    let camera = |v: Value| {
        Settings::resolve(&RenderHints::default(), &changes(json!({ "camera": v })))
            .map(|s| s.image.camera)
    };
    assert_eq!(camera(json!(2)).unwrap(), CameraMode::Numbered(2));
    assert_eq!(camera(json!("1")).unwrap(), CameraMode::Numbered(1));
    assert_eq!(camera(json!("file")).unwrap(), CameraMode::File);
    assert!(camera(json!("front")).is_err());
    assert!(camera(json!(-1)).is_err());
    for mode in [CameraMode::Cs184, CameraMode::File, CameraMode::Numbered(3)] {
        assert_eq!(mode.to_string().parse::<CameraMode>().unwrap(), mode);
        assert_eq!(
            serde_json::from_value::<CameraMode>(serde_json::to_value(mode).unwrap()).unwrap(),
            mode
        );
    }
    let mut s = Settings::default();
    s.image.camera = CameraMode::Numbered(2);
    assert!(s.image.validate_for_scene(3).is_ok());
    let e = s.image.validate_for_scene(2).unwrap_err().to_string();
    assert!(e.contains("--camera") && e.contains("2 camera(s)"), "{e}");
    assert!(
        ImageSettings::default().validate_for_scene(0).is_ok(),
        "cs184 needs no camera"
    );
}

#[test]
fn an_explicit_camera_needs_both_points_and_a_valid_view() {
    let json = |v: serde_json::Value| v.as_object().unwrap().clone();
    let only_eye = Settings::from_json(&json(serde_json::json!({"eye": [0, 1, 5]})));
    assert!(only_eye
        .unwrap_err()
        .to_string()
        .starts_with("eye, look_at (--eye, --look-at)"));
    let same = Settings::from_json(&json(
        serde_json::json!({"eye": [1, 1, 1], "look_at": [1, 1, 1]}),
    ));
    assert!(same
        .unwrap_err()
        .to_string()
        .contains("the eye is at the look-at point"));
    let wide = json(serde_json::json!({"eye": [0, 1, 5], "look_at": [0, 1, 0], "fov": 180}));
    assert!(Settings::from_json(&wide).is_err());
    let good = json(serde_json::json!({"eye": [0, 1, 5], "look_at": [0, 1, 0], "fov": 40}));
    let view = Settings::from_json(&good)
        .unwrap()
        .camera_options()
        .view
        .unwrap();
    assert_eq!(view.eye, glam::Vec3::new(0.0, 1.0, 5.0));
    assert_eq!(view.up, glam::Vec3::Y, "up defaults to +Y");
    assert_eq!(view.vfov_deg, Some(40.0));
    assert!(Settings::default().camera_options().view.is_none());
}

#[test]
fn the_filter_is_one_string_setting_checked_once() {
    use crate::camera::PixelFilter;
    let s = Settings::from_json(&changes(json!({"filter": "gaussian:stddev=0.4"}))).unwrap();
    assert_eq!(
        s.image.filter,
        PixelFilter::Gaussian {
            stddev: 0.4,
            radius: 1.6
        }
    );
    // The wire format writes the canonical spelling, which reads back.
    let json = s.to_json();
    assert_eq!(json["filter"], json!("gaussian:stddev=0.4,radius=1.6"));
    assert_eq!(Settings::from_json(&json).unwrap(), s);
    assert_eq!(
        Settings::default().to_json()["filter"],
        json!("box:radius=0.5")
    );
    // A Mitsuba Gaussian hint gets Mitsuba's radius, 4σ.
    let hints = RenderHints {
        filter: Some(candela_scene::FilterHint::MITSUBA_DEFAULT),
        ..RenderHints::default()
    };
    let resolved = Settings::resolve(&hints, &Map::new()).unwrap();
    assert_eq!(resolved.image.filter, PixelFilter::MITSUBA_DEFAULT);
    assert_eq!(
        resolved.camera_options().filter,
        PixelFilter::MITSUBA_DEFAULT
    );
    for (bad, says) in [
        (
            json!({"filter": "sinc"}),
            "setting `filter` = \"sinc\": unknown filter \"sinc\"",
        ),
        (
            json!({"filter": "tent:radius=9"}),
            "the radius must be in (0, 8] pixels",
        ),
        (json!({"filter": 2}), "setting `filter` = 2"),
    ] {
        let err = refused(bad.clone());
        assert!(err.contains(says), "{bad}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
}
