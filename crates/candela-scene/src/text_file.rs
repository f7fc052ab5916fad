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
    let byte = char_start(text, byte);
    let line_start = text[..byte].rfind('\n').map_or(0, |i| i + 1);
    let line = text[..byte].bytes().filter(|&b| b == b'\n').count();
    located(text, line, line_start, byte)
}

/// The start of the character holding byte `byte` (clamped to the text).
fn char_start(text: &str, byte: usize) -> usize {
    let mut byte = byte.min(text.len());
    while !text.is_char_boundary(byte) {
        byte -= 1;
    }
    byte
}

/// The location of `byte`, on the line (0-based `line`) starting at `line_start`.
fn located(text: &str, line: usize, line_start: usize, byte: usize) -> SourceLoc {
    let col = text[line_start..byte].chars().count() + 1;
    SourceLoc {
        line: u32::try_from(line + 1).unwrap_or(u32::MAX),
        col: u32::try_from(col).unwrap_or(u32::MAX),
    }
}

/// Where each line of a text starts, for readers that locate many elements
/// (one per mesh, material, instance...): [`loc_in`] scans the text up to
/// the byte, which over a multi-megabyte file costs milliseconds a call.
/// Built on the first lookup, so a file read without a message pays nothing.
#[derive(Default)]
pub(crate) struct LineIndex {
    starts: std::cell::OnceCell<Vec<usize>>,
}

impl LineIndex {
    /// The same location as [`loc_in`], by a binary search over line starts.
    pub(crate) fn loc(&self, text: &str, byte: usize) -> SourceLoc {
        let starts = self.starts.get_or_init(|| {
            let newlines = text.bytes().enumerate().filter(|&(_, b)| b == b'\n');
            std::iter::once(0)
                .chain(newlines.map(|(i, _)| i + 1))
                .collect()
        });
        let byte = char_start(text, byte);
        let line = starts.partition_point(|&start| start <= byte) - 1;
        located(text, line, starts[line], byte)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_index_locates_as_the_scan_does() {
        let text = "<a>\n  <b é=\"1\"/>\n\n\té<c/>\n";
        let index = LineIndex::default();
        for byte in 0..=text.len() + 3 {
            assert_eq!(index.loc(text, byte), loc_in(text, byte), "byte {byte}");
        }
        let c = text.find("<c").unwrap();
        assert_eq!(index.loc(text, c), SourceLoc { line: 4, col: 3 });
    }

    #[test]
    fn places_are_line_and_character_column() {
        let text = "ab\nçd\n\nxyz";
        assert_eq!(loc_in(text, 0), SourceLoc { line: 1, col: 1 });
        assert_eq!(loc_in(text, 3), SourceLoc { line: 2, col: 1 });
        // 'ç' is two bytes, one character.
        assert_eq!(loc_in(text, 5), SourceLoc { line: 2, col: 2 });
        assert_eq!(loc_in(text, 8), SourceLoc { line: 4, col: 1 });
        assert_eq!(loc_in(text, 100), SourceLoc { line: 4, col: 4 });
    }
}
