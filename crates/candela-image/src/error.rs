//! The one error type of this crate.
//!
//! Every variant that concerns a file names it, so a caller printing the error
//! (or an `anyhow` chain in the binary) tells the user which file failed.

use std::path::PathBuf;

/// A boxed error from an encoder, decoder or caller-supplied writer.
///
/// Boxed so that [`crate::atomic_write`] can carry any writer's error without
/// this crate knowing its type.
pub type BoxError = Box<dyn std::error::Error + Send + Sync + 'static>;

/// Errors from building, reading, writing or comparing images.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The operating system refused an operation on a file (open, create,
    /// fsync, rename, read).
    #[error("{action} {path}: {source}")]
    Io {
        /// What we were doing, e.g. "cannot create temporary file for".
        action: &'static str,
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Encoding into a file failed (PNG or EXR encoder, or the caller's
    /// writer in [`crate::atomic_write`]); nothing was left at `path`.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The final path that was not written.
        path: PathBuf,
        /// The encoder's or writer's error.
        source: BoxError,
    },
    /// A file could not be decoded (corrupt, truncated, unsupported layout).
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file that could not be decoded.
        path: PathBuf,
        /// The decoder's error.
        source: BoxError,
    },
    /// Pixel data does not match the stated dimensions.
    #[error("{what}: expected {expected} values for the image size, got {actual}")]
    BadLength {
        /// Which buffer was wrong.
        what: &'static str,
        /// The number of values the dimensions call for.
        expected: usize,
        /// The number of values given.
        actual: usize,
    },
    /// Two images that must have equal size do not.
    #[error("{what}: image sizes differ ({0}x{1} vs {2}x{3})", .a.0, .a.1, .b.0, .b.1)]
    SizeMismatch {
        /// Which operation needed equal sizes.
        what: &'static str,
        /// Width and height of the first image.
        a: (usize, usize),
        /// Width and height of the second image.
        b: (usize, usize),
    },
    /// The image is too large for the file format or for memory indexing.
    #[error("image of {width}x{height} pixels is too large for {what}")]
    TooLarge {
        /// The format or operation whose limit was exceeded.
        what: &'static str,
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// Files that cannot be combined (different sizes, layers, scenes, or
    /// the same samples twice); the message names the files.
    #[error("{0}")]
    Incompatible(String),
    /// A parameter is outside its meaningful range (e.g. a zero block size).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
}
