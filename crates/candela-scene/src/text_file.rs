//! Reading a scene file, for every format: the size guard, UTF-8 checking
//! with the place of the first bad byte, and byte offsets turned into
//! `line:col`.

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use std::path::Path;

/// Largest scene file accepted, in bytes: a wrong path to a huge file fails
/// fast instead of being read.
pub(crate) const MAX_FILE_BYTES: u64 = 512 << 20;

/// Reads `path` as bytes, refusing files over [`MAX_FILE_BYTES`].
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, LoadError> {
    let io =
        |e: std::io::Error| LoadError::whole_file(path.to_path_buf(), ErrorKind::Io, e.to_string());
    let meta = std::fs::metadata(path).map_err(io)?;
    if meta.len() > MAX_FILE_BYTES {
        return Err(LoadError::whole_file(
            path.to_path_buf(),
            ErrorKind::TooLarge,
            format!("{} bytes exceeds the limit of {MAX_FILE_BYTES}", meta.len()),
        ));
    }
    crate::referenced::note_read(path);
    std::fs::read(path).map_err(io)
}

/// Reads `path` as UTF-8 text, refusing files over [`MAX_FILE_BYTES`]; text
/// that is not UTF-8 is an [`ErrorKind::NotXml`] error (the XML formats'
/// kind; line-based formats use [`utf8`] with [`ErrorKind::NotText`]).
pub(crate) fn read_text(path: &Path) -> Result<String, LoadError> {
    utf8(read_bytes(path)?, path, ErrorKind::NotXml)
}

/// `bytes` as UTF-8 text, or a `kind` error at the first bad byte.
pub(crate) fn utf8(bytes: Vec<u8>, path: &Path, kind: ErrorKind) -> Result<String, LoadError> {
    String::from_utf8(bytes).map_err(|e| {
        let byte = e.utf8_error().valid_up_to();
        let valid = std::str::from_utf8(&e.as_bytes()[..byte]).unwrap_or("");
        LoadError {
            loc: Some(loc_in(valid, byte)),
            ..LoadError::whole_file(path.to_path_buf(), kind, "not UTF-8 text".into())
        }
    })
}

/// Line and column (1-based, columns in characters) of byte `byte` of `text`.
pub(crate) fn loc_in(text: &str, byte: usize) -> SourceLoc {
    let mut byte = byte.min(text.len());
    while !text.is_char_boundary(byte) {
        byte -= 1;
    }
    let before = &text[..byte];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = before.bytes().filter(|&b| b == b'\n').count() + 1;
    let col = before[line_start..].chars().count() + 1;
    SourceLoc {
        line: u32::try_from(line).unwrap_or(u32::MAX),
        col: u32::try_from(col).unwrap_or(u32::MAX),
    }
}
