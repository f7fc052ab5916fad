//! Reading a text scene file, for every text-based format: the size guard,
//! UTF-8 checking with the place of the first bad byte, and byte offsets
//! turned into `line:col`.

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use std::path::Path;

/// Largest scene file accepted, in bytes: a wrong path to a huge file fails
/// fast instead of being read.
pub(crate) const MAX_FILE_BYTES: u64 = 512 << 20;

/// Reads `path` as UTF-8 text, refusing files over [`MAX_FILE_BYTES`].
pub(crate) fn read_text(path: &Path) -> Result<String, LoadError> {
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
    let bytes = std::fs::read(path).map_err(io)?;
    String::from_utf8(bytes).map_err(|e| {
        let byte = e.utf8_error().valid_up_to();
        let valid = std::str::from_utf8(&e.as_bytes()[..byte]).unwrap_or("");
        LoadError {
            loc: Some(loc_in(valid, byte)),
            // Text formats are XML so far; a second text format would make
            // this a generic "not text" kind.
            ..LoadError::whole_file(
                path.to_path_buf(),
                ErrorKind::NotXml,
                "not UTF-8 text".into(),
            )
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
