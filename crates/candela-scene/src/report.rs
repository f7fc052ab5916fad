//! Warnings: what a loader understood but chose to ignore.
//!
//! Each ignored feature is named once, at its first location, with a count of
//! how often it occurred, so that a file using an unsupported input semantic on
//! every mesh gives one line instead of thousands.

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use std::collections::HashMap;
use std::fmt;
use std::path::PathBuf;

/// One ignored element or feature.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Warning {
    /// First place it occurred.
    pub loc: SourceLoc,
    /// The element's tag, like `<library_animations>`.
    pub element: String,
    /// What was ignored and why.
    pub message: String,
    /// How many times it occurred (at least 1).
    pub count: u32,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}: {}", self.loc, self.element, self.message)?;
        if self.count > 1 {
            write!(f, " ({} times)", self.count)?;
        }
        Ok(())
    }
}

/// Everything a load ignored, in order of first occurrence.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// The scene file the warnings refer to.
    pub source: PathBuf,
    /// One entry per distinct ignored feature.
    pub warnings: Vec<Warning>,
    /// Decisions the loader took that change what is rendered without
    /// dropping anything the file asks for (e.g. a lamp described twice,
    /// counted once). Not warnings: `--strict` does not refuse them.
    pub notes: Vec<Warning>,
}

impl Report {
    /// True when the loader ignored nothing.
    pub fn is_empty(&self) -> bool {
        self.warnings.is_empty()
    }

    /// Number of distinct warnings.
    pub fn len(&self) -> usize {
        self.warnings.len()
    }

    /// Whether some warning's message contains `needle` (handy in tests and tools).
    pub fn mentions(&self, needle: &str) -> bool {
        self.warnings
            .iter()
            .any(|w| w.message.contains(needle) || w.element.contains(needle))
    }
}

impl fmt::Display for Report {
    /// One line per warning, `path:line:col: <element>: message (N times)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for w in &self.warnings {
            writeln!(f, "{}:{w}", self.source.display())?;
        }
        Ok(())
    }
}

/// Collects warnings during a load, merging repeats; in strict mode the first
/// warning becomes an [`ErrorKind::Unsupported`] error instead.
#[derive(Debug)]
pub(crate) struct Collector {
    strict: bool,
    report: Report,
    seen: HashMap<(String, String), usize>,
}

impl Collector {
    pub(crate) fn new(source: PathBuf, strict: bool) -> Self {
        Self {
            strict,
            report: Report {
                source,
                warnings: Vec::new(),
                notes: Vec::new(),
            },
            seen: HashMap::new(),
        }
    }

    /// Records a warning; `loc` is only evaluated for the first occurrence.
    pub(crate) fn warn(
        &mut self,
        element: String,
        message: String,
        loc: impl FnOnce() -> SourceLoc,
    ) -> Result<(), LoadError> {
        if self.strict {
            return Err(LoadError {
                file: self.report.source.clone(),
                loc: Some(loc()),
                element,
                kind: ErrorKind::Unsupported,
                message: format!("{message} (strict mode)"),
            });
        }
        let repeat = self.seen.contains_key(&(element.clone(), message.clone()));
        let loc = if repeat { SourceLoc::default() } else { loc() };
        self.record(element, message, loc);
        Ok(())
    }

    /// Records a note (see [`Report::notes`]: never an error, even in
    /// strict mode), once per element and message.
    pub(crate) fn note(&mut self, element: String, message: String, loc: SourceLoc) {
        let notes = &mut self.report.notes;
        match notes
            .iter_mut()
            .find(|n| n.element == element && n.message == message)
        {
            Some(n) => n.count += 1,
            None => notes.push(Warning {
                loc,
                element,
                message,
                count: 1,
            }),
        }
    }

    /// Whether warnings are errors (and repairs refused).
    pub(crate) fn strict(&self) -> bool {
        self.strict
    }

    /// A defect the loader can repair: in strict mode `err` itself (the
    /// error a strict load has always given); otherwise a warning at the
    /// error's place, naming its element, saying what was wrong and how it
    /// was repaired (`fix`).
    pub(crate) fn repair(&mut self, err: LoadError, fix: &str) -> Result<(), LoadError> {
        if self.strict {
            return Err(err);
        }
        let loc = err.loc.unwrap_or_default();
        let message = format!("{}; repaired: {fix}", err.message);
        self.record(err.element, message, loc);
        Ok(())
    }

    /// Adds a warning, or counts a repeat of one already recorded.
    fn record(&mut self, element: String, message: String, loc: SourceLoc) {
        let key = (element, message);
        if let Some(&i) = self.seen.get(&key) {
            self.report.warnings[i].count += 1;
            return;
        }
        self.seen.insert(key.clone(), self.report.warnings.len());
        self.report.warnings.push(Warning {
            loc,
            element: key.0,
            message: key.1,
            count: 1,
        });
    }

    pub(crate) fn finish(self) -> Report {
        self.report
    }
}
