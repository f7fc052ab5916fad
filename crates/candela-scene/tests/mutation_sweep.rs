//! The mutation sweep: the repository's own scenes in every format, each
//! with a fixed, seeded set of mutants (truncations, byte flips and
//! deletions, numbers replaced by huge, non-finite, negative and zero
//! values, counts set to billions, references pointed at nothing; the set
//! is `candela_testkit::scene_mutants`). Every mutant must load or fail
//! with one line naming the file, within a time limit, without a panic,
//! and without any single allocation over [`ALLOCATION_LIMIT`] (the
//! capped allocator aborts the run, naming the mutant, on the first).

use candela_scene::{load, LoadError, LoadOptions};
use candela_testkit::capped_alloc::CappedAlloc;
use candela_testkit::guard::{assert_all_behaved, guarded, Outcome};
use candela_testkit::scene_mutants::{scene_mutants, SceneMutant};
use candela_testkit::TempDir;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// The scenes are under 200 KB; no honest load of a mutant needs more in
/// one piece than this.
const ALLOCATION_LIMIT: usize = 256 << 20;

#[global_allocator]
static ALLOCATOR: CappedAlloc = CappedAlloc::new(ALLOCATION_LIMIT);

/// Generous for a loaded two-core machine: an honest load takes a few
/// milliseconds, a loop over a 4-billion count takes seconds.
const TIME_LIMIT: Duration = Duration::from_secs(3);

/// A count of billions must be refused before anything is allocated or
/// looped over: well under the hang limit.
const HUGE_COUNT_LIMIT: Duration = Duration::from_secs(1);

/// An error line's length past the file's path: room for a located
/// message with a quoted token, not for quoted binary data.
const MESSAGE_CHARS: usize = 400;

/// How one mutant's load went wrong, if it did.
fn problem(m: &SceneMutant, path: PathBuf, opts: LoadOptions) -> Option<String> {
    CappedAlloc::label(&m.label());
    let path_chars = path.display().to_string().chars().count();
    let outcome = guarded(TIME_LIMIT, move || load(&path, &opts).map(|_| ()));
    match outcome {
        Outcome::Returned(_, t) if asks_for_billions(m) && t > HUGE_COUNT_LIMIT => {
            Some(format!("took {t:?} to answer a count of billions"))
        }
        Outcome::Returned(Ok(()), _) => None,
        Outcome::Returned(Err(e), _) => badly_worded(&e, m, path_chars),
        Outcome::Panicked(message) => Some(format!("panicked: {message}")),
        Outcome::TimedOut => Some(format!("still loading after {TIME_LIMIT:?}")),
    }
}

fn asks_for_billions(m: &SceneMutant) -> bool {
    ["4294967295", "18446744073709551615", "2147483648"]
        .iter()
        .any(|n| m.mutant.name.ends_with(n))
}

/// The project's rule for an error: one short line of printable text,
/// naming the loaded file or the mutated one it draws.
fn badly_worded(e: &LoadError, m: &SceneMutant, path_chars: usize) -> Option<String> {
    let line = e.to_string();
    if line.contains(['\n', '\r']) {
        return Some(format!("error spans lines: {line:?}"));
    }
    if line.chars().any(char::is_control) {
        return Some(format!("error has control characters: {line:?}"));
    }
    if line.chars().count() > path_chars + MESSAGE_CHARS {
        return Some(format!("error is {} characters long: {line}", line.len()));
    }
    if !line.contains(&m.load) && !line.contains(&m.mutated) {
        return Some(format!("error names neither file: {line}"));
    }
    None
}

fn sweep(strict: bool) {
    let dir = TempDir::new("mutation-sweep");
    let mutants = scene_mutants();
    assert!(mutants.len() >= 300, "only {} mutants", mutants.len());
    let start = Instant::now();
    let mut failures = Vec::new();
    for m in &mutants {
        let path = m.stage(dir.path());
        let opts = LoadOptions {
            strict,
            ..Default::default()
        };
        if let Some(p) = problem(m, path, opts) {
            failures.push(format!("{}: {p}", m.label()));
        }
    }
    CappedAlloc::label("");
    assert_all_behaved(
        mutants.len(),
        &failures,
        start,
        &format!("strict: {strict}"),
    );
}

#[test]
fn every_mutant_loads_or_fails_with_one_named_line() {
    sweep(false);
}

#[test]
fn every_mutant_loads_strictly_or_fails_with_one_named_line() {
    sweep(true);
}
