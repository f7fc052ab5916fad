//! The error type every loader shares: one located, classified problem per
//! failed load, printed on one line as `file:line:col: <element>: message`.
//!
//! A loader stops at the first error it cannot recover from; everything it can
//! recover from becomes a [`crate::Warning`] instead. Each class of problem has
//! its own [`ErrorKind`] so that tests (and tools) can tell them apart without
//! matching on message text.

use crate::desc::SourceLoc;
use std::fmt;
use std::path::PathBuf;

/// Why a scene failed to load. One variant per class of problem.
///
/// The kinds are format-neutral: every loader reports an unreadable file, a
/// bad number or an index past the end with the same kind, so tools can
/// match on them whatever the format. The few that only make sense for one
/// family of formats are grouped last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    // --- Every format ---
    /// The file could not be read.
    Io,
    /// The file's extension names no format this crate can load.
    UnknownFormat,
    /// A file or array larger than the loader accepts.
    TooLarge,
    /// Nesting deeper than the loader accepts.
    TooDeep,
    /// A reference (COLLADA `#url`, a material or texture name, a mesh
    /// index) names nothing, or something of the wrong kind.
    MissingReference,
    /// A count (or the amount a count implies) disagrees with the data.
    CountMismatch,
    /// An index points past the end of what it indexes.
    IndexOutOfRange,
    /// Text that should be a number is not one.
    BadNumber,
    /// A number is infinite or NaN.
    NonFinite,
    /// A polygon with fewer than three vertices.
    BadPolygon,
    /// A camera with an impossible field of view, aspect or transform.
    DegenerateCamera,
    /// A required element, attribute or field is absent.
    MissingElement,
    /// A value that parses but is outside its domain (unknown `up_axis`,
    /// non-positive radius, zero rotation axis, ...).
    BadValue,
    /// An unsupported feature, reported as an error because of strict mode.
    Unsupported,
    /// A text format's file (or header) is not UTF-8 (or ASCII) text.
    NotText,
    /// A binary or line-based file ends before the data its header or
    /// statements promise.
    Truncated,
    // --- XML-based formats ---
    /// The text is not well-formed XML.
    NotXml,
    /// Well-formed XML whose root element is not `<COLLADA>`.
    NotCollada,
    /// The file has a `<!DOCTYPE>` (DTDs and entities are refused outright).
    Dtd,
}

/// A located loading error. `Display` prints one line:
/// `path:line:col: <element>: message`.
#[derive(Clone, Debug, thiserror::Error)]
#[error("{}", self.one_line())]
pub struct LoadError {
    /// The scene file (as given by the caller).
    pub file: PathBuf,
    /// Where in the file, when the problem has a place (I/O errors do not).
    pub loc: Option<SourceLoc>,
    /// The element at fault, written like `<float_array id="x">`; may be empty.
    pub element: String,
    /// The class of problem.
    pub kind: ErrorKind,
    /// What is wrong, for a human.
    pub message: String,
}

/// An error at `loc` in `file`, on `element`: what every loader reports.
pub(crate) fn located(
    file: &std::path::Path,
    loc: SourceLoc,
    element: &str,
    kind: ErrorKind,
    message: String,
) -> LoadError {
    LoadError {
        loc: Some(loc),
        element: element.to_string(),
        ..LoadError::whole_file(file.to_path_buf(), kind, message)
    }
}

impl LoadError {
    /// An error that has no place in the file (reading it failed, or it is too big).
    pub(crate) fn whole_file(file: PathBuf, kind: ErrorKind, message: String) -> Self {
        Self {
            file,
            loc: None,
            element: String::new(),
            kind,
            message,
        }
    }

    fn one_line(&self) -> String {
        let mut s = self.file.display().to_string();
        if let Some(loc) = self.loc {
            s.push_str(&format!(":{loc}"));
        }
        if !self.element.is_empty() {
            s.push_str(&format!(": {}", self.element));
        }
        s.push_str(&format!(": {}", clip_quoted(&self.message)));
        printable(&s)
    }
}

/// At most [`TOKEN_CHARS`] characters of `s`, then `...`: how much of a
/// token from the file a message quotes, so a binary body read as text
/// shows as a recognisable start, not a screenful.
pub(crate) fn clip(s: &str) -> String {
    clip_to(s, TOKEN_CHARS)
}

/// Characters of a quoted token a message keeps.
const TOKEN_CHARS: usize = 32;

/// Characters any quoted text keeps in the printed line: enough for a long
/// path, short enough to keep the error one readable line whatever a
/// loader quoted.
const QUOTED_CHARS: usize = 160;

fn clip_to(s: &str, n: usize) -> String {
    let mut t: String = s.chars().take(n).collect();
    if t.len() < s.len() {
        t.push_str("...");
    }
    t
}

/// `message` with the text between each pair of double quotes clipped to
/// [`QUOTED_CHARS`]: every loader quotes the file's text this way, and
/// this is the one place all their messages pass.
fn clip_quoted(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(1024));
    let mut rest = message;
    while let Some(open) = rest.find('"') {
        out.push_str(&rest[..=open]);
        rest = &rest[open + 1..];
        match rest.find('"') {
            Some(close) => {
                out.push_str(&clip_to(&rest[..close], QUOTED_CHARS));
                out.push('"');
                rest = &rest[close + 1..];
            }
            None => break,
        }
    }
    out.push_str(rest);
    out
}

/// The line with line breaks as spaces (an error is one line of a log) and
/// other control characters escaped (`\u{1b}`), so bytes from a corrupt
/// file cannot reach the reader's terminal as escapes.
fn printable(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    for c in line.chars() {
        match c {
            '\n' | '\r' | '\t' => out.push(' '),
            c if c.is_control() => out.extend(c.escape_unicode()),
            c => out.push(c),
        }
    }
    out
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}
