//! The render side of the mutation sweep (`candela-scene`'s
//! `tests/mutation_sweep.rs` sweeps the loaders): every mutant of the
//! repository's scenes that still loads is built into a render-ready
//! [`Scene`] as the CLI builds it. A build must succeed or fail with one
//! line of printable text (the CLI prefixes the file's name), within a time
//! limit, without a panic, and without any single allocation over
//! [`ALLOCATION_LIMIT`]. Textures are read here, so the glTF scene's
//! mutated PNG is first decoded in this sweep.

use candela_render::scene::{Scene, SceneOptions};
use candela_scene::{load, LoadOptions};
use candela_testkit::capped_alloc::CappedAlloc;
use candela_testkit::guard::{assert_all_behaved, guarded, Outcome};
use candela_testkit::scene_mutants::scene_mutants;
use candela_testkit::TempDir;
use std::time::{Duration, Instant};

/// The scenes are under 200 KB; no honest build of a mutant needs more in
/// one piece than this.
const ALLOCATION_LIMIT: usize = 256 << 20;

#[global_allocator]
static ALLOCATOR: CappedAlloc = CappedAlloc::new(ALLOCATION_LIMIT);

/// Generous for a loaded two-core machine: an honest load and build of
/// these scenes takes milliseconds.
const TIME_LIMIT: Duration = Duration::from_secs(5);

/// What the guarded call reports: how far the mutant got.
enum Reached {
    NotLoaded,
    Built,
    Refused(String),
}

#[test]
fn every_mutant_that_loads_builds_or_fails_with_one_line() {
    let dir = TempDir::new("mutation-build");
    let mutants = scene_mutants();
    let start = Instant::now();
    let (mut built, mut refused, mut failures) = (0, 0, Vec::new());
    for m in &mutants {
        let path = m.stage(dir.path());
        CappedAlloc::label(&m.label());
        let outcome = guarded(TIME_LIMIT, move || {
            let Ok(loaded) = load(&path, &LoadOptions::default()) else {
                return Reached::NotLoaded;
            };
            match Scene::build(&loaded.scene, &SceneOptions::default()) {
                Ok(_) => Reached::Built,
                Err(e) => Reached::Refused(e.to_string()),
            }
        });
        let problem = match outcome {
            Outcome::Returned(Reached::NotLoaded, _) => None,
            Outcome::Returned(Reached::Built, _) => {
                built += 1;
                None
            }
            Outcome::Returned(Reached::Refused(line), _) => {
                refused += 1;
                (line.chars().any(char::is_control) || line.len() > 400)
                    .then(|| format!("error is not one short printable line: {line:?}"))
            }
            Outcome::Panicked(message) => Some(format!("panicked: {message}")),
            Outcome::TimedOut => Some(format!("still building after {TIME_LIMIT:?}")),
        };
        if let Some(p) = problem {
            failures.push(format!("{}: {p}", m.label()));
        }
    }
    CappedAlloc::label("");
    let summary = format!("{built} loaded and built, {refused} loaded and refused");
    assert_all_behaved(mutants.len(), &failures, start, &summary);
}
