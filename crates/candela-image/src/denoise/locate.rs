//! Where Open Image Denoise's shared library may be, in the order tried.
//!
//! 1. `CANDELA_OIDN_LIB`: the library file, or the folder holding it. When
//!    it is set, nothing else is tried (so a wrong value is an error, not a
//!    silent fallback to another copy).
//! 2. Folders the caller knows (the Python package passes the `pyoidn`
//!    package of its own interpreter).
//! 3. The `pyoidn` package of the Python interpreter on the path
//!    (`$CANDELA_PYTHON`, else `python3`): its wheel ships the library in
//!    `pyoidn/oidn/lib`, with TBB beside it (found through its `$ORIGIN`
//!    run path). `pip install pyoidn` is therefore all a user needs.
//! 4. The system's library search path (a distribution's `libopenimagedenoise`).

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable naming the library (file or folder).
pub const LIB_ENV: &str = "CANDELA_OIDN_LIB";

/// The library's file names, newest major version first.
pub(super) const FILE_NAMES: &[&str] = if cfg!(target_os = "windows") {
    &["OpenImageDenoise.dll"]
} else if cfg!(target_os = "macos") {
    &[
        "libOpenImageDenoise.2.dylib",
        "libOpenImageDenoise.1.dylib",
        "libOpenImageDenoise.dylib",
    ]
} else {
    &[
        "libOpenImageDenoise.so.2",
        "libOpenImageDenoise.so.1",
        "libOpenImageDenoise.so",
    ]
};

/// Where to look: one explicit place, or a list of candidates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) enum Search {
    /// `CANDELA_OIDN_LIB` was set: only these files (the path itself, or
    /// the library names inside the folder it names).
    Explicit(OsString, Vec<PathBuf>),
    /// Files to try in order; bare file names go to the system's search.
    Candidates(Vec<PathBuf>),
}

/// The search for this process: `CANDELA_OIDN_LIB`, else `hint_dirs`, the
/// path interpreter's `pyoidn`, and the system.
pub(super) fn search(hint_dirs: &[PathBuf]) -> Search {
    if let Some(value) = std::env::var_os(LIB_ENV).filter(|v| !v.is_empty()) {
        let files = in_place(Path::new(&value));
        return Search::Explicit(value, files);
    }
    let mut files: Vec<PathBuf> = hint_dirs.iter().flat_map(|d| in_folder(d)).collect();
    if let Some(dir) = pyoidn_lib_dir() {
        files.extend(in_folder(&dir));
    }
    files.extend(FILE_NAMES.iter().map(PathBuf::from));
    Search::Candidates(files)
}

/// The library files a path names: itself if it is a file, else the
/// library's names inside it.
fn in_place(path: &Path) -> Vec<PathBuf> {
    if path.is_dir() {
        in_folder(path)
    } else {
        vec![path.to_path_buf()]
    }
}

/// The library's names inside `dir` that exist.
fn in_folder(dir: &Path) -> Vec<PathBuf> {
    FILE_NAMES
        .iter()
        .map(|name| dir.join(name))
        .filter(|p| p.is_file())
        .collect()
}

/// The library folder of the `pyoidn` wheel installed for the Python on the
/// path, asked without importing the package.
fn pyoidn_lib_dir() -> Option<PathBuf> {
    let python = std::env::var_os("CANDELA_PYTHON").unwrap_or_else(|| "python3".into());
    let probe = "import importlib.util as u, os\n\
                 s = u.find_spec('pyoidn')\n\
                 print(os.path.join(os.path.dirname(s.origin), 'oidn', 'lib') if s and s.origin else '')";
    let out = Command::new(python).args(["-c", probe]).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    let dir = PathBuf::from(text.trim());
    (out.status.success() && !text.trim().is_empty() && dir.is_dir()).then_some(dir)
}

/// `pyoidn`'s library folder inside a package folder (what the Python
/// package finds with `importlib`).
pub fn pyoidn_lib_folder(package_dir: &Path) -> PathBuf {
    package_dir.join("oidn").join("lib")
}
