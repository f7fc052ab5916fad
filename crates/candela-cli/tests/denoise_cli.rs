//! `candela --denoise`: the denoised image beside the raw one, and a clear
//! refusal before rendering where Open Image Denoise cannot be loaded.

use candela_testkit::{optional_dependency, TempDir};
use std::process::Command;

fn candela(env: &[(&str, &str)], args: &[&str]) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_candela"));
    cmd.args(["-r", "32", "24", "-t", "2", "-q"]).args(args);
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("candela runs")
}

const DEMO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/demo.dae");

#[test]
fn without_the_library_denoise_is_refused_before_rendering() {
    let dir = TempDir::new("denoise-missing");
    let out = dir.join("out.png");
    let missing = dir.join("no-such-lib.so");
    let run = candela(
        &[("CANDELA_OIDN_LIB", missing.to_str().unwrap())],
        // `--denoise` takes no value unless written `--denoise=BOOL`: the
        // scene after it stays the scene.
        &["-s", "1", "-f", out.to_str().unwrap(), "--denoise", DEMO],
    );
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("candela: error: --denoise: CANDELA_OIDN_LIB="),
        "{stderr}"
    );
    assert!(!out.exists(), "nothing is rendered");
    // Without --denoise the same environment renders as always.
    let run = candela(
        &[("CANDELA_OIDN_LIB", missing.to_str().unwrap())],
        &["-s", "1", "-f", out.to_str().unwrap()],
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(out.is_file());
}

#[test]
fn denoise_writes_its_own_file_and_keeps_the_raw_image() {
    let loaded = candela_image::denoise::Oidn::load().map(|o| o.library_path().to_path_buf());
    let Some(library) = optional_dependency(loaded, "CANDELA_REQUIRE_OIDN") else {
        return;
    };
    let dir = TempDir::new("denoise-files");
    for ext in ["png", "exr"] {
        let out = dir.join(format!("out.{ext}"));
        let run = candela(
            &[("CANDELA_OIDN_LIB", library.to_str().unwrap())],
            &["--denoise=true", "-s", "4", "-f", out.to_str().unwrap()],
        );
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(out.is_file());
        assert!(dir.join(format!("out.denoised.{ext}")).is_file());
    }
}
