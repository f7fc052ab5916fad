//! The line structure OBJ and MTL share: one statement per line, a keyword
//! and whitespace-separated arguments, `#` comments, CRLF or LF endings.
//! Every token keeps its column so errors point at it.

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use std::path::Path;

/// One non-empty line: its keyword and arguments, comments removed.
pub(crate) struct Statement<'t> {
    /// 1-based line number.
    pub line: u32,
    /// The first token.
    pub keyword: &'t str,
    /// Every later token with its 1-based column.
    pub args: Vec<(&'t str, u32)>,
    /// Everything after the keyword, trimmed (file names may hold spaces).
    pub rest: &'t str,
    /// Column of the keyword.
    pub col: u32,
}

impl Statement<'_> {
    /// Where the keyword stands.
    pub fn loc(&self) -> SourceLoc {
        self.at(self.col)
    }

    /// Column `col` of this statement's line.
    pub fn at(&self, col: u32) -> SourceLoc {
        SourceLoc {
            line: self.line,
            col,
        }
    }

    /// Where argument `i` stands (the keyword if there is no such argument).
    pub fn arg_loc(&self, i: usize) -> SourceLoc {
        self.at(self.args.get(i).map_or(self.col, |a| a.1))
    }
}

/// The statements of `text`, in order.
pub(crate) fn statements(text: &str) -> impl Iterator<Item = Statement<'_>> {
    text.split('\n').enumerate().filter_map(|(i, raw)| {
        let code = raw.split('#').next().unwrap_or("");
        let code = code.strip_suffix('\r').unwrap_or(code);
        let mut tokens = tokens(code);
        let (col, keyword) = tokens.next()?;
        let after = keyword.as_ptr() as usize + keyword.len() - code.as_ptr() as usize;
        Some(Statement {
            line: u32::try_from(i + 1).unwrap_or(u32::MAX),
            keyword,
            args: tokens.map(|(c, t)| (t, c)).collect(),
            rest: code[after..].trim(),
            col,
        })
    })
}

/// Whitespace-separated tokens of `line` with their 1-based columns (in
/// characters).
fn tokens(line: &str) -> impl Iterator<Item = (u32, &str)> {
    let mut chars = line.char_indices().peekable();
    let mut col = 0u32;
    std::iter::from_fn(move || {
        while let Some(&(_, c)) = chars.peek() {
            if !c.is_whitespace() {
                break;
            }
            chars.next();
            col += 1;
        }
        let &(start, _) = chars.peek()?;
        let start_col = col + 1;
        let mut end = line.len();
        while let Some(&(i, c)) = chars.peek() {
            if c.is_whitespace() {
                end = i;
                break;
            }
            chars.next();
            col += 1;
        }
        Some((start_col, &line[start..end]))
    })
}

/// A located error (the one constructor every loader shares).
pub(crate) use crate::error::located as error;

/// Argument `i` of `st` as a finite number.
pub(crate) fn number(file: &Path, st: &Statement, i: usize) -> Result<f32, LoadError> {
    let Some(&(token, col)) = st.args.get(i) else {
        return Err(error(
            file,
            st.loc(),
            st.keyword,
            ErrorKind::CountMismatch,
            format!("expected a number as argument {}", i + 1),
        ));
    };
    let value: f32 = token.parse().map_err(|_| {
        error(
            file,
            st.at(col),
            st.keyword,
            ErrorKind::BadNumber,
            format!("\"{token}\" is not a number"),
        )
    })?;
    if !value.is_finite() {
        return Err(error(
            file,
            st.at(col),
            st.keyword,
            ErrorKind::NonFinite,
            format!("\"{token}\" is not finite"),
        ));
    }
    Ok(value)
}
