use super::*;
use candela_render::settings::{Bvh, ToneCurve};

fn parse(args: &[&str]) -> (Cli, ArgMatches) {
    let matches = Cli::command().try_get_matches_from(args).unwrap();
    (Cli::from_arg_matches(&matches).unwrap(), matches)
}

fn explicit(args: &[&str]) -> Map<String, Value> {
    let (cli, m) = parse(args);
    cli.render.explicit_settings(&m)
}

#[test]
fn flags_are_consistent() {
    Cli::command().debug_assert();
}

#[test]
fn cs184_command_line_parses() {
    let (cli, _) = parse(&[
        "candela",
        "-t",
        "2",
        "-s",
        "16",
        "-r",
        "480",
        "360",
        "-f",
        "out.png",
        "scene.dae",
    ]);
    let r = cli.render;
    assert_eq!(r.cs184.resolution, Some(vec![480, 360]));
    assert_eq!(r.settings.sampling.spp, Some(16));
    assert_eq!(r.settings.run.threads, 2);
    assert_eq!(r.scene, Some(PathBuf::from("scene.dae")));
}

#[test]
fn part5_flags_parse() {
    let (cli, _) = parse(&[
        "candela",
        "-a",
        "64",
        "0.05",
        "-p",
        "10",
        "20",
        "30",
        "40",
        "--time",
        "2.5",
        "--exposure",
        "-1.5",
        "--tone",
        "cs184",
        "--tile",
        "8",
        "--bvh",
        "median",
    ]);
    let r = cli.render;
    assert_eq!(r.cs184.adaptive, Some(vec![64.0, 0.05]));
    assert_eq!(r.cs184.cell, Some(vec![10, 20, 30, 40]));
    assert_eq!(r.settings.sampling.time, Some(2.5));
    assert_eq!(r.settings.output.exposure, -1.5);
    assert_eq!(r.settings.output.tone, ToneCurve::Cs184);
    assert_eq!(r.settings.run.bvh, Bvh::Median);
    assert_eq!((r.settings.run.tile, r.settings.sampling.spp), (8, None));
    assert!(Cli::try_parse_from(["candela", "-p", "1", "2", "3"]).is_err());
}

#[test]
fn unknown_flag_is_a_usage_error() {
    let err = Cli::try_parse_from(["candela", "--bogus"]).unwrap_err();
    assert_eq!(err.exit_code(), 2);
}

#[test]
fn only_flags_given_are_explicit() {
    let e = explicit(&["candela", "-s", "8", "-m", "3", "scene.dae"]);
    let keys: Vec<&str> = e.keys().map(String::as_str).collect();
    assert_eq!(keys, ["max_depth", "spp"]);
    assert_eq!(e["spp"], 8);
    // Defaults (clap's default values) are not explicit.
    assert!(explicit(&["candela"]).is_empty());
}

#[test]
fn cs184_spellings_set_the_settings_they_name() {
    let e = explicit(&[
        "candela",
        "-r",
        "64",
        "48",
        "-H",
        "--direct-only",
        "-o",
        "0",
        "--no-roulette",
    ]);
    assert_eq!(
        (e["width"].as_u64(), e["height"].as_u64()),
        (Some(64), Some(48))
    );
    assert_eq!(e["lighting"], "hemisphere");
    assert_eq!(e["integrator"], "direct");
    assert_eq!(e["accumulate"], false);
    assert_eq!(e["roulette"], false);
    let s = Settings::from_json(&e).unwrap();
    // As the CS184 program: --direct-only wins over -o 0.
    assert_eq!(s.integrator.bounces(), 0..=1);
    assert_eq!(explicit(&["candela", "--normals"])["integrator"], "normals");
    assert_eq!(explicit(&["candela", "--light-only"])["lighting"], "light");
    assert_eq!(
        explicit(&["candela", "--integrator", "indirect"])["integrator"],
        "indirect"
    );
    assert!(Cli::try_parse_from(["candela", "--normals", "--integrator", "path"]).is_err());
}

#[test]
fn every_setting_has_a_flag_or_a_cs184_spelling() {
    // A setting the command line cannot reach would be silently missing
    // from one front end.
    let cmd = Cli::command();
    let ids: Vec<String> = cmd
        .get_arguments()
        .map(|a| a.get_id().to_string())
        .collect();
    let spelled = ["adaptive", "cell"];
    for key in Settings::default().to_json().keys() {
        assert!(
            ids.contains(key) || spelled.contains(&key.as_str()),
            "setting `{key}` has no command-line flag"
        );
    }
}

#[test]
fn a_cs184_flag_given_twice_keeps_its_last_values() {
    let e = explicit(&[
        "candela", "-r", "48", "36", "-r", "64", "40", "-p", "0", "0", "8", "8", "-p", "1", "1",
        "4", "4",
    ]);
    assert_eq!(
        (e["width"].as_u64(), e["height"].as_u64()),
        (Some(64), Some(40))
    );
    assert_eq!(e["cell"]["x"], 1);
}

#[test]
fn the_camera_flags_parse_and_need_each_other() {
    let e = explicit(&[
        "candela",
        "--eye",
        "1,2,3",
        "--look-at=-1,0,0.5",
        "--fov",
        "30",
    ]);
    assert_eq!(e["eye"], serde_json::json!([1.0, 2.0, 3.0]));
    assert_eq!(e["look_at"], serde_json::json!([-1.0, 0.0, 0.5]));
    assert_eq!(e["fov"], serde_json::json!(30.0));
    for bad in [
        &["--eye", "1,2,3"][..],
        &["--eye", "1,2", "--look-at", "0,0,0"],
    ] {
        let args = std::iter::once("candela").chain(bad.iter().copied());
        assert!(
            Cli::command().try_get_matches_from(args).is_err(),
            "{bad:?}"
        );
    }
}

#[test]
fn view_takes_the_render_settings() {
    let (cli, matches) = parse(&[
        "candela",
        "view",
        "--no-browser",
        "-r",
        "160",
        "120",
        "-s",
        "4",
        "x.dae",
    ]);
    let Some(Command::View(view)) = cli.command else {
        panic!("not the view command");
    };
    assert!(view.no_browser);
    let sub = matches.subcommand_matches("view").unwrap();
    let e = explicit_settings(&view.settings, &view.cs184, sub);
    let mut keys: Vec<&str> = e.keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(keys, ["height", "spp", "width"]);
}

/// An optional-value flag before the scene takes its value only after `=`:
/// `--hide-emitters scene.xml` hides emitters and renders scene.xml (a
/// space-separated value swallowed the path and failed as "not a boolean").
#[test]
fn optional_boolean_flags_leave_the_scene_path_alone() {
    for flag in ["--hide-emitters", "--denoise"] {
        let (cli, _) = parse(&["candela", flag, "scene.xml"]);
        assert_eq!(cli.render.scene, Some(PathBuf::from("scene.xml")), "{flag}");
    }
    let (cli, _) = parse(&["candela", "--hide-emitters", "scene.xml"]);
    assert!(cli.render.settings.integrator.hide_emitters);
    let (cli, _) = parse(&["candela", "--hide-emitters=false", "scene.xml"]);
    assert!(!cli.render.settings.integrator.hide_emitters);
}
