//! Helpers shared by every crate's tests, written once: a temporary folder
//! that cleans up after itself, a small seeded generator for statistical
//! tests, the way to the shared scene corpus beside the repository, and
//! the pieces of bad-input sweeps (seeded mutations, a panic and hang
//! guard, an allocator that refuses absurd requests).
#![warn(missing_docs)]

pub mod capped_alloc;
pub mod glb;
pub mod guard;
pub mod mutate;
pub mod scene_mutants;

use glam::Vec3;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A fresh, empty folder under the system temporary folder, removed with
/// its contents when dropped.
pub struct TempDir(PathBuf);

impl TempDir {
    /// Creates `candela-<label>-<pid>-<n>`.
    ///
    /// # Panics
    /// If the folder cannot be created (a test environment problem).
    pub fn new(label: &str) -> Self {
        static N: AtomicU64 = AtomicU64::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("candela-{label}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create test folder");
        Self(path)
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.0
    }

    /// A path inside the folder.
    pub fn join(&self, name: impl AsRef<Path>) -> PathBuf {
        self.0.join(name)
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// One file in a folder of its own, both removed when dropped; it derefs
/// to the file's path, so `load(&temp_file(..))` cleans up after the call.
pub struct TempFile {
    path: PathBuf,
    _dir: TempDir,
}

impl TempFile {
    /// Writes `bytes` to `name` in a fresh [`TempDir`] labelled `label`.
    ///
    /// # Panics
    /// If the file cannot be written (a test environment problem).
    pub fn new(label: &str, name: &str, bytes: &[u8]) -> Self {
        let dir = TempDir::new(label);
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write test file");
        Self { path, _dir: dir }
    }
}

impl std::ops::Deref for TempFile {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for TempFile {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// A small deterministic generator (SplitMix64, Steele et al. 2014) so
/// statistical tests use fixed seeds and every failure reproduces. The
/// field is the state: `SplitMix64(seed)`.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// A generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 53 bits of precision.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[0, 1)` as an `f32` (24 bits).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }

    /// A point uniform in the cube `[lo, hi)^3`.
    pub fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }

    /// A direction uniform on the unit sphere (by rejection).
    pub fn dir(&mut self) -> Vec3 {
        loop {
            let v = self.vec(-1.0, 1.0);
            if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }

    /// 10^x for x uniform in `[lo, hi]`: scales spread over decades.
    pub fn log(&mut self, lo: f32, hi: f32) -> f32 {
        10f32.powf(lo + (hi - lo) * self.f32())
    }
}

/// The folder `shared/` beside the repository (the CS184 corpus and the
/// benchmark data), found from this crate's location.
///
/// # Panics
/// If it is missing: a test that needs the corpus fails rather than passing
/// without it.
pub fn shared_dir() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    // crates/candela-testkit -> repository -> its parent.
    let shared = here.join("../../../shared");
    assert!(
        shared.join("scenes").is_dir(),
        "the shared corpus is missing: expected {} beside the repository (CI lays it there)",
        shared.display()
    );
    shared
}

/// A CS184 scene of the shared corpus, e.g. `cs184_scene("CBbunny.dae")`.
///
/// # Panics
/// If the corpus or the file is missing.
pub fn cs184_scene(name: &str) -> PathBuf {
    let path = shared_dir().join("scenes/cs184").join(name);
    assert!(path.is_file(), "missing CS184 scene {}", path.display());
    path
}

/// For tests that need something optional (a shared library a user may not
/// have): `Ok(x)` is used; on `Err(why)` the test skips with a printed
/// reason, unless the environment variable `require` is `1`, which CI sets
/// where it installed the dependency, and then the test fails. So a plain
/// `cargo test` is green on any machine, and CI cannot skip silently.
pub fn optional_dependency<T, E: std::fmt::Display>(
    found: Result<T, E>,
    require: &str,
) -> Option<T> {
    match found {
        Ok(x) => Some(x),
        Err(why) if std::env::var(require).as_deref() == Ok("1") => {
            panic!("{require}=1 but the dependency is unavailable: {why}")
        }
        Err(why) => {
            eprintln!("skipped (set {require}=1 to make this a failure): {why}");
            None
        }
    }
}
