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
    let line = count_newlines(before.as_bytes()) + 1;
    let col = before[line_start..].chars().count() + 1;
    SourceLoc {
        line: u32::try_from(line).unwrap_or(u32::MAX),
        col: u32::try_from(col).unwrap_or(u32::MAX),
    }
}

/// Number of `\n` bytes in `bytes`. Counted in blocks of 255 with a byte
/// counter per block, which the compiler turns into wide compares and adds:
/// every mesh, camera and light of a scene asks for its place, each from the
/// start of the file, and a plain `filter().count()` cost about two
/// instructions per byte of a 1.8 MB COLLADA file per query (75 M instructions
/// to load CBbunny, BENCHMARKS.md "Less work per sample outside the BVH").
fn count_newlines(bytes: &[u8]) -> usize {
    bytes
        .chunks(255)
        .map(|block| usize::from(block.iter().fold(0u8, |n, &b| n + u8::from(b == b'\n'))))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newlines_are_counted_across_block_boundaries() {
        // Lines of every length around the 255-byte block, so newlines fall
        // on, before and after block edges.
        let mut text = String::new();
        for len in 0..600 {
            text.push_str(&"x".repeat(len % 300));
            text.push('\n');
        }
        for end in [0, 1, 254, 255, 256, 509, 510, 511, text.len()] {
            let naive = text.as_bytes()[..end]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            assert_eq!(count_newlines(&text.as_bytes()[..end]), naive, "end {end}");
        }
        assert_eq!(count_newlines(text.as_bytes()), 600);
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
