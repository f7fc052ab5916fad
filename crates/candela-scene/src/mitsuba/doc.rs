//! One XML file of a Mitsuba scene: located errors, attribute reading with
//! `$name` substitution, and the property lookup every plugin reader uses
//! (`<float name="radius" value=".."/>` is the property `radius`).

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use crate::text_file::LineIndex;
use roxmltree::Node;
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// An element of a parsed file.
pub(super) type XNode<'a, 'i> = Node<'a, 'i>;

/// A file being read: its text (for locations), its path (for messages and
/// relative paths) and the parameters `$name` expands to.
pub(super) struct Doc<'a> {
    pub text: &'a str,
    pub file: &'a Path,
    pub defines: &'a RefCell<HashMap<String, String>>,
    /// Line starts of `text`, for [`Doc::loc`].
    pub lines: LineIndex,
}

impl Doc<'_> {
    /// Where an element starts.
    pub fn loc(&self, node: XNode) -> SourceLoc {
        self.lines.loc(self.text, node.range().start)
    }

    /// An error located at the start of `node`.
    pub fn err(&self, node: XNode, kind: ErrorKind, message: impl Into<String>) -> LoadError {
        LoadError {
            file: self.file.to_path_buf(),
            loc: Some(self.loc(node)),
            element: describe(node),
            kind,
            message: message.into(),
        }
    }

    /// Attribute `name` of `node` with every `$param` replaced by its value;
    /// an undefined or empty parameter name is an error.
    pub fn attr(&self, node: XNode, name: &str) -> Result<Option<String>, LoadError> {
        match node.attribute(name) {
            None => Ok(None),
            Some(raw) => self.substitute(node, raw).map(Some),
        }
    }

    /// Attribute `name`, which must be present.
    pub fn required(&self, node: XNode, name: &str) -> Result<String, LoadError> {
        self.attr(node, name)?.ok_or_else(|| {
            self.err(
                node,
                ErrorKind::MissingElement,
                format!("missing attribute \"{name}\""),
            )
        })
    }

    fn substitute(&self, node: XNode, raw: &str) -> Result<String, LoadError> {
        let mut out = String::with_capacity(raw.len());
        let mut rest = raw;
        while let Some(i) = rest.find('$') {
            out.push_str(&rest[..i]);
            let after = &rest[i + 1..];
            let len = after
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(after.len());
            let name = &after[..len];
            if name.is_empty() {
                return Err(self.err(
                    node,
                    ErrorKind::BadValue,
                    format!("\"$\" not followed by a parameter name in \"{raw}\""),
                ));
            }
            let defines = self.defines.borrow();
            let value = defines.get(name).ok_or_else(|| {
                self.err(
                    node,
                    ErrorKind::MissingReference,
                    format!(
                        "undefined parameter ${name} (no <default> and not given by the caller)"
                    ),
                )
            })?;
            out.push_str(value);
            rest = &after[len..];
        }
        out.push_str(rest);
        Ok(out)
    }

    /// The child element of `node` that is the property `name`.
    pub fn prop<'a, 'i>(
        &self,
        node: XNode<'a, 'i>,
        name: &str,
    ) -> Result<Option<XNode<'a, 'i>>, LoadError> {
        for c in node.children().filter(|c| c.is_element()) {
            if self.attr(c, "name")?.as_deref() == Some(name) {
                return Ok(Some(c));
            }
        }
        Ok(None)
    }

    /// A path named by a file's attribute, relative to the file's folder.
    pub fn path(&self, relative: &str) -> PathBuf {
        self.file.parent().unwrap_or(Path::new("")).join(relative)
    }

    /// The `type` attribute of a plugin element.
    pub fn plugin_type(&self, node: XNode) -> Result<String, LoadError> {
        self.required(node, "type")
    }
}

/// An element as written in messages: `<shape type="ply" id="floor">`.
pub(super) fn describe(node: XNode) -> String {
    let mut s = format!("<{}", node.tag_name().name());
    for key in ["type", "name", "id"] {
        if let Some(v) = node.attribute(key) {
            s.push_str(&format!(" {key}=\"{v}\""));
        }
    }
    s.push('>');
    s
}

/// Child elements of `node`.
pub(super) fn elements<'a, 'i: 'a>(node: XNode<'a, 'i>) -> impl Iterator<Item = XNode<'a, 'i>> {
    node.children().filter(|c| c.is_element())
}
