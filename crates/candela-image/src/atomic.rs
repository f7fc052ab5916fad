//! Atomic file output: a file appears complete at its final path, or not at all.
//!
//! A render that takes hours must not leave a truncated PNG behind when the
//! disk fills or the process is killed, and a viewer polling the output must
//! never read half a file. So every writer goes through [`atomic_write`]:
//! write to a temporary file in the same folder (same file system, so the
//! rename is atomic), flush and fsync it, then rename it onto the final path.
//! On any error, or a panic in the caller's writer, the temporary is removed
//! and whatever was at the final path before is left untouched.

use std::fs::{self, File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{BoxError, ImageError};

/// Distinguishes temporaries of concurrent writes within one process.
static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Checks, before hours of rendering, that [`atomic_write`] will be able to
/// create its temporary beside `path`: creates that temporary and removes
/// it again. Nothing is left at `path` or beside it.
///
/// # Errors
/// [`ImageError::Io`] naming `path` (a missing folder, no permission, a
/// read-only file system).
pub fn check_writable(path: impl AsRef<Path>) -> Result<(), ImageError> {
    let path = path.as_ref();
    if path.is_dir() {
        return Err(ImageError::InvalidArgument(format!(
            "output path {} is a folder",
            path.display()
        )));
    }
    let temp_path = temp_path_for(path)?;
    OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temp_path)
        .map_err(|source| ImageError::Io {
            action: "cannot create",
            path: path.to_path_buf(),
            source,
        })?;
    drop(RemoveOnDrop(Some(temp_path)));
    Ok(())
}

/// Writes a file atomically: `write` fills a buffered temporary file which
/// then replaces `path` in one rename.
///
/// The temporary is named `.<file name>.tmp-<pid>-<n>` in the folder of
/// `path`, so it is hidden from casual listings and never collides with
/// another process or thread. The writer is seekable because some formats
/// (OpenEXR) patch offsets after writing the data.
///
/// # Errors
/// [`ImageError::Io`] naming `path` if the temporary cannot be created (for
/// example when the folder does not exist), synced or renamed;
/// [`ImageError::Write`] carrying the writer's own error if `write` fails.
/// In every error case nothing new exists at `path` or beside it.
pub fn atomic_write<F, E>(path: impl AsRef<Path>, write: F) -> Result<(), ImageError>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<(), E>,
    E: Into<BoxError>,
{
    let path = path.as_ref();
    let temp_path = temp_path_for(path)?;
    let io_err = |action: &'static str| {
        move |source| ImageError::Io {
            action,
            path: path.to_path_buf(),
            source,
        }
    };
    let file = OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temp_path)
        .map_err(io_err("cannot create"))?;
    // From here on the guard deletes the temporary unless we reach the rename.
    let guard = RemoveOnDrop(Some(temp_path));
    let mut writer = BufWriter::new(file);
    write(&mut writer).map_err(|e| ImageError::Write {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    let file = writer
        .into_inner()
        .map_err(|e| io_err("cannot write")(e.into_error()))?;
    file.sync_all().map_err(io_err("cannot sync"))?;
    drop(file);
    let temp_path = guard.path();
    fs::rename(temp_path, path).map_err(io_err("cannot rename temporary file onto"))?;
    guard.disarm();
    sync_parent_folder(path);
    Ok(())
}

/// The temporary path beside `path`, or an error if `path` names no file.
fn temp_path_for(path: &Path) -> Result<PathBuf, ImageError> {
    let Some(name) = path.file_name() else {
        return Err(ImageError::InvalidArgument(format!(
            "output path {} does not name a file",
            path.display()
        )));
    };
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut temp_name = std::ffi::OsString::from(".");
    temp_name.push(name);
    temp_name.push(format!(".tmp-{}-{n}", std::process::id()));
    Ok(path.with_file_name(temp_name))
}

/// Makes the rename itself durable by syncing the folder entry. Best effort:
/// some file systems refuse to sync folders, and the file is already
/// complete and in place, so a failure here is not worth reporting.
fn sync_parent_folder(path: &Path) {
    #[cfg(unix)]
    {
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if let Ok(folder) = File::open(parent) {
            let _ = folder.sync_all();
        }
    }
    #[cfg(not(unix))]
    let _ = path;
}

/// Removes the temporary file when dropped, unless disarmed after a rename.
struct RemoveOnDrop(Option<PathBuf>);

impl RemoveOnDrop {
    fn path(&self) -> &Path {
        self.0.as_deref().unwrap_or(Path::new(""))
    }

    fn disarm(mut self) {
        self.0 = None;
    }
}

impl Drop for RemoveOnDrop {
    fn drop(&mut self) {
        if let Some(path) = self.0.take() {
            let _ = fs::remove_file(path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use candela_testkit::TempDir;
    use std::io::Write;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writes_the_whole_file_and_nothing_else() {
        let dir = TempDir::new("atomic-ok");
        let path = dir.path().join("out.txt");
        atomic_write(&path, |w| w.write_all(b"hello")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"hello");
        assert_eq!(entries(dir.path()), vec!["out.txt"]);
    }

    #[test]
    fn a_writer_failing_midway_leaves_no_file_and_no_temporary() {
        let dir = TempDir::new("atomic-fail");
        let path = dir.path().join("out.bin");
        let result = atomic_write(&path, |w| {
            w.write_all(&[7u8; 100_000])?;
            Err(std::io::Error::other("disk full (simulated)"))
        });
        let err = result.unwrap_err();
        assert!(matches!(err, ImageError::Write { .. }));
        let message = err.to_string();
        assert!(
            message.contains("out.bin") && message.contains("simulated"),
            "{message}"
        );
        assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
    }

    #[test]
    fn a_failure_keeps_the_previous_file_intact() {
        let dir = TempDir::new("atomic-keep");
        let path = dir.path().join("out.txt");
        atomic_write(&path, |w| w.write_all(b"old")).unwrap();
        let result = atomic_write(&path, |w| {
            w.write_all(b"new but broken")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(result.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"old");
        assert_eq!(entries(dir.path()), vec!["out.txt"]);
    }

    #[test]
    fn a_panicking_writer_leaves_no_temporary() {
        let dir = TempDir::new("atomic-panic");
        let path = dir.path().join("out.txt");
        let caught = std::panic::catch_unwind(|| {
            let _ = atomic_write(&path, |w| -> std::io::Result<()> {
                w.write_all(b"partial")?;
                panic!("writer bug (deliberate)");
            });
        });
        assert!(caught.is_err());
        assert!(entries(dir.path()).is_empty());
    }

    #[test]
    fn a_missing_folder_gives_an_error_naming_the_path() {
        let dir = TempDir::new("atomic-nofolder");
        let path = dir.path().join("no-such-folder").join("out.png");
        let err = atomic_write(&path, |w| w.write_all(b"x")).unwrap_err();
        assert!(matches!(err, ImageError::Io { .. }));
        let message = err.to_string();
        assert!(message.contains(&path.display().to_string()), "{message}");
        assert!(!path.exists());
    }

    #[test]
    fn a_path_without_file_name_is_rejected() {
        let err = atomic_write("..", |w| w.write_all(b"x")).unwrap_err();
        assert!(matches!(err, ImageError::InvalidArgument(_)));
    }
}
