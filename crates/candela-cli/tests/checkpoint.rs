//! `--checkpoint` and `candela resume` end to end: a render killed with
//! SIGKILL after a checkpoint resumes to the uninterrupted image bit for bit;
//! checkpoints of another scene or other settings, and damaged ones, are
//! refused with one line and exit code 2; a very long render's checkpoint
//! stays the size of its film and its memory does not grow.

use candela_image::read_exr_layers;
use candela_testkit::TempDir;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn candela() -> Command {
    Command::new(env!("CARGO_BIN_EXE_candela"))
}

fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temp path")
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("candela runs")
}

/// The error line of a refused command: exit code 2, one line, no panic.
fn refused(out: &Output) -> String {
    let log = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{log}");
    assert!(!log.contains("panicked"), "{log}");
    assert_eq!(log.trim_end().lines().count(), 1, "{log}");
    log
}

/// Waits (polling, no fixed sleep) until `file` exists.
fn wait_for(file: &Path, child: &mut std::process::Child) {
    let deadline = Instant::now() + Duration::from_secs(120);
    while !file.exists() {
        assert!(
            child.try_wait().expect("child state").is_none(),
            "the render ended before writing a checkpoint"
        );
        assert!(Instant::now() < deadline, "no checkpoint after 120 s");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Every layer of an EXR with every float printed exactly (Debug prints the
/// shortest text that reads back to the same bits, -0 included).
/// Every layer of an EXR, bit for bit, without the header's render
/// metadata (the render time differs between any two runs).
fn layers(file: &Path) -> String {
    let mut layers = read_exr_layers(file).expect("EXR reads");
    layers.info = Default::default();
    format!("{layers:?}")
}

#[cfg(unix)]
#[test]
fn a_render_killed_after_a_checkpoint_resumes_to_the_same_image_bit_for_bit() {
    use std::os::unix::process::ExitStatusExt;
    let dir = TempDir::new("ckpt-kill");
    let (reference, out, ck) = (dir.join("ref.exr"), dir.join("out.exr"), dir.join("ck"));
    // Adaptive sampling too: its stop decisions must be read back from the
    // sums of the checkpoint.
    let flags = [
        "-r", "24", "18", "-t", "2", "-s", "256", "-a", "16", "0.02", "--seed", "5", "-q",
    ];
    let whole = run(candela().args(flags).args(["-f", path(&reference)]));
    assert!(whole.status.success());
    let mut child = candela()
        .args(flags)
        .args(["-f", path(&out), "--checkpoint", path(&ck)])
        .args(["--checkpoint-every", "0"])
        .stderr(Stdio::null())
        .spawn()
        .expect("candela starts");
    wait_for(&ck, &mut child);
    child.kill().expect("SIGKILL");
    let status = child.wait().expect("candela ends");
    assert_eq!(status.signal(), Some(9), "killed, not finished");
    assert!(!out.exists(), "a killed render writes no image");
    let resumed = run(candela().args(["resume", path(&ck), "-t", "1"]));
    let log = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{log}");
    assert!(log.contains("continuing"), "{log}");
    assert!(
        layers(&out) == layers(&reference),
        "the resumed image differs from the uninterrupted one"
    );
    // The finished checkpoint resumes to the same image again, at once.
    std::fs::remove_file(&out).unwrap();
    assert!(run(candela().args(["resume", path(&ck), "-q"]))
        .status
        .success());
    assert!(layers(&out) == layers(&reference));
}

#[test]
fn a_finished_render_resumed_to_more_samples_is_the_render_of_that_many() {
    let dir = TempDir::new("ckpt-more");
    let (reference, out, ck) = (dir.join("ref.exr"), dir.join("out.exr"), dir.join("ck"));
    // Adaptive sampling too: a pixel that stopped stays stopped, one that
    // used all 32 samples continues where it was.
    let flags = [
        "-r", "24", "18", "-t", "2", "-a", "16", "0.05", "--seed", "3", "-q",
    ];
    let whole = run(candela()
        .args(flags)
        .args(["-s", "128", "-f", path(&reference)]));
    assert!(whole.status.success());
    let first =
        run(candela()
            .args(flags)
            .args(["-s", "32", "-f", path(&out), "--checkpoint", path(&ck)]));
    assert!(first.status.success());
    assert!(layers(&out) != layers(&reference), "32 and 128 spp differ");
    let log = refused(&run(candela().args(["resume", path(&ck), "-s", "16"])));
    assert!(log.contains("spp = 32 in the checkpoint, 16 here"), "{log}");
    let log = refused(&run(candela().args([
        "resume",
        path(&ck),
        "--dask",
        "local:1",
    ])));
    assert!(
        log.contains("--dask applies to a distributed render"),
        "{log}"
    );
    let more = run(candela().args(["resume", path(&ck), "-s", "128", "-t", "1"]));
    assert!(
        more.status.success(),
        "{}",
        String::from_utf8_lossy(&more.stderr)
    );
    assert!(
        layers(&out) == layers(&reference),
        "the render resumed to 128 spp differs from one started with 128"
    );
}

#[test]
fn a_checkpoint_of_other_settings_or_another_scene_is_refused() {
    let dir = TempDir::new("ckpt-mismatch");
    let scene = dir.join("box.dae");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/demo.dae");
    std::fs::copy(&source, &scene).expect("scene copies");
    let (out, ck) = (dir.join("out.png"), dir.join("ck"));
    let render = |seed: &str| {
        run(candela()
            .args(["-r", "12", "9", "-t", "2", "-s", "4", "-q", "--seed", seed])
            .args(["-f", path(&out), "--checkpoint", path(&ck), path(&scene)]))
    };
    assert!(render("1").status.success());
    assert!(ck.exists());
    // The same command again continues the (finished) checkpoint.
    assert!(render("1").status.success());
    let log = refused(&render("2"));
    assert!(log.contains("seed = 1 in the checkpoint, 2 here"), "{log}");
    // Move the floor: another scene.
    let text = std::fs::read_to_string(&scene).unwrap();
    let moved = text.replace(
        "-1 -1 0 1 -1 0 1 1 0 -1 1 0",
        "-1 -1 0.1 1 -1 0.1 1 1 0 -1 1 0",
    );
    assert_ne!(text, moved);
    std::fs::write(&scene, moved).unwrap();
    let log = refused(&run(candela().args(["resume", path(&ck)])));
    assert!(log.contains("another scene"), "{log}");
    let log = refused(&render("1"));
    assert!(log.contains("another scene"), "{log}");
}

#[test]
fn a_damaged_checkpoint_is_one_line_and_exit_2() {
    let dir = TempDir::new("ckpt-damaged");
    let (out, ck) = (dir.join("out.png"), dir.join("ck"));
    let made = run(candela()
        .args(["-r", "12", "9", "-t", "2", "-s", "2", "-q"])
        .args(["-f", path(&out), "--checkpoint", path(&ck)]));
    assert!(made.status.success());
    let bytes = std::fs::read(&ck).unwrap();
    let damaged = dir.join("damaged");
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 1;
    let cases: [(&[u8], &str); 4] = [
        (&bytes[..bytes.len() / 2], "truncated"),
        (&flipped, "corrupt"),
        (b"", "not a candela checkpoint"),
        (b"P6 not a checkpoint at all", "not a candela checkpoint"),
    ];
    for (content, expect) in cases {
        std::fs::write(&damaged, content).unwrap();
        let log = refused(&run(candela().args(["resume", path(&damaged)])));
        assert!(log.contains(expect), "{log}");
    }
    let log = refused(&run(candela().args(["resume", path(&dir.join("missing"))])));
    assert!(log.contains("cannot read the checkpoint"), "{log}");
}

/// Peak resident memory (VmHWM, KiB) of a running process, polled until it
/// exits; returns the last value read and the exit status.
#[cfg(target_os = "linux")]
fn peak_rss(mut child: std::process::Child) -> (u64, std::process::ExitStatus) {
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    loop {
        if let Some(status) = child.try_wait().expect("child state") {
            return (peak, status);
        }
        let text = std::fs::read_to_string(&status_file).unwrap_or_default();
        if let Some(line) = text.lines().find(|l| l.starts_with("VmHWM:")) {
            let kib = line.split_whitespace().nth(1).and_then(|v| v.parse().ok());
            peak = peak.max(kib.unwrap_or(0));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_million_spp_render_stays_the_size_of_its_film() {
    // 8x8 pixels at up to 1,000,000 spp, stopped by --time: the checkpoint
    // is the film (64 pixels x 144 bytes) plus a header, and the memory of a
    // run 4 times longer (4 times the passes, samples and checkpoints) is
    // the same up to allocator noise.
    let dir = TempDir::new("ckpt-bounded");
    let sizes: Vec<(u64, u64)> = ["0.5", "2"]
        .iter()
        .map(|time| {
            let ck = dir.join(format!("ck-{time}"));
            let child = candela()
                .args([
                    "-r", "8", "8", "-t", "2", "-s", "1000000", "--time", time, "-q",
                ])
                .args(["-f", path(&dir.join("out.png")), "--checkpoint", path(&ck)])
                .args(["--checkpoint-every", "0"])
                .spawn()
                .expect("candela starts");
            let (peak, status) = peak_rss(child);
            assert!(status.success());
            (std::fs::metadata(&ck).unwrap().len(), peak)
        })
        .collect();
    let film = 64 * 144;
    for &(size, _) in &sizes {
        assert!(
            (film..film + 4096).contains(&size),
            "checkpoint of {size} bytes"
        );
    }
    let (short, long) = (sizes[0].1, sizes[1].1);
    eprintln!("checkpoint bytes and peak KiB after 0.5 s and 2 s: {sizes:?}");
    assert!(short > 0, "VmHWM was read");
    assert!(
        long <= short + 2048,
        "peak memory grew from {short} KiB to {long} KiB with a longer render"
    );
}
